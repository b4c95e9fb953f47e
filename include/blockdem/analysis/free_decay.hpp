#pragma once
// The frequency and damping ratio of a free decay: the period from the upward zero crossings, the damping ratio by
// the logarithmic decrement of the peaks one period apart, zeta = ln(A_0 / A_n) / sqrt((2 pi n)^2 + ln(A_0 / A_n)^2);
// for a response of several modes, the first mode is isolated by a zero-phase band-pass around its spectral peak.

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/butterworth.hpp"

namespace blockdem::analysis {

struct FreeDecay {
  double frequency_hz = 0;    // damped natural frequency, from the mean period
  double damping_ratio = 0;   // from the logarithmic decrement
  int cycles = 0;             // whole cycles used
  double first_amplitude = 0; // largest |x| in the first cycle used
  double last_amplitude = 0;  // in the last
};

/// `x` sampled at increasing times `t` (s), oscillating about zero; the first `skip_cycles` cycles (the forced part)
/// are left out, then at most `max_cycles` are used. Throws InvalidArgument if fewer than two cycles remain.
inline FreeDecay analyse_free_decay(std::span<const double> t, std::span<const double> x, int skip_cycles = 1, int max_cycles = 8) {
  if (t.size() != x.size() || t.size() < 4) throw InvalidArgument("free decay: needs matching times and values, at least 4");
  std::vector<double> crossing;  // times of upward zero crossings, by linear interpolation
  for (std::size_t i = 1; i < x.size(); ++i)
    if (x[i - 1] < 0 && x[i] >= 0) crossing.push_back(t[i - 1] + (t[i] - t[i - 1]) * (-x[i - 1]) / (x[i] - x[i - 1]));
  const int available = static_cast<int>(crossing.size()) - 1 - skip_cycles;
  if (available < 2)
    throw InvalidArgument("free decay: " + std::to_string(std::max(available, 0)) + " whole cycles after the first " +
                          std::to_string(skip_cycles) + "; at least 2 are needed");
  const int n = std::min(available, max_cycles);
  const auto first = static_cast<std::size_t>(skip_cycles);
  auto amplitude = [&](std::size_t cycle) {  // largest |x| between crossings cycle and cycle + 1
    double a = 0;
    for (std::size_t i = 0; i < x.size(); ++i)
      if (t[i] >= crossing[cycle] && t[i] < crossing[cycle + 1]) a = std::max(a, std::abs(x[i]));
    return a;
  };
  FreeDecay d;
  d.cycles = n;
  d.frequency_hz = n / (crossing[first + static_cast<std::size_t>(n)] - crossing[first]);
  d.first_amplitude = amplitude(first);
  d.last_amplitude = amplitude(first + static_cast<std::size_t>(n) - 1);
  const double delta = std::log(d.first_amplitude / d.last_amplitude);  // over n - 1 periods
  const double periods = n - 1;
  d.damping_ratio = delta / std::sqrt(4 * pi * pi * periods * periods + delta * delta);
  return d;
}

/// The lowest frequency (Hz) in [lower_hz, upper_hz] whose discrete Fourier amplitude is a local maximum of at least
/// `relative` times the largest in that range: the first mode of a free response `x` sampled every `dt` s.
inline double first_spectral_peak(std::span<const double> x, double dt, double lower_hz, double upper_hz, double relative = 0.3) {
  const double duration = dt * static_cast<double>(x.size());
  const double resolution = 0.25 / duration;  // a quarter of the DFT bin
  std::vector<double> f, amplitude;
  for (double q = lower_hz; q <= upper_hz; q += resolution) {
    double re = 0, im = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double phase = 2 * pi * q * dt * static_cast<double>(i);
      re += x[i] * std::cos(phase);
      im -= x[i] * std::sin(phase);
    }
    f.push_back(q);
    amplitude.push_back(std::hypot(re, im));
  }
  if (f.size() < 3) throw InvalidArgument("first spectral peak: the record is too short for the band");
  double largest = 0;
  for (double a : amplitude) largest = std::max(largest, a);
  for (std::size_t k = 1; k + 1 < f.size(); ++k)
    if (amplitude[k] >= relative * largest && amplitude[k] >= amplitude[k - 1] && amplitude[k] >= amplitude[k + 1]) return f[k];
  return f[static_cast<std::size_t>(std::max_element(amplitude.begin(), amplitude.end()) - amplitude.begin())];
}

/// The first mode of a free response sampled every `dt` s: its spectral peak in [lower_hz, upper_hz], a 4th-order
/// zero-phase Butterworth band-pass from 0.6 to 1.5 times it, then analyse_free_decay on what passes.
inline FreeDecay analyse_first_mode(std::span<const double> x, double dt, double lower_hz = 1, double upper_hz = 100,
                                    int skip_cycles = 2, int max_cycles = 8) {
  const double f1 = first_spectral_peak(x, dt, lower_hz, std::min(upper_hz, 0.4 / dt));
  const motion::ButterworthFilter high(motion::FilterType::highpass, 4, 0.6 * f1, dt);
  const motion::ButterworthFilter low(motion::FilterType::lowpass, 4, std::min(1.5 * f1, 0.45 / dt), dt);
  const auto filtered = low.filtfilt(high.filtfilt(x));
  std::vector<double> t(filtered.size());
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = dt * static_cast<double>(i);
  return analyse_free_decay(t, filtered, skip_cycles, max_cycles);
}

}  // namespace blockdem::analysis
