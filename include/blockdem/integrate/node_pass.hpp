#pragma once
// The node side of the step (DESIGN.md §4, steps 1 and 3): the node contacts of deformable blocks (3DEC's
// sub-contacts: one per face node on a joint's overlap), the trusses, the forces these put on rigid blocks, and the
// node pass: gather (elements, contacts, trusses in a fixed order), gravity with the real mass, damped velocity
// update with the scaled one, position.

#include <cstddef>
#include <cstdint>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/damping/frame.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

/// The node contact loop of one group. inverse_omega_squared: as for contact_pass (the laws' closure impulse).
template <class G, class Damping>
void node_contact_pass(G& g, const model::Model& m, const Damping& damping, double increment_dt,
                       double inverse_omega_squared) {
  using L = typename G::LawType;
  const auto& b = m.bodies;
  const Vec3* __restrict const x = m.deformable.nodes.position.data();
  const Vec3* __restrict const velocity = m.deformable.nodes.velocity.data();
  const auto count = static_cast<std::ptrdiff_t>(g.size());
#pragma omp parallel for schedule(static) if (count > 256)
  for (std::ptrdiff_t kk = 0; kk < count; ++kk) {
    const auto k = static_cast<std::size_t>(kk);
    const std::uint32_t node = g.node[k];
    Vec3 n, t1, v_face, arm;
    if constexpr (G::FaceKinematics::deformable) {
      const auto& tri = g.triangle[k];
      const auto& w = g.weight[k];
      const Vec3 e1 = x[tri[1]] - x[tri[0]];
      n = -e1.cross(x[tri[2]] - x[tri[0]]).normalized();
      t1 = e1.normalized();
      v_face = w[0] * velocity[tri[0]] + w[1] * velocity[tri[1]] + w[2] * velocity[tri[2]];
    } else {
      const std::uint32_t fb = g.face_block[k];
      const Mat3& r = b.rotation[fb];
      n = rotate(r, g.normal_local[k]);
      t1 = rotate(r, g.tangent_local[k]);
      arm = rotate(r, g.point_local[k]);
      v_face = b.velocity[fb] + b.angular_velocity[fb].cross(arm);
    }
    const Vec3 t2 = n.cross(t1);
    const Vec3 du = increment_dt * (v_face - velocity[node]);
    const double du_n = du.dot(n);
    const contact::Shear du_s{du.dot(t1), du.dot(t2)};
    const auto& p = g.properties[g.property[k]];
    const double kn = L::normal_stiffness(p), ks = L::shear_stiffness(p);
    const contact::Response r = L::update(p, g.history[k], du_n, du_s, contact::Step{increment_dt, inverse_omega_squared});
    const bool active = r.damping_active;  // L::damping_active(p, g.history[k])
    double dissipated = 0.0;
    auto& spring = g.spring_state[k];
    const double sn = r.normal_stress + damping.spring_stress(spring[0], kn, -du_n, increment_dt, active, dissipated);
    const double s1 = r.shear_stress[0] + damping.spring_stress(spring[1], ks, -du_s[0], increment_dt, active, dissipated);
    const double s2 = r.shear_stress[1] + damping.spring_stress(spring[2], ks, -du_s[1], increment_dt, active, dissipated);
    g.traction[k] = {sn, s1, s2};
    const double area = g.area[k];
    const Vec3 f = area * (sn * n + s1 * t1 + s2 * t2);
    g.force[k] = f;
    if constexpr (!G::FaceKinematics::deformable) g.moment[k] = arm.cross(f);
    g.slip_dissipation[k] += area * r.dissipated;
    g.viscous_dissipation[k] += area * dissipated;
  }
}

/// Node contacts of every node group of `d`: relative velocity of the face point and the node -> increment -> law ->
/// damping -> force.
template <class State, class Damping>
void node_contact_passes(State& state, const model::Model& m, const Damping& damping, double increment_dt,
                         double inverse_omega_squared) {
  state.for_each_group([&](auto& g) { node_contact_pass(g, m, damping, increment_dt, inverse_omega_squared); });
}

/// Trusses: axial force pretension + EA (L - L0) / L0 along the current axis.
template <class State>
void truss_pass(State& state, const model::Model& m) {
  const auto& trusses = m.deformable.trusses;
  for (std::size_t t = 0; t < trusses.size(); ++t) {
    const auto& tr = trusses[t];
    const Vec3 d = m.end_position(tr.end[1]) - m.end_position(tr.end[0]);
    const double length = d.norm();
    const double axial = tr.pretension + tr.axial_stiffness() * (length - tr.length0);
    state.truss_force[t] = axial / length * d;  // on end 0, toward end 1 in tension
  }
}

