#pragma once
// The Mavroeidis-Papageorgiou velocity pulse (Mavroeidis and Papageorgiou 2003; paper eq. 31): a cosine carrier of
// period T_p under a raised-cosine envelope of width gamma T_p centred at t_0, with its closed-form acceleration
// (derivative) and displacement (integral from the start of the support).

#include <cmath>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/record.hpp"

namespace blockdem::motion {

struct MavroeidisPapageorgiouPulse {
  double amplitude = 0.0;  // m/s, A
  double gamma = 2.0;      // envelope width in carrier periods, > 1
  double period = 1.0;     // s, carrier period T_p
  double t0 = 0.0;         // s, centre of the envelope
  double phase = 0.0;      // rad, phase of the carrier at t_0

  /// Throws InvalidArgument unless gamma > 1, T_p > 0 and all fields are finite.
  void validate() const {
    if (!(gamma > 1.0) || !std::isfinite(gamma))
      throw InvalidArgument("M&P pulse: gamma = " + std::to_string(gamma) + " must be > 1");
    if (!(period > 0.0) || !std::isfinite(period))
      throw InvalidArgument("M&P pulse: period T_p = " + std::to_string(period) + " s must be > 0");
    if (!std::isfinite(amplitude) || !std::isfinite(t0) || !std::isfinite(phase))
      throw InvalidArgument("M&P pulse: amplitude, t0 and phase must be finite");
  }

  /// Support [t_0 - gamma T_p / 2, t_0 + gamma T_p / 2] in s; the pulse (velocity, acceleration) is zero outside.
  double start() const noexcept { return t0 - 0.5 * gamma * period; }
  double end() const noexcept { return t0 + 0.5 * gamma * period; }
  bool inside(double t) const noexcept { return t >= start() && t <= end(); }

  double carrier_frequency() const noexcept { return two_pi / period; }             // rad/s
  double envelope_frequency() const noexcept { return two_pi / (gamma * period); }  // rad/s

  /// Velocity in m/s (eq. 31).
  double velocity(double t) const noexcept {
    if (!inside(t)) return 0.0;
    const double tau = t - t0;
    return 0.5 * amplitude * (1.0 + std::cos(envelope_frequency() * tau)) *
           std::cos(carrier_frequency() * tau + phase);  // eq. 31
  }

  /// Acceleration in m/s^2: the derivative of eq. 31.
  double acceleration(double t) const noexcept {
    if (!inside(t)) return 0.0;
    const double tau = t - t0;
    const double we = envelope_frequency();
    const double wp = carrier_frequency();
    return -0.5 * amplitude *
           (we * std::sin(we * tau) * std::cos(wp * tau + phase) +
            (1.0 + std::cos(we * tau)) * wp * std::sin(wp * tau + phase));
  }

  /// Displacement in m: the integral of eq. 31 from the start of the support (zero before it, constant after it).
  /// Written as three carriers, (A/2) cos(wp tau + phi) + (A/4) [cos((wp + we) tau + phi) + cos((wp - we) tau + phi)],
  /// each integrated exactly; wp - we = wp (1 - 1/gamma) is non-zero because gamma > 1.
  double displacement(double t) const noexcept {
    if (t <= start()) return 0.0;
    const double half = 0.5 * gamma * period;
    const double tau = std::min(t - t0, half);
    const auto primitive = [&](double x) {
      const double wp = carrier_frequency();
      const double we = envelope_frequency();
      return 0.5 * amplitude * std::sin(wp * x + phase) / wp +
             0.25 * amplitude *
                 (std::sin((wp + we) * x + phase) / (wp + we) + std::sin((wp - we) * x + phase) / (wp - we));
    };
    return primitive(tau) - primitive(-half);
  }
};

/// The pulse sampled as an acceleration record over [start, start + (n - 1) dt].
inline Record to_record(const MavroeidisPapageorgiouPulse& pulse, double dt, std::size_t n, double start = 0.0) {
  pulse.validate();
  Record record;
  record.name = "M&P pulse";
  record.source = "synthetic (Mavroeidis-Papageorgiou pulse, eq. 31)";
  record.synthetic = true;
  record.dt = dt;
  record.start_time = start;
  record.acceleration.resize(n);
  for (std::size_t i = 0; i < n; ++i) record.acceleration[i] = pulse.acceleration(record.time(i));
  return record;
}

}  // namespace blockdem::motion
