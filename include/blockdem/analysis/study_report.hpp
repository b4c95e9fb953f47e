#pragma once
// What a study reports (paper Table 4, Sect. 5): the result structs, report.json, the files written at the end of
// each level (damage and contact points for ParaView, a contact table for the plots) and the snapshots. Every file is
// written under a temporary name and renamed when complete.

#include <array>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <system_error>
#include <vector>

#include "blockdem/analysis/damage_memory.hpp"
#include "blockdem/analysis/free_decay.hpp"
#include "blockdem/analysis/structure.hpp"
#include "blockdem/analysis/study_options.hpp"
#include "blockdem/analysis/study_recorders.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/json.hpp"
#include "blockdem/io/vtk.hpp"

namespace blockdem::analysis {

struct LevelResult {
  double level = 0;          // % of the original record
  double duration = 0;       // s asked for: the record's window and the rest after it
  double simulated = 0;      // s run (less if interrupted)
  long long steps = 0;
  double wall_seconds = 0;
  bool interrupted = false;
  double final_table_velocity = 0;  // m/s left by the baseline correction at the end of the record
  std::vector<ChannelPeaks> peaks;  // per monitor channel
  std::vector<Vec3> residual_displacement;  // m, per monitor point at the end of the level, relative to the table
  DamageCensus damage;              // at the end of the level (accumulated over the levels so far)
  EnergyReport energy;              // since the start of the dynamic run, at the end of the level
  EnergyReport energy_at_start;     // the same at the start of the level
  TimestepHold hold;                // since the start of the dynamic run, at the end of the level (cumulative)
  long long detections = 0;         // contact detections since the start of the dynamic run (cumulative)
  double detection_seconds = 0;     // wall time in them (s, cumulative; since the run was started or resumed)
  // The structure collapsed in this level (a monitor point moved --collapse-displacement from where it settled):
  // the level ended then, the point and the time into the level.
  struct Collapse {
    bool collapsed = false;
    std::string point;
    double time = 0;          // s into the level
    double displacement = 0;  // m, of that point
  } collapse;

  double steps_per_second() const { return wall_seconds > 0 ? steps / wall_seconds : 0; }

  void save_state(io::CheckpointWriter& w) const { visit_state(*this, w); }
  void load_state(io::CheckpointReader& r) { visit_state(*this, r); }

 private:
  template <class Self, class Archive>
  static void visit_state(Self& s, Archive& ar) {
    ar("level", s.level);
    ar("level duration", s.duration);
    ar("simulated", s.simulated);
    ar("level steps", s.steps);
    ar("level wall time", s.wall_seconds);
    ar("level interrupted", s.interrupted);
    ar("final table velocity", s.final_table_velocity);
    ar("peaks", s.peaks);
    ar("residual displacements", s.residual_displacement);
    ar("damage census", s.damage);
    ar("energy", s.energy);
    ar("energy at the start", s.energy_at_start);
    ar("timestep hold", s.hold);
    ar("detections", s.detections);
    ar("detection wall time", s.detection_seconds);
    ar("collapsed", s.collapse.collapsed);
    ar("collapse point", s.collapse.point);
    ar("collapse time", s.collapse.time);
    ar("collapse displacement", s.collapse.displacement);
  }
};

struct SettlingResult {
  long long steps = 0;
  double wall_seconds = 0, unbalanced_ratio = 1;
  double dt = 0;  // s, of the static mass scaling
  bool converged = false;
  long long damaged_joints = 0, cracked_joints = 0, crushed_joints = 0;  // contact points, once settled
  /// Its bool members, which a checkpoint reader checks (io/checkpoint.hpp).
  static constexpr std::array<bool SettlingResult::*, 1> checkpoint_flags() { return {&SettlingResult::converged}; }
};

/// The first mode of the settled structure in free decay at its first monitor point (measure_free_vibration).
struct FreeVibrationResult {
  bool measured = false;
  FreeDecay decay;
  double expected_damping_ratio = 0;  // of the damping scheme at the measured frequency (eq. 10, eq. 19)
  double pulse_velocity = 0, pulse_duration = 0;  // m/s, s
  std::string note;                   // why it was not measured
  std::string point;                  // the monitor point measured
  std::vector<double> time, response; // s from the pulse, m: that point along the axis relative to the table

  void save_state(io::CheckpointWriter& w) const { visit_state(*this, w); }
  void load_state(io::CheckpointReader& r) { visit_state(*this, r); }

