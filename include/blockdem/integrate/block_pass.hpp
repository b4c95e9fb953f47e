#pragma once
// The block pass (paper Sect. 3.1, DESIGN.md §4, steps 3-4): for every rigid block, tile by tile, gather the
// resultants of its contacts in a fixed order (no atomics: results do not depend on the number of threads), add
// gravity, the damped central-difference velocity update (the damping policy's per-degree-of-freedom hook,
// damping::PerDofDamping), then position and orientation; base blocks follow the base motion. One block per vector
// lane, fixed degrees of freedom selected, not branched around.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <vector>

#include "blockdem/core/rotation.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/damping/frame.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

/// The integrator's own per-block arrays (the model holds positions, velocities and masses): energies, inverse
/// masses, and the poses at the last detection that decide when contacts are detected again.
struct BlockState {
  std::vector<double> kinetic, gravity_work, base_work, viscous;  // J, per block
  std::vector<double> frame_work;  // J, per block: done by dashpots anchored to the table (damping/frame.hpp)
  std::vector<double> radius;                // m, largest distance of a vertex from the centroid
  std::vector<double> redetection_distance;  // m, per block (model::redetection_distances)
  std::vector<double> inverse_mass;          // 1/kg
  std::vector<Vec3> inverse_inertia;         // 1/(kg m^2), principal
  std::vector<Vec3> detected_position;       // at the last detection
  std::vector<Quaternion> detected_orientation;
  Vec3 base_displacement = Vec3::Zero();           // m, integral of the base velocity
  Vec3 detected_base_displacement = Vec3::Zero();  // at the last detection

  /// Sized for the blocks of `b`: energies zero but the kinetic energy of the free blocks at their velocities, the
  /// detection poses the present ones, inverse masses from the present masses, radii from the shapes. The
  /// redetection distances are the caller's (model::redetection_distances).
  void reset(const model::RigidBodies& b) {
    const std::size_t n = b.size();
    kinetic.assign(n, 0.0);
    gravity_work.assign(n, 0.0);
    base_work.assign(n, 0.0);
    viscous.assign(n, 0.0);
    frame_work.assign(n, 0.0);
    detected_position = b.position;
    detected_orientation = b.orientation;
    set_inverse_masses(b);
    radius.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      for (const auto& v : b.shape[i].vertices) radius[i] = std::max(radius[i], v.norm());
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 w = b.rotation[i].transpose() * b.angular_velocity[i];
      kinetic[i] = b.motion[i] == model::Motion::free
                       ? 0.5 * b.mass[i] * b.velocity[i].squaredNorm() + 0.5 * w.cwiseProduct(w).dot(b.principal_inertia[i])
                       : 0.0;
    }
  }

  /// Inverse masses and inertias from the model's present ones.
  void set_inverse_masses(const model::RigidBodies& b) {
    inverse_mass.assign(b.size(), 0.0);
    inverse_inertia.assign(b.size(), Vec3::Zero());
    for (std::size_t i = 0; i < b.size(); ++i) {
      inverse_mass[i] = 1.0 / b.mass[i];
      inverse_inertia[i] = b.principal_inertia[i].cwiseInverse();
    }
  }
};

/// Forces and moments on rigid blocks from outside the rigid contact groups (node contacts, trusses, the weight
/// correction of density-scaled blocks), per block; empty for a rigid-only step.
struct ExtraForces {
  const Vec3* force = nullptr;   // N
  const Vec3* moment = nullptr;  // N m
};

/// Calls f(group) for every group of a tuple of contact groups, in order.
template <class Groups, class F>
void for_each_in(Groups& groups, F&& f) {
  std::apply([&](auto&... g) { (f(g), ...); }, groups);
}

/// Blocks per tile of the block pass. Tiles, not threads, decide which blocks share a group of vector lanes, so
/// that results do not depend on the number of threads; and a tile's gathered resultants are still in L1 when its
/// update reads them.
inline constexpr std::size_t block_tile = 64;

