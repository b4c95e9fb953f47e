// Wavelet truncation (Sect. 6.1.2): eq. 32 corrected recovers a pulse's amplitude from its own spectrum while the
// printed form does not; a known M&P pulse in broadband noise is recovered (amplitude within 2 %, t0 within 0.05 s,
// gamma within 5 %); the peak constraints hold; the window is the pulse support.

#include <doctest/doctest.h>

#include "../approx.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <random>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/butterworth.hpp"
#include "blockdem/motion/integration.hpp"
#include "blockdem/motion/readers.hpp"
#include "blockdem/motion/spectrum.hpp"
#include "blockdem/motion/wavelet_truncation.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_wavelet_truncation {
using namespace blockdem::motion;

namespace {

const MavroeidisPapageorgiouPulse truth{0.4, 3.0, 0.8, 6.0, 0.0};  // A (m/s), gamma, T_p (s), t0 (s), phi (rad)

/// The pulse, sampled at 200 Hz for 20 s, plus Gaussian white noise band-passed to 1-15 Hz under a Gaussian
/// envelope centred at 7 s, scaled to 30 % of the pulse's peak acceleration. std::mt19937 is portable; the normal
/// deviates come from our own Box-Muller, since std::normal_distribution is not.
Record pulse_in_noise(std::uint32_t seed) {
  auto record = to_record(truth, 0.005, 4001);
  std::mt19937 generator(seed);
  const auto uniform = [&] { return (static_cast<double>(generator()) + 0.5) / 4294967296.0; };
  std::vector<double> noise(record.size());
  for (double& x : noise) {
    const double radius = std::sqrt(-2.0 * std::log(uniform()));  // two statements: a fixed order of draws
    x = radius * std::cos(two_pi * uniform());
  }
  noise = ButterworthFilter(FilterType::lowpass, 4, 15.0, 0.005)
              .filtfilt(ButterworthFilter(FilterType::highpass, 4, 1.0, 0.005).filtfilt(noise));
  const double scale = 0.3 * peak_absolute(record.acceleration) / peak_absolute(noise);
  for (std::size_t i = 0; i < record.size(); ++i)
    record.acceleration[i] += scale * std::exp(-std::pow((record.time(i) - 7.0) / 5.0, 2)) * noise[i];
  record.name = "pulse in noise";
  return record;
}

}  // namespace

TEST_CASE("wavelet truncation: eq. 32 corrected recovers the amplitude from the pulse's own PSV, but as printed it does not") {
  // Reference: the pulse's amplitude A = 0.4 m/s; PSV(T_p) from the exact recursion of the sampled pulse.
  for (auto [gamma_, phase] : {std::pair{3.0, 0.0}, std::pair{5.0, pi / 2.0}, std::pair{8.0, 0.0}}) {
    const double gamma = gamma_;  // (a name a lambda can capture: CAPTURE below)
    const MavroeidisPapageorgiouPulse pulse{0.4, gamma, 0.526, 8.0, phase};
    const auto record = to_record(pulse, 0.005, 4001);
    const double psv = two_pi / 0.526 * spectral_displacement(record, 0.526, 0.05);
    CAPTURE(gamma);
    CHECK(pulse_amplitude(psv, gamma, 0.05) == doctest::Approx(0.4).epsilon(0.025));
    const double printed = pulse_amplitude_as_printed(psv, gamma, 0.05);
    CHECK(printed / pulse_amplitude(psv, gamma, 0.05) == doctest::Approx(std::pow(1.0 + (gamma - 1.0) * 0.05, 2)));
    CHECK(printed > 1.15 * 0.4);  // off by the factor (1 + (gamma - 1) xi)^2 >= 1.21
  }
}

