#pragma once
// Ground velocity and displacement from the acceleration, and the peak values PGA, PGV, PGD. The acceleration is
// taken as linear between samples (the same assumption as the Nigam-Jennings spectrum), for which both integrals are
// exact; the motion starts at rest.

#include <algorithm>
#include <cmath>
#include <vector>

#include "blockdem/motion/record.hpp"

namespace blockdem::motion {

struct GroundMotion {
  std::vector<double> velocity;      // m/s
  std::vector<double> displacement;  // m
};

/// Velocity (trapezoid rule, exact for piecewise-linear acceleration) and displacement
/// u_{i+1} = u_i + v_i dt + dt^2 (a_i / 3 + a_{i+1} / 6), both zero at the first sample.
inline GroundMotion integrate(const Record& record) {
  const auto& a = record.acceleration;
  const double dt = record.dt;
  GroundMotion motion{std::vector<double>(a.size(), 0.0), std::vector<double>(a.size(), 0.0)};
  for (std::size_t i = 0; i + 1 < a.size(); ++i) {
    motion.velocity[i + 1] = motion.velocity[i] + 0.5 * dt * (a[i] + a[i + 1]);
    motion.displacement[i + 1] =
        motion.displacement[i] + dt * motion.velocity[i] + dt * dt * (a[i] / 3.0 + a[i + 1] / 6.0);
  }
  return motion;
}

inline double peak_absolute(const std::vector<double>& values) {
  double peak = 0.0;
  for (double v : values) peak = std::max(peak, std::abs(v));
  return peak;
}

struct PeakValues {
  double pga = 0.0;  // m/s^2
  double pgv = 0.0;  // m/s
  double pgd = 0.0;  // m
};

/// Largest absolute sample of acceleration, and of velocity and displacement integrated from rest.
inline PeakValues peak_values(const Record& record) {
  const auto motion = integrate(record);
  return {peak_absolute(record.acceleration), peak_absolute(motion.velocity), peak_absolute(motion.displacement)};
}

}  // namespace blockdem::motion