/// What the vector loops of a tile overwrite for blocks that are not free, put back afterwards.
struct KeptBlock {
  std::size_t i;
  Vec3 position, velocity, angular_velocity;
  Quaternion orientation;
  Mat3 rotation;
  double kinetic, viscous, gravity_work, frame_work;
};

namespace detail {

/// The contacts' resultants on blocks [begin, end), summed in a fixed order, plus gravity on free blocks; base
/// blocks follow the base velocity.
template <bool Mixed, class Groups>
void gather_resultants(model::Model& m, BlockState& state, const Groups& groups, const ExtraForces& extra, std::size_t begin,
                       std::size_t end, double dt, double increment_dt, const Vec3& base_velocity, bool move) {
  auto& b = m.bodies;
  const Vec3 gravity = m.gravity;
  for (std::size_t i = begin; i < end; ++i) {
    Vec3 force = Vec3::Zero();
    Vec3 moment = Vec3::Zero();
    for_each_in(groups, [&](const auto& g) {
      for (std::uint32_t e = g.first[i]; e < g.first[i + 1]; ++e) {
        const std::uint32_t code = g.entry[e];
        // Branch-free: the side of the block in the contact is random from one entry to the next.
        const double sign = static_cast<double>(code & 1u) * 2.0 - 1.0;
        force += sign * g.force[code >> 1];
        moment += g.moment[code];
      }
    });
    if constexpr (Mixed) {  // node contacts, trusses, weight correction of scaled blocks
      force += extra.force[i];
      moment += extra.moment[i];
    }
    const model::Motion motion = b.motion[i];
    if (motion == model::Motion::free) force += b.mass[i] * gravity;
    // The move that led to x_n, against the mean of the forces at x_(n-1) and x_n (b.force, still the last step's):
    // the work the leapfrog's energy 1/2 m v(n-1/2).v(n+1/2) + U(x_n) sees. The force at x_n alone is off by
    // dt/2 times the integral of F.a, which does not shrink over a record: 1 J of 1.1 in a 2.5 g sine.
    if (motion == model::Motion::base && move)
      state.base_work[i] -= 0.5 * (force + b.force[i]).dot(b.velocity[i]) * increment_dt;
    b.force[i] = force;
    b.moment[i] = moment;
    if (motion == model::Motion::base && move) {
      b.velocity[i] = base_velocity;
      b.angular_velocity[i].setZero();
      b.position[i] += dt * base_velocity;
    }
  }
}

static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Mat3) == 9 * sizeof(double) &&
              sizeof(Quaternion) == 4 * sizeof(double), "the block update reads Eigen's coefficients in place");

/// a where the mask is all ones, b where it is zero. A ternary would let the compiler move the arithmetic of the
/// side not taken into a branch, which the vectoriser does not turn back into a selection (floating-point
/// operations may trap).
[[gnu::always_inline]] inline double select(std::uint64_t mask, double a, double b) noexcept {
  return std::bit_cast<double>((std::bit_cast<std::uint64_t>(a) & mask) | (std::bit_cast<std::uint64_t>(b) & ~mask));
}