TEST_CASE("wavelet truncation: a known pulse in broadband noise is recovered") {
  // T_p given; the default grid (gamma 1.01-10, t0 over the record, 36 phases), refined. Of ten noise seeds, those
  // that leave the record's PGV at or above the pulse amplitude must recover it; for the others the paper's
  // constraint |v_MP| <= PGV excludes the true pulse, and the fit must honour the constraint instead.
  int recovered = 0;
  for (std::uint32_t seed = 1; seed <= 10; ++seed) {
    CAPTURE(seed);
    const auto record = pulse_in_noise(seed);
    WaveletTruncationOptions options;
    options.period = truth.period;
    const auto fit = wavelet_truncation(record, options);
    CHECK(fit.candidates == 100 * 100 * 36);
    CHECK(fit.correlation > 0.99);
    CHECK(fit.correlation >= fit.grid_correlation);
    CHECK(fit.pulse.period == truth.period);
    CHECK_FALSE(fit.period_from_spectrum);
    // The window is the fitted pulse's support.
    CHECK(std::abs(fit.truncation.start - fit.pulse.start()) <= record.dt);
    CHECK(std::abs(fit.truncation.end - fit.pulse.end()) <= record.dt);
    CHECK(fit.truncation.arias_fraction > 0.5);
    CHECK(fit.truncation.arias_fraction <= 1.0);
    if (peak_values(record).pgv < truth.amplitude) {
      CHECK(pulse_peaks(fit.pulse).velocity <= peak_values(record).pgv * (1.0 + 1e-9));
      continue;
    }
    ++recovered;
    CHECK(fit.pulse.amplitude == doctest::Approx(truth.amplitude).epsilon(0.02));
    CHECK(std::abs(fit.pulse.t0 - truth.t0) <= 0.05);
    CHECK(fit.pulse.gamma == doctest::Approx(truth.gamma).epsilon(0.05));

    options.amplitude = PulseAmplitude::least_squares;
    const auto regression = wavelet_truncation(record, options);
    CHECK(regression.pulse.amplitude == doctest::Approx(truth.amplitude).epsilon(0.02));
    CHECK(std::abs(regression.pulse.t0 - truth.t0) <= 0.05);
  }
  CHECK(recovered >= 5);
}

TEST_CASE("wavelet truncation: the correlation from support sums equals a direct Pearson correlation") {
  // Reference: Pearson's r between the record's velocity (integrated from rest) and the fitted pulse's velocity,
  // computed here directly over every sample of the record.
  for (std::uint32_t seed : {2u, 5u}) {
    const auto record = pulse_in_noise(seed);
    for (bool refine : {false, true}) {
      WaveletTruncationOptions options;
      options.period = truth.period;
      options.refine = refine;
      const auto fit = wavelet_truncation(record, options);
      const auto v = integrate(record).velocity;
      const double n = static_cast<double>(v.size());
      double sv = 0, sw = 0, svv = 0, sww = 0, svw = 0;
      for (std::size_t i = 0; i < v.size(); ++i) {
        const double w = fit.pulse.velocity(record.time(i));
        sv += v[i];
        sw += w;
        svv += v[i] * v[i];
        sww += w * w;
        svw += v[i] * w;
      }
      const double r = (svw - sv * sw / n) / std::sqrt((svv - sv * sv / n) * (sww - sw * sw / n));
      CAPTURE(seed);
      CAPTURE(refine);
      CHECK(fit.correlation == doctest::Approx(r).epsilon(1e-9));
    }
  }
}

TEST_CASE("wavelet truncation: the tabulated pulse peaks match densely sampled closed forms") {
  for (double gamma : {1.01, 2.2, 5.0, 10.0})
    for (double phase : {0.0, 1.0, 2.0, 4.0}) {
      const MavroeidisPapageorgiouPulse pulse{0.3, gamma, 0.7, 1.0, phase};
      PulsePeaks dense;
      const int n = 20000;
      for (int k = 0; k <= n; ++k) {
        const double t = pulse.start() + (pulse.end() - pulse.start()) * k / n;
        dense.velocity = std::max(dense.velocity, std::abs(pulse.velocity(t)));
        dense.acceleration = std::max(dense.acceleration, std::abs(pulse.acceleration(t)));
        dense.displacement = std::max(dense.displacement, std::abs(pulse.displacement(t)));
      }
      const auto peaks = pulse_peaks(pulse);
      CAPTURE(gamma);
      CAPTURE(phase);
      // 64 samples per carrier period: within (1 - cos(pi / 64)) (1 + 1 / (2 gamma^2)) of the peak, 0.12 % for a long
      // envelope and 0.18 % for the shortest (gamma 1.01, phase 0: 0.177 %).
      const double bound = (1 - std::cos(pi / 64)) * (1 + 0.5 / (gamma * gamma));
      CHECK(peaks.velocity == test::approx(dense.velocity).epsilon(bound));
      CHECK(peaks.acceleration == test::approx(dense.acceleration).epsilon(bound));
      CHECK(peaks.displacement == test::approx(dense.displacement).epsilon(bound));
      CHECK(peaks.velocity <= dense.velocity * (1.0 + 1e-9));
    }
}

