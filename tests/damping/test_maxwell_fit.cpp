// The Maxwell branch fit (paper Sect. 4.2.3) against the paper's Fig. 10b, an independent MINPACK fit, and the
// properties it must have: the literal eq. 23 map does worse, more branches flatten the curve, bad input is named.

#include <doctest/doctest.h>

#include "../approx.hpp"

#include <cmath>
#include <string>

#include "blockdem/core/units.hpp"
#include "blockdem/damping/maxwell_fit.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_maxwell_fit {
using damping::MaxwellFitOptions;
using damping::OrderingMap;

namespace {
MaxwellFitOptions paper_fig10(double margin = 2.0) {
  MaxwellFitOptions options;
  options.damping_ratio = 0.04;
  options.lower_hz = 1.0;
  options.upper_hz = 40.0;
  options.branches = 3;
  options.points = 500;
  options.centre_margin = margin;
  return options;
}
}  // namespace

TEST_CASE("maxwell fit: 4 % over 1-40 Hz with 3 branches gives |M_T| max = 1 + sum alpha = 1.39 (paper Fig. 10b)") {
  for (double margin : {1.0, 2.0}) {  // 1 is eq. 25 as printed
    CAPTURE(margin);
    const auto fit = damping::fit_maxwell(paper_fig10(margin));
    CHECK(fit.converged);
    CHECK(fit.branches == 3);
    CHECK(1.0 + fit.sum_alpha == test::approx(1.39).epsilon(0.01 / 1.39));
    CHECK(fit.modulus_max == test::approx(1.0 + fit.sum_alpha).epsilon(1e-9));
    CHECK(fit.rel_error_min >= -0.025);
    CHECK(fit.rel_error_max <= 0.012);
    CHECK(fit.rel_error_min < -0.02);  // a 3-branch fit cannot be much flatter than this
    CHECK(fit.dt_factor == test::approx(1.0 / std::sqrt(1.0 + fit.sum_alpha)));
    CHECK(fit.iterations <= 30);
    for (int i = 0; i < 3; ++i) {  // eq. 25: ordered peaks inside the (widened) band
      CHECK(fit.peak_hz(i) >= 1.0 / margin - 1e-9);
      CHECK(fit.peak_hz(i) <= 40.0 * margin + 1e-9);
      if (i > 0) CHECK(fit.peak_hz(i) > fit.peak_hz(i - 1));
    }
  }
}

TEST_CASE("maxwell fit: agrees with an independent MINPACK fit of the unconstrained problem") {
  // scipy.optimize.least_squares(method='lm') (MINPACK lmder) on log(tau), log(alpha), best of 20 starts,
  // 4 % over 1-40 Hz, 500 points: 1 + sum alpha = 1.3947, error -2.256 % / +1.048 %,
  // peaks 0.994, 6.291, 39.717 Hz, alpha 0.1290, 0.1006, 0.1652.
  const auto fit = damping::fit_maxwell(paper_fig10());
  CHECK(1.0 + fit.sum_alpha == test::approx(1.3947).epsilon(2e-4));
  CHECK(fit.rel_error_min == test::approx(-0.02256).epsilon(2e-3));
  CHECK(fit.rel_error_max == test::approx(0.01048).epsilon(5e-3));
  const double peaks[] = {0.994, 6.291, 39.717};
  const double alphas[] = {0.1290, 0.1006, 0.1652};
  for (int i = 0; i < 3; ++i) {
    CHECK(fit.peak_hz(i) == test::approx(peaks[i]).epsilon(2e-3));
    CHECK(fit.branch[i].alpha == test::approx(alphas[i]).epsilon(2e-3));
  }
}

TEST_CASE("maxwell fit: the relative error does not depend on zeta* (the paper's 3 % setting)") {
  auto options = paper_fig10();
  const auto four = damping::fit_maxwell(options);
  options.damping_ratio = 0.03;
  const auto three = damping::fit_maxwell(options);
  CHECK(three.converged);
  CHECK(three.rel_error_min == test::approx(four.rel_error_min).epsilon(1e-3));
  CHECK(three.rel_error_max == test::approx(four.rel_error_max).epsilon(1e-3));
  CHECK(three.sum_alpha < four.sum_alpha);
}

TEST_CASE("maxwell fit: the literal eq. 23-24 map does measurably worse from the log-uniform start") {
  for (double margin : {1.0, 2.0}) {
    CAPTURE(margin);
    auto options = paper_fig10(margin);
    const auto cumulative = damping::fit_maxwell(options);
    options.ordering = OrderingMap::literal_eq23;
    const auto literal = damping::fit_maxwell(options);
    CHECK(literal.max_rel_error > 3.0 * cumulative.max_rel_error);
    CHECK(literal.cost > 10.0 * cumulative.cost);
  }
}

