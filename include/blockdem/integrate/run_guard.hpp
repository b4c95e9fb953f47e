#pragma once
// Bounds that no earthquake reaches: a run that goes wrong stops and says why. Every few steps the simulation
// checks that each contact point's overlap is finite and shallower than a fraction of its contact's size, that each
// element's stress is finite, and that each block's and node's velocity is finite and below a speed no shaking
// gives. A run that crosses any of them has diverged (a timestep above the critical one, a stiffness the timestep
// cannot follow) or lost a block, and RunawayError stops it naming the block, node, element or contact, the
// component, the time, the step and the value, instead of letting it write NaN or flying blocks as results.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "blockdem/core/error.hpp"
#include "blockdem/integrate/block_pass.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

struct RunGuard {
  double max_speed = 100;     // m/s: far beyond any table or block under an earthquake (PGV is below 2 m/s)
  int check_interval = 16;    // steps between checks (a check costs one pass over the blocks, nodes and CPs)
  double max_overlap = 0.25;  // of a contact's size (the square root of its area): joints crush long before
  double overlap_floor = 0.01;  // m: the bound of small contacts (a sliver at a corner, a node's share of a face)

  void validate() const {
    if (!(max_speed > 0) || !std::isfinite(max_speed))
      throw InvalidArgument("run guard: max speed must be > 0 m/s and finite, got " + std::to_string(max_speed));
    if (!(max_overlap > 0 && max_overlap <= 10))
      throw InvalidArgument("run guard: max overlap must be in (0, 10] times the contact's size, got " +
                            std::to_string(max_overlap));
    if (!(overlap_floor > 0 && overlap_floor <= 10))
      throw InvalidArgument("run guard: overlap floor must be in (0, 10] m, got " + std::to_string(overlap_floor));
    if (check_interval < 1 || check_interval > 1000000)
      throw InvalidArgument("run guard: check interval must be in 1..1000000 steps, got " + std::to_string(check_interval));
  }
};

namespace detail {
[[noreturn]] inline void stop_run(double time, long long step, const std::string& what) {
  char head[96];
  std::snprintf(head, sizeof head, "t = %.6g s (step %lld): ", time, step);
  throw RunawayError(head + what);
}

inline std::string diverged() {
  return ": the run diverged (a timestep above the critical one, or a stiffness the timestep cannot follow)";
}

inline std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

[[noreturn]] inline void runaway(double time, long long step, const std::string& what, const char* quantity, double value,
                                 double bound) {
  if (!std::isfinite(value))
    stop_run(time, step, "the " + std::string(quantity) + " of " + what + " is not finite" + diverged());
  stop_run(time, step, what + " moves at " + number(value) + " m/s (" + quantity + "), beyond " + number(bound) +
                           " m/s that no earthquake gives: the run diverged (a timestep above the critical one?) or "
                           "the block was thrown off");
}

inline std::string block_name(const model::Model& m, std::size_t i) {
  return "block '" + m.bodies.name[i] + "' (" + std::to_string(i) + ")";
}

inline std::string contact_point_name(const model::Model& m, std::size_t k, std::size_t a, std::size_t b) {
  return "contact point " + std::to_string(k) + " between " + block_name(m, a) + " and " + block_name(m, b);
}

inline constexpr std::array<const char*, 3> traction_components{"normal stress", "shear stress 1", "shear stress 2"};
inline constexpr std::array<const char*, 6> stress_components{"sigma_xx", "sigma_yy", "sigma_zz",
                                                              "sigma_xy", "sigma_yz", "sigma_zx"};
}  // namespace detail

/// Throws RunawayError naming the first block or node whose velocity (or a block's angular velocity) is not finite,
/// or whose speed exceeds guard.max_speed.
inline void check_velocities(const model::Model& m, const RunGuard& guard, double time, long long step) {
  const auto& b = m.bodies;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const double speed = b.velocity[i].norm();
    const double spin = b.angular_velocity[i].norm();
    if (speed <= guard.max_speed && std::isfinite(spin)) continue;
    if (!std::isfinite(spin)) detail::runaway(time, step, detail::block_name(m, i), "angular velocity", spin, guard.max_speed);
    detail::runaway(time, step, detail::block_name(m, i), "velocity", speed, guard.max_speed);
  }
  const auto& n = m.deformable.nodes;
  for (std::size_t i = 0; i < n.velocity.size(); ++i) {
    const double speed = n.velocity[i].norm();
    if (speed <= guard.max_speed) continue;
    detail::runaway(time, step, "node " + std::to_string(i) + " of " + detail::block_name(m, n.block[i]), "velocity",
                    speed, guard.max_speed);
  }
}

