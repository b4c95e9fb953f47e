// Contact detection (model/contact_detection.hpp), face to face only against general (vertex, edge and face), on
// three assemblies: the wall of bench_wall (2021 blocks, all face to face), the rigid cross vault (the paper's model
// with its default bricks) and the 40-voussoir arch in the middle of its collapse (voussoirs tumbling onto the
// floor, where the general contacts are found). Counters: contact points found, time per contact point.
//
//   ./build/benchmarks/bench_detection --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include "blockdem/analysis/arch.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "blockdem/models/cross_vault.hpp"
#include "wall_model.hpp"

namespace {

using namespace blockdem;

const model::Model& wall() {
  static const model::Model m = benchmarks::make_wall();
  return m;
}

const model::Model& vault() {
  static const model::Model m = models::build_rigid_model(models::make_cross_vault());
  return m;
}

/// The arch of analysis::analyse_arch (lambda 0.3, joints 1e8 Pa/m, floor), 6000 steps into its collapse.
const model::Model& collapsing_arch() {
  static const model::Model m = [] {
    model::Model a;
    const double thickness = 0.15;
    for (const auto& b : geometry::semicircular_arch(40, 1.0, thickness, 0.5))
      a.add_block(b.shape, 2000, b.name, 0, b.support ? model::Motion::fixed : model::Motion::free);
    a.add_block(geometry::make_box(Vec3(-0.85, -1, -thickness), Vec3(0.85, 1, 0)), 2000, "floor", 0, model::Motion::fixed);
    a.gravity = Vec3(0.3 * 9.81, 0, -9.81);
    model::ContactSettings contacts;
    contacts.tolerance = 1e-4;
    const contact::MohrCoulomb::Parameters joint(1e8, 5e7, 0, 0, 40 * pi / 180);
    Simulation<damping::Local, contact::MohrCoulomb> sim(a, damping::Local{}, [&](int, int) { return joint; }, contacts);
    for (int i = 0; i < 6000; ++i) sim.step();
    return a;
  }();
  return m;
}

void detect(benchmark::State& state, const model::Model& m, model::ContactKinds kinds, double tolerance) {
  model::ContactSettings s;
  s.kinds = kinds;
  s.tolerance = tolerance;
  std::size_t points = 0;
  for (auto _ : state) {
    const auto c = model::detect_contacts(m.bodies, s);
    points = c.size();
    benchmark::DoNotOptimize(c.data());
  }
  state.counters["contact_points"] = static_cast<double>(points);
  state.counters["s_per_contact_point"] = benchmark::Counter(static_cast<double>(points) * static_cast<double>(state.iterations()),
                                                             benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void wall_faces(benchmark::State& s) { detect(s, wall(), model::ContactKinds::faces, 1e-3); }
void wall_general(benchmark::State& s) { detect(s, wall(), model::ContactKinds::general, 1e-3); }
void vault_faces(benchmark::State& s) { detect(s, vault(), model::ContactKinds::faces, 1e-3); }
void vault_general(benchmark::State& s) { detect(s, vault(), model::ContactKinds::general, 1e-3); }
void arch_faces(benchmark::State& s) { detect(s, collapsing_arch(), model::ContactKinds::faces, 1e-4); }
void arch_general(benchmark::State& s) { detect(s, collapsing_arch(), model::ContactKinds::general, 1e-4); }

}  // namespace

BENCHMARK(wall_faces)->Unit(benchmark::kMillisecond);
BENCHMARK(wall_general)->Unit(benchmark::kMillisecond);
BENCHMARK(vault_faces)->Unit(benchmark::kMillisecond);
BENCHMARK(vault_general)->Unit(benchmark::kMillisecond);
BENCHMARK(arch_faces)->Unit(benchmark::kMicrosecond);
BENCHMARK(arch_general)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
