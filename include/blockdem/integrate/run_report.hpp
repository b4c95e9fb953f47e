#pragma once
// The JSON run report of a simulation: timestep, steps, wall time, cost per contact-point-step, energy terms and
// the balance error.

#include <string>

#include "blockdem/integrate/run.hpp"
#include "blockdem/io/json.hpp"

namespace blockdem::io {

template <class Simulation>
JsonObject run_report(const Simulation& simulation, const RunSummary& run) {
  const auto e = simulation.energy();
  const double cp_steps = static_cast<double>(run.steps) * static_cast<double>(simulation.contact_points());
  JsonObject j;
  j.add("dt", simulation.timestep())
      .add("dt_critical", simulation.critical_timestep())
      .add("time", simulation.time())
      .add("steps", run.steps)
      .add("wall_seconds", run.wall_seconds)
      .add("ns_per_cp_step", cp_steps > 0 ? 1e9 * run.wall_seconds / cp_steps : 0.0)
      .add("blocks", static_cast<long long>(simulation.model().bodies.size()))
      .add("contact_points", static_cast<long long>(simulation.contact_points()))
      .add("detections", simulation.detections())
      .add("interrupted", run.interrupted)
      .add("kinetic_energy_j", e.kinetic)
      .add("elastic_energy_j", e.elastic)
      .add("gravity_work_j", e.gravity_work)
      .add("base_work_j", e.base_work)
      .add("viscous_dissipation_j", e.viscous)
      .add("slip_dissipation_j", e.slip)
      .add("energy_balance_error", e.balance_error);
  return j;
}

}  // namespace blockdem::io
