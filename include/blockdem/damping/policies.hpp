#pragma once
// The one list of the damping policies blockdem ships, which tests and benchmarks iterate.

#include <tuple>

#include "blockdem/damping/concepts.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/damping/mass_proportional.hpp"
#include "blockdem/damping/maxwell.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/damping/rayleigh.hpp"
#include "blockdem/damping/stiffness_proportional.hpp"

namespace blockdem::damping {

/// Every shipped damping policy. Maxwell<3> stands for Maxwell<N>: the paper's three branches and the benchmark
/// tables' (every N is the same code; tests of other N name them). The concept tests, the policy tests of the
/// integrator and the wall benchmarks run each policy of this list, or say for each why it is not in their subset.
/// A new policy: one header, one test file and one line here (then each test or benchmark that needs per-policy
/// parameters names what it wants for it, or fails to compile).
using ShippedPolicies = std::tuple<None, Local, MassProportional, StiffnessProportional, Rayleigh, Maxwell<3>>;

static_assert([]<class... D>(std::tuple<D...>*) { return (DampingPolicy<D> && ...); }(static_cast<ShippedPolicies*>(nullptr)));

}  // namespace blockdem::damping
