// Response spectra by the Nigam-Jennings recursion against Boost.Odeint integration of the same oscillator (the real
// PEER records, within 0.5 %), against the closed-form response to a ramp, and against the limits of a rigid and a
// resonant oscillator.

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/integration.hpp"
#include "blockdem/motion/readers.hpp"
#include "blockdem/motion/spectrum.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_spectrum {
using namespace blockdem::motion;

namespace {

/// Independent reference: u'' + 2 xi w u' + w^2 u = -a_g(t), a_g linear between samples, integrated by a controlled
/// Dormand-Prince 5(4) stepper (abs. and rel. tolerance 1e-10) segment by segment (the kinks of a_g fall on segment
/// ends), observed `per_step` times per sample interval; returns max |u|.
double odeint_sd(const Record& record, double period, double xi, int per_step) {
  namespace odeint = boost::numeric::odeint;
  using State = std::array<double, 2>;
  const double w = two_pi / period;
  auto stepper = odeint::make_controlled(1e-10, 1e-10, odeint::runge_kutta_dopri5<State>());
  State x{0.0, 0.0};
  double peak = 0.0;
  const double h = record.dt / per_step;
  for (std::size_t i = 0; i + 1 < record.size(); ++i) {
    const double t0 = record.time(i);
    const double a0 = record.acceleration[i];
    const double slope = (record.acceleration[i + 1] - a0) / record.dt;
    const auto rhs = [&](const State& s, State& ds, double t) {
      ds[0] = s[1];
      ds[1] = -(a0 + slope * (t - t0)) - 2.0 * xi * w * s[1] - w * w * s[0];
    };
    for (int k = 0; k < per_step; ++k) {
      odeint::integrate_adaptive(stepper, rhs, x, t0 + k * h, t0 + (k + 1) * h, h);
      peak = std::max(peak, std::abs(x[0]));
    }
  }
  return peak;
}

int library_substeps(double dt, double period) {
  return std::max(1, static_cast<int>(std::ceil(spectrum_points_per_period * dt / period - 1e-9)));
}

}  // namespace

TEST_CASE("spectrum: the real PEER records agree with Boost.Odeint within 0.5 %") {
  const auto data = std::filesystem::path(BLOCKDEM_SHARED_DIR) / "data";
  if (!std::filesystem::exists(data / "ImperialValley1979_ElCentroArray4_140.AT2")) {
    MESSAGE("skipped: " << data.string() << " is absent");
    return;
  }
  const auto periods = log_spaced_periods(0.05, 10.0, 12);
  for (const std::string file :
       {"ImperialValley1979_ElCentroArray4_140.AT2", "ImperialValley1979_ElCentroArray4_230.AT2"}) {
    CAPTURE(file);
    const auto record = read_record(data / file);
    const auto spectrum = response_spectrum(record, periods, 0.05);
    double worst = 0.0;
    for (std::size_t j = 0; j < periods.size(); ++j) {
      // Odeint observed 4 times as often as the recursion, so the difference also bounds the recursion's error in
      // taking the peak at its observation times.
      const double reference = odeint_sd(record, periods[j], 0.05, 4 * library_substeps(record.dt, periods[j]));
      const double difference = std::abs(spectrum.sd[j] - reference) / reference;
      worst = std::max(worst, difference);
      CAPTURE(periods[j]);
      CHECK(difference < 0.005);
      CHECK(spectrum.psv[j] == doctest::Approx(two_pi / periods[j] * spectrum.sd[j]));
      CHECK(spectrum.psa[j] == doctest::Approx(std::pow(two_pi / periods[j], 2) * spectrum.sd[j]));
    }
    MESSAGE(file << ": largest relative difference from Odeint " << worst);
  }
}

