#pragma once
// Elastic response spectra of a damped single-degree-of-freedom oscillator, u'' + 2 xi w u' + w^2 u = -a_g(t), by
// the exact recursion for acceleration linear between samples (Nigam and Jennings 1969): SD, PSV = w SD and
// PSA = w^2 SD, and the dominant period (the peak of PSV) that the wavelet truncation takes as T_p (Sect. 6.1.2).

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/record.hpp"

namespace blockdem::motion {

/// The response is observed at least this many times per oscillator period (the step is split when the record is
/// coarser), which bounds the error of taking the peak at the observation times to 1 - cos(pi / 50) = 0.2 %.
inline constexpr int spectrum_points_per_period = 50;

namespace detail {

/// Exact state transition over a step h for piecewise-linear ground acceleration:
/// [u, v]_{i+1} = A [u, v]_i + B [a_i, a_{i+1}].
struct NigamJennings {
  double a11, a12, a21, a22, b11, b12, b21, b22;

  NigamJennings(double omega, double xi, double h) {
    const double root = std::sqrt(1.0 - xi * xi);
    const double wd = omega * root;
    const double e = std::exp(-xi * omega * h);
    const double s = std::sin(wd * h);
    const double c = std::cos(wd * h);
    const double r = xi / root;
    a11 = e * (r * s + c);
    a12 = e * s / wd;
    a21 = -omega / root * e * s;
    a22 = e * (c - r * s);
    const double w2 = omega * omega;
    const double t1 = (2.0 * xi * xi - 1.0) / (w2 * h);
    const double t2 = 2.0 * xi / (w2 * omega * h);
    const double ds = wd * s + xi * omega * c;  // -(d/dt)(e^{-xi w t} cos) / e^{-xi w t}
    b11 = e * ((t1 + xi / omega) * s / wd + (t2 + 1.0 / w2) * c) - t2;
    b12 = -e * (t1 * s / wd + t2 * c) - 1.0 / w2 + t2;
    b21 = e * ((t1 + xi / omega) * (c - r * s) - (t2 + 1.0 / w2) * ds) + 1.0 / (w2 * h);
    b22 = -e * (t1 * (c - r * s) - t2 * ds) - 1.0 / (w2 * h);
  }
};

inline void check_damping(double xi) {
  if (!(xi >= 0.0 && xi < 1.0))
    throw InvalidArgument("response spectrum: damping ratio " + std::to_string(xi) + " is outside [0, 1)");
}

inline void check_period(double period) {
  if (!(period > 0.0) || !std::isfinite(period))
    throw InvalidArgument("response spectrum: period " + std::to_string(period) + " s must be > 0");
}

}  // namespace detail

/// Peak relative displacement (m) of the oscillator of natural period `period` (s) and damping ratio `xi`, at rest
/// at the first sample, over the duration of the record.
inline double spectral_displacement(const Record& record, double period, double xi) {
  detail::check_period(period);
  detail::check_damping(xi);
  record.validate("response spectrum");
  const double omega = two_pi / period;
  const int substeps =
      std::max(1, static_cast<int>(std::ceil(spectrum_points_per_period * record.dt / period - 1e-9)));
  const detail::NigamJennings step(omega, xi, record.dt / substeps);
  const auto& a = record.acceleration;
  double u = 0.0;
  double v = 0.0;
  double peak = 0.0;
  for (std::size_t i = 0; i + 1 < a.size(); ++i) {
    const double slope = (a[i + 1] - a[i]) / substeps;
    double a_begin = a[i];
    for (int k = 1; k <= substeps; ++k) {
      const double a_end = k == substeps ? a[i + 1] : a[i] + k * slope;
      const double u_next = step.a11 * u + step.a12 * v + step.b11 * a_begin + step.b12 * a_end;
      v = step.a21 * u + step.a22 * v + step.b21 * a_begin + step.b22 * a_end;
      u = u_next;
      peak = std::max(peak, std::abs(u));
      a_begin = a_end;
    }
  }
  return peak;
}

struct ResponseSpectrum {
  double damping_ratio = 0.05;
  std::vector<double> period;  // s
  std::vector<double> sd;      // m, spectral displacement
  std::vector<double> psv;     // m/s, pseudo-spectral velocity w SD
  std::vector<double> psa;     // m/s^2, pseudo-spectral acceleration w^2 SD
};

/// SD, PSV and PSA at every period (s, > 0) for the damping ratio xi in [0, 1).
inline ResponseSpectrum response_spectrum(const Record& record, std::span<const double> periods, double xi = 0.05) {
  detail::check_damping(xi);
  if (periods.empty()) throw InvalidArgument("response spectrum: no periods given");
  ResponseSpectrum spectrum;
  spectrum.damping_ratio = xi;
  for (double period : periods) {
    const double sd = spectral_displacement(record, period, xi);
    const double omega = two_pi / period;
    spectrum.period.push_back(period);
    spectrum.sd.push_back(sd);
    spectrum.psv.push_back(omega * sd);
    spectrum.psa.push_back(omega * omega * sd);
  }
  return spectrum;
}

/// `count` periods spaced evenly in log between `lower` and `upper` (s).
inline std::vector<double> log_spaced_periods(double lower, double upper, int count) {
  if (!(lower > 0.0 && upper > lower) || count < 2)
    throw InvalidArgument("periods: need 0 < lower < upper and at least 2 of them");
  std::vector<double> periods(static_cast<std::size_t>(count));
  for (int j = 0; j < count; ++j)
    periods[static_cast<std::size_t>(j)] = lower * std::pow(upper / lower, static_cast<double>(j) / (count - 1));
  return periods;
}

/// The default period list: 100 periods from 0.02 s to 10 s, evenly spaced in log.
inline std::vector<double> default_periods() { return log_spaced_periods(0.02, 10.0, 100); }

struct DominantPeriod {
  double period = 0.0;  // s, where PSV peaks
  double psv = 0.0;     // m/s, PSV there
};

/// The period of the largest PSV between `lower` and `upper` (s): a 200-point log grid, then golden-section search
/// between the neighbours of the best grid point (to 1e-5 relative).
inline DominantPeriod dominant_period(const Record& record, double xi = 0.05, double lower = 0.05,
                                      double upper = 10.0) {
  const auto grid = log_spaced_periods(lower, upper, 200);
  const auto psv = [&](double period) { return two_pi / period * spectral_displacement(record, period, xi); };
  std::size_t best = 0;
  double best_psv = -1.0;
  for (std::size_t j = 0; j < grid.size(); ++j)
    if (const double value = psv(grid[j]); value > best_psv) {
      best_psv = value;
      best = j;
    }
  double lo = std::log(grid[best == 0 ? 0 : best - 1]);
  double hi = std::log(grid[std::min(best + 1, grid.size() - 1)]);
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = hi - ratio * (hi - lo);
  double x2 = lo + ratio * (hi - lo);
  double f1 = psv(std::exp(x1));
  double f2 = psv(std::exp(x2));
  while (hi - lo > 1e-5) {
    if (f1 >= f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - ratio * (hi - lo);
      f1 = psv(std::exp(x1));
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + ratio * (hi - lo);
      f2 = psv(std::exp(x2));
    }
  }
  DominantPeriod result{grid[best], best_psv};
  const double x = 0.5 * (lo + hi);
  if (const double value = psv(std::exp(x)); value > result.psv) result = {std::exp(x), value};
  return result;
}

}  // namespace blockdem::motion
