#pragma once
// The DampingPolicy concept: what the fused explicit loop asks of a viscous damping scheme.

#include <concepts>

namespace blockdem::damping {

/// A damping policy provides
/// - `ContactState`: per contact point and spring direction (normal, shear 1, shear 2) state, e.g. the stresses of
///   the Maxwell branches; an empty struct if the policy does not act on springs;
/// - `spring_stress(state, stiffness, du, dt, active, dissipated) -> double`: the viscous stress (Pa) the policy adds
///   to a spring of stiffness (Pa/m) whose elongation grew by du (m) during the step dt (s); with active == false
///   (joint failed or open) it releases its state and returns 0; adds the work its elements received (J/m^2) to
///   `dissipated` (policies with springs of their own also provide `stored_energy(state, stiffness)`, which the
///   energy report subtracts from that work);
/// - `held_stress(state) -> double`: the viscous stress (Pa) the state holds, the one spring_stress returned last
///   while the joint is active (the contact pass stores no traction per CP; output asks the state);
/// - `velocity_update(v, force, inertia, dt, dissipated) -> double`: the central-difference update of one degree
///   of freedom, velocity v (m/s or rad/s) at the half step, force (N or N m), inertia the mass (kg) or principal
///   moment of inertia (kg m^2) with its inverse; adds the energy its damping force dissipated (J) to `dissipated`;
/// - `timestep_factor(omega_max) -> double`: the reduction of the critical timestep 2 / omega_max (eq. 11, eq. 20).
/// A mass or a principal moment of inertia with its inverse, both computed once per block: the velocity update
/// multiplies by the inverse (no division in the block loop), the dissipated energy uses the value.
struct Inertia {
  double value = 1;    // kg or kg m^2
  double inverse = 1;  // 1 / value
  static constexpr Inertia of(double value) noexcept { return {value, 1.0 / value}; }
};

template <class D>
concept DampingPolicy = requires(const D& d, typename D::ContactState& s, double x, bool active, double& e, Inertia m) {
  { d.spring_stress(s, x, x, x, active, e) } noexcept -> std::same_as<double>;
  { D::held_stress(s) } noexcept -> std::same_as<double>;
  { d.velocity_update(x, x, m, x, e) } noexcept -> std::same_as<double>;
  { d.timestep_factor(x) } noexcept -> std::convertible_to<double>;
};

/// Per-spring state of the policies that keep none.
struct NoState {};

/// The plain central-difference velocity update, v+ = v- + dt F / m.
constexpr double undamped_velocity_update(double v, double force, Inertia mass, double dt) noexcept {
  return v + dt * force * mass.inverse;
}

/// v+ = ((1 - a dt/2) v- + dt F/m) / (1 + a dt/2): the damping force -a m v at the mid-step velocity (v- + v+)/2.
constexpr double mass_damped_velocity_update(double a, double v, double force, Inertia mass, double dt,
                                             double& dissipated) noexcept {
  const double h = 0.5 * a * dt;
  // 1 / (1 + h) is the same for every degree of freedom: the compiler hoists it out of the block loop.
  const double v_new = ((1.0 - h) * v + dt * force * mass.inverse) * (1.0 / (1.0 + h));
  const double v_mid = 0.5 * (v + v_new);
  dissipated += a * mass.value * v_mid * v_mid * dt;
  return v_new;
}

}  // namespace blockdem::damping
