#pragma once
// Wavelet-based truncation (paper Sect. 6.1.2, after Repapis et al. 2020): fit one Mavroeidis-Papageorgiou pulse
// (eq. 31) to the velocity of a record and keep the record over the pulse's support. T_p is the dominant PSV peak
// unless given; the amplitude follows from PSV(T_p) (eq. 32 corrected, DESIGN §7); gamma, t_0 and phi maximise the
// Pearson correlation with the record's velocity over a grid, subject to peak constraints, and are then refined by a
// compass search.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/integration.hpp"
#include "blockdem/motion/pulse.hpp"
#include "blockdem/motion/record.hpp"
#include "blockdem/motion/spectrum.hpp"
#include "blockdem/motion/truncation.hpp"

namespace blockdem::motion {

namespace detail {
/// (cos, sin) of an angle advanced by a fixed step, by the angle-addition recurrence (no trigonometric call).
inline void advance_phasor(double& c, double& s, double c_step, double s_step) noexcept {
  const double c_next = c * c_step - s * s_step;
  s = s * c_step + c * s_step;
  c = c_next;
}
}  // namespace detail

/// Pulse amplitude A (m/s) from the pseudo-spectral velocity at T_p (m/s), gamma and the damping ratio xi:
/// A = 4 xi PSV(T_p) / ((1 - exp(-2 pi gamma xi)) (1 + (gamma - 1) xi)).
/// Eq. 32 as printed multiplies by (1 + (gamma - 1) xi); only dividing by it recovers the amplitude of a pulse from
/// its own spectrum (DESIGN §7; the test shows the printed form is off by that factor squared).
inline double pulse_amplitude(double psv, double gamma, double xi) {
  return 4.0 * xi * psv / ((1.0 - std::exp(-two_pi * gamma * xi)) * (1.0 + (gamma - 1.0) * xi));  // eq. 32 corrected
}

/// Eq. 32 exactly as printed, kept for comparison.
inline double pulse_amplitude_as_printed(double psv, double gamma, double xi) {
  return 4.0 * xi * psv / (1.0 - std::exp(-two_pi * gamma * xi)) * (1.0 + (gamma - 1.0) * xi);  // eq. 32
}

struct PulsePeaks {
  double velocity = 0.0;      // m/s
  double acceleration = 0.0;  // m/s^2
  double displacement = 0.0;  // m
};

/// Peak absolute velocity, acceleration and displacement of a pulse, sampled 64 times per carrier period over its
/// support: within (1 - cos(pi / 64)) (1 + 1 / (2 gamma^2)) of the continuous peaks, 0.12 % for a long envelope and
/// 0.18 % for the shortest (gamma near 1, where the envelope sharpens the carrier's peak). The grid search tabulates thousands of
/// these, so the carrier and envelope angles advance by rotation instead of calls to sin and cos.
inline PulsePeaks pulse_peaks(const MavroeidisPapageorgiouPulse& pulse) {
  const int points = static_cast<int>(std::ceil(64.0 * pulse.gamma)) + 1;
  const double half = 0.5 * pulse.gamma * pulse.period;
  const double step = 2.0 * half / (points - 1);
  const double wp = pulse.carrier_frequency();
  const double we = pulse.envelope_frequency();
  const double amplitude = pulse.amplitude;
  // Carrier angle wp tau + phi and envelope angle we tau at tau = -half, and their increments per step.
  double ca = std::cos(-wp * half + pulse.phase), sa = std::sin(-wp * half + pulse.phase);
  double cb = std::cos(-we * half), sb = std::sin(-we * half);
  const double dca = std::cos(wp * step), dsa = std::sin(wp * step);
  const double dcb = std::cos(we * step), dsb = std::sin(we * step);
  // Primitive of eq. 31 (see MavroeidisPapageorgiouPulse::displacement) from sin(A), sin(A + B), sin(A - B).
  const auto primitive = [&](double c_a, double s_a, double c_b, double s_b) {
    return 0.5 * amplitude * s_a / wp +
           0.25 * amplitude * ((s_a * c_b + c_a * s_b) / (wp + we) + (s_a * c_b - c_a * s_b) / (wp - we));
  };
  const double origin = primitive(ca, sa, cb, sb);
  PulsePeaks peaks;
  for (int k = 0; k < points; ++k) {
    peaks.velocity = std::max(peaks.velocity, std::abs(0.5 * amplitude * (1.0 + cb) * ca));  // eq. 31
    peaks.acceleration =
        std::max(peaks.acceleration, std::abs(0.5 * amplitude * (we * sb * ca + (1.0 + cb) * wp * sa)));
    peaks.displacement = std::max(peaks.displacement, std::abs(primitive(ca, sa, cb, sb) - origin));
    detail::advance_phasor(ca, sa, dca, dsa);
    detail::advance_phasor(cb, sb, dcb, dsb);
  }
  return peaks;
}

/// `samples` values from `lower` to `upper` inclusive (one sample: `lower`).
struct GridRange {
  double lower = 0.0;
  double upper = 0.0;
  int samples = 1;