TEST_CASE("wavelet truncation: the paper's grid alone lands on grid points, the peak constraints hold") {
  const auto record = pulse_in_noise(2);
  WaveletTruncationOptions options;
  options.period = truth.period;
  options.t0 = GridRange{0.0, 10.0, 100};
  options.refine = false;
  const auto grid = wavelet_truncation(record, options);
  CHECK(grid.correlation == doctest::Approx(grid.grid_correlation));
  const double gamma_index = (grid.pulse.gamma - 1.01) / ((10.0 - 1.01) / 99.0);
  CHECK(std::abs(gamma_index - std::round(gamma_index)) < 1e-9);
  const double phase_index = grid.pulse.phase / (two_pi / 36.0);
  CHECK(std::abs(phase_index - std::round(phase_index)) < 1e-9);

  // A velocity bound below the true amplitude: the fitted pulse obeys it.
  options.refine = true;
  options.max_velocity = 0.3;
  const auto bounded = wavelet_truncation(record, options);
  CHECK(bounded.limits.velocity == 0.3);
  CHECK(pulse_peaks(bounded.pulse).velocity <= 0.3 * (1.0 + 1e-9));
  CHECK(bounded.feasible_candidates < bounded.candidates);
  CHECK(bounded.correlation < grid.correlation + 1e-12);

  // By default the bounds are the record's own peaks.
  options.max_velocity.reset();
  const auto fit = wavelet_truncation(record, options);
  const auto peaks = peak_values(record);
  CHECK(fit.limits.velocity == peaks.pgv);
  CHECK(fit.limits.acceleration == peaks.pga);
  CHECK(fit.limits.displacement == peaks.pgd);
  const auto p = pulse_peaks(fit.pulse);
  CHECK(p.velocity <= peaks.pgv * (1.0 + 1e-9));
  CHECK(p.acceleration <= peaks.pga * (1.0 + 1e-9));
  CHECK(p.displacement <= peaks.pgd * (1.0 + 1e-9));

  options.max_acceleration = 1e-6;  // nothing fits
  CHECK_THROWS_WITH_AS(wavelet_truncation(record, options), doctest::Contains("no pulse on the grid meets the peak"),
                       InvalidArgument);
}

TEST_CASE("wavelet truncation: without T_p the dominant PSV peak is taken") {
  const auto record = pulse_in_noise(3);
  WaveletTruncationOptions options;
  options.t0 = GridRange{4.0, 8.0, 40};
  options.gamma = GridRange{1.5, 6.0, 40};
  const auto fit = wavelet_truncation(record, options);
  CHECK(fit.period_from_spectrum);
  const auto dominant = dominant_period(record, 0.05, 0.05, 10.0);
  CHECK(fit.pulse.period == doctest::Approx(dominant.period));
  CHECK(fit.psv_at_period == doctest::Approx(dominant.psv));
  // The PSV peak of an M&P pulse lies a little below its carrier period (here about 7 % below).
  CHECK(fit.pulse.period == doctest::Approx(truth.period).epsilon(0.1));
  CHECK(fit.correlation > 0.95);
}

TEST_CASE("wavelet truncation: the pulse-like real record fits a pulse closely") {
  // Imperial Valley 1979, El Centro Array #4, 230 degrees: classified pulse-like by Shahi and Baker; its velocity
  // is dominated by one long-period pulse, so the fit correlates strongly.
  const auto data = std::filesystem::path(BLOCKDEM_SHARED_DIR) / "data";
  if (!std::filesystem::exists(data / "ImperialValley1979_ElCentroArray4_230.AT2")) {
    MESSAGE("skipped: " << data.string() << " is absent");
    return;
  }
  const auto record = read_record(data / "ImperialValley1979_ElCentroArray4_230.AT2");
  const auto fit = wavelet_truncation(record);
  CHECK(fit.correlation > 0.9);
  CHECK(fit.pulse.period > 3.0);
  CHECK(fit.truncation.arias_fraction > 0.5);
  CHECK(fit.truncation.start >= record.start_time);
  CHECK(fit.truncation.end <= record.end_time());
}

TEST_CASE("wavelet truncation: options are checked") {
  const auto record = pulse_in_noise(2);
  WaveletTruncationOptions options;
  options.gamma = GridRange{1.0, 10.0, 100};
  CHECK_THROWS_WITH_AS(wavelet_truncation(record, options), doctest::Contains("gamma range needs 1 < lower"),
                       InvalidArgument);
  options = {};
  options.phase_samples = 0;
  CHECK_THROWS_WITH_AS(wavelet_truncation(record, options), doctest::Contains("phase samples 0 is outside 1..3600"),
                       InvalidArgument);
  options = {};
  options.damping_ratio = 0.0;
  CHECK_THROWS_AS(wavelet_truncation(record, options), InvalidArgument);
  options = {};
  options.period = -1.0;
  CHECK_THROWS_AS(wavelet_truncation(record, options), InvalidArgument);
}

}  // namespace test_wavelet_truncation