/// Throws RunawayError naming the first tetrahedron whose stress has a component that is not finite.
inline void check_stresses(const model::Model& m, double time, long long step) {
  const auto& te = m.deformable.tetrahedra;
  for (std::size_t t = 0; t < te.size(); ++t) {
    const auto& s = te.stress[t];
    if (std::isfinite(s[0] + s[1] + s[2] + s[3] + s[4] + s[5])) continue;
    std::size_t c = 0;
    while (c < 5 && std::isfinite(s[c])) ++c;
    detail::stop_run(time, step, "the stress " + std::string(detail::stress_components[c]) + " of tetrahedron " +
                                     std::to_string(t) + " of " + detail::block_name(m, m.deformable.nodes.block[te.node[t][0]]) +
                                     " is not finite" + detail::diverged());
  }
}

/// Throws RunawayError naming the first contact point whose gap is not finite or whose overlap (minus the gap) is
/// deeper than guard.max_overlap times its contact's size (the square root of the contact's area; of the node's
/// tributary area for a node contact) and than guard.overlap_floor, or whose stored traction (node contacts) is not
/// finite. With
/// `tractions`, also evaluates the traction of every block contact point (the law's and the damping's), which
/// the step does not store: the diagnosis of a state already found not finite.
template <class Groups, class Deformable>
void check_contacts(const model::Model& m, const Groups& groups, const Deformable* deformable, const RunGuard& guard,
                    double time, long long step, bool tractions = false) {
  const auto overlap = [&](double gap, double area, std::size_t k, std::size_t a, std::size_t b) {
    const double bound = std::max(guard.max_overlap * std::sqrt(area), guard.overlap_floor);
    if (gap >= -bound) return;
    const std::string where = detail::contact_point_name(m, k, a, b);
    if (!std::isfinite(gap)) detail::stop_run(time, step, "the normal displacement (gap) of " + where + " is not finite" + detail::diverged());
    detail::stop_run(time, step, where + " overlaps by " + detail::number(-gap) + " m (normal displacement), deeper than " +
                                     detail::number(guard.max_overlap) + " times its contact's size " +
                                     detail::number(std::sqrt(area)) + " m and than " + detail::number(guard.overlap_floor) +
                                     " m: the run diverged or the blocks passed through each other");
  };
  const auto finite_traction = [&](const auto& t, std::size_t k, std::size_t a, std::size_t b) {
    for (std::size_t j = 0; j < 3; ++j)
      if (!std::isfinite(t[j]))
        detail::stop_run(time, step, "the " + std::string(detail::traction_components[j]) + " of " +
                                         detail::contact_point_name(m, k, a, b) + " is not finite" + detail::diverged());
  };
  for_each_in(groups, [&](const auto& g) {
    for (std::size_t c = 0; c < g.contacts(); ++c) {
      double area = 0;
      for (std::uint32_t k = g.first_point[c]; k < g.first_point[c + 1]; ++k) area += g.area[k];
      for (std::uint32_t k = g.first_point[c]; k < g.first_point[c + 1]; ++k) {
        overlap(g.history[k].gap, area, k, g.body_a[c], g.body_b[c]);
        if (tractions) finite_traction(g.traction_at(c, k), k, g.body_a[c], g.body_b[c]);
      }
    }
  });
  if (!deformable) return;
  deformable->for_each_group([&](const auto& g) {
    for (std::size_t k = 0; k < g.size(); ++k) {
      overlap(g.history[k].gap, g.area[k], k, g.node_block[k], g.face_block[k]);
      finite_traction(g.traction[k], k, g.node_block[k], g.face_block[k]);
    }
  });
}

/// All of the guard's checks: velocities, then contact overlaps and element stresses. A velocity that is not finite
/// makes everything it touches not finite by the next check, so the message adds the first element stress or
/// contact traction found not finite, which is often where it started.
template <class Groups, class Deformable>
void check_run(const model::Model& m, const Groups& groups, const Deformable* deformable, const RunGuard& guard,
               double time, long long step) {
  try {
    check_velocities(m, guard, time, step);
  } catch (const RunawayError& stopped) {
    std::string also;
    try {
      check_stresses(m, time, step);
      check_contacts(m, groups, deformable, guard, time, step, /*tractions=*/true);
    } catch (const RunawayError& found) {
      const std::string text = found.what();
      also = text.substr(text.find("): ") + 3);
    }
    if (also.empty()) throw;
    throw RunawayError(std::string(stopped.what()) + "; also: " + also);
  }
  check_contacts(m, groups, deformable, guard, time, step);
  check_stresses(m, time, step);
}

}  // namespace blockdem
