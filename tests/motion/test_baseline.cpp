// Baseline correction: a polynomial trend of the detrend's order is removed exactly and the signal orthogonal to it is
// left alone; the high-pass removes drift below its corner and keeps content above it; the specification grammar.

#include <doctest/doctest.h>

#include <cmath>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/baseline.hpp"
#include "blockdem/motion/integration.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_baseline {
using namespace blockdem::motion;

namespace {
Record sampled(double dt, std::size_t n, double (*a)(double)) {
  Record record;
  record.dt = dt;
  for (std::size_t i = 0; i < n; ++i) record.acceleration.push_back(a(record.time(i)));
  return record;
}
}  // namespace

TEST_CASE("baseline: a polynomial detrend removes a trend of its order exactly") {
  // Trend 0.3 - 0.02 t + 0.004 t^2 - 1e-4 t^3 on [0, 20] s plus a sine with an integer number of cycles.
  const auto trend = [](double t) { return 0.3 - 0.02 * t + 0.004 * t * t - 1e-4 * t * t * t; };
  const auto record = sampled(0.01, 2001, [](double t) {
    return 0.3 - 0.02 * t + 0.004 * t * t - 1e-4 * t * t * t + std::sin(2.0 * pi * 2.0 * t);
  });
  const auto pure = sampled(0.01, 2001, [](double t) { return std::sin(2.0 * pi * 2.0 * t); });
  const auto cubic = detrend_polynomial(record, 3);
  const auto cubic_of_sine = detrend_polynomial(pure, 3);
  for (std::size_t i = 0; i < record.size(); i += 97)  // same result as detrending the sine alone
    CHECK(cubic.acceleration[i] == doctest::Approx(cubic_of_sine.acceleration[i]).epsilon(1e-9).scale(1.0));
  // A pure trend is removed to rounding.
  Record only_trend = record;
  for (std::size_t i = 0; i < record.size(); ++i) only_trend.acceleration[i] = trend(record.time(i));
  CHECK(peak_absolute(detrend_polynomial(only_trend, 3).acceleration) < 1e-12);
  CHECK(peak_absolute(detrend_polynomial(only_trend, 2).acceleration) > 1e-3);  // a lower order cannot
}

TEST_CASE("baseline: mean removal leaves a zero-mean record") {
  const auto record = sampled(0.01, 777, [](double t) { return 0.25 + std::cos(3.0 * t); });
  const auto corrected = remove_mean(record);
  double sum = 0.0;
  for (double a : corrected.acceleration) sum += a;
  CHECK(std::abs(sum) / static_cast<double>(corrected.size()) < 1e-14);
  CHECK(corrected.acceleration[5] == doctest::Approx(record.acceleration[5] - (record.acceleration[5] - corrected.acceleration[5])));
}

TEST_CASE("baseline: the zero-phase high-pass keeps content well above its corner and removes an offset") {
  // 5 Hz content passes a 0.1 Hz order-4 high-pass with gain |H|^2 = 1 - 1e-11; in the middle of the record (away
  // from the padded ends) the filtered sine equals the sine.
  const auto sine = sampled(0.005, 8001, [](double t) { return 0.05 + std::sin(2.0 * pi * 5.0 * t); });
  const auto filtered = highpass(sine, 0.1, 4);
  double worst = 0.0;
  for (std::size_t i = 2000; i < 6000; ++i)
    worst = std::max(worst, std::abs(filtered.acceleration[i] - std::sin(2.0 * pi * 5.0 * sine.time(i))));
  CHECK(worst < 2e-3);

  // A 2 Hz burst on a sensor offset of 0.02 m/s^2: the offset drifts the displacement by 0.02 t^2 / 2 = 16 m over
  // 40 s; high-passed, the record moves like the burst alone and ends at rest.
  const auto clean = sampled(0.005, 8001, [](double t) {
    return std::exp(-std::pow((t - 15.0) / 4.0, 2)) * std::sin(2.0 * pi * 2.0 * t);
  });
  const auto offset = sampled(0.005, 8001, [](double t) {
    return 0.02 + std::exp(-std::pow((t - 15.0) / 4.0, 2)) * std::sin(2.0 * pi * 2.0 * t);
  });
  CHECK(peak_values(offset).pgd == doctest::Approx(16.0).epsilon(1e-6));
  const auto corrected = highpass(offset, 0.1, 4);
  const auto reference = peak_values(clean);
  const auto peaks = peak_values(corrected);
  CHECK(peaks.pgv == doctest::Approx(reference.pgv).epsilon(0.01));
  CHECK(peaks.pgd == doctest::Approx(reference.pgd).epsilon(0.02));
  const auto motion = integrate(corrected);
  CHECK(std::abs(motion.velocity.back()) < 1e-3 * reference.pgv);
  CHECK(std::abs(motion.displacement.back()) < 0.05 * reference.pgd);
}

TEST_CASE("baseline: specifications parse, chain and name their errors") {
  auto steps = parse_baseline("mean,poly:2,highpass:0.1");
  REQUIRE(steps.size() == 3);
  CHECK(steps[0].kind == BaselineStep::Kind::mean);
  CHECK(steps[1].kind == BaselineStep::Kind::polynomial);
  CHECK(steps[1].order == 2);
  CHECK(steps[2].kind == BaselineStep::Kind::highpass);
  CHECK(steps[2].corner_hz == 0.1);
  CHECK(steps[2].order == 4);
  CHECK(to_string(steps) == "mean,poly:2,highpass:0.1:4");
  CHECK(parse_baseline("none").empty());
  CHECK(parse_baseline("highpass:0.05:2")[0].order == 2);
  CHECK_THROWS_WITH_AS(parse_baseline("poly:11"), doctest::Contains("'poly:11' needs an order in 0..10"), InvalidArgument);
  CHECK_THROWS_WITH_AS(parse_baseline("highpass:-1"), doctest::Contains("corner frequency > 0 Hz"), InvalidArgument);
  CHECK_THROWS_WITH_AS(parse_baseline("highpass:0.1:9"), doctest::Contains("filter order in 1..8"), InvalidArgument);
  CHECK_THROWS_WITH_AS(parse_baseline("smooth"), doctest::Contains("'smooth' is not a baseline step (allowed: none, mean"),
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(parse_baseline("poly:x"), doctest::Contains("'poly:x' has a bad number"), InvalidArgument);
  CHECK_THROWS_WITH_AS(parse_baseline("mean,"), doctest::Contains("'mean,' ends with a comma, an empty step"), InvalidArgument);
  CHECK_THROWS_WITH_AS(parse_baseline("mean,,poly:1"), doctest::Contains("'' is not a baseline step"), InvalidArgument);

  const auto record = sampled(0.01, 1000, [](double t) { return 1.0 + t; });
  const auto corrected = correct_baseline(record, parse_baseline("poly:1"));
  CHECK(peak_absolute(corrected.acceleration) < 1e-12);
  CHECK_THROWS_WITH_AS(correct_baseline(record, parse_baseline("highpass:60")), doctest::Contains("Nyquist"),
                       InvalidArgument);
}

}  // namespace test_baseline
