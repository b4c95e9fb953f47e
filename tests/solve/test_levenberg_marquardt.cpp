// The Levenberg-Marquardt solver on problems with certified minima: Rosenbrock (minimum (1, 1)) and four NIST StRD
// nonlinear regressions. Every start is far from the minimum, so a solver that does nothing fails.

#include <doctest/doctest.h>

#include "../approx.hpp"

#include <cmath>
#include <limits>

#include "blockdem/solve/levenberg_marquardt.hpp"
#include "nist_problems.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_levenberg_marquardt {

namespace {

using solve::Vector;

/// r = (10 (x2 - x1^2), 1 - x1): Rosenbrock's function as least squares, minimum 0 at (1, 1).
struct Rosenbrock {
  static constexpr int num_parameters = 2;
  constexpr int num_residuals() const { return 2; }
  constexpr Vector<2> prepare(const Vector<2>& x) const { return x; }
  constexpr double residual(const Vector<2>& x, int i) const { return i == 0 ? 10.0 * (x[1] - x[0] * x[0]) : 1.0 - x[0]; }
  constexpr double residual(const Vector<2>& x, int i, Vector<2>& g) const {
    if (i == 0) {
      g = {-20.0 * x[0], 10.0};
    } else {
      g = {-1.0, 0.0};
    }
    return residual(x, i);
  }
};

/// The same problem without the analytic Jacobian: the solver falls back to central differences.
struct RosenbrockNumeric {
  static constexpr int num_parameters = 2;
  constexpr int num_residuals() const { return 2; }
  constexpr Vector<2> prepare(const Vector<2>& x) const { return x; }
  constexpr double residual(const Vector<2>& x, int i) const { return Rosenbrock{}.residual(x, i); }
};

template <int N, std::size_t M, class Model, bool Analytic>
void check_nist(const test::NistData<N, M>& data, const Vector<N>& start) {
  CAPTURE(data.name);
  CAPTURE(Analytic);
  const test::NistProblem<N, M, Model, Analytic> problem{&data, Model{}};
  Vector<N> b = start;
  solve::Options options;  // NIST certifies 11 digits: ask for a small gradient, not the defaults
  options.max_iterations = 1000;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-15;
  const auto summary = solve::levenberg_marquardt(problem, b, options);
  CAPTURE(solve::to_string(summary.status));
  CHECK(summary.converged());
  // NIST asks for agreement to about 6 significant digits with the certified values.
  for (int k = 0; k < N; ++k) {
    CAPTURE(k);
    CHECK(b[k] == test::approx(data.certified[k]).epsilon(1e-6));
  }
  CHECK(2.0 * summary.final_cost == test::approx(data.certified_residual_sum_of_squares).epsilon(1e-8));
}

}  // namespace

TEST_CASE("levenberg_marquardt: Rosenbrock from (-1.2, 1) reaches (1, 1), analytic and central-difference Jacobian") {
  Vector<2> x{-1.2, 1.0};
  const auto summary = solve::levenberg_marquardt(Rosenbrock{}, x);
  CHECK(summary.converged());
  CHECK(x[0] == test::approx(1.0).epsilon(1e-8));
  CHECK(x[1] == test::approx(1.0).epsilon(1e-8));
  CHECK(summary.final_cost < 1e-16);
  CHECK(summary.initial_cost == test::approx(0.5 * (4.4 * 4.4 + 2.2 * 2.2)));

  Vector<2> y{-1.2, 1.0};
  const auto numeric = solve::levenberg_marquardt(RosenbrockNumeric{}, y);
  CHECK(numeric.converged());
  CHECK(y[0] == test::approx(1.0).epsilon(1e-8));
  CHECK(y[1] == test::approx(1.0).epsilon(1e-8));
  CHECK(numeric.residual_evaluations > 0);
}

TEST_CASE("levenberg_marquardt: NIST StRD Misra1a, Roszman1, MGH09, Thurber reach the certified values") {
  using test::NistData;
  check_nist<2, 14, test::Misra1aModel, true>(test::misra1a, test::misra1a.start_1);
  check_nist<2, 14, test::Misra1aModel, false>(test::misra1a, test::misra1a.start_1);
  check_nist<4, 25, test::Roszman1Model, true>(test::roszman1, test::roszman1.start_1);
  check_nist<4, 25, test::Roszman1Model, false>(test::roszman1, test::roszman1.start_1);
  check_nist<4, 11, test::Mgh09Model, true>(test::mgh09, test::mgh09.start_2);
  check_nist<7, 37, test::ThurberModel, true>(test::thurber, test::thurber.start_1);
  check_nist<7, 37, test::ThurberModel, true>(test::thurber, test::thurber.start_2);
  check_nist<7, 37, test::ThurberModel, false>(test::thurber, test::thurber.start_1);
}

TEST_CASE("levenberg_marquardt: each stopping rule reports its status") {
  SUBCASE("max iterations") {
    Vector<2> x{-1.2, 1.0};
    solve::Options options;
    options.max_iterations = 4;
    const auto summary = solve::levenberg_marquardt(Rosenbrock{}, x, options);
    CHECK(summary.status == solve::Status::max_iterations_reached);
    CHECK_FALSE(summary.converged());
    CHECK(summary.iterations == 4);
    CHECK(summary.final_cost < summary.initial_cost);
  }
  SUBCASE("cost threshold") {
    Vector<2> x{-1.2, 1.0};
    solve::Options options;
    options.cost_threshold = 1e-6;
    const auto summary = solve::levenberg_marquardt(Rosenbrock{}, x, options);
    CHECK(summary.status == solve::Status::cost_too_small);
    CHECK(summary.final_cost <= 1e-6);
  }
  SUBCASE("gradient at the start") {
    Vector<2> x{1.0, 1.0};
    const auto summary = solve::levenberg_marquardt(Rosenbrock{}, x);
    CHECK(summary.status == solve::Status::gradient_too_small);
    CHECK(summary.iterations == 0);
  }
  SUBCASE("non-finite start") {
    Vector<2> x{std::numeric_limits<double>::quiet_NaN(), 1.0};
    const auto summary = solve::levenberg_marquardt(Rosenbrock{}, x);
    CHECK(summary.status == solve::Status::non_finite_start);
    CHECK_FALSE(summary.converged());
  }
}

}  // namespace test_levenberg_marquardt
