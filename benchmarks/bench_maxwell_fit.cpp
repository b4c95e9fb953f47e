// Time of one Maxwell fit (paper Sect. 4.2.3): 3 branches, 500 points, analytic Jacobian, and its variations.
// The reference is MINPACK's LM driven from Python on the same problem: benchmarks/minpack_reference.py.

#include <benchmark/benchmark.h>

#include "blockdem/damping/maxwell_fit.hpp"

namespace {

using blockdem::damping::MaxwellFitOptions;

/// A problem that hides the analytic Jacobian, so the solver uses central differences.
template <int N>
struct CentralDifferences {
  static constexpr int num_parameters = 2 * N;
  blockdem::damping::detail::MaxwellFitProblem<N> problem;
  int num_residuals() const { return problem.num_residuals(); }
  auto prepare(const blockdem::solve::Vector<2 * N>& x) const { return problem.prepare(x); }
  double residual(const typename blockdem::damping::detail::MaxwellFitProblem<N>::State& s, int j) const {
    return problem.residual(s, j);
  }
};

void fit(benchmark::State& state) {
  MaxwellFitOptions options;
  options.damping_ratio = 0.04;
  options.branches = static_cast<int>(state.range(0));
  options.points = static_cast<int>(state.range(1));
  int iterations = 0;
  for (auto _ : state) {
    const auto result = blockdem::damping::fit_maxwell(options);
    benchmark::DoNotOptimize(result.sum_alpha);
    iterations = result.total_iterations;
  }
  state.counters["lm_iterations"] = iterations;
}
BENCHMARK(fit)->ArgNames({"branches", "points"})->Args({3, 500})->Args({1, 500})->Args({2, 500})->Args({4, 500})
    ->Args({5, 500})->Args({3, 100})->Args({3, 2000})->Unit(benchmark::kMicrosecond);

void fit_central_differences(benchmark::State& state) {
  MaxwellFitOptions options;
  options.damping_ratio = 0.04;
  const CentralDifferences<3> problem{blockdem::damping::detail::MaxwellFitProblem<3>(options)};
  const auto start = blockdem::damping::detail::initial_parameters<3>(options);
  for (auto _ : state) {
    auto x = start;
    const auto summary = blockdem::solve::levenberg_marquardt(problem, x, options.solver);
    benchmark::DoNotOptimize(summary.final_cost);
  }
}
BENCHMARK(fit_central_differences)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
