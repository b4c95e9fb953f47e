#pragma once
// Local damping of a deformable block split into its rigid-body motion and its deformation (damping::Local with
// split_rigid_motion): the static solve of deformable blocks that may form a mechanism (an arch's collapse load).
//
// Cundall's local damping on each node takes c |f| against the node's velocity, component by component. In a
// deformable block whose nodes' forces are mostly the elements' vibration while the block drifts as a whole (a
// voussoir turning about a hinge), that acts as a friction c <|f|> against the drift. Here the block's resultant
// force and moment are damped against its rigid-body velocity and angular velocity (as a rigid block's), and the
// rest of each node's force against the rest of its velocity, with the resultant and moment of that second part
// removed, so that neither part does work on the other's motion. Measured on a 40-voussoir arch (docs/arch.md): it
// stands at lambda 0.1 in 56,549 steps instead of 98,999, and collapses at 0.2 in 173,799 where nodal damping gave
// no verdict in 400,000. It does not remove the drag of the contacts' chatter on the block's resultant: a deformable
// arch still creeps where a rigid one collapses.
//
//   M = sum m_i, c = sum m_i x_i / M, r_i = x_i - c, J = sum m_i (r_i.r_i 1 - r_i r_i^T)
//   V = sum m_i v_i / M, Omega = J^-1 sum m_i r_i x v_i; F = sum f_i, T = sum r_i x f_i
//   rigid part:   f_i^r = m_i (F / M + (J^-1 T) x r_i),  v_i^r = V + Omega x r_i
//   damping:      D = -c |F| sign(V), G = -c |T| sign(Omega) (components, world axes)
//                 d_i = m_i (D / M + (J^-1 G) x r_i) + p_i,   p_i = e_i - m_i (E / M + (J^-1 Q) x r_i)
//                 e_i = -c |f_i - f_i^r| sign(v_i - v_i^r),  E = sum e_i, Q = sum r_i x e_i
// Its power is D.V + G.Omega + sum e_i.(v_i - v_i^r) <= 0: the rigid part's field has no power on the deformation
// (which has no momentum or angular momentum), and p has no resultant or moment, so none on the rigid motion.
// A block with a node fixed on any axis has no free rigid-body motion: its nodes are damped one by one.

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "blockdem/core/types.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem::detail {

/// -c |f| sign(v), component by component (damping::Local's force).
[[gnu::always_inline]] inline Vec3 local_damping_force(double c, const Vec3& f, const Vec3& v) {
  Vec3 d;
  for (int k = 0; k < 3; ++k) d[k] = v[k] > 0 ? -c * std::abs(f[k]) : (v[k] < 0 ? c * std::abs(f[k]) : 0.0);
  return d;
}

/// A deformable block's split local damping, formed from its nodes' forces (nd.force, gathered) and half-step
/// velocities; force(i) is then the damping force on its node i.
struct SplitLocalDamping {
  double c = 0;
  Vec3 centre = Vec3::Zero(), velocity = Vec3::Zero(), omega = Vec3::Zero();
  Vec3 acceleration = Vec3::Zero(), angular_acceleration = Vec3::Zero();
  Vec3 rigid = Vec3::Zero(), angular = Vec3::Zero();  // the damping field's accelerations: D / M - E / M, J^-1 G - J^-1 Q

  /// e_i: the node's own damping of its deformation.
  Vec3 deformation(const model::Nodes& nd, std::uint32_t i) const {
    const Vec3 r = nd.position[i] - centre;
    const Vec3 rigid_force = nd.mass[i] * (acceleration + angular_acceleration.cross(r));
    return local_damping_force(c, nd.force[i] - rigid_force, nd.velocity[i] - (velocity + omega.cross(r)));
  }
  Vec3 force(const model::Nodes& nd, std::uint32_t i) const {
    return deformation(nd, i) + nd.mass[i] * (rigid + angular.cross(nd.position[i] - centre));
  }
};

/// The split damping of block `blk` (nodes [first_node, end_node)); false if a node of the block is fixed on some
/// axis or its inertia is singular (then its nodes are damped one by one).
inline bool split_local_damping(const model::DeformableBodies::Block& blk, const model::Nodes& nd, double c,
                                SplitLocalDamping& s) {
  const std::uint32_t a = blk.first_node, e = blk.end_node;
  double mass = 0;
  Vec3 centre = Vec3::Zero(), momentum = Vec3::Zero(), force = Vec3::Zero();
  for (std::uint32_t i = a; i < e; ++i) {
    if (nd.fixity[i] != 0) return false;
    mass += nd.mass[i];
    centre += nd.mass[i] * nd.position[i];
    momentum += nd.mass[i] * nd.velocity[i];
    force += nd.force[i];
  }
  if (!(mass > 0)) return false;
  centre /= mass;
  Mat3 inertia = Mat3::Zero();
  Vec3 angular_momentum = Vec3::Zero(), moment = Vec3::Zero();
  for (std::uint32_t i = a; i < e; ++i) {
    const Vec3 r = nd.position[i] - centre;
    inertia += nd.mass[i] * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
    angular_momentum += nd.mass[i] * r.cross(nd.velocity[i]);
    moment += r.cross(nd.force[i]);
  }
  bool invertible = false;
  Mat3 inverse;
  double determinant = 0;
  inertia.computeInverseAndDetWithCheck(inverse, determinant, invertible, 0.0);
  if (!invertible || !(determinant > 0)) return false;
  s.c = c;
  s.centre = centre;
  s.velocity = momentum / mass;
  s.omega = inverse * angular_momentum;
  s.acceleration = force / mass;
  s.angular_acceleration = inverse * moment;
  // The deformation's damping: its resultant E and moment Q, removed from it through the field.
  Vec3 resultant = Vec3::Zero(), resultant_moment = Vec3::Zero();
  for (std::uint32_t i = a; i < e; ++i) {
    const Vec3 d = s.deformation(nd, i);
    resultant += d;
    resultant_moment += (nd.position[i] - centre).cross(d);
  }
  s.rigid = (local_damping_force(c, force, s.velocity) - resultant) / mass;
  s.angular = inverse * (local_damping_force(c, moment, s.omega) - resultant_moment);
  return true;
}

}  // namespace blockdem::detail