  double at(int k) const noexcept { return samples == 1 ? lower : lower + (upper - lower) * k / (samples - 1); }
  double spacing() const noexcept { return samples == 1 ? 0.0 : (upper - lower) / (samples - 1); }
};

enum class PulseAmplitude {
  spectral,      // from PSV(T_p), eq. 32 corrected (the paper's method)
  least_squares  // the regression slope of the record's velocity on the pulse shape
};

struct WaveletTruncationOptions {
  double damping_ratio = 0.05;              // xi of eq. 32 and of the spectrum that gives T_p
  std::optional<double> period;             // T_p in s; default: the dominant PSV peak in [min_period, max_period]
  double min_period = 0.05;                 // s
  double max_period = 10.0;                 // s (also capped at the record's duration)
  GridRange gamma{1.01, 10.0, 100};         // Sect. 6.1.2: [1.01, 10], 100 samples
  std::optional<GridRange> t0;              // s; default: the record's span, 100 samples (the paper: [0, 5] s)
  int phase_samples = 36;                   // over [0, 2 pi): 10 degree steps
  std::optional<double> max_velocity;       // m/s, |v_MP| bound; default: the record's PGV
  std::optional<double> max_acceleration;   // m/s^2, |a_MP| bound; default: the record's PGA
  std::optional<double> max_displacement;   // m, |u_MP| bound; default: the record's PGD
  bool refine = true;                       // compass search from the best grid point
  PulseAmplitude amplitude = PulseAmplitude::spectral;

