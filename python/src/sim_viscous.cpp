// The dynamic simulations without damping and under mass-proportional, stiffness-proportional and Rayleigh damping,
// for blockdem.Simulation (simulation.hpp).

#include "simulation.hpp"

namespace blockdem::python {

DynamicPlan plan_viscous(Settling& settle, const FrequencyBound& bound, const analysis::StudyOptions& o, analysis::StudyResult& r) {
  return plan_of_kind<false>(settle, bound, o, r);
}

}  // namespace blockdem::python
