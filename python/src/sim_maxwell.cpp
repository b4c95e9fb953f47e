// The dynamic simulations under Maxwell damping (1 to 4 branches), for blockdem.Simulation (simulation.hpp).

#include "simulation.hpp"

namespace blockdem::python {

DynamicPlan plan_maxwell(Settling& settle, const FrequencyBound& bound, const analysis::StudyOptions& o, analysis::StudyResult& r) {
  return plan_of_kind<true>(settle, bound, o, r);
}

}  // namespace blockdem::python
