// Complete Levenberg-Marquardt solves evaluated by the compiler: Rosenbrock and a Maxwell fit in static_asserts.

#include <doctest/doctest.h>

#include "../approx.hpp"

#include <utility>

#include "blockdem/damping/maxwell_fit.hpp"
#include "blockdem/solve/levenberg_marquardt.hpp"

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_constexpr_fit {

namespace {
using blockdem::cmath::abs;
using blockdem::solve::Vector;

struct Rosenbrock {
  static constexpr int num_parameters = 2;
  constexpr int num_residuals() const { return 2; }
  constexpr Vector<2> prepare(const Vector<2>& x) const { return x; }
  constexpr double residual(const Vector<2>& x, int i) const { return i == 0 ? 10.0 * (x[1] - x[0] * x[0]) : 1.0 - x[0]; }
};

constexpr auto rosenbrock = [] {
  Vector<2> x{-1.2, 1.0};
  const auto summary = blockdem::solve::levenberg_marquardt(Rosenbrock{}, x);  // central differences
  return std::pair{x, summary};
}();
static_assert(rosenbrock.second.converged());
static_assert(abs(rosenbrock.first[0] - 1.0) < 1e-8 && abs(rosenbrock.first[1] - 1.0) < 1e-8);

// Clang before 15 with libstdc++ refuses the fit's std::vector in a constant expression (it does not take the fill
// of a new double[n] as starting the elements' lifetime); GCC, the project's compiler, and later Clang accept it.
#if defined(__clang__) && __clang_major__ < 15
#define BLOCKDEM_CONSTEXPR_FIT const
#else
#define BLOCKDEM_CONSTEXPR_FIT constexpr
#define BLOCKDEM_HAS_CONSTEXPR_FIT 1
#endif
constexpr blockdem::damping::MaxwellFitOptions constexpr_options = [] {
  blockdem::damping::MaxwellFitOptions o;
  o.damping_ratio = 0.04;
  o.points = 100;  // fewer points than the paper's 500 keep the compile time short; the optimum barely moves
  return o;
}();
BLOCKDEM_CONSTEXPR_FIT auto constexpr_fit = blockdem::damping::fit_maxwell(constexpr_options);
#ifdef BLOCKDEM_HAS_CONSTEXPR_FIT
static_assert(constexpr_fit.converged);
static_assert(abs(1.0 + constexpr_fit.sum_alpha - 1.39) < 0.01);  // paper Fig. 10b
static_assert(constexpr_fit.rel_error_min > -0.025 && constexpr_fit.rel_error_max < 0.012);
#endif
}  // namespace

TEST_CASE("static: the compile-time Maxwell fit equals the run-time one") {
  const auto runtime_fit = blockdem::damping::fit_maxwell(constexpr_options);
  for (int i = 0; i < 3; ++i) {
    CHECK(constexpr_fit.branch[i].alpha == blockdem::test::approx(runtime_fit.branch[i].alpha).epsilon(1e-9));
    CHECK(constexpr_fit.branch[i].tau == blockdem::test::approx(runtime_fit.branch[i].tau).epsilon(1e-9));
  }
  CHECK(constexpr_fit.iterations == runtime_fit.iterations);
}

}  // namespace test_constexpr_fit
