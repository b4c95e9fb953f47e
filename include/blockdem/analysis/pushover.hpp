#pragma once
// The equivalent-static pushover of any structure (analysis/structure.hpp): its own weight plus a horizontal body
// acceleration lambda g along an axis, solved by the DEM with Cundall's local damping (DESIGN §4). The structure
// stands at lambda if the unbalanced force vanishes with every block within the collapse displacement of where it
// was built; it collapses if a mechanism keeps moving. The collapse multiplier is bisected between a lambda that
// stands and one that collapses (De Lorenzis et al. 2007; the arch of analysis/arch.hpp is one such structure).
// Each trial starts from the structure as built, loaded at once: a trial does not inherit the damage of another.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "blockdem/analysis/pushover_options.hpp"
#include "blockdem/analysis/structure.hpp"
#include "blockdem/analysis/study.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/number_text.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/json.hpp"
#include "blockdem/io/vtk.hpp"

namespace blockdem::analysis {

namespace detail {

/// The height of the structure's free blocks, m (max - min of their vertices' z).
inline double free_height(const model::Model& m) {
  double lo = 1e300, hi = -1e300;
  for (std::size_t i = 0; i < m.bodies.size(); ++i)
    if (m.bodies.motion[i] == model::Motion::free)
      for (const auto& v : m.bodies.world_shape(i).vertices) {
        lo = std::min(lo, v.z());
        hi = std::max(hi, v.z());
      }
  return hi > lo ? hi - lo : 0.0;
}

/// One trial: the structure as built under gravity + lambda g along the axis, to equilibrium or collapse. With
/// `vtu` set, writes the blocks (displacement from where they were built, largest damage of their contact points).
inline PushoverTrial pushover_trial(Structure s, const PushoverOptions& o, double contact_kinds_general, double limit, double lambda,
                                    const std::string& vtu) {
  const auto start = std::chrono::steady_clock::now();
  PushoverTrial t;
  t.lambda = lambda;
  model::Model& m = s.model;
  m.gravity += o.sign * lambda * m.gravity.norm() * axis_vector(o.axis);  // lambda g, g the model's own
  model::ContactSettings contacts = s.contacts;
  contacts.kinds = contact_kinds_general != 0 ? model::ContactKinds::general : model::ContactKinds::faces;
  s.laws.fill(contacts);
  using Sim = StudySimulation<damping::Local>;
  Sim sim(m, damping::Local{}, structure_properties<Sim>(s), contacts);
  const auto initial = m.bodies.position;
  const auto initial_nodes = m.deformable.nodes.position;
  for (t.steps = 0; t.steps < o.max_steps; ++t.steps) {
    sim.step();
    if ((t.steps & 1023) == 1023 && o.poll) o.poll();
    if (t.steps % 50 != 49) continue;
    t.max_displacement = 0;
    for (std::size_t i = 0; i < m.bodies.size(); ++i)
      if (m.bodies.motion[i] == model::Motion::free) t.max_displacement = std::max(t.max_displacement, (m.bodies.position[i] - initial[i]).norm());
    for (std::size_t i = 0; i < initial_nodes.size(); ++i)
      t.max_displacement = std::max(t.max_displacement, (m.deformable.nodes.position[i] - initial_nodes[i]).norm());
    t.unbalanced_ratio = sim.unbalanced_force_ratio();
    if (t.max_displacement > limit) break;
    if (t.unbalanced_ratio <= o.tolerance) {
      t.stands = true;
      break;
    }
    if (interrupted()) break;
  }
  if (!vtu.empty()) {
    io::BlockFields fields;
    auto& displacement = fields["displacement"];
    auto& damage = fields["max_damage"];
    damage.assign(m.bodies.size(), 0.0);
    for (std::size_t i = 0; i < m.bodies.size(); ++i) {
      displacement.push_back((m.bodies.position[i] - initial[i]).norm());
      fields["component"].push_back(static_cast<double>(m.bodies.joint_tag[i]));
    }
    sim.visit_contacts([&](const auto& c) {
      damage[c.block_a] = std::max(damage[c.block_a], c.damage);
      damage[c.block_b] = std::max(damage[c.block_b], c.damage);
    });
    io::write_blocks_vtu(vtu, m, fields);
  }
  t.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

inline void write_pushover_outputs(const std::string& dir, const Structure& s, const PushoverOptions& o, const PushoverResult& r) {
  io::write_atomically(dir + "/pushover.csv", [&](std::ostream& out) {
    out << "lambda,stands,max_displacement_m,unbalanced_force_ratio,steps,wall_seconds\n";
    std::vector<PushoverTrial> sorted = r.trials;
    std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.lambda < b.lambda; });
    char line[200];
    for (const auto& t : sorted) {
      std::snprintf(line, sizeof line, "%.6g,%d,%.6g,%.4g,%lld,%.3f\n", t.lambda, t.stands ? 1 : 0, t.max_displacement, t.unbalanced_ratio,
                    t.steps, t.wall_seconds);
      out << line;
    }
  });
  io::JsonObject report, options, model;
  options.add("axis", std::string(1, o.axis)).add("direction", o.sign).add("upper", o.upper).add("resolution", o.resolution)
      .add("collapse_displacement_m", r.collapse_displacement).add("tolerance", o.tolerance).add("max_steps_per_trial", o.max_steps);
  model.add("name", s.name).add("groups", s.groups()).add("blocks", static_cast<long long>(s.model.bodies.size()))
      .add("free_mass_kg", s.model.total_mass());
  std::vector<io::JsonObject> trials;
  for (const auto& t : r.trials) {
    io::JsonObject j;
    j.add("lambda", t.lambda).add("stands", t.stands).add("max_displacement_m", t.max_displacement)
        .add("unbalanced_force_ratio", t.unbalanced_ratio).add("steps", t.steps).add("wall_seconds", t.wall_seconds);
    trials.push_back(j);
  }
  report.add("program", "blockdem run (pushover)").add("model", model).add("pushover", options)
      .add("collapse_multiplier", r.collapse_multiplier).add("bracket", std::vector<double>{r.lower, r.upper})
      .add("stands_at_upper", r.stands_at_upper).add("falls_under_own_weight", r.falls_under_weight).add("trials", trials)
      .add("wall_seconds", r.wall_seconds);
  const std::string text = report.str() + "\n";
  io::write_atomically(dir + "/report.json", [&](std::ostream& out) { out << text; });
}

}  // namespace detail

