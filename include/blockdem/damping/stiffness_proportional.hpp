#pragma once
// Stiffness-proportional viscous damping, the C = beta K half of Rayleigh damping (paper eq. 9-11).

#include "blockdem/core/constexpr_math.hpp"
#include "blockdem/core/units.hpp"

namespace blockdem::damping {

/// Stiffness-proportional damping: a dashpot beta k in parallel with every spring of stiffness k. beta in s.
struct StiffnessProportional {
  double beta = 0.0;  // s

  /// The coefficient that gives `damping_ratio` at `frequency_hz`.
  static constexpr StiffnessProportional from_damping_ratio(double damping_ratio, double frequency_hz) noexcept {
    return {2.0 * damping_ratio / angular_frequency(frequency_hz)};
  }

  /// zeta(omega) = beta omega / 2, eq. 10 with alpha = 0; omega in rad/s.
  constexpr double damping_ratio(double omega) const noexcept { return 0.5 * beta * omega; }

  /// Reduction of the critical timestep, sqrt(1 + zeta^2) - zeta with zeta at omega_max (eq. 11).
  constexpr double timestep_factor(double omega_max) const noexcept {
    const double z = damping_ratio(omega_max);
    return cmath::sqrt(1.0 + z * z) - z;
  }
};

}  // namespace blockdem::damping