/// Damped velocity update of blocks [begin, end), one block per vector lane and all of them as if free (the
/// caller puts back the others). Fixed degrees of freedom are selected, not branched around.
template <class Damping>
void update_velocities(model::Model& m, BlockState& state, const Damping& policy, double timestep, std::size_t begin,
                       std::size_t end, double increment_dt, const damping::FrameVelocity& frame) {
  auto& b = m.bodies;
  // The arrays as restrict parameters of a function: with restrict local pointers GCC 12 left this loop scalar
  // (too many run-time alias checks).
  // Fixity widened to the width of the doubles: one byte-sized array makes the vectoriser put as many blocks in
  // a vector iteration as bytes fit in a register (32), which spilled most of the loop's state to the stack.
  const std::size_t count = end - begin;
  std::uint64_t fixity_wide[block_tile];
  for (std::size_t k = 0; k < count; ++k) fixity_wide[k] = b.fixity[begin + k];
  // The frame's velocity before and after, and its change over the step per unit time (damping/frame.hpp).
  [[maybe_unused]] const double frame_before[3] = {frame.before[0], frame.before[1], frame.before[2]};
  [[maybe_unused]] const double frame_after[3] = {frame.after[0], frame.after[1], frame.after[2]};
  [[maybe_unused]] const double frame_change[3] = {(frame_after[0] - frame_before[0]) / timestep,
                                                   (frame_after[1] - frame_before[1]) / timestep,
                                                   (frame_after[2] - frame_before[2]) / timestep};
  // (The frame's arrays by reference, and only where the policy uses them.)
  const auto update = [&, damping = policy, dt = timestep, increment_dt, count, gravity = m.gravity](
                          const std::uint64_t* __restrict fixity_of, const double* __restrict mass,
                          const double* __restrict inverse_mass, const double* __restrict principal_inertia,
                          const double* __restrict inverse_principal_inertia, const double* __restrict orientation,
                          const double* __restrict force, const double* __restrict moment, double* __restrict velocity,
                          double* __restrict angular_velocity, double* __restrict kinetic, double* __restrict viscous,
                          double* __restrict gravity_work, double* __restrict frame_work) {
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint64_t fixity = fixity_of[i];
      const double mass_i = mass[i], inverse_mass_i = inverse_mass[i];
      const double* inertia = principal_inertia + 3 * i;
      const double* inverse_inertia = inverse_principal_inertia + 3 * i;
      double r[9];  // r(j, k) at 3 k + j
      rotation_coefficients(orientation + 4 * i, r);
      double dissipated = 0.0, by_frame = 0.0;
      double v_old[3], v[3], w_old[3], m_world[3];
      for (int c = 0; c < 3; ++c) {
        v_old[c] = velocity[3 * i + c];
        w_old[c] = angular_velocity[3 * i + c];
        m_world[c] = moment[3 * i + c];
        double with_this = dissipated;
        const std::uint64_t fixed = 0 - ((fixity >> c) & 1u);
        double updated;
        if constexpr (damping::damps_velocities<Damping>()) {
          // Relative to the frame: the update of v - v_frame under the force less the frame's inertial force, then
          // back. The dashpot's force on the block, m (v(n+1/2) - v(n-1/2)) / dt - F, times the frame's velocity is
          // the work the frame (the table's drive) does through it; the policy books the dissipation, relative.
          updated = damping.velocity_update(v_old[c] - frame_before[c], force[3 * i + c] - mass_i * frame_change[c],
                                            damping::Inertia{mass_i, inverse_mass_i}, dt, with_this) +
                    frame_after[c];
          const double dashpot = mass_i * (updated - v_old[c]) / dt - force[3 * i + c];
          by_frame += select(fixed, 0.0, dashpot * 0.5 * (frame_before[c] + frame_after[c]) * dt);
        } else {
          updated = damping.velocity_update(v_old[c], force[3 * i + c], damping::Inertia{mass_i, inverse_mass_i}, dt, with_this);
        }
        v[c] = select(fixed, 0.0, updated);
        dissipated = select(fixed, dissipated, with_this);
      }
      // Rotation in the principal frame (Euler's equations). The gyroscopic term is taken at the mid-step angular
      // velocity (implicit midpoint, fixed-point passes: dt |w| is tiny), which keeps the scheme time reversible.
      double w_old_body[3], m_applied[3], w_body[3];
      for (int k = 0; k < 3; ++k) {
        w_old_body[k] = r[3 * k] * w_old[0] + r[3 * k + 1] * w_old[1] + r[3 * k + 2] * w_old[2];
        m_applied[k] = r[3 * k] * m_world[0] + r[3 * k + 1] * m_world[1] + r[3 * k + 2] * m_world[2];
        w_body[k] = w_old_body[k];
      }
      double rotation_dissipated = 0.0;
      for (int pass = 0; pass < 3; ++pass) {
        double w_mid[3], l[3];
        for (int c = 0; c < 3; ++c) {
          w_mid[c] = 0.5 * (w_old_body[c] + w_body[c]);
          l[c] = inertia[c] * w_mid[c];  // angular momentum
        }
        const double m_body[3] = {m_applied[0] - (w_mid[1] * l[2] - w_mid[2] * l[1]),
                                  m_applied[1] - (w_mid[2] * l[0] - w_mid[0] * l[2]),
                                  m_applied[2] - (w_mid[0] * l[1] - w_mid[1] * l[0])};
        rotation_dissipated = 0.0;
        for (int c = 0; c < 3; ++c)
          w_body[c] = damping.velocity_update(w_old_body[c], m_body[c], damping::Inertia{inertia[c], inverse_inertia[c]},
                                              dt, rotation_dissipated);
      }
      dissipated += rotation_dissipated;
      double w[3], w_back[3];
      for (int j = 0; j < 3; ++j)
        w[j] = select(0 - ((fixity >> (3 + j)) & 1u), 0.0, r[j] * w_body[0] + r[3 + j] * w_body[1] + r[6 + j] * w_body[2]);
      for (int k = 0; k < 3; ++k) w_back[k] = r[3 * k] * w[0] + r[3 * k + 1] * w[1] + r[3 * k + 2] * w[2];
      const std::uint64_t rotation_fixed = 0 - static_cast<std::uint64_t>((fixity & model::Fixity::all_rotations) != 0);
      for (int c = 0; c < 3; ++c) {
        w_body[c] = select(rotation_fixed, w_back[c], w_body[c]);
        velocity[3 * i + c] = v[c];
        angular_velocity[3 * i + c] = w[c];
      }
      // Kinetic energy at step n from the two half-step velocities: conserved exactly by the undamped leapfrog.
      kinetic[i] = 0.5 * mass_i * (v_old[0] * v[0] + v_old[1] * v[1] + v_old[2] * v[2]) +
                   0.5 * (w_old_body[0] * inertia[0] * w_body[0] + w_old_body[1] * inertia[1] * w_body[1] +
                          w_old_body[2] * inertia[2] * w_body[2]);
      viscous[i] += dissipated;
      if constexpr (damping::damps_velocities<Damping>()) frame_work[i] += by_frame;
      // Work of gravity over the move that brought the block to x_n, where the forces and energies are evaluated.
      gravity_work[i] += mass_i * (gravity[0] * v_old[0] + gravity[1] * v_old[1] + gravity[2] * v_old[2]) * increment_dt;
    }
  };
  // The rotation matrix from the orientation (four numbers per block, loaded as whole vectors) instead of from
  // `rotation` (nine, whose stride the vectoriser cannot load as a group); rotation is rotation_matrix(orientation).
  update(fixity_wide, b.mass.data() + begin, state.inverse_mass.data() + begin, b.principal_inertia[begin].data(),
         state.inverse_inertia[begin].data(), b.orientation[begin].coeffs().data(), b.force[begin].data(),
         b.moment[begin].data(), b.velocity[begin].data(), b.angular_velocity[begin].data(), state.kinetic.data() + begin,
         state.viscous.data() + begin, state.gravity_work.data() + begin, state.frame_work.data() + begin);
}