TEST_CASE("spectrum: at the same observation times the recursion matches Odeint to its tolerance") {
  // A short, non-trivial record; damping 0, 2 % and 20 %.
  Record record;
  record.dt = 0.01;
  for (int i = 0; i < 600; ++i) {
    const double t = 0.01 * i;
    record.acceleration.push_back(std::exp(-0.3 * t) * (std::sin(4.0 * t) + 0.5 * std::cos(23.0 * t)));
  }
  for (double xi : {0.0, 0.02, 0.2})
    for (double period : {0.08, 0.5, 3.0}) {
      CAPTURE(xi);
      CAPTURE(period);
      const double reference = odeint_sd(record, period, xi, library_substeps(record.dt, period));
      CHECK(spectral_displacement(record, period, xi) == doctest::Approx(reference).epsilon(1e-7));
    }
}

TEST_CASE("spectrum: the response to a ramp equals the closed form (piecewise-linear input is exact)") {
  // a_g = c t from rest: u = -c t / w^2 + 2 xi c / w^3 + exp(-xi w t) (A cos(wd t) + B sin(wd t)),
  // A = -2 xi c / w^3, B = (c / w^2 + xi w A) / wd.
  const double c = 0.7;
  Record record;
  record.dt = 0.02;
  for (int i = 0; i <= 400; ++i) record.acceleration.push_back(c * 0.02 * i);
  for (double xi : {0.0, 0.05, 0.3})
    for (double period : {0.3, 1.0, 4.0}) {
      const double w = two_pi / period;
      const double wd = w * std::sqrt(1.0 - xi * xi);
      const double a = -2.0 * xi * c / (w * w * w);
      const double b = (c / (w * w) + xi * w * a) / wd;
      double peak = 0.0;
      for (int k = 0; k <= 400 * 200; ++k) {  // the closed form on a grid 200 times finer than the record
        const double t = 8.0 * k / (400.0 * 200.0);
        const double u = -c * t / (w * w) + 2.0 * xi * c / (w * w * w) +
                         std::exp(-xi * w * t) * (a * std::cos(wd * t) + b * std::sin(wd * t));
        peak = std::max(peak, std::abs(u));
      }
      CAPTURE(xi);
      CAPTURE(period);
      CHECK(spectral_displacement(record, period, xi) == doctest::Approx(peak).epsilon(1e-6));
    }
}

TEST_CASE("spectrum: a rigid oscillator feels the PGA, and a harmonic input has its dominant period at resonance") {
  Record record;
  record.dt = 0.005;
  for (int i = 0; i <= 4000; ++i) {
    const double t = 0.005 * i;
    record.acceleration.push_back(std::sin(two_pi * 0.8 * t) * std::sin(pi * t / 20.0));  // 0.8 Hz, smooth envelope
  }
  const double pga = peak_absolute(record.acceleration);
  const auto rigid = response_spectrum(record, std::vector<double>{0.01}, 0.05);
  CHECK(rigid.psa[0] == doctest::Approx(pga).epsilon(1e-3));  // PSA -> PGA as T -> 0
  const auto dominant = dominant_period(record, 0.05, 0.1, 5.0);
  CHECK(dominant.period == doctest::Approx(1.25).epsilon(0.02));  // resonance with the 0.8 Hz input
  CHECK(dominant.psv == doctest::Approx(two_pi / dominant.period * spectral_displacement(record, dominant.period, 0.05)));
  for (double p : log_spaced_periods(0.1, 5.0, 40))
    CHECK(two_pi / p * spectral_displacement(record, p, 0.05) <= dominant.psv * (1.0 + 1e-12));
}

TEST_CASE("spectrum: periods, damping and default grid") {
  Record record;
  record.dt = 0.01;
  record.acceleration = {0.0, 1.0, 0.0, -1.0, 0.0};
  CHECK_THROWS_WITH_AS(spectral_displacement(record, 0.0, 0.05), doctest::Contains("period 0.000000 s must be > 0"),
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(spectral_displacement(record, 1.0, 1.0), doctest::Contains("damping ratio 1.000000 is outside [0, 1)"),
                       InvalidArgument);
  CHECK_THROWS_AS(response_spectrum(record, std::vector<double>{}, 0.05), InvalidArgument);
  const auto periods = default_periods();
  CHECK(periods.size() == 100);
  CHECK(periods.front() == doctest::Approx(0.02));
  CHECK(periods.back() == doctest::Approx(10.0));
}

}  // namespace test_spectrum