  void validate() const {
    if (!(damping_ratio > 0.0 && damping_ratio < 1.0))
      throw InvalidArgument("wavelet truncation: damping ratio " + std::to_string(damping_ratio) +
                            " is outside (0, 1)");
    if (period && !(*period > 0.0 && std::isfinite(*period)))
      throw InvalidArgument("wavelet truncation: T_p = " + std::to_string(*period) + " s must be > 0");
    if (!(min_period > 0.0 && max_period > min_period))
      throw InvalidArgument("wavelet truncation: the T_p search range needs 0 < min < max");
    if (!(gamma.lower > 1.0 && gamma.upper >= gamma.lower && std::isfinite(gamma.upper)))
      throw InvalidArgument("wavelet truncation: the gamma range needs 1 < lower <= upper");
    if (gamma.samples < 1 || gamma.samples > 100000 || (t0 && (t0->samples < 1 || t0->samples > 100000)))
      throw InvalidArgument("wavelet truncation: grid samples must be in 1..100000");
    if (t0 && !(t0->upper >= t0->lower && std::isfinite(t0->lower) && std::isfinite(t0->upper)))
      throw InvalidArgument("wavelet truncation: the t0 range needs lower <= upper");
    if (phase_samples < 1 || phase_samples > 3600)
      throw InvalidArgument("wavelet truncation: phase samples " + std::to_string(phase_samples) +
                            " is outside 1..3600");
    // Each candidate of the grid is a pulse to evaluate: the default grid has 3.6e5 (under a second), 1e7 some seconds.
    const double candidates = static_cast<double>(gamma.samples) * (t0 ? t0->samples : 100) * phase_samples;
    if (candidates > 1e7) {
      char text[160];
      std::snprintf(text, sizeof text, "wavelet truncation: the grid has %.3g candidates (gamma samples x t0 samples x "
                    "phase samples), at most 1e7", candidates);
      throw InvalidArgument(text);
    }
    for (auto bound : {max_velocity, max_acceleration, max_displacement})
      if (bound && !(*bound > 0.0))
        throw InvalidArgument("wavelet truncation: peak constraints must be > 0");
  }
};

struct WaveletTruncationResult {
  MavroeidisPapageorgiouPulse pulse;  // the fitted pulse
  double correlation = 0.0;           // Pearson r of pulse and record velocity over the whole record
  double grid_correlation = 0.0;      // the best r on the grid, before refinement
  double psv_at_period = 0.0;         // m/s, PSV(T_p) of the record
  bool period_from_spectrum = false;  // T_p was the dominant PSV peak (not given)
  PulsePeaks limits;                  // the peak constraints used
  long long candidates = 0;           // grid points evaluated
  long long feasible_candidates = 0;  // grid points that met the peak constraints
  Truncation truncation;              // the record over the pulse support (clamped to the record)
};

namespace detail {

/// Sums over the pulse support of the record velocity v against the envelope E = (1 + cos(we tau)) / 2 times the
/// carrier's cosine C and sine S; from them the Pearson correlation at any phase follows in O(1), since
/// w = A E (C cos(phi) - S sin(phi)).
struct SupportSums {
  double vc = 0, vs = 0, c = 0, s = 0, cc = 0, ss = 0, cs = 0;
};

class PulseCorrelation {
 public:
  PulseCorrelation(const Record& record, double period)
      : record_(record), period_(period), velocity_(integrate(record).velocity) {
    const double n = static_cast<double>(velocity_.size());
    for (double v : velocity_) sum_v_ += v;
    const double mean = sum_v_ / n;
    for (double v : velocity_) centred_vv_ += (v - mean) * (v - mean);
  }

  SupportSums sums(double gamma, double t0) const {
    SupportSums out;
    const double half = 0.5 * gamma * period_;
    const double last = static_cast<double>(velocity_.size() - 1);
    const double x0 = std::ceil((t0 - half - record_.start_time) / record_.dt);
    const double x1 = std::floor((t0 + half - record_.start_time) / record_.dt);
    if (x1 < 0.0 || x0 > last) return out;
    const auto lo = static_cast<std::size_t>(std::max(0.0, x0));
    const auto hi = static_cast<std::size_t>(std::min(last, x1));
    const double we = two_pi / (gamma * period_);
    const double wp = two_pi / period_;
    // cos and sin advance by rotation; re-seeded every 256 samples so rounding cannot build up.
    const double ce_step = std::cos(we * record_.dt), se_step = std::sin(we * record_.dt);
    const double cp_step = std::cos(wp * record_.dt), sp_step = std::sin(wp * record_.dt);
    double ce = 0, se = 0, cp = 0, sp = 0;
    for (std::size_t i = lo; i <= hi; ++i) {
      if ((i - lo) % 256 == 0) {
        const double tau = record_.time(i) - t0;
        ce = std::cos(we * tau);
        se = std::sin(we * tau);
        cp = std::cos(wp * tau);
        sp = std::sin(wp * tau);
      }
      const double e = 0.5 * (1.0 + ce);
      const double ec = e * cp;
      const double es = e * sp;
      const double v = velocity_[i];
      out.vc += v * ec;
      out.vs += v * es;
      out.c += ec;
      out.s += es;
      out.cc += ec * ec;
      out.ss += es * es;
      out.cs += ec * es;
      detail::advance_phasor(ce, se, ce_step, se_step);
      detail::advance_phasor(cp, sp, cp_step, sp_step);
    }
    return out;
  }

