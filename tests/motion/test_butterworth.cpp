// Butterworth filters against the analytic magnitude of the bilinear-transformed Butterworth response and against
// scipy.signal.sosfiltfilt on a fixed signal; the forward-backward form has zero phase.

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/butterworth.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_butterworth {
using namespace blockdem::motion;

namespace {
/// |H(f)| of the digital Butterworth filter: the analog response 1 / sqrt(1 + (w / wc)^(2N)) with w = tan(pi f dt)
/// (bilinear transform, corner prewarped).
double analytic_gain(FilterType type, int order, double fc, double f, double dt) {
  const double ratio = std::tan(pi * f * dt) / std::tan(pi * fc * dt);
  const double x = type == FilterType::lowpass ? ratio : 1.0 / ratio;
  return 1.0 / std::sqrt(1.0 + std::pow(x, 2.0 * order));
}
}  // namespace

TEST_CASE("butterworth: the gain of every order equals the bilinear Butterworth magnitude") {
  const double dt = 0.005;
  for (auto type : {FilterType::lowpass, FilterType::highpass})
    for (int order = 1; order <= 8; ++order)
      for (double fc : {0.1, 2.0, 30.0}) {
        const ButterworthFilter filter(type, order, fc, dt);
        CHECK(filter.sections().size() == static_cast<std::size_t>((order + 1) / 2));
        for (double f : {0.01, 0.05, 0.3, 1.0, 2.0, 5.0, 20.0, 60.0, 99.0}) {
          CAPTURE(order);
          CAPTURE(fc);
          CAPTURE(f);
          CHECK(filter.gain(f) == doctest::Approx(analytic_gain(type, order, fc, f, dt)).epsilon(1e-9));
        }
        CHECK(filter.gain(fc) == doctest::Approx(std::sqrt(0.5)).epsilon(1e-9));  // -3 dB at the corner
      }
}

TEST_CASE("butterworth: zero-phase filtering agrees with scipy.signal.sosfiltfilt") {
  // Reference: scipy 1.10.1, sosfiltfilt(butter(order, fc, kind, fs=100, output='sos'), x) with default padding,
  // x_i = sin(0.05 i) + 0.5 sin(0.9 i) + 0.001 i, i = 0..199; values at i = 0, 50, 100, 199.
  std::vector<double> x(200);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double s = static_cast<double>(i);
    x[i] = std::sin(0.05 * s) + 0.5 * std::sin(0.9 * s) + 0.001 * s;
  }
  struct Case {
    FilterType type;
    int order;
    double fc;
    double expected[4];
  };
  const Case cases[] = {
      {FilterType::highpass, 4, 5.0, {-0.0035243377064522463, 0.4254304396260996, 0.44693785908736217, 0.06902020436775524}},
      {FilterType::lowpass, 3, 10.0, {0.002422259716025256, 0.6845348630017459, -0.8210348654950217, -0.31871189152934903}},
      {FilterType::highpass, 1, 2.0, {-0.1681264058142274, 0.49968688164889574, 0.30872961246582314, -0.1786623287973047}}};
  for (const auto& c : cases) {
    CAPTURE(c.order);
    const auto y = ButterworthFilter(c.type, c.order, c.fc, 0.01).filtfilt(x);
    REQUIRE(y.size() == x.size());
    const std::size_t at[] = {0, 50, 100, 199};
    for (int k = 0; k < 4; ++k) CHECK(y[at[k]] == doctest::Approx(c.expected[k]).epsilon(1e-10));
  }
}

TEST_CASE("butterworth: forward-backward filtering scales a sine by |H|^2 without shifting it") {
  const double dt = 0.01;
  const double f = 3.0;
  const ButterworthFilter filter(FilterType::highpass, 4, 2.0, dt);
  std::vector<double> x(4000);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = std::sin(two_pi * f * dt * static_cast<double>(i));
  const auto y = filter.filtfilt(x);
  const double g2 = filter.gain(f) * filter.gain(f);
  double worst = 0.0;
  for (std::size_t i = 1000; i < 3000; ++i) worst = std::max(worst, std::abs(y[i] - g2 * x[i]));
  CHECK(worst < 1e-6);  // transients from the ends have died out in the middle
  // The causal pass alone lags: it does not reproduce the sine in phase.
  const auto causal = filter.apply(x);
  double causal_error = 0.0;
  for (std::size_t i = 1000; i < 3000; ++i) causal_error = std::max(causal_error, std::abs(causal[i] - filter.gain(f) * x[i]));
  CHECK(causal_error > 0.1);
}

TEST_CASE("butterworth: bad designs are rejected with the allowed range") {
  CHECK_THROWS_WITH_AS(ButterworthFilter(FilterType::highpass, 9, 1.0, 0.01), "butterworth filter: order 9 is outside 1..8",
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(ButterworthFilter(FilterType::highpass, 4, 60.0, 0.01),
                       doctest::Contains("must be in (0, 50.000000) Hz"), InvalidArgument);
  CHECK_THROWS_AS(ButterworthFilter(FilterType::lowpass, 4, 0.0, 0.01), InvalidArgument);
  const ButterworthFilter filter(FilterType::highpass, 4, 1.0, 0.01);
  CHECK_THROWS_WITH_AS(filter.filtfilt(std::vector<double>(15, 1.0)), doctest::Contains("padding of 15 samples needs more than 15 samples, got 15"),
                       InvalidArgument);
}

}  // namespace test_butterworth
