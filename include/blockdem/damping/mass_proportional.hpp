#pragma once
// Mass-proportional viscous damping, the C = alpha M half of Rayleigh damping (paper eq. 9-10).

#include "blockdem/core/units.hpp"
#include "blockdem/damping/concepts.hpp"

namespace blockdem::damping {

/// Mass-proportional damping, force -alpha m v on every degree of freedom. alpha in 1/s.
/// Its damping ratio falls as 1/omega: it over-damps low frequencies and under-damps high ones (paper Fig. 8).
struct MassProportional {
  double alpha = 0.0;  // 1/s

  /// The coefficient that gives `damping_ratio` at `centre_hz` (the paper's MassProp: 4 % at 7.5 Hz).
  static constexpr MassProportional from_damping_ratio(double damping_ratio, double centre_hz) noexcept {
    return {2.0 * damping_ratio * angular_frequency(centre_hz)};
  }

  /// zeta(omega) = alpha / (2 omega), eq. 10 with beta = 0; omega in rad/s.
  constexpr double damping_ratio(double omega) const noexcept { return alpha / (2.0 * omega); }

  // DampingPolicy: acts on every degree of freedom (translations and rotations), not on the springs; translations
  // relative to the table or to the ground (damping/frame.hpp).
  static constexpr bool damps_velocities = true;
  using ContactState = NoState;
  constexpr double spring_stress(ContactState&, double, double, double, bool, double&) const noexcept { return 0.0; }
  static constexpr double held_stress(const ContactState&) noexcept { return 0.0; }
  constexpr double velocity_update(double v, double force, Inertia mass, double dt, double& dissipated) const noexcept {
    return mass_damped_velocity_update(alpha, v, force, mass, dt, dissipated);
  }
  /// Mass-proportional damping at mid-step velocities does not lower the critical timestep.
  constexpr double timestep_factor(double) const noexcept { return 1.0; }
};

static_assert(DampingPolicy<MassProportional>);

}  // namespace blockdem::damping