 private:
  template <class Self, class Archive>
  static void visit_state(Self& s, Archive& ar) {
    ar("free vibration measured", s.measured);
    ar("free decay", s.decay);
    ar("expected damping ratio", s.expected_damping_ratio);
    ar("pulse velocity", s.pulse_velocity);
    ar("pulse duration", s.pulse_duration);
    ar("free vibration note", s.note);
    ar("free vibration point", s.point);
    ar("free vibration times", s.time);
    ar("free vibration response", s.response);
  }
};

struct StudyResult {
  StudyOptions options;
  struct {
    std::string name, cut, baseline;
    bool synthetic = false;
    double duration = 0;             // s, of the cut at 100 % of the input
    double pga = 0, pgv = 0, pgd = 0;  // of the corrected cut as given (at --record-level)
  } input;
  struct ModelSummary {
    std::string name;                // the structure's
    std::vector<std::string> groups;
    std::vector<std::pair<std::string, std::string>> report;  // Structure::report
    std::size_t blocks = 0, contact_points = 0, ties = 0;
    std::size_t deformable_blocks = 0, nodes = 0, tetrahedra = 0;
    double free_mass = 0;  // kg

    // What a checkpoint keeps: the counts (the names come from the structure, which the hash ties to it).
    void save_state(io::CheckpointWriter& w) const { visit_state(*this, w); }
    void load_state(io::CheckpointReader& r) { visit_state(*this, r); }
    template <class Self, class Archive>
    static void visit_state(Self& s, Archive& ar) {
      ar("blocks", s.blocks);
      ar("contact points", s.contact_points);
      ar("ties", s.ties);
      ar("deformable blocks", s.deformable_blocks);
      ar("nodes", s.nodes);
      ar("tetrahedra", s.tetrahedra);
      ar("free mass", s.free_mass);
    }
  } model;
  SettlingResult settling;
  struct {
    std::string scheme, description;
    std::string frame;  // of its mass-proportional term (damping/frame.hpp); empty for a scheme without one
  } damping;
  struct AddedMass {
    long long blocks = 0, nodes = 0;
    double added_mass = 0;  // kg
  };
  struct Timestep {
    double critical_unscaled = 0;  // s, eq. 1-3 with the damping factor, before density scaling
    double damping_factor = 1;     // eq. 11 / eq. 20 at omega_max
    double critical = 0;           // s, after density scaling
    double dt = 0;                 // s, the timestep of the dynamic run
    DensityScaling scaling;
    std::vector<AddedMass> added_by_group;  // by the structure's groups

