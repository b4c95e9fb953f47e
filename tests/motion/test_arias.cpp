// Arias intensity and significant durations against closed forms and an independent trapezoid computation written
// here from the definition I_A = pi / (2 g) int a^2 dt (DESIGN §7).

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/arias.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_arias {
using namespace blockdem::motion;

namespace {
Record sampled(double dt, double duration, double (*a)(double)) {
  Record record;
  record.dt = dt;
  const auto n = static_cast<std::size_t>(std::llround(duration / dt)) + 1;
  for (std::size_t i = 0; i < n; ++i) record.acceleration.push_back(a(record.time(i)));
  return record;
}

/// Independent reference: cumulative trapezoid of a^2 in long double, then the time at which a fraction is first
/// reached by bisection on the piecewise-linear cumulative curve.
struct Reference {
  std::vector<long double> cumulative;
  double dt;
  explicit Reference(const Record& r) : cumulative(r.size(), 0.0L), dt(r.dt) {
    for (std::size_t i = 1; i < r.size(); ++i) {
      const long double a0 = r.acceleration[i - 1], a1 = r.acceleration[i];
      cumulative[i] = cumulative[i - 1] + 0.5L * dt * (a0 * a0 + a1 * a1);
    }
  }
  double total() const { return static_cast<double>(cumulative.back() * pi / (2.0L * standard_gravity)); }
  double time_at(double fraction) const {
    const long double target = fraction * cumulative.back();
    double lo = 0.0, hi = dt * static_cast<double>(cumulative.size() - 1);
    for (int k = 0; k < 200; ++k) {
      const double mid = 0.5 * (lo + hi);
      const auto i = std::min(static_cast<std::size_t>(mid / dt), cumulative.size() - 2);
      const long double s = mid / dt - static_cast<double>(i);
      ((1 - s) * cumulative[i] + s * cumulative[i + 1] < target ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }
};
}  // namespace

TEST_CASE("arias: a sine burst against the closed form and the independent trapezoid") {
  // a = A sin(w t) on [0, T]: I_A = pi / (2 g) A^2 (T / 2 - sin(2 w T) / (4 w)).
  const auto record = sampled(0.005, 10.0, [](double t) { return 3.0 * std::sin(2.0 * pi * 1.3 * t); });
  const double w = 2.0 * pi * 1.3, T = 10.0;
  const double exact = pi / (2.0 * standard_gravity) * 9.0 * (T / 2.0 - std::sin(2.0 * w * T) / (4.0 * w));
  const Reference reference(record);
  CHECK(arias_intensity(record) == doctest::Approx(reference.total()).epsilon(1e-12));
  CHECK(arias_intensity(record) == doctest::Approx(exact).epsilon(1e-4));
  const auto history = arias_intensity_history(record);
  CHECK(history.front() == 0.0);
  for (std::size_t i = 1; i < history.size(); ++i) CHECK(history[i] >= history[i - 1]);
}

TEST_CASE("arias: significant durations of a constant and of a ramp against closed forms and the reference") {
  // Constant a: I(t) grows linearly, so t_p = p T and D5-95 = 0.9 T, D10-90 = 0.8 T.
  const auto flat = sampled(0.01, 20.0, [](double) { return 2.0; });
  auto d = significant_duration(flat, 0.05, 0.95);
  CHECK(d.start == doctest::Approx(1.0).epsilon(1e-9));
  CHECK(d.end == doctest::Approx(19.0).epsilon(1e-9));
  CHECK(d.duration == doctest::Approx(18.0).epsilon(1e-9));
  CHECK(significant_duration(flat, 0.10, 0.90).duration == doctest::Approx(16.0).epsilon(1e-9));

  // Ramp a = t: I(t) ~ t^3, so t_p = T p^(1/3) (to the trapezoid's O(dt^2)); the reference matches exactly.
  const auto ramp = sampled(0.001, 10.0, [](double t) { return t; });
  const Reference reference(ramp);
  for (auto [lo, hi] : {std::pair{0.05, 0.95}, std::pair{0.10, 0.90}}) {
    d = significant_duration(ramp, lo, hi);
    CHECK(d.start == doctest::Approx(10.0 * std::cbrt(lo)).epsilon(1e-5));
    CHECK(d.end == doctest::Approx(10.0 * std::cbrt(hi)).epsilon(1e-5));
    CHECK(d.start == doctest::Approx(reference.time_at(lo)).epsilon(1e-9));
    CHECK(d.end == doctest::Approx(reference.time_at(hi)).epsilon(1e-9));
  }
}

TEST_CASE("arias: a decaying random-looking signal against the independent trapezoid") {
  const auto record = sampled(0.01, 30.0, [](double t) {
    return std::exp(-0.15 * t) * (std::sin(7.1 * t) + 0.6 * std::cos(19.3 * t + 0.4) + 0.3 * std::sin(31.7 * t * t / 30.0));
  });
  const Reference reference(record);
  CHECK(arias_intensity(record) == doctest::Approx(reference.total()).epsilon(1e-12));
  for (auto [lo, hi] : {std::pair{0.05, 0.95}, std::pair{0.10, 0.90}}) {
    const auto d = significant_duration(record, lo, hi);
    CHECK(d.start == doctest::Approx(reference.time_at(lo)).epsilon(1e-9));
    CHECK(d.end == doctest::Approx(reference.time_at(hi)).epsilon(1e-9));
  }
}

TEST_CASE("arias: bad fractions and silent records are named") {
  const auto flat = sampled(0.01, 1.0, [](double) { return 1.0; });
  CHECK_THROWS_WITH_AS(significant_duration(flat, 0.9, 0.1), doctest::Contains("0 <= lower < upper <= 1"),
                       InvalidArgument);
  auto silent = sampled(0.01, 1.0, [](double) { return 0.0; });
  silent.name = "silent.txt";
  CHECK_THROWS_WITH_AS(significant_duration(silent), doctest::Contains("silent.txt: the record has zero Arias"),
                       InvalidArgument);
}

}  // namespace test_arias
