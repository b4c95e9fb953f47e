#pragma once
// The frame in which viscous damping proportional to mass (C = alpha M: mass-proportional damping, the mass term of
// Rayleigh damping) measures the velocities it damps (docs/damping.md, "The frame of mass-proportional damping").
//
// - table (the default): relative to the moving base. The model is then a fixed-base model under effective
//   earthquake forces, the frame where alpha M stands for the dissipation of the structure itself: a structure that
//   the table carries along rigidly feels no damping force. The dashpots act between each block (or node) and the
//   table, whose drive supplies the work they exchange with it (booked with the base's work).
// - absolute: relative to the fixed ground (3DEC's, and the paper's): the dashpots tie the structure to the ground,
//   so that a moving table drags it with alpha m v_table, during a record and during the rests, where the table
//   moves on at its final velocity.
//
// The frame changes nothing for the other policies (stiffness-proportional, Maxwell: relative velocities of the
// joints; none; local damping, for settling on a table at rest).

#include "blockdem/core/types.hpp"

namespace blockdem::damping {

enum class Frame { table, absolute };
constexpr bool valid_enumerator(Frame f) noexcept { return f == Frame::table || f == Frame::absolute; }

/// The velocity of the frame over the move that led to the present positions and over the next one: the table's, or
/// zero (the ground's frame).
struct FrameVelocity {
  Vec3 before = Vec3::Zero(), after = Vec3::Zero();  // m/s, at t(n) - dt/2 and t(n) + dt/2
};

inline constexpr const char* name(Frame f) { return f == Frame::table ? "table" : "absolute"; }

/// Whether a policy damps the velocities themselves (`static constexpr bool damps_velocities = true`): those it damps
/// in the chosen frame.
template <class Policy>
constexpr bool damps_velocities() {
  if constexpr (requires { Policy::damps_velocities; }) return Policy::damps_velocities;
  else return false;
}

}  // namespace blockdem::damping
