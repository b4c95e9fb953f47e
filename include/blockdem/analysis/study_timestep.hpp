#pragma once
// The timestep of a study's dynamic run (paper eq. 1-3, 11, 20; partial density scaling, Sect. 3.2): chosen from the
// settling simulation before it settles, so that a target that needs too much mass is refused at once, then set on
// the dynamic simulation continued from it. The study (study.hpp) and blockdem.Simulation take the same steps.

#include <cmath>
#include <cstddef>
#include <vector>

#include "blockdem/analysis/structure.hpp"
#include "blockdem/analysis/study_options.hpp"
#include "blockdem/analysis/study_report.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/number_text.hpp"
#include "blockdem/integrate/frequency_bound.hpp"

namespace blockdem::analysis {

/// The timestep of a study's dynamic run.
struct DynamicTimestep {
  double unscaled = 0;  // s, the safety factor times the policy's critical timestep (eq. 1, 11, 20), unscaled
  double target = 0;    // s, the timestep to run at: o.target_dt, or the largest whose density scaling adds at most
                        // o.default_mass_increase_percent of the free mass
};

/// The timestep of the dynamic run under `policy`, from the settling simulation `settle` before it settles and its
/// frequency bound `bound` (one bound for the whole search: the masses do not change during it). Fills t's damping
/// factor and unscaled critical timestep. Throws InvalidArgument for a target that needs more mass than
/// o.max_mass_increase_percent.
template <class Settle, class D>
DynamicTimestep choose_dynamic_timestep(const Settle& settle, const FrequencyBound& bound, const D& policy, const StudyOptions& o,
                                        double free_mass, StudyResult::Timestep& t) {
  auto factor = [&](double omega) { return policy.timestep_factor(omega); };
  // The dynamic policy multiplies 2 / omega_max (eq. 1) by its factor at omega_max (eq. 11, eq. 20).
  const double omega_max = settle.bounded_frequency() ? bound.omega_max() : settle.omega_max();
  t.damping_factor = factor(omega_max);
  t.critical_unscaled = 2.0 / omega_max * t.damping_factor;
  DynamicTimestep dt;
  dt.unscaled = settle.safety_factor() * t.critical_unscaled;
  dt.target = o.target_dt;
  if (dt.target == 0) {
    double lo = dt.unscaled, hi = 1e-3;
    for (int it = 0; it < 60; ++it) {
      const double mid = std::sqrt(lo * hi);
      (100 * settle.density_scaling_mass(mid, factor, bound) / free_mass <= o.default_mass_increase_percent ? lo : hi) = mid;
    }
    dt.target = lo;
  }
  if (dt.target > dt.unscaled) {
    const double percent = 100 * settle.density_scaling_mass(dt.target, factor, bound) / free_mass;
    if (percent > o.max_mass_increase_percent)
      throw InvalidArgument(o.context + ": --target-dt " + num(dt.target) + " s needs " + num(percent) +
                            " % more mass by density scaling, above --max-mass-increase " + num(o.max_mass_increase_percent) +
                            " %; this model runs unscaled at " + num(dt.unscaled) + " s");
  }
  return dt;
}

/// Sets the dynamic simulation `sim` (continued from the settling one) to run at `target`: as given below its own
/// timestep, by partial density scaling above it (Sect. 3.2). Fills t: the scaling, the mass it added by group of
/// `s`, the timestep and the critical one.
template <class Dynamic>
void set_dynamic_timestep(Dynamic& sim, double target, const Structure& s, StudyResult::Timestep& t) {
  const model::Model& model = s.model;
  if (target < sim.timestep()) sim.set_timestep(target);  // a --target-dt below the unscaled one: run at it
  if (target > sim.timestep()) {
    const std::vector<double> real_mass = model.bodies.mass, real_node_mass = model.deformable.nodes.mass;
    t.scaling = sim.scale_density_to(target);
    const auto& tag = model.bodies.joint_tag;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
      if (!model.deformable.is_deformable(i) && model.bodies.mass[i] > real_mass[i]) {
        auto& where = t.added_by_group[static_cast<std::size_t>(tag[i])];
        where.blocks += 1;
        where.added_mass += model.bodies.mass[i] - real_mass[i];
      }
    const auto& nd = model.deformable.nodes;
    for (std::size_t i = 0; i < nd.size(); ++i)
      if (nd.mass[i] > real_node_mass[i]) {
        auto& where = t.added_by_group[static_cast<std::size_t>(tag[nd.block[i]])];
        where.nodes += 1;
        where.added_mass += nd.mass[i] - real_node_mass[i];
      }
  }
  t.dt = sim.timestep();
  t.critical = sim.critical_timestep();
}

}  // namespace blockdem::analysis
