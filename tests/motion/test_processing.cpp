// Scaling and resampling: exact for what linear interpolation represents exactly, the low-frequency content kept and
// the content above the new Nyquist frequency removed when downsampling.

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/processing.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_processing {
using namespace blockdem::motion;

namespace {
Record sampled(double dt, double duration, double (*a)(double)) {
  Record record;
  record.name = "test";
  record.dt = dt;
  const auto n = static_cast<std::size_t>(std::llround(duration / dt)) + 1;
  for (std::size_t i = 0; i < n; ++i) record.acceleration.push_back(a(record.time(i)));
  return record;
}
}  // namespace

TEST_CASE("processing: scaling by a factor and to a target PGA") {
  const auto record = sampled(0.01, 5.0, [](double t) { return std::sin(3.0 * t) - 0.4; });
  const auto scaled = scale(record, 0.75);  // the paper's AQA75 is the record at 75 %
  CHECK(scaled.acceleration[123] == doctest::Approx(0.75 * record.acceleration[123]));
  const auto target = scale_to_pga(record, 4.25);
  CHECK(peak_absolute(target.acceleration) == doctest::Approx(4.25).epsilon(1e-14));
  CHECK_THROWS_WITH_AS(scale_to_pga(record, -1.0), doctest::Contains("target PGA -1.000000 m/s^2 must be > 0"),
                       InvalidArgument);
  Record silent = record;
  silent.acceleration.assign(record.size(), 0.0);
  CHECK_THROWS_AS(scale_to_pga(silent, 1.0), InvalidArgument);
}

TEST_CASE("processing: upsampling a piecewise-linear record is exact and keeps the time span") {
  const auto record = sampled(0.02, 4.0, [](double t) { return 1.5 - 0.5 * t; });
  const auto fine = resample(record, 0.005);
  CHECK(fine.size() == 801);
  CHECK(fine.duration() == doctest::Approx(4.0));
  for (std::size_t i = 0; i < fine.size(); i += 37) CHECK(fine.acceleration[i] == doctest::Approx(1.5 - 0.5 * fine.time(i)));
}

TEST_CASE("processing: downsampling keeps content below the new Nyquist frequency and removes content above it") {
  // 1 Hz (kept) plus 40 Hz (above the new 25 Hz Nyquist frequency; would alias to 10 Hz) sampled at 200 Hz, to 50 Hz.
  const auto record = sampled(0.005, 20.0, [](double t) {
    return std::sin(2.0 * pi * 1.0 * t) + 0.5 * std::sin(2.0 * pi * 40.0 * t);
  });
  const auto coarse = resample(record, 0.02);
  CHECK(coarse.size() == 1001);
  double worst = 0.0;
  for (std::size_t i = 100; i < 900; ++i)
    worst = std::max(worst, std::abs(coarse.acceleration[i] - std::sin(2.0 * pi * coarse.time(i))));
  CHECK(worst < 0.01);  // without the anti-alias filter the 40 Hz term would leave errors of up to 0.5
  CHECK_THROWS_AS(resample(record, 0.0), InvalidArgument);
  CHECK_THROWS_WITH_AS(resample(record, 15.0), doctest::Contains("fewer than 3 samples"), InvalidArgument);
}

TEST_CASE("processing: samples at given times become a record, even ones as they were, uneven ones on a finer grid") {
  // Even, with the rounding of decimal times (0.07 - 0.06 = 0.010000000000000009): the same samples.
  std::vector<double> times, values;
  for (int i = 0; i <= 50; ++i) {
    times.push_back(0.5 + 0.01 * i);
    values.push_back(std::sin(0.3 * i));
  }
  const auto even = record_from_samples(times, values, "even.txt");
  CHECK(even.size() == 51);
  CHECK(even.dt == doctest::Approx(0.01).epsilon(1e-12));
  CHECK(even.start_time == 0.5);
  for (std::size_t i = 0; i < values.size(); ++i)
    CHECK(even.acceleration[i] == doctest::Approx(values[i]).epsilon(1e-12));
  // Uneven: steps 0.02 then 0.01; the polyline through (0, 0), (0.02, 2), (0.03, 1) at dt = 0.01.
  const auto uneven = record_from_samples({0.0, 0.02, 0.03}, {0.0, 2.0, 1.0}, "uneven.txt");
  REQUIRE(uneven.size() == 4);
  CHECK(uneven.dt == doctest::Approx(0.01));
  CHECK(uneven.acceleration[1] == doctest::Approx(1.0));
  CHECK(uneven.acceleration[2] == doctest::Approx(2.0));
  CHECK(uneven.acceleration[3] == 1.0);
  CHECK_THROWS_WITH_AS(record_from_samples({0.0, 0.0}, {1.0, 2.0}, "f.txt"),
                       doctest::Contains("f.txt: time 0.000000 s of sample 1 does not increase"), InvalidArgument);
  CHECK_THROWS_WITH_AS(record_from_samples({0.0}, {1.0}, "f.txt"), doctest::Contains("at least 2"), InvalidArgument);
  CHECK_THROWS_WITH_AS(record_from_samples({0.0, 1e-12, 1.0}, {1.0, 1.0, 1.0}, "f.txt"), doctest::Contains("more than 1e8"),
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(record_from_samples({0.0, 1.0}, {1.0}, "f.txt"), doctest::Contains("2 times for 1 accelerations"),
                       InvalidArgument);
}

}  // namespace test_processing
