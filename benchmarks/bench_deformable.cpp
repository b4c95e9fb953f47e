// Cost of one explicit step on a wall of deformable blocks (constant-strain tetrahedra, node contacts on a rigid
// foundation and between blocks) for the damping policies None, MassProportional and Maxwell<3>, on one thread and on
// two. Counters: ns per node-step (node_step_ns) and per tetrahedron-step (tet_step_ns), each the whole step's time
// divided by the number of nodes or tetrahedra; and ns per contact-point-step for reference.

#include <benchmark/benchmark.h>
#include <omp.h>

#include <memory>
#include <string>
#include <type_traits>

#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/damping/maxwell_fit.hpp"
#include "blockdem/damping/policies.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "shipped.hpp"

namespace {

using namespace blockdem;
using benchmarks::for_each_type;
using benchmarks::short_name;
using benchmarks::unlisted;

/// 6 courses of 8 units (0.24 x 0.12 x 0.055 m) in running bond, each unit meshed with edges of at most 2 cm.
model::Model make_wall() {
  model::Model m;
  for (const auto& b : geometry::running_bond_wall(6, 8, 0.24, 0.12, 0.055)) {
    const auto i = m.add_block(b.shape, 1800, b.name, 0, b.support ? model::Motion::fixed : model::Motion::free);
    if (!b.support) m.make_deformable(i, 0.02, model::IsotropicElastic(5e9, 0.2));
  }
  return m;
}

/// Whether the deformable table has a row for the policy: the tensor form of the element branches (Maxwell<3>)
/// against the policies without element damping (not the seven-spring element form of StiffnessProportional and
/// Rayleigh; not Local, which settles a model).
template <class Damping>
constexpr bool in_deformable_table() {
  if constexpr (std::is_same_v<Damping, damping::None> || std::is_same_v<Damping, damping::MassProportional> ||
                std::is_same_v<Damping, damping::Maxwell<3>>)
    return true;
  else if constexpr (std::is_same_v<Damping, damping::Local> || std::is_same_v<Damping, damping::StiffnessProportional> ||
                     std::is_same_v<Damping, damping::Rayleigh>)
    return false;
  else static_assert(unlisted<Damping>, "a new policy: say whether the deformable table has it (and give it a make_damping)");
}

template <class Damping>
Damping make_damping() {
  if constexpr (std::is_same_v<Damping, damping::None>) return {};
  else if constexpr (std::is_same_v<Damping, damping::MassProportional>) return damping::MassProportional::from_damping_ratio(0.04, 7.5);
  else if constexpr (std::is_same_v<Damping, damping::Maxwell<3>>) return damping::to_policy<3>(damping::fit_maxwell(damping::MaxwellFitOptions{}));
  else static_assert(unlisted<Damping>, "a new policy: give the deformable wall its coefficients here");
}

template <class Damping>
void step(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  auto model = std::make_unique<model::Model>(make_wall());
  Simulation<Damping, contact::MohrCoulomb> sim(*model, make_damping<Damping>(),
                                                [](int, int) { return contact::MohrCoulomb::Parameters(1e10, 4e9, 1e5, 2e5, 0.6); });
  for (int i = 0; i < 20; ++i) sim.step();
  for (auto _ : state) sim.step();
  const auto nodes = static_cast<double>(model->deformable.nodes.size());
  const auto tets = static_cast<double>(model->deformable.tetrahedra.size());
  const auto n = static_cast<double>(state.iterations());
  using C = benchmark::Counter;
  state.counters["node_step_ns"] = C(n * nodes * 1e-9, C::kIsRate | C::kInvert);
  state.counters["tet_step_ns"] = C(n * tets * 1e-9, C::kIsRate | C::kInvert);
  state.counters["cp_step_ns"] = C(n * static_cast<double>(sim.contact_points()) * 1e-9, C::kIsRate | C::kInvert);
  state.counters["nodes"] = nodes;
  state.counters["tetrahedra"] = tets;
  state.counters["contact_points"] = static_cast<double>(sim.contact_points());
}

/// The rows of the table, named "deformable_wall/damping::None" and so on.
[[maybe_unused]] const bool deformable_benchmarks = [] {
  for_each_type<damping::ShippedPolicies>([](auto policy) {
    using Damping = typename decltype(policy)::type;
    if constexpr (in_deformable_table<Damping>()) {
      const std::string name = "deformable_wall/" + short_name<Damping>();
      benchmark::RegisterBenchmark(name.c_str(), step<Damping>)
          ->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);
    }
  });
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
