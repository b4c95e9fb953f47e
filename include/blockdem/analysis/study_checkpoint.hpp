#pragma once
// The checkpoints of a study: where the study stands (StudyCursor), the hash that ties a checkpoint to
// one model and one set of options, and the one list of what a checkpoint holds, for writing and reading.

#include <array>
#include <cstdint>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "blockdem/analysis/structure.hpp"
#include "blockdem/analysis/study_options.hpp"
#include "blockdem/analysis/study_recorders.hpp"
#include "blockdem/analysis/study_report.hpp"
#include "blockdem/io/checkpoint.hpp"
#include "blockdem/model/model.hpp"
#include "blockdem/motion/record.hpp"

namespace blockdem::analysis {

/// Where the level loop stands. Between levels (in_level false) `level` is the next level to run; inside one, the
/// level in progress with what its recorders need to go on.
struct StudyCursor {
  std::uint64_t level = 0;        // index into options.levels
  bool in_level = false;
  double level_start = 0;         // s, simulation time at which the level began
  double start_velocity = 0;      // m/s, table velocity when the level began
  double table_velocity = 0;      // m/s, where the last finished level left the table
  double next_sample = 0, next_snapshot = 0;  // s, simulation time of the next history sample and snapshot
  long long level_steps = 0;      // steps of the level so far
  double level_wall_seconds = 0;  // wall time of the level so far, over every run that worked on it
  long long dynamic_steps = 0;    // steps of the dynamic run so far, all levels
  EnergyReport energy_at_level_start;
  /// Its bool members, which a checkpoint reader checks (io/checkpoint.hpp).
  static constexpr std::array<bool StudyCursor::*, 1> checkpoint_flags() { return {&StudyCursor::in_level}; }
};

inline constexpr const char* study_checkpoint_file = "checkpoint.bin";

/// The hash that a study's checkpoint carries: the model as built (blocks, ties, nodes), the joint laws and their
/// grids, the monitor points, the input as cut, and every option that changes the run's results. Output folder,
/// progress, checkpoint interval and stop are left out: a run may be resumed with other ones.
inline std::uint64_t study_hash(const StudyOptions& o, const Structure& s, const motion::Record& cut) {
  io::Hasher h;
  h.add("blockdem study, checkpoint layout 4");
  const model::Model& m = s.model;
  auto add_points = [&h](const std::vector<Vec3>& points) {
    h.add(static_cast<std::uint64_t>(points.size()));
    for (const auto& p : points) h.add(p.x()).add(p.y()).add(p.z());
  };
  const auto& b = m.bodies;
  h.add(b.mass).add(b.joint_tag);
  add_points(b.position);
  add_points(b.principal_inertia);
  for (std::size_t i = 0; i < b.size(); ++i) h.add(static_cast<int>(b.motion[i]));
  for (const auto& t : m.deformable.trusses) h.add(t.area).add(t.young).add(t.density).add(t.pretension).add(t.length0);
  add_points(m.deformable.nodes.position);
  h.add(m.deformable.nodes.real_mass).add(static_cast<std::uint64_t>(m.deformable.tetrahedra.size()));
  const auto& laws = s.laws;
  h.add(laws.group_names().size());
  for (const auto& g : laws.group_names()) h.add(g);
  for (std::size_t ga = 0; ga < laws.groups(); ++ga)
    for (std::size_t gb = ga; gb < laws.groups(); ++gb) {
      h.add(laws.has(ga, gb)).add(laws.contact_point_area(ga, gb));
      if (!laws.has(ga, gb)) continue;
      const auto& law = laws.law(ga, gb);
      h.add(law.index());
      std::visit([&h]<class P>(const P& p) {
        // Every law's parameters are doubles only: their bytes are their values.
        static_assert(std::is_trivially_copyable_v<P> && sizeof(P) % sizeof(double) == 0);
        h.add_bytes(&p, sizeof p);
      }, law);
    }
  h.add(s.contacts.tolerance).add(s.contacts.max_contact_point_area).add(s.contacts.max_normal_angle);
  for (const auto& p : s.monitors) h.add(p.name).add(p.block).add(p.position.x()).add(p.position.y()).add(p.position.z());
  h.add(s.table.has_value()).add(s.table.value_or(0));
  h.add(cut.dt).add(cut.start_time).add(cut.acceleration);
  h.add(o.axis).add(o.record_level).add(o.levels).add(o.rest).add(o.collapse_displacement);
  h.add(static_cast<int>(o.damping)).add(static_cast<int>(o.damping_frame)).add(o.scheme_zeta()).add(o.frequency_hz).add(o.lower_hz).add(o.upper_hz).add(o.branches);
  h.add(o.target_dt).add(o.default_mass_increase_percent).add(o.settle_tolerance).add(o.settle_max_steps);
  h.add(static_cast<int>(o.settling));
  h.add(o.free_vibration).add(o.history_dt).add(o.snapshots_every);
  h.add(static_cast<int>(o.contacts));
  return h.value();
}

namespace detail {

/// The one list of a study checkpoint's contents, for both directions (Archive: io::CheckpointWriter or Reader).
template <class Archive, class Result, class Cursor, class Sim, class History, class Snapshots, class Positions, class Memory>
void visit_study_state(Archive& ar, Result& r, Cursor& cursor, Sim& sim, History& history, Snapshots& snapshots,
                       Positions& settled_position, Memory& memory) {
  ar("model summary", r.model);
  ar("settling", r.settling);
  ar("timestep", r.timestep);
  ar("free vibration", r.free_vibration);
  ar("finished levels", r.levels);
  ar("study cursor", cursor);
  ar("simulation", sim);
  ar("monitor histories", history);
  ar("snapshots", snapshots);
  ar.same_size("settled block positions", settled_position);
  ar("damage memory", memory);
}

}  // namespace detail
}  // namespace blockdem::analysis