/// Positions and orientations of blocks [begin, end), one block per vector lane and all of them as if free (the
/// caller puts back the others); whether a free block moved (relative to the base) by more than its redetection
/// distance (update_redetection_distances) since the last detection, rotation counting with the block's radius.
/// Turns beyond the range of turned()'s series, and blocks near their redetection distance, are finished one by
/// one afterwards.
inline bool update_positions(model::RigidBodies& b, BlockState& state, double dt, std::size_t begin, std::size_t end,
                             const Vec3& base_moved) {
  const double h = 0.5 * dt;
  const double shift[3] = {base_moved[0], base_moved[1], base_moved[2]};
  // The turned quaternion before its normalisation, whose square root (with libm's errno check) would keep the
  // loop from being vectorised; the half angle squared, to find turns beyond the series; the reach (|d|^2 + a^2)
  // of the move since the last detection; the old orientation, for turns beyond the series.
  alignas(64) double turned_x[block_tile], turned_y[block_tile], turned_z[block_tile], turned_w[block_tile];
  alignas(64) double half_angle2[block_tile], scale[block_tile], reach[block_tile], old_orientation[4 * block_tile];
  const std::size_t count = end - begin;
  // Restrict parameters, as in update_velocities().
  const auto turn = [&](const double* __restrict velocity, const double* __restrict angular_velocity,
                        double* __restrict position, const double* __restrict orientation) {
    for (std::size_t k = 0; k < count; ++k) {
      for (int c = 0; c < 3; ++c) position[3 * k + c] += dt * velocity[3 * k + c];
      // turned(), with cos x and sin x / x of the half angle x from their series.
      const double wx = angular_velocity[3 * k], wy = angular_velocity[3 * k + 1], wz = angular_velocity[3 * k + 2];
      const double x2 = 0.25 * dt * dt * (wx * wx + wy * wy + wz * wz);
      double cx, sx;
      half_angle_series(x2, cx, sx);
      const double f = h * sx;
      const double vx = f * wx, vy = f * wy, vz = f * wz;
      const double qx = orientation[4 * k], qy = orientation[4 * k + 1], qz = orientation[4 * k + 2], qw = orientation[4 * k + 3];
      turned_x[k] = cx * qx + qw * vx + (vy * qz - vz * qy);
      turned_y[k] = cx * qy + qw * vy + (vz * qx - vx * qz);
      turned_z[k] = cx * qz + qw * vz + (vx * qy - vy * qx);
      turned_w[k] = cx * qw - (vx * qx + vy * qy + vz * qz);
      half_angle2[k] = x2;
    }
  };
  turn(b.velocity[begin].data(), b.angular_velocity[begin].data(), b.position[begin].data(),
       b.orientation[begin].coeffs().data());
  for (std::size_t k = 0; k < count; ++k)
    scale[k] = 1.0 / std::sqrt(turned_w[k] * turned_w[k] + turned_x[k] * turned_x[k] + turned_y[k] * turned_y[k] +
                               turned_z[k] * turned_z[k]);
  // The rotation matrices, column by column (r(j, m) in rotation_of[3 m + j]): nine numbers per block at a stride
  // of nine are no group the vectoriser stores, so they are copied into `rotation` one by one below.
  alignas(64) double rotation_of[9][block_tile];
  const auto normalise = [&](double* __restrict orientation, const double* __restrict position,
                             const double* __restrict detected_position, const double* __restrict detected_orientation,
                             const double* __restrict radius) {
    for (std::size_t k = 0; k < count; ++k) {
      for (int c = 0; c < 4; ++c) old_orientation[4 * k + c] = orientation[4 * k + c];
      const double s = scale[k];
      const double q[4] = {s * turned_x[k], s * turned_y[k], s * turned_z[k], s * turned_w[k]};
      for (int c = 0; c < 4; ++c) orientation[4 * k + c] = q[c];
      double r[9];
      rotation_coefficients(q, r);
      for (int j = 0; j < 9; ++j) rotation_of[j][k] = r[j];
      const double dx = position[3 * k] - detected_position[3 * k] - shift[0];
      const double dy = position[3 * k + 1] - detected_position[3 * k + 1] - shift[1];
      const double dz = position[3 * k + 2] - detected_position[3 * k + 2] - shift[2];
      // Twice the vector part of q q0^-1 (small_angle_between()).
      const double* q0 = detected_orientation + 4 * k;
      const double ex = q0[3] * q[0] - q[3] * q0[0] - (q[1] * q0[2] - q[2] * q0[1]);
      const double ey = q0[3] * q[1] - q[3] * q0[1] - (q[2] * q0[0] - q[0] * q0[2]);
      const double ez = q0[3] * q[2] - q[3] * q0[2] - (q[0] * q0[1] - q[1] * q0[0]);
      reach[k] = (dx * dx + dy * dy + dz * dz) + 4.0 * (ex * ex + ey * ey + ez * ez) * radius[k] * radius[k];
    }
  };
  normalise(b.orientation[begin].coeffs().data(), b.position[begin].data(),
            state.detected_position[begin].data(), state.detected_orientation[begin].coeffs().data(), state.radius.data() + begin);
  bool moved = false;
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = begin + k;
    for (int j = 0; j < 9; ++j) b.rotation[i].data()[j] = rotation_of[j][k];
    if (b.motion[i] != model::Motion::free) continue;
    const bool large_turn = !(half_angle2[k] < 1e-4);
    if (large_turn) {
      b.orientation[i] = turned(Quaternion(old_orientation[4 * k + 3], old_orientation[4 * k], old_orientation[4 * k + 1],
                                           old_orientation[4 * k + 2]),
                                b.angular_velocity[i], dt);
      b.rotation[i] = rotation_matrix(b.orientation[i]);
    }
    // (|d| + a)^2 <= 2 (|d|^2 + a^2): most blocks are far below the redetection distance, without square roots.
    const double redetection = state.redetection_distance[i];
    if (large_turn || 2.0 * reach[k] > redetection * redetection) {
      const double angle = small_angle_between(b.orientation[i], state.detected_orientation[i]);
      moved = moved || (b.position[i] - state.detected_position[i] - base_moved).norm() + angle * state.radius[i] > redetection;
    }
  }
  return moved;
}

}  // namespace detail