    void save_state(io::CheckpointWriter& w) const { visit_state(*this, w); }
    void load_state(io::CheckpointReader& r) { visit_state(*this, r); }
    template <class Self, class Archive>
    static void visit_state(Self& s, Archive& ar) {
      ar("critical timestep unscaled", s.critical_unscaled);
      ar("damping factor", s.damping_factor);
      ar("critical timestep", s.critical);
      ar("timestep", s.dt);
      ar("density scaling", s.scaling);
      ar("added mass by group", s.added_by_group);
    }
  } timestep;
  FreeVibrationResult free_vibration;       // if options.free_vibration
  std::vector<std::string> monitor_points;  // names, in the order of the histories' columns
  std::vector<std::string> warnings;  // about the model as the study found it (analysis/corner_point_warnings.hpp)
  std::vector<LevelResult> levels;
  bool interrupted = false;
  double wall_seconds = 0;
};

/// The paper's Table 4 for one run: dynamic timestep, minutes per level, total hours.
inline std::string table4(const StudyResult& r) {
  std::string s;
  char line[256];
  std::snprintf(line, sizeof line, "%-10s %-14s", "Model", "dt [s]");
  s += line;
  for (const auto& L : r.levels) {
    std::string head = num(L.level);
    head += " % [min]";
    std::snprintf(line, sizeof line, " %12s", head.c_str());
    s += line;
  }
  s += "  Total [h]\n";
  double total = 0;
  std::snprintf(line, sizeof line, "%-10s %-14.3e", r.damping.scheme.c_str(), r.timestep.dt);
  s += line;
  for (const auto& L : r.levels) {
    std::snprintf(line, sizeof line, " %12.2f", L.wall_seconds / 60);
    s += line;
    total += L.wall_seconds;
  }
  std::snprintf(line, sizeof line, "  %9.4f\n", total / 3600);
  s += line;
  return s;
}

namespace detail {

/// Creates the output folder and checks that a file can be written in it; a fresh run (not `resuming`) removes the
/// report of an earlier one. `note` follows the folder's name in messages (" (the default)").
inline void prepare_output_folder(const std::string& dir, bool resuming = false, const std::string& note = "") {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error || !std::filesystem::is_directory(dir))
    throw InvalidArgument("--out: cannot create the output folder '" + dir + "'" + note + (error ? ": " + error.message() : std::string()));
  const std::string probe = dir + "/.blockdem_write_test";
  {
    std::ofstream out(probe);
    if (!(out << "ok")) throw InvalidArgument("--out: cannot write in the output folder '" + dir + "'" + note);
  }
  std::filesystem::remove(probe, error);
  // A report left by an earlier run would look like this run's until this one writes its own.
  if (!resuming) std::filesystem::remove(dir + "/report.json", error);
}

inline io::JsonObject energy_json(const EnergyReport& e) {
  io::JsonObject j;
  j.add("work_in_j", e.gravity_work + e.base_work).add("gravity_work_j", e.gravity_work).add("base_work_j", e.base_work)
      .add("kinetic_j", e.kinetic).add("elastic_j", e.elastic).add("viscous_j", e.viscous).add("hysteretic_j", e.slip)
      .add("contact_update_j", e.contact_update).add("balance_error", e.balance_error);
  return j;
}

inline io::JsonObject census_json(const DamageCensus::Counts& c) {
  io::JsonObject j;
  j.add("contact_points", c.contact_points).add("cracked", c.cracked).add("crushed", c.crushed).add("slipped", c.slipped)
      .add("damaged", c.damaged).add("max_damage", c.max_damage).add("new_contacts", c.new_contacts);
  return j;
}

inline std::string report_json(const StudyResult& r) {
  using io::JsonObject;
  const auto& o = r.options;
  JsonObject input, model, settling, damping, timestep, table;
  input.add("record", r.input.name).add("synthetic", r.input.synthetic).add("record_level_percent", o.record_level)
      .add("cut", r.input.cut).add("duration_s", r.input.duration).add("baseline", r.input.baseline)
      .add("axis", std::string(1, o.axis)).add("pga_m_s2", r.input.pga).add("pgv_m_s", r.input.pgv).add("pgd_m", r.input.pgd);
  if (r.input.synthetic) input.add("note", "the built-in synthetic AQA75 stand-in, NOT the AQA recording");
  model.add("name", r.model.name);
  for (const auto& [key, value] : r.model.report) model.add_raw(key, value);
  model.add("contacts", o.contacts == model::ContactKinds::general ? "general" : "faces")
      .add("groups", r.model.groups).add("blocks", static_cast<long long>(r.model.blocks))
      .add("deformable_blocks", static_cast<long long>(r.model.deformable_blocks))
      .add("nodes", static_cast<long long>(r.model.nodes)).add("tetrahedra", static_cast<long long>(r.model.tetrahedra))
      .add("contact_points", static_cast<long long>(r.model.contact_points)).add("ties", static_cast<long long>(r.model.ties))
      .add("free_mass_kg", r.model.free_mass);
  settling.add("method", name(resolved(o.settling, r.model.deformable_blocks > 0)))
      .add("steps", r.settling.steps).add("wall_seconds", r.settling.wall_seconds)
      .add("unbalanced_force_ratio", r.settling.unbalanced_ratio).add("tolerance", o.settle_tolerance)
      .add("converged", r.settling.converged).add("static_mass_scaling_dt_s", r.settling.dt)
      .add("damaged_contact_points", r.settling.damaged_joints).add("cracked_contact_points", r.settling.cracked_joints)
      .add("crushed_contact_points", r.settling.crushed_joints);
  damping.add("scheme", r.damping.scheme).add("description", r.damping.description).add("frame", r.damping.frame);
  JsonObject where;
  for (std::size_t g = 0; g < r.timestep.added_by_group.size() && g < r.model.groups.size(); ++g) {
    const auto& a = r.timestep.added_by_group[g];
    if (a.blocks == 0 && a.nodes == 0) continue;
    JsonObject w;
    w.add("blocks", a.blocks).add("nodes", a.nodes).add("added_mass_kg", a.added_mass);
    where.add(r.model.groups[g], w);
  }
  const auto& s = r.timestep.scaling;
  timestep.add("critical_unscaled_s", r.timestep.critical_unscaled).add("damping_factor", r.timestep.damping_factor)
      .add("critical_s", r.timestep.critical).add("dt_s", r.timestep.dt)
      .add("density_scaling_mass_added_kg", s.added_mass).add("density_scaling_mass_increase_percent", s.mass_increase_percent)
      .add("density_scaled_blocks", static_cast<long long>(s.scaled_blocks))
      .add("density_scaled_nodes", static_cast<long long>(s.scaled_nodes))
      .add("max_density_scaling_factor", s.max_density_scaling_factor).add("density_scaling_by_component", where);
  std::vector<JsonObject> levels;
  std::vector<double> minutes;
  double total = 0;
  for (const auto& L : r.levels) {
    JsonObject l, peaks, residual, damage;
    for (const auto& p : L.peaks) {
      JsonObject q;
      q.add("max", p.max).add("min", p.min);
      peaks.add(p.name, q);
    }
    for (std::size_t p = 0; p < L.residual_displacement.size(); ++p) {
      const auto& u = L.residual_displacement[p];
      std::string vector(1, '[');  // (GCC 12 warns, wrongly, of an overlap in "[" + std::string)
      for (int c = 0; c < 3; ++c) {
        vector += JsonObject::number(u[c]);
        vector += c < 2 ? ", " : "]";
      }
      residual.add_raw(r.monitor_points[p], vector);
    }
    damage.add("total", census_json(L.damage.total)).add("loose_blocks", L.damage.loose_blocks);
    for (std::size_t g = 0; g < L.damage.by_group.size() && g < r.model.groups.size(); ++g)
      damage.add(r.model.groups[g], census_json(L.damage.by_group[g]));
    EnergyReport delta = L.energy;
    delta.gravity_work -= L.energy_at_start.gravity_work;
    delta.base_work -= L.energy_at_start.base_work;
    delta.kinetic -= L.energy_at_start.kinetic;
    delta.elastic -= L.energy_at_start.elastic;
    delta.viscous -= L.energy_at_start.viscous;
    delta.slip -= L.energy_at_start.slip;
    delta.contact_update -= L.energy_at_start.contact_update;
    l.add("level_percent", L.level).add("duration_s", L.duration).add("simulated_s", L.simulated).add("steps", L.steps)
        .add("wall_seconds", L.wall_seconds).add("steps_per_second", L.steps_per_second()).add("dt_s", r.timestep.dt)
        .add("interrupted", L.interrupted).add("final_table_velocity_m_s", L.final_table_velocity)
        .add("peaks", peaks).add("residual_displacement_m", residual).add("damage", damage)
        .add("energy", energy_json(L.energy)).add("energy_change_over_level", energy_json(delta))
        .add("detections", L.detections).add("detection_seconds", L.detection_seconds);
    if (L.collapse.collapsed) {
      JsonObject c;
      c.add("monitor_point", L.collapse.point).add("time_into_level_s", L.collapse.time)
          .add("displacement_m", L.collapse.displacement).add("collapse_displacement_m", o.collapse_displacement);
      l.add("collapse", c);
    }
    JsonObject hold;  // cumulative since the start of the dynamic run
    hold.add("checks", L.hold.checks).add("raises", L.hold.raises).add("raised_nodes", L.hold.raised_nodes)
        .add("raised_blocks", L.hold.raised_blocks).add("added_mass_kg", L.hold.added_mass)
        .add("kinetic_energy_added_J", L.hold.kinetic_energy).add("timestep_reductions", L.hold.reductions);
    l.add("timestep_hold", hold);
    levels.push_back(l);
    minutes.push_back(L.wall_seconds / 60);
    total += L.wall_seconds;
  }
  table.add("model", r.damping.scheme).add("dynamic_timestep_s", r.timestep.dt).add("minutes_per_level", minutes)
      .add("total_hours", total / 3600);
  JsonObject out;
  out.add("program", o.program).add("input", input).add("model", model).add("monitor_points", r.monitor_points).add("settling", settling);
  out.add("warnings", r.warnings);
  if (o.free_vibration) {
    const auto& f = r.free_vibration;
    JsonObject j;
    j.add("measured", f.measured).add("frequency_hz", f.decay.frequency_hz).add("damping_ratio", f.decay.damping_ratio)
        .add("expected_damping_ratio", f.expected_damping_ratio).add("cycles", f.decay.cycles)
        .add("first_amplitude_m", f.decay.first_amplitude).add("pulse_velocity_m_s", f.pulse_velocity)
        .add("pulse_duration_s", f.pulse_duration);
    if (!f.note.empty()) j.add("note", f.note);
    out.add("free_vibration", j);
  }
  out
      .add("damping", damping).add("timestep", timestep).add("levels", levels).add("table4", table)
      .add("interrupted", r.interrupted).add("complete", !r.interrupted && r.levels.size() == o.levels.size())
      .add("collapsed", !r.levels.empty() && r.levels.back().collapse.collapsed)
      .add("wall_seconds", r.wall_seconds);
  return out.str();
}

/// free_vibration.csv: the response of measure_free_vibration at its monitor point.
inline void write_free_vibration(const std::string& dir, const FreeVibrationResult& f) {
  io::write_atomically(dir + "/free_vibration.csv", [&](std::ostream& out) {
    out << "time," << f.point << "_u\n";
    char line[64];
    for (std::size_t i = 0; i < f.time.size(); ++i) {
      std::snprintf(line, sizeof line, "%.6f,%.9g\n", f.time[i], f.response[i]);
      out << line;
    }
  });
}

inline void write_report(const std::string& dir, const StudyResult& r) {
  const std::string text = report_json(r) + "\n";
  io::write_atomically(dir + "/report.json", [&](std::ostream& out) { out << text; });
}

/// The blocks' fields for ParaView: "component" (the index of the block's group: the vault's component) and
/// "displacement" (m, since `reference`, relative to the table: what the structure did, not where the table took it).
inline io::BlockFields block_fields(const model::Model& model, const Structure& structure, const std::vector<Vec3>& reference) {
  io::BlockFields fields;
  auto& component = fields["component"];
  auto& displacement = fields["displacement"];
  const Vec3 table = structure.table ? Vec3(model.bodies.position[*structure.table] - reference[*structure.table]) : Vec3::Zero();
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    component.push_back(static_cast<double>(model.bodies.joint_tag[i]));
    displacement.push_back((model.bodies.position[i] - reference[i] - table).norm());
  }
  return fields;
}