  struct Fit {
    double correlation;  // Pearson r
    double slope;        // least-squares amplitude (m/s per unit pulse)
  };

  /// Pearson correlation of the unit-amplitude pulse at phase phi with the velocity, over the whole record (the
  /// pulse is zero off its support), and the regression slope.
  Fit fit(const SupportSums& s, double phase) const {
    const double n = static_cast<double>(velocity_.size());
    const double cp = std::cos(phase), sp = std::sin(phase);
    const double vw = cp * s.vc - sp * s.vs;
    const double w = cp * s.c - sp * s.s;
    const double ww = cp * cp * s.cc - 2.0 * cp * sp * s.cs + sp * sp * s.ss;
    const double covariance = vw - sum_v_ * w / n;
    const double variance_w = ww - w * w / n;
    if (!(variance_w > 0.0) || !(centred_vv_ > 0.0)) return {0.0, 0.0};
    return {covariance / std::sqrt(variance_w * centred_vv_), covariance / variance_w};
  }

  const std::vector<double>& velocity() const noexcept { return velocity_; }

 private:
  const Record& record_;
  double period_;
  std::vector<double> velocity_;
  double sum_v_ = 0.0;
  double centred_vv_ = 0.0;
};

}  // namespace detail

/// Fits the pulse and cuts the record to its support. Throws InvalidArgument for bad options, or when no pulse on
/// the grid meets the peak constraints.
inline WaveletTruncationResult wavelet_truncation(const Record& record, const WaveletTruncationOptions& options = {}) {
  options.validate();
  record.validate("wavelet truncation");
  const double xi = options.damping_ratio;

  WaveletTruncationResult result;
  double period = 0.0;
  if (options.period) {
    period = *options.period;
    result.psv_at_period = two_pi / period * spectral_displacement(record, period, xi);
  } else {
    const double upper = std::min(options.max_period, record.duration());
    if (!(upper > options.min_period))
      throw InvalidArgument("wavelet truncation: " + record.name + " is too short for the T_p search range");
    const auto dominant = dominant_period(record, xi, options.min_period, upper);
    period = dominant.period;
    result.psv_at_period = dominant.psv;
    result.period_from_spectrum = true;
  }

  const auto peaks = peak_values(record);
  result.limits = {options.max_velocity.value_or(peaks.pgv), options.max_acceleration.value_or(peaks.pga),
                   options.max_displacement.value_or(peaks.pgd)};
  const auto& limits = result.limits;
  // Peaks scale with the amplitude, so a unit pulse's peaks decide every amplitude at once.
  const auto within = [&](const PulsePeaks& unit, double amplitude) {
    constexpr double slack = 1.0 + 1e-9;
    return amplitude > 0.0 && amplitude * unit.velocity <= limits.velocity * slack &&
           amplitude * unit.acceleration <= limits.acceleration * slack &&
           amplitude * unit.displacement <= limits.displacement * slack;
  };
  const bool spectral = options.amplitude == PulseAmplitude::spectral;

  const detail::PulseCorrelation correlation(record, period);
  const GridRange t0_grid = options.t0.value_or(GridRange{record.start_time, record.end_time(), 100});
  const GridRange& gamma_grid = options.gamma;
  const int phases = options.phase_samples;
  const auto phase_at = [phases](int k) { return two_pi * k / phases; };

  // Peaks of the unit-amplitude pulse depend on gamma and phi only: tabulate them once.
  std::vector<PulsePeaks> unit_peaks(static_cast<std::size_t>(gamma_grid.samples * phases));
  for (int g = 0; g < gamma_grid.samples; ++g)
    for (int k = 0; k < phases; ++k)
      unit_peaks[static_cast<std::size_t>(g * phases + k)] =
          pulse_peaks(MavroeidisPapageorgiouPulse{1.0, gamma_grid.at(g), period, 0.0, phase_at(k)});

  double best_r = -std::numeric_limits<double>::infinity();
  double best_gamma = 0.0, best_t0 = 0.0, best_phase = 0.0;
  for (int g = 0; g < gamma_grid.samples; ++g) {
    const double gamma = gamma_grid.at(g);
    const double spectral_amplitude = pulse_amplitude(result.psv_at_period, gamma, xi);
    for (int j = 0; j < t0_grid.samples; ++j) {
      const double t0 = t0_grid.at(j);
      const auto sums = correlation.sums(gamma, t0);
      for (int k = 0; k < phases; ++k) {
        ++result.candidates;
        const auto fit = correlation.fit(sums, phase_at(k));
        const double amplitude = spectral ? spectral_amplitude : fit.slope;
        if (!within(unit_peaks[static_cast<std::size_t>(g * phases + k)], amplitude)) continue;
        ++result.feasible_candidates;
        if (fit.correlation > best_r) {
          best_r = fit.correlation;
          best_gamma = gamma;
          best_t0 = t0;
          best_phase = phase_at(k);
        }
      }
    }
  }
  if (result.feasible_candidates == 0)
    throw InvalidArgument("wavelet truncation: no pulse on the grid meets the peak constraints |v| <= " +
                          std::to_string(limits.velocity) + " m/s, |a| <= " + std::to_string(limits.acceleration) +
                          " m/s^2, |u| <= " + std::to_string(limits.displacement) + " m");
  result.grid_correlation = best_r;

  const auto evaluate = [&](double gamma, double t0, double phase) {
    if (gamma < gamma_grid.lower || gamma > gamma_grid.upper || t0 < t0_grid.lower || t0 > t0_grid.upper)
      return -std::numeric_limits<double>::infinity();
    const auto fit = correlation.fit(correlation.sums(gamma, t0), phase);
    const double amplitude = spectral ? pulse_amplitude(result.psv_at_period, gamma, xi) : fit.slope;
    if (!within(pulse_peaks(MavroeidisPapageorgiouPulse{1.0, gamma, period, 0.0, phase}), amplitude))
      return -std::numeric_limits<double>::infinity();
    return fit.correlation;
  };
  if (options.refine) {
    // Compass search: try +/- each step, keep any improvement, halve the steps when none helps.
    std::array<double, 3> x{best_gamma, best_t0, best_phase};
    std::array<double, 3> step{gamma_grid.samples > 1 ? gamma_grid.spacing() : 0.1 * best_gamma,
                               t0_grid.samples > 1 ? t0_grid.spacing() : 0.1 * period, two_pi / phases};
    constexpr std::array<double, 3> tolerance{1e-6, 1e-6, 1e-6};
    for (int evaluations = 0; evaluations < 5000;) {
      bool improved = false;
      for (int d = 0; d < 3; ++d)
        for (double sign : {1.0, -1.0}) {
          auto trial = x;
          trial[static_cast<std::size_t>(d)] += sign * step[static_cast<std::size_t>(d)];
          const double r = evaluate(trial[0], trial[1], trial[2]);
          ++evaluations;
          if (r > best_r) {
            best_r = r;
            x = trial;
            improved = true;
          }
        }
      if (!improved) {
        for (auto& s : step) s *= 0.5;
        if (step[0] < tolerance[0] && step[1] < tolerance[1] && step[2] < tolerance[2]) break;
      }
    }
    best_gamma = x[0];
    best_t0 = x[1];
    best_phase = std::fmod(std::fmod(x[2], two_pi) + two_pi, two_pi);
  }

  const auto fit = correlation.fit(correlation.sums(best_gamma, best_t0), best_phase);
  result.correlation = fit.correlation;
  const double amplitude = spectral ? pulse_amplitude(result.psv_at_period, best_gamma, xi) : fit.slope;
  result.pulse = MavroeidisPapageorgiouPulse{amplitude, best_gamma, period, best_t0, best_phase};
  const double start = std::max(result.pulse.start(), record.start_time);
  const double end = std::min(result.pulse.end(), record.end_time());
  result.truncation = truncate_window(record, start, end);
  return result;
}

}  // namespace blockdem::motion
