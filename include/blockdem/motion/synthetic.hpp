#pragma once
// A deterministic synthetic ground motion with prescribed peaks, and the default that stands in for the AQA75 input
// of the paper (Sect. 2): the L'Aquila 2009 AQA record is not redistributable, so blockdem generates a record with
// its published peaks (PGA 4.25 m/s^2, PGV 26.33 cm/s, PGD 37.0 mm), its dominant period (0.526 s) and its length
// (25 s). It is SYNTHETIC, not the recording: every record it returns says so in its name, source and flag. And a
// ramp to a constant acceleration, the simplest test input.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/random.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/butterworth.hpp"
#include "blockdem/motion/integration.hpp"
#include "blockdem/motion/pulse.hpp"
#include "blockdem/motion/record.hpp"

namespace blockdem::motion {

/// The recipe of a synthetic record: a velocity pulse (eq. 31) that sets the dominant period, a long-period pulse
/// that sets the displacement, and band-limited noise under a Saragoni-Hart envelope that sets the peak
/// acceleration. The three amplitudes are solved so that PGA, PGV and PGD are met to 1e-9 relative.
struct SyntheticRecordSpec {
  std::string name = "synthetic";
  double pga = 4.25;             // m/s^2
  double pgv = 0.2633;           // m/s
  double pgd = 0.037;            // m
  double duration = 25.0;        // s
  double dt = 0.005;             // s
  double pulse_period = 0.532;   // s, carrier period of the main pulse (its PSV peaks at 0.526 s)
  double pulse_gamma = 8.0;      // envelope width of the main pulse, in carrier periods
  double pulse_centre = 3.0;     // s
  double long_period = 2.5;      // s, carrier period of the displacement pulse
  double long_gamma = 2.0;
  double long_centre = 4.0;      // s
  double noise_peak_time = 3.0;  // s, peak of the Saragoni-Hart envelope (t/tm)^b exp(b (1 - t/tm))
  double noise_shape = 0.825;    // b
  double noise_low_hz = 3.0;     // Hz, band of the noise (4th-order Butterworth edges)
  double noise_high_hz = 15.0;   // Hz
  std::uint64_t seed = 20090406;
};


/// Generates the record of `spec`. Throws InvalidArgument for non-positive targets or a spec whose peaks cannot be
/// met (the solve does not converge).
inline Record synthetic_record(const SyntheticRecordSpec& spec) {
  if (!(spec.pga > 0.0 && spec.pgv > 0.0 && spec.pgd > 0.0))
    throw InvalidArgument("synthetic record: PGA, PGV and PGD must be > 0");
  if (!(spec.dt > 0.0 && spec.duration > 100.0 * spec.dt))
    throw InvalidArgument("synthetic record: need dt > 0 and a duration of at least 100 steps");
  const auto n = static_cast<std::size_t>(std::llround(spec.duration / spec.dt)) + 1;

  Record shape;
  shape.dt = spec.dt;
  shape.acceleration.assign(n, 0.0);
  // phase pi/2 makes both pulses' velocity odd about their centre, so they leave no residual displacement.
  const MavroeidisPapageorgiouPulse pulse{1.0, spec.pulse_gamma, spec.pulse_period, spec.pulse_centre, 0.5 * pi};
  const MavroeidisPapageorgiouPulse long_pulse{1.0, spec.long_gamma, spec.long_period, spec.long_centre, 0.5 * pi};
  std::vector<double> a_pulse(n), a_long(n), a_noise(n);
  for (std::size_t i = 0; i < n; ++i) {
    a_pulse[i] = pulse.acceleration(shape.time(i));
    a_long[i] = long_pulse.acceleration(shape.time(i));
  }
  SplitMix64 random(spec.seed);
  for (double& x : a_noise) x = random.normal();
  const ButterworthFilter low(FilterType::lowpass, 4, spec.noise_high_hz, spec.dt);
  const ButterworthFilter high(FilterType::highpass, 4, spec.noise_low_hz, spec.dt);
  a_noise = high.filtfilt(low.filtfilt(a_noise));
  for (std::size_t i = 0; i < n; ++i) {
    const double x = shape.time(i) / spec.noise_peak_time;
    a_noise[i] *= std::pow(x, spec.noise_shape) * std::exp(spec.noise_shape * (1.0 - x));
  }
  // The envelope brings back low frequencies; high-pass again, then subtract the straight line p0 + p1 t whose
  // velocity and displacement cancel the noise's at the end, so that the record ends at rest where it started.
  a_noise = high.filtfilt(a_noise);
  {
    shape.acceleration = a_noise;
    const auto motion = integrate(shape);
    const double t = shape.duration();
    // int_0^T (p0 + p1 t) dt = V, int_0^T int (p0 + p1 t) = U; exact for our integrators since the line is linear.
    const double v_end = motion.velocity.back(), u_end = motion.displacement.back();
    const double det = t * t * t * t / 6.0 - t * t * t * t / 4.0;
    const double p0 = (v_end * t * t * t / 6.0 - u_end * t * t / 2.0) / det;
    const double p1 = (t * u_end - t * t / 2.0 * v_end) / det;
    for (std::size_t i = 0; i < n; ++i) a_noise[i] -= p0 + p1 * shape.time(i);
  }

  // Each amplitude mostly drives one peak (noise: PGA, pulse: PGV, long pulse: PGD): rescale each by the ratio of
  // target to current peak until all three are met.
  double c_noise = spec.pga / peak_absolute(a_noise);
  double c_pulse = spec.pgv;
  double c_long = 0.2 * spec.pgd * two_pi / spec.long_period;
  for (int iteration = 0;; ++iteration) {
    for (std::size_t i = 0; i < n; ++i)
      shape.acceleration[i] = c_noise * a_noise[i] + c_pulse * a_pulse[i] + c_long * a_long[i];
    const auto peaks = peak_values(shape);
    const double ra = spec.pga / peaks.pga, rv = spec.pgv / peaks.pgv, rd = spec.pgd / peaks.pgd;
    if (std::abs(ra - 1.0) < 1e-12 && std::abs(rv - 1.0) < 1e-12 && std::abs(rd - 1.0) < 1e-12) break;
    if (iteration == 500 || !(c_noise > 0.0 && c_pulse > 0.0 && c_long > 0.0))
      throw InvalidArgument("synthetic record: the peaks PGA " + std::to_string(spec.pga) + " m/s^2, PGV " +
                            std::to_string(spec.pgv) + " m/s, PGD " + std::to_string(spec.pgd) +
                            " m cannot be met with this recipe");
    c_noise *= ra;
    c_pulse *= rv;
    c_long *= rd;
  }
  shape.name = spec.name;
  shape.source = "synthetic (generated by blockdem; not a recording)";
  shape.synthetic = true;
  return shape;
}

/// The recipe of the AQA75 stand-in. Besides the peaks and the dominant period it was tuned to resemble the
/// published record in duration: 5-95 % significant duration 8.31 s (paper 8.28 s), 10-90 % 5.62 s (5.34 s), and a
/// wavelet window of 0.88-5.14 s (0.86-5.20 s, Sect. 6.1.2); its first 15 s hold 99.6 % of the Arias intensity
/// (the paper's 97 %).
inline SyntheticRecordSpec aqa75_spec() {
  SyntheticRecordSpec spec;
  spec.name = "synthetic AQA75 stand-in (NOT the AQA record)";
  return spec;
}

/// The synthetic stand-in for the paper's AQA75 input (Sect. 2): PGA 4.25 m/s^2, PGV 26.33 cm/s, PGD 37.0 mm,
/// dominant period 0.526 s, 25 s at dt = 0.005 s. Synthetic: it is not the AQA recording.
inline Record synthetic_aqa75() { return synthetic_record(aqa75_spec()); }

/// An acceleration rising linearly from 0 to `level` (m/s^2) over `ramp` s (0: a step) and held, sampled every `dt` s
/// from 0 to at least `duration` s. A ramp long against a model's periods loads it quasi-statically; a step makes an
/// undamped one overshoot to twice the static response.
inline Record ramp_record(double level, double ramp, double duration, double dt) {
  if (!std::isfinite(level)) throw InvalidArgument("ramp record: the level must be finite");
  if (!(ramp >= 0.0) || !std::isfinite(ramp)) throw InvalidArgument("ramp record: the ramp time must be >= 0 s");
  if (!(dt > 0.0) || !std::isfinite(dt)) throw InvalidArgument("ramp record: the time step must be > 0 s");
  if (!(duration >= dt) || !(duration / dt < 1e8))
    throw InvalidArgument("ramp record: the duration must be at least one time step and at most 1e8 of them");
  Record record;
  record.name = "ramp to " + std::to_string(level) + " m/s^2 over " + std::to_string(ramp) + " s";
  record.source = "synthetic (ramp)";
  record.synthetic = true;
  record.dt = dt;
  const auto n = static_cast<std::size_t>(std::ceil(duration / dt * (1.0 - 1e-12))) + 1;
  record.acceleration.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = record.time(i);
    record.acceleration[i] = ramp > 0.0 ? level * std::min(1.0, t / ramp) : level;
  }
  return record;
}

}  // namespace blockdem::motion