/// At the end of a level: damage_<level>.vtu (blocks with their group, displacement since settling relative to the
/// table and the largest damage of their contact points), contacts_<level>.vtu (the contact points with damage, gap,
/// stresses) and contacts_<level>.csv (the same as a table, with the groups on each side, for the plots). The contact
/// points are those of the damage memory (damage_memory.hpp): every point of a joint bonded at the start, with the
/// worst state it reached and, if it is still there (present = 1), its present gap and stresses; a joint whose
/// blocks have moved apart is drawn where it was on block A, with no gap or stress (present = 0). Then the points
/// made during the run (never_bonded = 1), which never hide a joint.
template <class Sim>
void write_level_outputs(const std::string& dir, const std::string& label, const Sim& sim, const model::Model& model,
                         const Structure& structure, const std::vector<Vec3>& reference, const DamageMemory& memory) {
  std::vector<ContactView> present;
  sim.visit_contacts([&](const ContactView& c) { present.push_back(c); });
  const auto& joints = memory.joints();
  std::vector<std::ptrdiff_t> heir(joints.size(), -1);
  for (std::size_t k = 0; k < present.size(); ++k)
    if (!present[k].never_bonded)
      if (const auto* j = memory.heir_of(model, present[k])) heir[static_cast<std::size_t>(j - joints.data())] = static_cast<std::ptrdiff_t>(k);
  std::vector<ContactView> rows;
  std::vector<char> there;
  memory.visit(model, [&](const DamageMemory::Joint& j, const Vec3& world) {
    const auto k = heir[rows.size()];
    ContactView v;
    if (k >= 0) {
      v = present[static_cast<std::size_t>(k)];
    } else {
      v.position = world;
      v.normal = Vec3::Zero();
      v.area = j.area;
      v.gap = std::numeric_limits<double>::quiet_NaN();
    }
    v.block_a = j.a;
    v.block_b = j.b;
    v.damage = j.damage;
    v.never_bonded = false;
    v.cracked = (j.state & DamageMemory::cracked) != 0;
    v.crushed = (j.state & DamageMemory::crushed) != 0;
    v.slipped = (j.state & DamageMemory::slipped) != 0;
    rows.push_back(v);
    there.push_back(k >= 0 ? 1 : 0);
  });
  for (const auto& v : present)
    if (v.never_bonded) {
      rows.push_back(v);
      there.push_back(1);
    }
  auto fields = block_fields(model, structure, reference);
  auto& block_damage = fields["max_damage"];
  block_damage.assign(model.bodies.size(), 0.0);
  for (const auto& c : rows) {
    block_damage[c.block_a] = std::max(block_damage[c.block_a], c.damage);
    block_damage[c.block_b] = std::max(block_damage[c.block_b], c.damage);
  }
  io::write_blocks_vtu(dir + "/damage_" + label + ".vtu", model, fields);
  {
    io::BlockFields f;
    for (const auto& c : rows) {
      f["cracked"].push_back(c.cracked ? 1.0 : 0.0);
      f["crushed"].push_back(c.crushed ? 1.0 : 0.0);
    }
    f["present"].assign(there.begin(), there.end());
    io::write_contact_points_vtu(dir + "/contacts_" + label + ".vtu", [&](auto&& visit) {
      for (const auto& c : rows) visit(c);
    }, std::move(f));
  }
  io::write_atomically(dir + "/contacts_" + label + ".csv", [&](std::ostream& out) {
    out << "x,y,z,nx,ny,nz,area,gap,normal_stress,shear_stress,damage,never_bonded,component_a,component_b,present,cracked,crushed,slipped\n";
    char line[360];
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const auto& c = rows[r];
      std::snprintf(line, sizeof line, "%.6g,%.6g,%.6g,%.5g,%.5g,%.5g,%.5g,%.5g,%.6g,%.6g,%.5g,%d,%s,%s,%d,%d,%d,%d\n", c.position.x(),
                    c.position.y(), c.position.z(), c.normal.x(), c.normal.y(), c.normal.z(), c.area, c.gap, c.normal_stress,
                    c.shear_stress, c.damage, c.never_bonded ? 1 : 0, structure.group_of(c.block_a).c_str(),
                    structure.group_of(c.block_b).c_str(), there[r], c.cracked ? 1 : 0, c.crushed ? 1 : 0, c.slipped ? 1 : 0);
      out << line;
    }
  });
}

}  // namespace detail

