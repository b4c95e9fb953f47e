#pragma once
// Stiffness-proportional viscous damping, the C = beta K half of Rayleigh damping (paper eq. 9-11).

#include "blockdem/core/constexpr_math.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/concepts.hpp"

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

  // DampingPolicy: a dashpot beta k on each spring, at the rate of the last step (the lagged velocity for which
  // eq. 11 is the exact stability limit of the central-difference scheme).
  /// The dashpot stress of the previous step: its work is completed with this step's increment, so that the
  /// dissipation booked is that of the central-difference kick, 1/2 stress (du_n + du_n+1), exactly.
  using ContactState = double;
  constexpr double spring_stress(ContactState& previous, double stiffness, double du, double dt, bool active,
                                 double& dissipated) const noexcept {
    if (dt <= 0.0) return active ? previous : 0.0;  // no time passes (forces recomputed after a detection)
    const double stress = active ? beta * stiffness * du / dt : 0.0;
    dissipated += 0.5 * (previous + stress) * du;
    previous = stress;
    return stress;
  }
  static constexpr double held_stress(const ContactState& previous) noexcept { return previous; }
  constexpr double velocity_update(double v, double force, Inertia mass, double dt, double&) const noexcept {
    return undamped_velocity_update(v, force, mass, dt);
  }
};

static_assert(DampingPolicy<StiffnessProportional>);

}  // namespace blockdem::damping
