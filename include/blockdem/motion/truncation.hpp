#pragma once
// Truncation of a record to a time window, or to the interval between two fractions of its Arias intensity, with the
// fraction of the Arias intensity the cut keeps (the paper's 15 s window keeps 97 % of the 25 s AQA sample, Sect. 2).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "blockdem/core/error.hpp"
#include "blockdem/motion/arias.hpp"
#include "blockdem/motion/record.hpp"

namespace blockdem::motion {

struct Truncation {
  Record record;                // the cut, with start_time = start
  double start = 0.0;           // s, time of its first sample in the original record
  double end = 0.0;             // s, time of its last sample
  double arias_fraction = 0.0;  // Arias intensity of [start, end] over that of the whole record
};

/// Keeps the samples from the last one at or before `start_s` to the first one at or after `end_s` (times in s on
/// the record's clock), clamped to the record.
inline Truncation truncate_window(const Record& record, double start_s, double end_s) {
  record.validate("truncate");
  if (!(start_s < end_s) || !std::isfinite(start_s) || !std::isfinite(end_s))
    throw InvalidArgument("truncate: the window start " + std::to_string(start_s) + " s must be before its end " +
                          std::to_string(end_s) + " s");
  if (end_s <= record.start_time || start_s >= record.end_time())
    throw InvalidArgument("truncate: the window [" + std::to_string(start_s) + ", " + std::to_string(end_s) +
                          "] s lies outside the record, which spans [" + std::to_string(record.start_time) + ", " +
                          std::to_string(record.end_time()) + "] s");
  const double last = static_cast<double>(record.size() - 1);
  const double x0 = std::clamp((start_s - record.start_time) / record.dt, 0.0, last);
  const double x1 = std::clamp((end_s - record.start_time) / record.dt, 0.0, last);
  const auto i0 = static_cast<std::size_t>(std::floor(x0 + 1e-9));
  auto i1 = static_cast<std::size_t>(std::ceil(x1 - 1e-9));
  if (i1 <= i0) i1 = i0 + 1;

  const auto history = arias_intensity_history(record);
  Truncation cut;
  cut.start = record.time(i0);
  cut.end = record.time(i1);
  cut.arias_fraction = history.back() > 0.0 ? (history[i1] - history[i0]) / history.back() : 0.0;
  cut.record = record;
  cut.record.acceleration.assign(record.acceleration.begin() + static_cast<std::ptrdiff_t>(i0),
                                 record.acceleration.begin() + static_cast<std::ptrdiff_t>(i1) + 1);
  cut.record.start_time = cut.start;
  cut.record.header_pga.reset();  // the provider's peak may lie outside the cut
  char label[96];
  std::snprintf(label, sizeof label, " [%.4g-%.4g s]", cut.start, cut.end);
  cut.record.name += label;
  return cut;
}

/// Keeps the interval in which the Arias intensity grows from `lower` to `upper` of its total (5-95 % by default).
inline Truncation truncate_arias(const Record& record, double lower = 0.05, double upper = 0.95) {
  const auto interval = significant_duration(record, lower, upper);
  return truncate_window(record, interval.start, interval.end);
}

}  // namespace blockdem::motion
