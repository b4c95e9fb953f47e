#pragma once
// Amplitude scaling and resampling of a record; a record from samples at uneven times.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
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
  // A step far below the record's would make more samples than memory holds (std::bad_alloc).
  if (const double samples = std::floor(record.duration() / dt * (1.0 + 1e-12)) + 1; !(samples <= 1e8)) {
    char text[160];
    std::snprintf(text, sizeof text, "resample: the new time step %g s makes %.3g samples (more than 1e8: the step must "
                  "be >= %g s) of ", dt, samples, record.duration() / 1e8);
    throw InvalidArgument(text + record.name);
  }
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

/// The record of accelerations (m/s^2) given at increasing, not necessarily even, times (s): the polyline through
/// them, sampled from the first time to the last at the longest even step no longer than their shortest one (to
/// 1e-6: the rounding of decimal times adds no step). Evenly spaced samples come back as they were, to rounding;
/// the corners of uneven ones are kept where they fall on the new grid. Errors name `name`.
inline Record record_from_samples(const std::vector<double>& times, const std::vector<double>& acceleration,
                                  const std::string& name) {
  if (times.size() != acceleration.size())
    throw InvalidArgument(name + ": " + std::to_string(times.size()) + " times for " +
                          std::to_string(acceleration.size()) + " accelerations");
  if (times.size() < 2) throw InvalidArgument(name + ": a record needs at least 2 samples");
  double shortest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (!std::isfinite(times[i]) || !std::isfinite(acceleration[i]))
      throw InvalidArgument(name + ": sample " + std::to_string(i) + " is not finite");
    if (i > 0) {
      if (!(times[i] > times[i - 1]))
        throw InvalidArgument(name + ": time " + std::to_string(times[i]) + " s of sample " + std::to_string(i) +
                              " does not increase");
      shortest = std::min(shortest, times[i] - times[i - 1]);
    }
  }
  const double span = times.back() - times.front();
  const double even_steps = std::ceil(span / shortest * (1.0 - 1e-6));
  if (!(even_steps <= 1e8))
    throw InvalidArgument(name + ": its shortest step, " + std::to_string(shortest) +
                          " s, would need more than 1e8 even ones");
  const auto steps = static_cast<std::size_t>(even_steps);
  Record record;
  record.name = name;
  record.source = "samples at given times";
  record.dt = span / static_cast<double>(steps);
  record.start_time = times.front();
  record.acceleration.resize(steps + 1);
  std::size_t k = 0;  // times[k] <= t < times[k + 1]
  for (std::size_t j = 0; j <= steps; ++j) {
    const double t = j == steps ? times.back() : record.time(j);
    while (k + 2 < times.size() && times[k + 1] <= t) ++k;
    const double f = std::clamp((t - times[k]) / (times[k + 1] - times[k]), 0.0, 1.0);
    record.acceleration[j] = (1.0 - f) * acceleration[k] + f * acceleration[k + 1];
  }
  return record;
}

}  // namespace blockdem::motion
