// Scaling and resampling: exact for what linear interpolation represents exactly, the low-frequency content kept and
// the content above the new Nyquist frequency removed when downsampling.

#include <doctest/doctest.h>

#include <cmath>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/processing.hpp"

using namespace blockdem;
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