TEST_CASE("maxwell fit: more branches flatten the curve, the smallest N meeting a tolerance is chosen") {
  auto options = paper_fig10();
  options.branches = 4;
  const auto four = damping::fit_maxwell(options);
  CHECK(four.converged);
  CHECK(four.max_rel_error < 0.004);  // DESIGN.md §5: about +/-0.4 %
  options.branches = 5;
  const auto five = damping::fit_maxwell(options);
  CHECK(five.max_rel_error < 0.001);

  const auto chosen = damping::fit_maxwell_to_tolerance(paper_fig10(), 0.01);
  CHECK(chosen.branches == 4);
  CHECK(chosen.max_rel_error <= 0.01);
  const auto finer = damping::fit_maxwell_to_tolerance(paper_fig10(), 0.001);
  CHECK(finer.branches == 5);
}

TEST_CASE("maxwell fit: the analytic Jacobian matches central differences, for both ordering maps") {
  for (auto map : {OrderingMap::cumulative, OrderingMap::literal_eq23}) {
    auto options = paper_fig10();
    options.ordering = map;
    options.points = 40;
    const damping::detail::MaxwellFitProblem<3> problem(options);
    const solve::Vector<6> x{0.3, -0.7, 1.1, -2.0, -2.4, -1.7};
    const auto state = problem.prepare(x);
    for (int j = 0; j < problem.num_residuals(); j += 7) {
      solve::Vector<6> gradient{};
      problem.residual(state, j, gradient);
      for (int k = 0; k < 6; ++k) {
        const double h = 1e-6;
        auto xp = x;
        auto xm = x;
        xp[k] += h;
        xm[k] -= h;
        const double numeric = (problem.residual(problem.prepare(xp), j) - problem.residual(problem.prepare(xm), j)) / (2 * h);
        CAPTURE(j);
        CAPTURE(k);
        CHECK(gradient[k] == test::approx(numeric).epsilon(1e-6).scale(1e-3));
      }
    }
  }
}

TEST_CASE("maxwell fit: deterministic, and branches given as 3DEC peak pairs evaluate to the same statistics") {
  const auto a = damping::fit_maxwell(paper_fig10());
  const auto b = damping::fit_maxwell(paper_fig10());
  for (int i = 0; i < 3; ++i) {
    CHECK(a.branch[i].alpha == b.branch[i].alpha);
    CHECK(a.branch[i].tau == b.branch[i].tau);
  }
  std::array<damping::MaxwellBranch, 3> from_3dec{};
  for (int i = 0; i < 3; ++i)
    from_3dec[i] = damping::MaxwellBranch::from_peak(a.peak_damping_ratio(i), angular_frequency(a.peak_hz(i)));
  const auto again = damping::evaluate_branches(from_3dec, 0.04, 1.0, 40.0);
  CHECK(again.sum_alpha == test::approx(a.sum_alpha).epsilon(1e-12));
  CHECK(again.rel_error_min == test::approx(a.rel_error_min).epsilon(1e-9));
  CHECK(again.rel_error_max == test::approx(a.rel_error_max).epsilon(1e-9));
}

TEST_CASE("maxwell fit: bad options name the field and its range") {
  auto expect_error = [](MaxwellFitOptions options, const std::string& field) {
    CAPTURE(field);
    try {
      damping::fit_maxwell(options);
      FAIL("no exception");
    } catch (const InvalidArgument& e) {
      CHECK(std::string(e.what()).find(field) != std::string::npos);
    }
  };
  struct Case {
    void (*spoil)(MaxwellFitOptions&);
    const char* field;
  };
  const Case cases[] = {
      {[](MaxwellFitOptions& o) { o.damping_ratio = 0.0; }, "zeta"},
      {[](MaxwellFitOptions& o) { o.damping_ratio = 0.5; }, "(0, 0.5)"},
      {[](MaxwellFitOptions& o) { o.lower_hz = 0.0; }, "f_lb"},
      {[](MaxwellFitOptions& o) { o.upper_hz = 1.0; }, "f_lb < f_ub"},
      {[](MaxwellFitOptions& o) { o.branches = 9; }, "1..8"},
      {[](MaxwellFitOptions& o) { o.branches = 0; }, "branches"},
      {[](MaxwellFitOptions& o) { o.points = 5; }, "points"},
      {[](MaxwellFitOptions& o) { o.centre_margin = 0.5; }, "centre margin"},
  };
  for (const auto& c : cases) {
    auto o = paper_fig10();
    c.spoil(o);
    expect_error(o, c.field);
  }
  CHECK_THROWS_AS(damping::fit_maxwell_to_tolerance(paper_fig10(), 0.0), InvalidArgument);
}

}  // namespace test_maxwell_fit
