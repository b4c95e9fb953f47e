#pragma once
// Bounds that no earthquake reaches: a run that goes wrong stops and says why. Every few steps the
// simulation checks that each block's and node's velocity is finite and below a speed no shaking gives; a run that
// crosses either has diverged (a timestep above the critical one, a stiffness the timestep cannot follow) or lost a
// block, and RunawayError stops it naming the block or node, the time, the step and the value, instead of letting
// it write NaN or flying blocks as results.

#include <cmath>
#include <cstdio>
#include <string>

#include "blockdem/core/error.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

struct RunGuard {
  double max_speed = 100;   // m/s: far beyond any table or block under an earthquake (PGV is below 2 m/s)
  int check_interval = 16;  // steps between checks (a check costs one pass over the blocks and nodes)

  void validate() const {
    if (!(max_speed > 0) || !std::isfinite(max_speed))
      throw InvalidArgument("run guard: max speed must be > 0 m/s and finite, got " + std::to_string(max_speed));
    if (check_interval < 1 || check_interval > 1000000)
      throw InvalidArgument("run guard: check interval must be in 1..1000000 steps, got " + std::to_string(check_interval));
  }
};

namespace detail {
[[noreturn]] inline void runaway(double time, long long step, const std::string& what, const char* quantity, double value,
                                 double bound) {
  char text[512];
  if (std::isfinite(value))
    std::snprintf(text, sizeof text, "t = %.6g s (step %lld): %s moves at %.4g m/s (%s), beyond %.4g m/s that no "
                  "earthquake gives: the run diverged (a timestep above the critical one?) or the block was thrown off",
                  time, step, what.c_str(), value, quantity, bound);
  else
    std::snprintf(text, sizeof text, "t = %.6g s (step %lld): the %s of %s is not finite: the run diverged (a timestep "
                  "above the critical one, or a stiffness the timestep cannot follow)", time, step, quantity, what.c_str());
  throw RunawayError(text);
}
}  // namespace detail

/// Throws RunawayError naming the first block or node whose velocity (or a block's angular velocity) is not finite,
/// or whose speed exceeds guard.max_speed.
inline void check_velocities(const model::Model& m, const RunGuard& guard, double time, long long step) {
  const auto& b = m.bodies;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const double speed = b.velocity[i].norm();
    const double spin = b.angular_velocity[i].norm();
    if (speed <= guard.max_speed && std::isfinite(spin)) continue;
    const std::string what = "block '" + b.name[i] + "' (" + std::to_string(i) + ")";
    if (!std::isfinite(spin)) detail::runaway(time, step, what, "angular velocity", spin, guard.max_speed);
    detail::runaway(time, step, what, "velocity", speed, guard.max_speed);
  }
  const auto& n = m.deformable.nodes;
  for (std::size_t i = 0; i < n.velocity.size(); ++i) {
    const double speed = n.velocity[i].norm();
    if (speed <= guard.max_speed) continue;
    detail::runaway(time, step, "node " + std::to_string(i) + " of block '" + b.name[n.block[i]] + "'", "velocity", speed,
                    guard.max_speed);
  }
}

}  // namespace blockdem
