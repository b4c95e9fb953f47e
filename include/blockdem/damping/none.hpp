#pragma once
// No viscous damping: energy is dissipated only by the joint laws (the paper's noDamp model).

#include "blockdem/damping/concepts.hpp"

namespace blockdem::damping {

struct None {
  using ContactState = NoState;
  constexpr double spring_stress(ContactState&, double, double, double, bool, double&) const noexcept { return 0.0; }
  static constexpr double held_stress(const ContactState&) noexcept { return 0.0; }
  constexpr double velocity_update(double v, double force, Inertia mass, double dt, double&) const noexcept {
    return undamped_velocity_update(v, force, mass, dt);
  }
  constexpr double timestep_factor(double) const noexcept { return 1.0; }
};

static_assert(DampingPolicy<None>);

}  // namespace blockdem::damping