/// The collapse multiplier of `s` by bisection: lambda 0 (its own weight), `upper`, then halves of the bracket until
/// it is narrower than the resolution. `general_contacts`: vertex, edge and face contacts (blocks that turn far).
inline PushoverResult run_pushover(const Structure& s, const PushoverOptions& o, bool general_contacts = true) {
  o.validate();
  s.validate();
  const auto start = std::chrono::steady_clock::now();
  PushoverResult r;
  const double height = detail::free_height(s.model);
  r.collapse_displacement = o.collapse_displacement > 0 ? o.collapse_displacement : 0.02 * height;
  if (!(r.collapse_displacement > 0)) throw InvalidArgument("pushover: '" + s.name + "' has no free block to push");
  if (!o.out_dir.empty()) detail::prepare_output_folder(o.out_dir);
  auto vtu = [&](const char* name) { return o.out_dir.empty() ? std::string() : o.out_dir + "/" + name; };
  auto trial = [&](double lambda, const std::string& file) {
    const auto t = detail::pushover_trial(s, o, general_contacts ? 1 : 0, r.collapse_displacement, lambda, file);
    r.trials.push_back(t);
    if (o.progress)
      std::fprintf(stderr, "pushover: lambda %.4f %s (largest displacement %.3g m, %lld steps, %.1f s)\n", lambda,
                   t.stands ? "stands" : "COLLAPSES", t.max_displacement, t.steps, t.wall_seconds);
    return t.stands;
  };
  r.lower = 0;
  r.upper = o.upper;
  if (!trial(0, vtu("pushover_weight.vtu"))) {
    r.falls_under_weight = true;
    r.collapse_multiplier = 0;
    r.upper = 0;
  } else if (trial(o.upper, vtu("pushover_collapse.vtu"))) {
    r.stands_at_upper = true;
    r.collapse_multiplier = r.lower = o.upper;
  } else {
    while (r.upper - r.lower > o.resolution && !interrupted()) {
      const double mid = 0.5 * (r.lower + r.upper);
      if (trial(mid, "")) r.lower = mid;
      else r.upper = mid;
    }
    r.collapse_multiplier = 0.5 * (r.lower + r.upper);
    // The outputs of the bracket's ends: the last lambda that stood and the first that fell.
    if (!o.out_dir.empty()) {
      (void)detail::pushover_trial(s, o, general_contacts ? 1 : 0, r.collapse_displacement, r.lower, vtu("pushover_stands.vtu"));
      (void)detail::pushover_trial(s, o, general_contacts ? 1 : 0, r.collapse_displacement, r.upper, vtu("pushover_collapse.vtu"));
    }
  }
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!o.out_dir.empty()) detail::write_pushover_outputs(o.out_dir, s, o, r);
  return r;
}

}  // namespace blockdem::analysis
