#pragma once
// Cundall's local damping for static equilibrium: a force -c |F| sign(v) on every degree of freedom. Not viscous,
// not for dynamics: it brings a model to rest under gravity before a dynamic run.
//
// Its timestep: the sign is that of the velocity of the half step before, so a mode that changes sign every step
// (the highest, near the limit) sees the force amplified by (1 + c) instead of reduced: a stiffness (1 + c) k, so
// the explicit scheme holds for omega dt < 2 / sqrt(1 + c) (0.745 of 2 / omega for c = 0.8; tested on one
// degree of freedom, where it settles just below and diverges just above).

#include <array>

#include "blockdem/core/constexpr_math.hpp"
#include "blockdem/damping/concepts.hpp"

namespace blockdem::damping {

struct Local {
  double coefficient = 0.8;  // 3DEC's default
  // Deformable blocks: damp each block's rigid-body motion by its resultant force and moment, and its deformation
  // by the rest of each node's force (integrate/local_split.hpp), instead of every node by its own force. For static
  // solves where deformable blocks may form a mechanism; rigid blocks are damped the same either way.
  bool split_rigid_motion = false;
  /// Its bool members, which a checkpoint reader checks (io/checkpoint.hpp).
  static constexpr std::array<bool Local::*, 1> checkpoint_flags() { return {&Local::split_rigid_motion}; }
  using ContactState = NoState;
  constexpr double spring_stress(ContactState&, double, double, double, bool, double&) const noexcept { return 0.0; }
  static constexpr double held_stress(const ContactState&) noexcept { return 0.0; }
  constexpr double velocity_update(double v, double force, Inertia mass, double dt, double& dissipated) const noexcept {
    const double magnitude = force < 0 ? -force : force;
    const double damping_force = v > 0 ? -coefficient * magnitude : (v < 0 ? coefficient * magnitude : 0.0);
    const double v_new = v + dt * (force + damping_force) * mass.inverse;
    const double work = damping_force * 0.5 * (v + v_new) * dt;
    dissipated -= work;  // the damping force opposes the motion: its work is negative
    return v_new;
  }
  constexpr double timestep_factor(double) const noexcept { return 1.0 / cmath::sqrt(1.0 + coefficient); }
};

static_assert(DampingPolicy<Local>);

}  // namespace blockdem::damping