/// The time series of the blocks for playing the shaking back in ParaView: snapshots/level<L>_<k>.vtu, and
/// snapshots.pvd listing them all by simulation time, rewritten with each frame so that it is always complete.
class SnapshotSeries {
 public:
  explicit SnapshotSeries(std::string dir) : dir_(std::move(dir)) {}

  /// The frames written so far, for a checkpoint (a resumed run rewrites the later ones and the collection).
  void save_state(io::CheckpointWriter& w) const {
    w.write(static_cast<std::uint64_t>(frames_.size()));
    for (const auto& [time, file] : frames_) {
      w.write(time);
      w.write(file);
    }
    w.write(static_cast<std::uint64_t>(frames_in_level_.size()));
    for (const auto& [label, count] : frames_in_level_) {
      w.write(label);
      w.write(count);
    }
  }
  void load_state(io::CheckpointReader& r) {
    const auto frames = r.read_value<std::uint64_t>("snapshot frames");
    if (frames > r.remaining() / (sizeof(double) + sizeof(std::uint64_t)))  // each a time and a file name
      r.fail("snapshot frames", "a count of " + std::to_string(frames) + " frames, more than the " +
                                    std::to_string(r.remaining()) + " bytes left can hold");
    frames_.resize(static_cast<std::size_t>(frames));
    for (auto& [time, file] : frames_) {
      r.read(time, "snapshot time");
      r.read(file, "snapshot file");
    }
    frames_in_level_.clear();
    for (auto n = r.read_value<std::uint64_t>("snapshot levels"); n > 0; --n) {
      auto label = r.read_value<std::string>("snapshot level");
      frames_in_level_[label] = r.read_value<int>("snapshot count");
    }
  }

  void write(const std::string& label, double time, const model::Model& model, const Structure& structure,
             const std::vector<Vec3>& reference) {
    std::filesystem::create_directories(dir_ + "/snapshots");
    const std::string name = "snapshots/level" + label + "_" + std::to_string(frames_in_level_[label]++) + ".vtu";
    const auto fields = detail::block_fields(model, structure, reference);
    io::write_blocks_vtu(dir_ + "/" + name, model, fields);
    frames_.emplace_back(time, name);
    io::write_atomically(dir_ + "/snapshots.pvd", [&](std::ostream& out) {
      out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
      char line[256];
      for (const auto& [when, file] : frames_) {
        std::snprintf(line, sizeof line, "<DataSet timestep=\"%.6f\" file=\"%s\"/>\n", when, file.c_str());
        out << line;
      }
      out << "</Collection>\n</VTKFile>\n";
    });
  }

 private:
  std::string dir_;
  std::map<std::string, int> frames_in_level_;
  std::vector<std::pair<double, std::string>> frames_;
};

}  // namespace blockdem::analysis