/// Gather, gravity, damped velocity update; then position and orientation update, for every block, tile by tile.
/// `frame`: the velocity of the frame mass-proportional damping works in (damping/frame.hpp; zero: the ground).
template <bool Mixed, class Damping, class Groups>
bool block_pass(model::Model& m, BlockState& state, const Groups& groups, const Damping& damping, const ExtraForces& extra,
                double time, double dt, double increment_dt, bool move = true, const damping::FrameVelocity& frame = {}) {
  auto& b = m.bodies;
  const std::size_t n = b.size();
  const auto tiles = static_cast<std::ptrdiff_t>((n + block_tile - 1) / block_tile);
  const Vec3 base_velocity = m.base_velocity(time + 0.5 * dt);
  if (move) state.base_displacement += dt * base_velocity;
  const Vec3 base_moved = state.base_displacement - state.detected_base_displacement;
  bool moved = false;
#pragma omp parallel for schedule(static) if (n > 1024) reduction(|| : moved)
  for (std::ptrdiff_t t = 0; t < tiles; ++t) {
    const std::size_t begin = static_cast<std::size_t>(t) * block_tile, end = std::min(begin + block_tile, n);
    detail::gather_resultants<Mixed>(m, state, groups, extra, begin, end, dt, increment_dt, base_velocity, move);
    std::array<KeptBlock, block_tile> kept;
    std::size_t kept_count = 0;
    for (std::size_t i = begin; i < end; ++i)
      if (b.motion[i] != model::Motion::free)
        kept[kept_count++] = {i, b.position[i], b.velocity[i], b.angular_velocity[i], b.orientation[i], b.rotation[i],
                              state.kinetic[i], state.viscous[i], state.gravity_work[i], state.frame_work[i]};
    detail::update_velocities(m, state, damping, dt, begin, end, increment_dt, frame);
    if (move) moved = detail::update_positions(b, state, dt, begin, end, base_moved) || moved;
    for (std::size_t k = 0; k < kept_count; ++k) {
      const KeptBlock& e = kept[k];
      b.position[e.i] = e.position;
      b.velocity[e.i] = e.velocity;
      b.angular_velocity[e.i] = e.angular_velocity;
      b.orientation[e.i] = e.orientation;
      b.rotation[e.i] = e.rotation;
      state.kinetic[e.i] = e.kinetic;
      state.viscous[e.i] = e.viscous;
      state.gravity_work[e.i] = e.gravity_work;
      state.frame_work[e.i] = e.frame_work;
    }
  }
  return moved;
}

}  // namespace blockdem
