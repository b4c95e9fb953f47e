#pragma once
// The contacts as output sees them (world frame): every contact point of the rigid groups and the node groups with
// its position, normal, force, stresses and damage (ContactView), and the joint histories with the law that holds
// them. For VTK files, CSV tables and the damage census; the step never calls these.

#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/integrate/block_pass.hpp"
#include "blockdem/integrate/contact_frame.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

/// One contact point as output sees it (world frame).
struct ContactView {
  Vec3 position;        // m, midway between the material points on A and B
  Vec3 normal;          // from A to B
  Vec3 force;           // N, on B
  double area = 0;      // m^2
  double gap = 0;       // m, positive open
  double normal_stress = 0;  // Pa, compression positive (joint law plus damping)
  double shear_stress = 0;   // Pa, magnitude
  double damage = 0;    // 0 intact .. 1 failed (laws without damage: 1 once failed); 0 if never bonded
  bool never_bonded = false;  // appeared during the run (contact::never_bonded): a new contact, not a broken joint
  // How a bonded joint is damaged, by the laws that say it: cracked (opened beyond the tensile strength: secant
  // unloading) and crushed (closed beyond the compressive hardening limit) by elasto-softening; slipped (at or past
  // the Coulomb limit) by Mohr-Coulomb, and by elasto-softening for damage neither cracked nor crushed.
  bool cracked = false, crushed = false, slipped = false;
  std::size_t block_a = 0, block_b = 0;
};

/// The damage of a CP for output: the law's (contact::ContactLaw::damage); 0 for a CP that appeared during the run
/// and was never bonded, which ContactView::never_bonded marks instead.
template <contact::ContactLaw L>
void set_damage(ContactView& v, const typename L::History& h) {
  v.never_bonded = L::never_bonded(h);
  v.damage = v.never_bonded ? 0.0 : L::damage(h);
  if (v.never_bonded) return;
  if constexpr (requires { h.tension_secant; }) {
    v.cracked = h.tension_secant < 1;
    v.crushed = h.compression_secant < 1;
    v.slipped = v.damage > 0 && !v.cracked && !v.crushed;
  } else if constexpr (requires { h.slipping; }) {
    v.slipped = h.failed || h.slipping;
  }
}

/// Calls f(block_a, block_b, const History&) for every contact point with its joint law's history, or
/// f(block_a, block_b, std::type_identity<Law>{}, const History&) if f takes the law too: the block contacts, then
/// the node contacts of deformable blocks (block_a: the node's block; `deformable` null for a rigid-only step).
template <class Groups, class Deformable, class F>
void visit_contact_histories(const Groups& groups, const Deformable* deformable, F&& f) {
  const auto call = [&]<class L>(std::type_identity<L> law, std::size_t a, std::size_t b, const typename L::History& h) {
    if constexpr (std::invocable<F&, std::size_t, std::size_t, std::type_identity<L>, const typename L::History&>) f(a, b, law, h);
    else f(a, b, h);
  };
  for_each_in(groups, [&](const auto& g) {
    using L = typename std::remove_cvref_t<decltype(g)>::LawType;
    for (std::size_t c = 0; c < g.contacts(); ++c)
      for (std::uint32_t k = g.first_point[c]; k < g.first_point[c + 1]; ++k)
        call(std::type_identity<L>{}, std::size_t{g.body_a[c]}, std::size_t{g.body_b[c]}, g.history[k]);
  });
  if (!deformable) return;
  deformable->for_each_group([&](const auto& g) {
    using L = typename std::remove_cvref_t<decltype(g)>::LawType;
    for (std::size_t k = 0; k < g.size(); ++k)
      call(std::type_identity<L>{}, std::size_t{g.node_block[k]}, std::size_t{g.face_block[k]}, g.history[k]);
  });
}

/// Calls f(const ContactView&) for every contact point, group by group (`deformable` null for a rigid-only step).
template <class Groups, class Deformable, class F>
void visit_contacts(const model::Model& m, const Groups& groups, const Deformable* deformable, F&& f) {
  for_each_in(groups, [&](const auto& g) {
    using L = typename std::remove_cvref_t<decltype(g)>::LawType;
    for (std::size_t c = 0; c < g.contacts(); ++c) {
      const ContactFrame fr = contact_frame(m.bodies, g, c);
      for (std::uint32_t k = g.first_point[c]; k < g.first_point[c + 1]; ++k) {
        ContactView v;
        v.block_a = g.body_a[c];
        v.block_b = g.body_b[c];
        v.position = fr.point(g.s1[k], g.s2[k]);
        v.normal = fr.n;
        v.area = g.area[k];
        const auto t = g.traction_at(c, k);
        v.force = v.area * (t[0] * fr.n + t[1] * fr.t1 + t[2] * fr.t2);
        const auto& h = g.history[k];
        v.gap = h.gap;
        v.normal_stress = t[0];
        v.shear_stress = std::hypot(t[1], t[2]);
        set_damage<L>(v, h);
        f(v);
      }
    }
  });
  if (!deformable) return;
  const auto& x = m.deformable.nodes.position;
  deformable->for_each_group([&](const auto& g) {
    using L = typename std::remove_cvref_t<decltype(g)>::LawType;
    for (std::size_t k = 0; k < g.size(); ++k) {
      ContactView v;
      v.block_a = g.node_block[k];
      v.block_b = g.face_block[k];
      v.position = x[g.node[k]];
      v.force = g.force[k];
      if constexpr (std::remove_cvref_t<decltype(g)>::FaceKinematics::deformable) {
        const auto& t = g.triangle[k];
        v.normal = -(x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).normalized();
      } else {
        v.normal = rotate(m.bodies.rotation[g.face_block[k]], g.normal_local[k]);
      }
      v.area = g.area[k];
      const auto& h = g.history[k];
      v.gap = h.gap;
      v.normal_stress = g.traction[k][0];
      v.shear_stress = std::hypot(g.traction[k][1], g.traction[k][2]);
      set_damage<L>(v, h);
      f(v);
    }
  });
}

}  // namespace blockdem
