#pragma once
// Digital Butterworth low- and high-pass filters as second-order sections (bilinear transform with the corner
// frequency prewarped), applied causally or forward-backward for zero phase. The zero-phase form pads and starts
// the filter as scipy.signal.sosfiltfilt does (odd extension, steady-state initial conditions), so with the same
// padding results agree with it to rounding.

#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"

namespace blockdem::motion {

enum class FilterType { lowpass, highpass };

/// y = (b0 + b1 z^-1 + b2 z^-2) / (1 + a1 z^-1 + a2 z^-2) x, applied in transposed direct form II.
struct SecondOrderSection {
  double b0 = 1.0, b1 = 0.0, b2 = 0.0, a1 = 0.0, a2 = 0.0;

  /// Gain at zero frequency.
  double dc_gain() const noexcept { return (b0 + b1 + b2) / (1.0 + a1 + a2); }
};

class ButterworthFilter {
 public:
  /// Order 1..8, corner frequency in Hz strictly between 0 and the Nyquist frequency 1 / (2 dt), dt in s.
  ButterworthFilter(FilterType type, int order, double corner_hz, double dt)
      : type_(type), order_(order), corner_hz_(corner_hz), dt_(dt) {
    if (order < 1 || order > 8)
      throw InvalidArgument("butterworth filter: order " + std::to_string(order) + " is outside 1..8");
    if (!(dt > 0.0)) throw InvalidArgument("butterworth filter: time step dt must be > 0 s");
    const double nyquist = 0.5 / dt;
    if (!(corner_hz > 0.0 && corner_hz < nyquist))
      throw InvalidArgument("butterworth filter: corner frequency " + std::to_string(corner_hz) +
                            " Hz must be in (0, " + std::to_string(nyquist) + ") Hz (below the Nyquist frequency)");
    const double k = std::tan(pi * corner_hz * dt);  // prewarped corner, normalised
    const bool high = type == FilterType::highpass;
    if (order % 2 == 1) {  // the real pole
      const double norm = 1.0 / (1.0 + k);
      sections_.push_back(high ? SecondOrderSection{norm, -norm, 0.0, (k - 1.0) * norm, 0.0}
                               : SecondOrderSection{k * norm, k * norm, 0.0, (k - 1.0) * norm, 0.0});
    }
    for (int j = 0; j < order / 2; ++j) {  // conjugate pole pairs, quality factor 1 / (2 sin((2j + 1) pi / 2N))
      const double q = 1.0 / (2.0 * std::sin(pi * (2.0 * j + 1.0) / (2.0 * order)));
      const double norm = 1.0 / (1.0 + k / q + k * k);
      const double a1 = 2.0 * (k * k - 1.0) * norm;
      const double a2 = (1.0 - k / q + k * k) * norm;
      sections_.push_back(high ? SecondOrderSection{norm, -2.0 * norm, norm, a1, a2}
                               : SecondOrderSection{k * k * norm, 2.0 * k * k * norm, k * k * norm, a1, a2});
    }
  }

  FilterType type() const noexcept { return type_; }
  int order() const noexcept { return order_; }
  double corner_hz() const noexcept { return corner_hz_; }
  const std::vector<SecondOrderSection>& sections() const noexcept { return sections_; }

  /// |H| of one pass at frequency f in Hz; the zero-phase filter's gain is its square.
  double gain(double frequency_hz) const {
    const std::complex<double> z_inv = std::polar(1.0, -two_pi * frequency_hz * dt_);
    std::complex<double> h = 1.0;
    for (const auto& s : sections_)
      h *= (s.b0 + z_inv * (s.b1 + z_inv * s.b2)) / (1.0 + z_inv * (s.a1 + z_inv * s.a2));
    return std::abs(h);
  }

  /// scipy's default padding of the zero-phase filter, 3 (N + 1) samples at each end.
  std::size_t default_padding() const noexcept { return 3 * static_cast<std::size_t>(order_ + 1); }

  /// Padding long enough for the filter's start-up transient to die out inside it: 1.5 N / (2 f_c) seconds at each
  /// end (the total pad 1.5 N / f_c recommended for acausal Butterworth filters of strong-motion records by Boore
  /// and Bommer 2005), capped at n - 1 samples by the caller.
  std::size_t transient_padding() const noexcept {
    return static_cast<std::size_t>(std::ceil(0.75 * order_ / (corner_hz_ * dt_)));
  }

  /// Zero-phase filtering of a record: filtfilt() with transient_padding() (at least default_padding(), at most
  /// n - 1 samples).
  std::vector<double> filtfilt_record(std::span<const double> x) const {
    const std::size_t cap = x.empty() ? 0 : x.size() - 1;
    return filtfilt(x, std::min(std::max(transient_padding(), default_padding()), cap));
  }

  /// One causal pass. `initial` scales the steady-state initial conditions: the filter starts as if the input had
  /// been `initial` forever (0: at rest).
  std::vector<double> apply(std::span<const double> x, double initial = 0.0) const {
    std::vector<double> y(x.begin(), x.end());
    double scale = initial;  // steady-state input of the current section
    for (const auto& s : sections_) {
      // Transposed direct form II state for a constant input `scale`: y = H(1) scale.
      const double h = s.dc_gain();
      double z2 = (s.b2 - s.a2 * h) * scale;
      double z1 = (s.b1 + s.b2 - (s.a1 + s.a2) * h) * scale;
      for (double& v : y) {
        const double in = v;
        const double out = s.b0 * in + z1;
        z1 = s.b1 * in - s.a1 * out + z2;
        z2 = s.b2 * in - s.a2 * out;
        v = out;
      }
      scale *= h;
    }
    return y;
  }

  /// Zero-phase forward-backward filtering (gain |H|^2, no phase shift), as scipy.signal.sosfiltfilt: the signal is
  /// extended at both ends by `padding` samples of its odd (point-symmetric) reflection, which continues its value
  /// and slope, and each pass starts in the steady state of its first input. The padding defaults to
  /// default_padding() and must be less than the number of samples.
  std::vector<double> filtfilt(std::span<const double> x, std::optional<std::size_t> padding = {}) const {
    const std::size_t pad = padding.value_or(default_padding());
    if (x.size() <= pad)
      throw InvalidArgument("butterworth filter: zero-phase filtering with a padding of " + std::to_string(pad) +
                            " samples needs more than " + std::to_string(pad) + " samples, got " +
                            std::to_string(x.size()));
    const std::size_t n = x.size();
    std::vector<double> extended;
    extended.reserve(n + 2 * pad);
    for (std::size_t i = pad; i >= 1; --i) extended.push_back(2.0 * x[0] - x[i]);  // odd extension
    extended.insert(extended.end(), x.begin(), x.end());
    for (std::size_t i = 1; i <= pad; ++i) extended.push_back(2.0 * x[n - 1] - x[n - 1 - i]);

    auto forward = apply(extended, extended.front());
    std::vector<double> reversed(forward.rbegin(), forward.rend());
    auto backward = apply(reversed, reversed.front());
    return std::vector<double>(backward.rbegin() + static_cast<std::ptrdiff_t>(pad),
                               backward.rend() - static_cast<std::ptrdiff_t>(pad));
  }

 private:
  FilterType type_;
  int order_;
  double corner_hz_;
  double dt_;
  std::vector<SecondOrderSection> sections_;
};

}  // namespace blockdem::motion
