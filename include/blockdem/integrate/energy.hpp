#pragma once
// The energy balance of a run: the terms the passes accumulate (kinetic, elastic, work of gravity and of the base,
// viscous and slip dissipation, and what re-detection stores in the contacts) and the balance error, the check that
// the explicit scheme, the laws and the damping policies conserve what they should.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "blockdem/damping/concepts.hpp"
#include "blockdem/integrate/block_pass.hpp"
#include "blockdem/integrate/contact_group.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

/// Energy terms since the start of the simulation (J). The balance: kinetic + elastic + viscous + slip
/// - gravity_work - base_work stays equal to its value at the start.
struct EnergyReport {
  double kinetic = 0;       // of the free blocks
  double elastic = 0;       // stored in the joint springs and the damping springs (Maxwell branches)
  double gravity_work = 0;  // done by gravity on the free blocks
  double base_work = 0;     // done by the base blocks on the rest (and by dashpots anchored to them: damping/frame.hpp)
  double viscous = 0;       // dissipated by viscous damping
  double slip = 0;          // dissipated by the joint laws (friction, softening)
  // Changes of the discrete model, done by no force: the energy re-detection stores in the contacts (CPs of a
  // re-drawn joint that take its state, minus the energy of CPs dropped while loaded, plus that of CPs whose
  // tributary area changed; CPs found in overlap start touching and store nothing; with
  // the joints intact it stays near 0), the kinetic energy of the masses the timestep hold raises, and the change of
  // the scheme's kinetic energy measure at a step taken with another timestep than the move before it
  // (half_step_kinetic).
  double contact_update = 0;
  double balance_error = 0; // |change of (kinetic + elastic + viscous + slip) - work - contact_update| / the largest term
};

/// `e` with its balance error against the reference `e0` (the terms at the first step). The whole sum is the
/// reference, dissipation of the first step included: a joint whose initial overlap stresses it beyond its strength
/// (allowed up to the contact tolerance) dissipates at the first step with no motion at all.
inline EnergyReport with_balance(EnergyReport e, const EnergyReport& e0) {
  const auto sum = [](const EnergyReport& x) {
    return x.kinetic + x.elastic + x.viscous + x.slip - x.gravity_work - x.base_work - x.contact_update;
  };
  const double change = sum(e) - sum(e0);
  const double scale = std::max({std::abs(e.gravity_work) + std::abs(e.base_work), e.kinetic + e.elastic + e.viscous + e.slip,
                                 e0.kinetic + e0.elastic, 1e-300});
  e.balance_error = std::abs(change) / scale;
  return e;
}

/// The kinetic energy of the free blocks and the nodes at their present half-step velocities alone,
/// 1/2 m v(n-1/2).v(n-1/2) (+ 1/2 w.I.w in the block's frame), before the velocity update of step n. The scheme's
/// kinetic energy at step n is 1/2 m v(n-1/2).v(n+1/2) (BlockState::kinetic): its part beyond this one,
/// 1/2 m v(n-1/2).(v(n+1/2) - v(n-1/2)), is the impulse of the step's forces over dt, so that a step taken with
/// another timestep than the move before it changes the measure by that part times 1 - dt_old / dt_new
/// (Simulation: the timestep change, booked with the model's other changes in contact_update).
inline double half_step_kinetic(const model::Model& m) {
  const auto& b = m.bodies;
  double sum = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b.motion[i] != model::Motion::free) continue;
    const Vec3 w = b.rotation[i].transpose() * b.angular_velocity[i];  // in the principal frame
    sum += 0.5 * b.mass[i] * b.velocity[i].squaredNorm() +
           0.5 * (b.principal_inertia[i].array() * w.array() * w.array()).sum();
  }
  const auto& nd = m.deformable.nodes;
  for (std::size_t i = 0; i < nd.size(); ++i) sum += 0.5 * nd.mass[i] * nd.velocity[i].squaredNorm();
  return sum;
}

/// Adds the blocks' kinetic energy, work of gravity and of the base, and viscous work to `e`.
inline void add_block_energy(const BlockState& s, EnergyReport& e) {
  for (std::size_t i = 0; i < s.kinetic.size(); ++i) {
    e.kinetic += s.kinetic[i];
    e.gravity_work += s.gravity_work[i];
    e.base_work += s.base_work[i] + s.frame_work[i];
    e.viscous += s.viscous[i];
  }
}

/// Adds the energy of the rigid contact groups to `e`: stored in the joints and the damping springs, dissipated by
/// slip and viscous damping (a contact field's work included).
template <class Groups, damping::DampingPolicy Damping>
void add_contact_energy(const Groups& groups, const Damping& damping, EnergyReport& e) {
  for_each_in(groups, [&](const auto& g) {
    using L = typename std::remove_cvref_t<decltype(g)>::LawType;
    for (std::size_t c = 0; c < g.contacts(); ++c) {
      const auto& p = g.properties[g.property[c]];
      if constexpr (std::remove_cvref_t<decltype(g)>::has_field) e.viscous += g.field_work(c);
      for (std::uint32_t k = g.first_point[c]; k < g.first_point[c + 1]; ++k)
        add_contact_point_energy<L>(damping, p, g.history[k], g.spring_at(c, k), g.area[k], g.slip_dissipation[k],
                                    g.viscous_dissipation[k], e.elastic, e.slip, e.viscous);
    }
  });
}

/// Sum of |unbalanced force| over sum of |applied force| (the real weights: `real_block_mass` of the rigid blocks,
/// the nodes' real masses) of the free blocks and nodes: the measure of static equilibrium.
inline double unbalanced_force_ratio(const model::Model& m, const std::vector<double>& real_block_mass) {
  const auto& b = m.bodies;
  double unbalanced = 0, applied = 0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b.motion[i] != model::Motion::free || m.deformable.is_deformable(i)) continue;
    unbalanced += b.force[i].norm();
    applied += real_block_mass[i] * m.gravity.norm();
  }
  const auto& nd = m.deformable.nodes;
  for (std::size_t i = 0; i < nd.size(); ++i) {
    if ((nd.fixity[i] & 7) == 7) continue;
    Vec3 f = nd.force[i];
    for (int c = 0; c < 3; ++c)
      if (nd.fixity[i] & (1u << c)) f[c] = 0;
    unbalanced += f.norm();
    applied += nd.real_mass[i] * m.gravity.norm();
  }
  return applied > 0 ? unbalanced / applied : 0.0;
}

}  // namespace blockdem
