#pragma once
// Amplitude scaling and resampling of a record.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/motion/butterworth.hpp"
#include "blockdem/motion/integration.hpp"
#include "blockdem/motion/record.hpp"

namespace blockdem::motion {

/// Multiplies the acceleration by `factor` (any finite value; the paper's AQA75 is the record at 0.75).
inline Record scale(Record record, double factor) {
  if (!std::isfinite(factor)) throw InvalidArgument("scale: the factor must be finite");
  for (double& a : record.acceleration) a *= factor;
  if (record.header_pga) record.header_pga = *record.header_pga * std::abs(factor);
  return record;
}

/// Scales the record so that its peak absolute acceleration is `target_pga` (m/s^2, > 0).
inline Record scale_to_pga(Record record, double target_pga) {
  if (!(target_pga > 0.0) || !std::isfinite(target_pga))
    throw InvalidArgument("scale: target PGA " + std::to_string(target_pga) + " m/s^2 must be > 0");
  const double pga = peak_absolute(record.acceleration);
  if (!(pga > 0.0)) throw InvalidArgument(record.name + ": cannot scale a record whose samples are all zero");
  return scale(std::move(record), target_pga / pga);
}

/// Resamples to the time step `dt` (s) by linear interpolation, over the same time span. When the new step is longer
/// than the old, a zero-phase order-8 Butterworth low-pass at 0.8 times the new Nyquist frequency removes the
/// content that would alias first.
inline Record resample(Record record, double dt) {
  record.validate("resample");
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw InvalidArgument("resample: the new time step " + std::to_string(dt) + " s must be > 0");
  if (dt > 0.5 * record.duration())
    throw InvalidArgument("resample: the new time step " + std::to_string(dt) + " s leaves fewer than 3 samples of " +
                          record.name);
  std::vector<double> source = record.acceleration;
  if (dt > record.dt * (1.0 + 1e-12)) {
    const ButterworthFilter antialias(FilterType::lowpass, 8, 0.8 * 0.5 / dt, record.dt);
    source = antialias.filtfilt_record(source);
  }
  const auto count = static_cast<std::size_t>(std::floor(record.duration() / dt * (1.0 + 1e-12))) + 1;
  std::vector<double> resampled(count);
  for (std::size_t j = 0; j < count; ++j) {
    const double x = static_cast<double>(j) * dt / record.dt;
    const auto i = std::min(static_cast<std::size_t>(x), source.size() - 2);
    const double s = x - static_cast<double>(i);
    resampled[j] = (1.0 - s) * source[i] + s * source[i + 1];
  }
  record.acceleration = std::move(resampled);
  record.dt = dt;
  return record;
}

}  // namespace blockdem::motion
