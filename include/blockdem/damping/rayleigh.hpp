#pragma once
// Rayleigh damping C = alpha M + beta K (paper eq. 9-11).

#include "blockdem/core/constexpr_math.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/damping/mass_proportional.hpp"
#include "blockdem/damping/stiffness_proportional.hpp"

namespace blockdem::damping {

struct Rayleigh {
  double alpha = 0.0;  // 1/s, mass-proportional coefficient
  double beta = 0.0;   // s, stiffness-proportional coefficient

  /// The coefficients whose damping ratio is zeta_1 at f_1 and zeta_2 at f_2 (eq. 10 written at two frequencies).
  /// Throws InvalidArgument unless 0 < f_1 < f_2 and both ratios are non-negative.
  static constexpr Rayleigh from_two_frequencies(double zeta_1, double f_1_hz, double zeta_2, double f_2_hz) {
    if (!(f_1_hz > 0.0) || !(f_2_hz > f_1_hz))
      throw InvalidArgument("rayleigh damping: frequencies must satisfy 0 < f_1 < f_2 (Hz)");
    if (!(zeta_1 >= 0.0) || !(zeta_2 >= 0.0))
      throw InvalidArgument("rayleigh damping: damping ratios must be >= 0");
    const double w1 = angular_frequency(f_1_hz);
    const double w2 = angular_frequency(f_2_hz);
    const double d = w2 * w2 - w1 * w1;
    return {2.0 * w1 * w2 * (zeta_1 * w2 - zeta_2 * w1) / d, 2.0 * (zeta_2 * w2 - zeta_1 * w1) / d};
  }

  /// zeta(omega) = (alpha / omega + beta omega) / 2 (eq. 10); omega in rad/s.
  constexpr double damping_ratio(double omega) const noexcept { return 0.5 * (alpha / omega + beta * omega); }

  /// Reduction of the critical timestep by the stiffness-proportional part (eq. 11).
  constexpr double timestep_factor(double omega_max) const noexcept {
    return StiffnessProportional{beta}.timestep_factor(omega_max);
  }

  // DampingPolicy: the mass part on every degree of freedom, the stiffness part as dashpots on the springs;
  // each is the policy of its own file (the mass part in the frame of damping/frame.hpp).
  static constexpr bool damps_velocities = true;
  using ContactState = StiffnessProportional::ContactState;
  constexpr double spring_stress(ContactState& previous, double stiffness, double du, double dt, bool active,
                                 double& dissipated) const noexcept {
    return StiffnessProportional{beta}.spring_stress(previous, stiffness, du, dt, active, dissipated);
  }
  static constexpr double held_stress(const ContactState& previous) noexcept { return previous; }
  constexpr double velocity_update(double v, double force, Inertia mass, double dt, double& dissipated) const noexcept {
    return MassProportional{alpha}.velocity_update(v, force, mass, dt, dissipated);
  }
};

static_assert(DampingPolicy<Rayleigh>);

}  // namespace blockdem::damping