/// Forces of node contacts and trusses on rigid blocks, and the weight correction of density-scaled rigid blocks.
template <class State>
void gather_rigid(State& state, const model::Model& m, double increment_dt) {
  const auto& b = m.bodies;
  const auto n = b.size();
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 f = Vec3::Zero(), mo = Vec3::Zero();
    std::size_t group = 0;
    state.for_each_group([&](const auto& g) {
      if constexpr (!std::remove_cvref_t<decltype(g)>::FaceKinematics::deformable) {
        const auto& first = state.rigid_first[group];
        const auto& entry = state.rigid_entry[group];
        for (std::uint32_t e = first[i]; e < first[i + 1]; ++e) {
          f += g.force[entry[e]];
          mo += g.moment[entry[e]];
        }
      }
      ++group;
    });
    for (std::uint32_t e = state.rigid_truss_first[i]; e < state.rigid_truss_first[i + 1]; ++e) {
      const std::uint32_t code = state.rigid_truss_entry[e];
      const auto& tr = m.deformable.trusses[code >> 1];
      const Vec3 force = (code & 1u) ? Vec3(-state.truss_force[code >> 1]) : state.truss_force[code >> 1];
      f += force;
      mo += rotate(b.rotation[i], tr.end[code & 1u].body_point).cross(force);
    }
    if (b.motion[i] == model::Motion::free && state.rigid_real_mass[i] != b.mass[i]) {
      const Vec3 correction = (state.rigid_real_mass[i] - b.mass[i]) * m.gravity;
      f += correction;
      state.extra_work += correction.dot(b.velocity[i]) * increment_dt;
    }
    state.extra_force[i] = f;
    state.extra_moment[i] = mo;
  }
}

/// Gather (elements, contacts, trusses in a fixed order), gravity with the real mass, damped velocity update with
/// the scaled mass (mass-proportional damping in the frame of `frame`, as block_pass), then positions. Returns whether
/// a node moved more than `redetection` since the last detection.
template <class State, class Damping>
bool node_pass(State& state, model::Model& m, const Damping& damping, double dt, double increment_dt, bool move,
               double redetection, const damping::FrameVelocity& frame = {}) {
  auto& nd = m.deformable.nodes;
  const Vec3 gravity = m.gravity;
  const auto count = static_cast<std::ptrdiff_t>(nd.size());
  bool moved = false;
#pragma omp parallel for schedule(static) if (count > 1024) reduction(|| : moved)
  for (std::ptrdiff_t ii = 0; ii < count; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    Vec3 force = Vec3::Zero();
    for (std::uint32_t e = state.element_first[i]; e < state.element_first[i + 1]; ++e) {
      const std::uint32_t code = state.element_entry[e];
      force += state.element_force[code >> 2][code & 3u];
    }
    std::size_t group = 0;
    state.for_each_group([&](const auto& g) {
      const auto& first = state.node_first[group];
      const auto& entry = state.node_entry[group];
      const auto& coefficient = state.node_coefficient[group];
      for (std::uint32_t e = first[i]; e < first[i + 1]; ++e) force += coefficient[e] * g.force[entry[e]];
      ++group;
    });
    for (std::uint32_t e = state.truss_first[i]; e < state.truss_first[i + 1]; ++e) {
      const std::uint32_t code = state.truss_entry[e];
      force += (code & 1u) ? Vec3(-state.truss_force[code >> 1]) : state.truss_force[code >> 1];
    }
    force += nd.real_mass[i] * gravity;
    nd.force[i] = force;
    const damping::Inertia mass{nd.mass[i], state.node_inverse_mass[i]};
    const Vec3 v_old = nd.velocity[i];
    Vec3 v;
    double dissipated = 0.0;
    const std::uint8_t fixity = nd.fixity[i];
    if constexpr (damping::damps_velocities<Damping>()) {
      double by_frame = 0.0;
      for (int c = 0; c < 3; ++c) {
        if (fixity & (1u << c)) {
          v[c] = 0.0;
          continue;
        }
        v[c] = damping.velocity_update(v_old[c] - frame.before[c], force[c] - mass.value * (frame.after[c] - frame.before[c]) / dt,
                                       mass, dt, dissipated) +
               frame.after[c];
        by_frame += (mass.value * (v[c] - v_old[c]) / dt - force[c]) * 0.5 * (frame.before[c] + frame.after[c]) * dt;
      }
      state.node_frame_work[i] += by_frame;
    } else {
      for (int c = 0; c < 3; ++c) v[c] = (fixity & (1u << c)) ? 0.0 : damping.velocity_update(v_old[c], force[c], mass, dt, dissipated);
    }
    nd.velocity[i] = v;
    state.node_kinetic[i] = 0.5 * mass.value * v_old.dot(v);
    state.node_viscous[i] += dissipated;
    state.node_gravity_work[i] += nd.real_mass[i] * gravity.dot(v_old) * increment_dt;
    if (move) {
      nd.position[i] += dt * v;
      moved = moved || (nd.position[i] - state.detected_node_position[i]).squaredNorm() > redetection * redetection;
    }
  }
  return moved;
}

}  // namespace blockdem
