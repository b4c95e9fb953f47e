#pragma once
// The node side of the step (DESIGN.md §4, steps 1 and 3): the node contacts of deformable blocks (3DEC's
// sub-contacts: one per face node on a joint's overlap), the trusses, the forces these put on rigid blocks, and the
// node pass: gather (elements, contacts, trusses in a fixed order), gravity with the real mass, damped velocity
// update with the scaled one, position.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/damping/frame.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/integrate/local_split.hpp"
#include "blockdem/model/model.hpp"
#include "blockdem/parallel/thread_ranges.hpp"

namespace blockdem {

/// Node contact points per tile of node_contact_pass (a thread's last tile may be shorter; nothing is summed across
/// points, so any tiling gives the same results). A tile's frames take 4.9 kB.
inline constexpr std::size_t node_contact_tile = 32;

/// The node contact loop of one group over its points [first_point, end_point), on the calling thread.
/// inverse_omega_squared: as for contact_pass (the laws' closure impulse).
/// A tile of node_contact_tile CPs at a time, in two loops: first the frame of every CP of the tile and its
/// displacement increment (gathered node velocities and positions, a cross product, two square roots and their
/// divisions), then the law, the damping and the force, one CP after another. In one loop each CP waited on its own
/// chain of loads, roots and divisions before the law could start (45 ns per CP with no damping, one thread); the
/// short first loop lets the chains of consecutive CPs overlap. No viscous stress, viscous work or slip work is
/// computed or stored for a policy or law that has none. Per CP the same operations in the same order as one loop.
template <class G, class Damping>
void node_contact_range(G& g, const model::Model& m, const Damping& damping, double increment_dt,
                        double inverse_omega_squared, std::size_t first_point, std::size_t end_point) {
  using L = typename G::LawType;
  constexpr bool viscous_here = damping::PerSpringDamping<Damping>;
  constexpr bool rigid_face = !G::FaceKinematics::deformable;
  constexpr std::size_t tile = node_contact_tile;
  const auto& b = m.bodies;
  const Vec3* __restrict const x = m.deformable.nodes.position.data();
  const Vec3* __restrict const velocity = m.deformable.nodes.velocity.data();
  const std::uint32_t* __restrict const node_of = g.node.data();
  const std::uint16_t* __restrict const property = g.property.data();
  const auto* __restrict const properties = g.properties.data();
  const double* __restrict const area_of = g.area.data();
  auto* __restrict const history = g.history.data();
  auto* __restrict const spring_state = g.spring_state.data();
  auto* __restrict const traction = g.traction.data();
  Vec3* __restrict const force = g.force.data();
  double* __restrict const slip_dissipation = g.slip_dissipation.data();
  double* __restrict const viscous_dissipation = g.viscous_dissipation.data();
  const contact::Step step{increment_dt, inverse_omega_squared};
  for (std::size_t first = first_point; first < end_point; first += tile) {
    const std::size_t used = std::min(tile, end_point - first);
    struct Frame {
      Vec3 n, t1, t2, arm;  // arm: from a rigid face block's centroid
      double du_n, du_1, du_2;
    };
    std::array<Frame, tile> frames;
    for (std::size_t l = 0; l < used; ++l) {
      const std::size_t k = first + l;
      Frame& fr = frames[l];
      // The frame in locals, stored once: read back from the tile's array, a vector written a component at a time
      // came back as a pair (a store-forwarding stall per CP).
      Vec3 n, t1, v_face;
      if constexpr (!rigid_face) {
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
        fr.arm = rotate(r, g.point_local[k]);
        v_face = b.velocity[fb] + b.angular_velocity[fb].cross(fr.arm);
      }
      const Vec3 t2 = n.cross(t1);
      const Vec3 du = increment_dt * (v_face - velocity[node_of[k]]);
      fr.n = n;
      fr.t1 = t1;
      fr.t2 = t2;
      fr.du_n = du.dot(n);
      fr.du_1 = du.dot(t1);
      fr.du_2 = du.dot(t2);
    }
    for (std::size_t l = 0; l < used; ++l) {
      const std::size_t k = first + l;
      const Frame& fr = frames[l];
      const double du_n = fr.du_n;
      const contact::Shear du_s{fr.du_1, fr.du_2};
      const auto& p = properties[property[k]];
      const contact::Response r = L::update(p, history[k], du_n, du_s, step);
      double sn = r.normal_stress, s1 = r.shear_stress[0], s2 = r.shear_stress[1];
      const double area = area_of[k];
      if constexpr (viscous_here) {
        const double kn = L::normal_stiffness(p), ks = L::shear_stiffness(p);
        const bool active = r.damping_active;  // L::damping_active(p, history[k])
        double dissipated = 0.0;
        // One spring after another: the three at once (spring_stresses, as the rigid pass) was slower here.
        auto& spring = spring_state[k];
        sn += damping.spring_stress(spring[0], kn, -du_n, increment_dt, active, dissipated);
        s1 += damping.spring_stress(spring[1], ks, -du_s[0], increment_dt, active, dissipated);
        s2 += damping.spring_stress(spring[2], ks, -du_s[1], increment_dt, active, dissipated);
        viscous_dissipation[k] += area * dissipated;
      }
      traction[k] = {sn, s1, s2};
      const Vec3 f = area * (sn * fr.n + s1 * fr.t1 + s2 * fr.t2);
      force[k] = f;
      if constexpr (rigid_face) g.moment[k] = fr.arm.cross(f);
      if constexpr (L::dissipates) slip_dissipation[k] += area * r.dissipated;
    }
  }
}

/// The node contact loop of one group, over the threads by the ranges `bounds` (parallel/thread_ranges.hpp; empty:
/// even splits).
template <class G, class Damping>
void node_contact_pass(G& g, const model::Model& m, const Damping& damping, double increment_dt,
                       double inverse_omega_squared, const parallel::Bounds& bounds = {}) {
#pragma omp parallel if (g.size() > 256)
  {
    const auto [first_point, end_point] = parallel::my_range(bounds, g.size());
    node_contact_range(g, m, damping, increment_dt, inverse_omega_squared, first_point, end_point);
  }
}

/// Node contacts of every node group of `d`: relative velocity of the face point and the node -> increment -> law ->
/// damping -> force.
template <class State, class Damping>
void node_contact_passes(State& state, const model::Model& m, const Damping& damping, double increment_dt,
                         double inverse_omega_squared) {
  std::size_t group = 0;
  state.for_each_group([&](auto& g) {
    node_contact_pass(g, m, damping, increment_dt, inverse_omega_squared, state.contact_bounds[group++]);
  });
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

/// The velocity and position update of every deformable block's nodes under split local damping
/// (integrate/local_split.hpp), after the node pass has gathered their forces into nd.force.
template <class State>
bool split_node_update(State& state, model::Model& m, const damping::Local& damping, double dt, double increment_dt,
                       bool move, double redetection) {
  auto& nd = m.deformable.nodes;
  const auto& blocks = m.deformable.blocks;
  const Vec3 gravity = m.gravity;
  const double c = damping.coefficient;
  const auto count = static_cast<std::ptrdiff_t>(blocks.size());
  bool moved = false;
#pragma omp parallel for schedule(dynamic, 8) if (count > 16) reduction(|| : moved)
  for (std::ptrdiff_t bb = 0; bb < count; ++bb) {
    const auto& blk = blocks[static_cast<std::size_t>(bb)];
    detail::SplitLocalDamping split;
    const bool whole = detail::split_local_damping(blk, nd, c, split);
    for (std::uint32_t i = blk.first_node; i < blk.end_node; ++i) {
      const Vec3 v_old = nd.velocity[i];
      const Vec3 d = whole ? split.force(nd, i) : detail::local_damping_force(c, nd.force[i], v_old);
      Vec3 v = v_old + (dt * state.node_inverse_mass[i]) * (nd.force[i] + d);
      for (int k = 0; k < 3; ++k)
        if (nd.fixity[i] & (1u << k)) v[k] = 0.0;
      nd.velocity[i] = v;
      state.node_kinetic[i] = 0.5 * nd.mass[i] * v_old.dot(v);
      state.node_viscous[i] -= d.dot(0.5 * (v_old + v)) * dt;
      state.node_gravity_work[i] += nd.real_mass[i] * gravity.dot(v_old) * increment_dt;
      if (move) {
        nd.position[i] += dt * v;
        moved = moved || (nd.position[i] - state.detected_node_position[i]).squaredNorm() > redetection * redetection;
      }
    }
  }
  return moved;
}

/// Gather (elements, contacts, trusses in a fixed order), gravity with the real mass, damped velocity update with
/// the scaled mass (mass-proportional damping in the frame of `frame`, as block_pass), then positions. Returns whether
/// a node moved more than `redetection` since the last detection.
template <class State, class Damping>
bool node_pass(State& state, model::Model& m, const Damping& damping, double dt, double increment_dt, bool move,
               double redetection, const damping::FrameVelocity& frame = {}) {
  auto& nd = m.deformable.nodes;
  const Vec3 gravity = m.gravity;
  const std::size_t count = nd.size();
  bool moved = false;
  // The node contact forces of every group, in the order of the groups (node entries name the group).
  std::array<const Vec3*, State::group_count> group_force{};
  {
    std::size_t group = 0;
    state.for_each_group([&](const auto& g) { group_force[group++] = g.force.data(); });
  }
  // The frame's acceleration over the step and its velocity at mid-step, the same for every node (no division per
  // node): the inertia force m a_frame of the moving frame, and the frame's work (m dv - F dt) . v_frame.
  [[maybe_unused]] const Vec3 frame_acceleration = (frame.after - frame.before) / dt;
  [[maybe_unused]] const Vec3 frame_middle = 0.5 * (frame.before + frame.after);
#pragma omp parallel if (count > 1024) reduction(|| : moved) \
    firstprivate(group_force, gravity, frame_acceleration, frame_middle, dt, increment_dt, move, redetection)
  {
    const auto [first_node, end_node] = parallel::my_range(state.node_bounds, count);
    // Every value the loop reads is a local of the thread (the scalars above firstprivate, the policy and the
    // frame copied, the arrays through local pointers): Eigen stores its packets through a type that may alias
    // anything (SSE's unaligned store), so through the shared references GCC reloaded them after each node's stores.
    const Damping policy = damping;
    const damping::FrameVelocity table = frame;
    const std::uint32_t* __restrict const element_first = state.element_first.data();
    const std::uint32_t* __restrict const element_entry = state.element_entry.data();
    const std::array<Vec3, 4>* __restrict const element_force = state.element_force.data();
    const std::uint32_t* __restrict const node_first = state.node_first.data();
    const std::uint32_t* __restrict const node_entry = state.node_entry.data();
    const double* __restrict const node_coefficient = state.node_coefficient.data();
    const std::uint32_t* __restrict const truss_first = state.truss_first.data();
    const std::uint32_t* __restrict const truss_entry = state.truss_entry.data();
    const Vec3* __restrict const truss_force = state.truss_force.data();
    const double* __restrict const mass_of = nd.mass.data();
    const double* __restrict const real_mass = nd.real_mass.data();
    const double* __restrict const inverse_mass = state.node_inverse_mass.data();
    const std::uint8_t* __restrict const fixity_of = nd.fixity.data();
    const Vec3* __restrict const detected = state.detected_node_position.data();
    Vec3* __restrict const node_force = nd.force.data();
    Vec3* __restrict const velocity = nd.velocity.data();
    Vec3* __restrict const position = nd.position.data();
    double* __restrict const kinetic = state.node_kinetic.data();
    double* __restrict const viscous = state.node_viscous.data();
    double* __restrict const gravity_work = state.node_gravity_work.data();
    [[maybe_unused]] double* __restrict const frame_work = state.node_frame_work.data();
    const double redetection_squared = redetection * redetection;
    bool moved_here = false;  // a register: the reduction's own copy lived on the stack, stored and read per node
    for (std::size_t i = first_node; i < end_node; ++i) {
      Vec3 force = Vec3::Zero();
      for (std::uint32_t e = element_first[i]; e < element_first[i + 1]; ++e) {
        const std::uint32_t code = element_entry[e];
        force += element_force[code >> 2][code & 3u];
      }
      for (std::uint32_t e = node_first[i]; e < node_first[i + 1]; ++e) {
        const std::uint32_t code = node_entry[e];
        force += node_coefficient[e] * group_force[code >> State::node_entry_group_shift][code & State::node_entry_point_mask];
      }
      for (std::uint32_t e = truss_first[i]; e < truss_first[i + 1]; ++e) {
        const std::uint32_t code = truss_entry[e];
        force += (code & 1u) ? Vec3(-truss_force[code >> 1]) : truss_force[code >> 1];
      }
      force += real_mass[i] * gravity;
      node_force[i] = force;
      if constexpr (std::is_same_v<Damping, damping::Local>)
        if (policy.split_rigid_motion) continue;  // updated block by block below, once every force is gathered
      const damping::Inertia mass{mass_of[i], inverse_mass[i]};
      const Vec3 v_old = velocity[i];
      double dissipated = 0.0;
      const std::uint8_t fixity = fixity_of[i];
      // The three components as scalars, one after the other: written into a vector one component at a time, the
      // new velocity went through the stack and was read back as a pair (a store-forwarding stall per node).
      double v0 = 0.0, v1 = 0.0, v2 = 0.0;
      if constexpr (damping::damps_velocities<Damping>()) {
        double by_frame = 0.0;
        const auto component = [&](int c) {
          const double v = policy.velocity_update(v_old[c] - table.before[c], force[c] - mass.value * frame_acceleration[c], mass, dt,
                                                   dissipated) +
                           table.after[c];
          by_frame += (mass.value * (v - v_old[c]) - force[c] * dt) * frame_middle[c];
          return v;
        };
        if (!(fixity & 1u)) v0 = component(0);
        if (!(fixity & 2u)) v1 = component(1);
        if (!(fixity & 4u)) v2 = component(2);
        frame_work[i] += by_frame;
      } else {
        if (!(fixity & 1u)) v0 = policy.velocity_update(v_old[0], force[0], mass, dt, dissipated);
        if (!(fixity & 2u)) v1 = policy.velocity_update(v_old[1], force[1], mass, dt, dissipated);
        if (!(fixity & 4u)) v2 = policy.velocity_update(v_old[2], force[2], mass, dt, dissipated);
      }
      const Vec3 v(v0, v1, v2);
      velocity[i] = v;
      kinetic[i] = 0.5 * mass.value * v_old.dot(v);
      viscous[i] += dissipated;
      gravity_work[i] += real_mass[i] * gravity.dot(v_old) * increment_dt;
      if (move) {
        position[i] += dt * v;
        moved_here |= (position[i] - detected[i]).squaredNorm() > redetection_squared;
      }
    }
    moved = moved || moved_here;
  }
  if constexpr (std::is_same_v<Damping, damping::Local>)
    if (damping.split_rigid_motion) moved = split_node_update(state, m, damping, dt, increment_dt, move, redetection);
  return moved;
}

}  // namespace blockdem
