#pragma once
// Arias intensity I_A = pi / (2 g) int a^2 dt (DESIGN §7) and the significant durations between two fractions of it
// (5-95 % and 10-90 %, Trifunac and Brady 1975). The integral uses the trapezoid rule on a^2.

#include <cmath>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/record.hpp"

namespace blockdem::motion {

/// Cumulative Arias intensity in m/s at every sample (0 at the first).
inline std::vector<double> arias_intensity_history(const Record& record) {
  const auto& a = record.acceleration;
  std::vector<double> history(a.size(), 0.0);
  const double factor = pi / (2.0 * standard_gravity) * 0.5 * record.dt;
  for (std::size_t i = 0; i + 1 < a.size(); ++i)
    history[i + 1] = history[i] + factor * (a[i] * a[i] + a[i + 1] * a[i + 1]);
  return history;
}

/// Total Arias intensity in m/s.
inline double arias_intensity(const Record& record) {
  const auto history = arias_intensity_history(record);
  return history.empty() ? 0.0 : history.back();
}

/// Time in s at which the cumulative Arias intensity first reaches `fraction` of its total, interpolated linearly
/// between samples. Throws InvalidArgument for a fraction outside [0, 1] or a record without energy.
inline double arias_time(const Record& record, const std::vector<double>& history, double fraction) {
  if (!(fraction >= 0.0 && fraction <= 1.0))
    throw InvalidArgument("arias fraction " + std::to_string(fraction) + " is outside [0, 1]");
  if (history.empty() || !(history.back() > 0.0))
    throw InvalidArgument(record.name + ": the record has zero Arias intensity (all samples are zero)");
  const double target = fraction * history.back();
  if (target <= 0.0) {  // the first moment energy arrives
    std::size_t i = 0;
    while (i + 1 < history.size() && history[i + 1] <= 0.0) ++i;
    return record.time(i);
  }
  for (std::size_t i = 0; i + 1 < history.size(); ++i)
    if (history[i + 1] >= target) {
      const double s = (target - history[i]) / (history[i + 1] - history[i]);
      return record.time(i) + s * record.dt;
    }
  return record.end_time();
}

struct SignificantDuration {
  double start = 0.0;     // s, time at the lower fraction
  double end = 0.0;       // s, time at the upper fraction
  double duration = 0.0;  // s, end - start
};

/// Interval between the times at which the Arias intensity reaches `lower` and `upper` of its total
/// (0 <= lower < upper <= 1).
inline SignificantDuration significant_duration(const Record& record, double lower = 0.05, double upper = 0.95) {
  if (!(lower >= 0.0 && lower < upper && upper <= 1.0))
    throw InvalidArgument("significant duration: fractions must satisfy 0 <= lower < upper <= 1, got " +
                          std::to_string(lower) + " and " + std::to_string(upper));
  const auto history = arias_intensity_history(record);
  const double start = arias_time(record, history, lower);
  const double end = arias_time(record, history, upper);
  return {start, end, end - start};
}

}  // namespace blockdem::motion
