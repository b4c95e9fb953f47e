#pragma once
// The Maxwell contact field (damping::ContactFieldDamping): the branches of a contact whose contact points are all
// bonded and closed act on the contact's resultant, advanced once per step in the contact pass
// (integrate/contact_pass.hpp). Here: what the contact pass adds per contact point to the resultants, and the release
// of a contact's field when one of its contact points fails or opens (its CPs then keep their own branch states).

#include <array>
#include <cstddef>
#include <cstdint>

#include "blockdem/core/lanes.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/integrate/contact_frame.hpp"
#include "blockdem/integrate/contact_group.hpp"

namespace blockdem {

/// Adds the force (an, a1, a2) (N; normal, t1, t2) of a CP at plane coordinates (x1, x2) to its contact's
/// resultants in the contact frame: the force and the moment S x f about the origin, S = x1 t1 + x2 t2
/// (n x t1 = t2, t1 x t2 = n, t2 x n = t1).
[[gnu::always_inline]] inline void add_cp_force(double x1, double x2, double an, double a1, double a2, double& fn,
                                                double& f1, double& f2, double& mn, double& m1, double& m2) {
  fn += an;
  f1 += a1;
  f2 += a2;
  mn += x1 * a2 - x2 * a1;
  m1 += x2 * an;
  m2 -= x1 * an;
}

/// Adds resultants in the contact frame (force along n, t1, t2, moment about the origin along n, t1, t2) to lane
/// `lane` of the contact pass's resultants.
[[gnu::always_inline]] inline void add_to_lane(Lanes (&resultant)[6], std::size_t lane, const std::array<double, 6>& r) {
  for (std::size_t j = 0; j < 6; ++j) resultant[j].set(lane, resultant[j][lane] + r[j]);
}

/// A contact in the field form some of whose CPs failed or opened in this step (contact_pass_of): those CPs
/// release their branches. A released CP's new stress is 0, and its work over the step is that of its old stress
/// only. (With no time passing, its branches only stop acting: nothing is released.) From the next step on every
/// CP of the contact keeps its own branch states, from the field's values; those of the released CPs are zero.
/// Adds the released stresses' force to the lane's resultants (the contact frame's six).
template <bool AdvanceFields, class Damping, class G>
void release_field(const Damping&, G& g, std::size_t c, const Lanes (&motion)[6], std::size_t lane, Lanes (&resultant)[6]) {
  using L = typename G::LawType;
  const auto& p = g.properties[g.property[c]];
  const double kn = L::normal_stiffness(p);
  const double ks = L::shear_stiffness(p);
  const std::uint32_t begin = g.first_point[c], end = g.first_point[c + 1];
  const typename G::FieldSum q{-motion[0][lane], -motion[1][lane], -motion[2][lane],
                               -motion[3][lane], -motion[4][lane], -motion[5][lane]};
  double field_work = 0.0;
  const auto elongations = g.field_elongations(c);
  typename G::FieldSum after{};
  for (const auto& branch : elongations)
    for (std::size_t j = 0; j < 6; ++j) after[j] += branch[j];
  double fn = 0, f1 = 0, f2 = 0, mn = 0, m1 = 0, m2 = 0;
  for (std::uint32_t k = begin; k < end; ++k) {
    if (L::damping_active(p, g.history[k])) continue;
    const double x1 = g.s1[k], x2 = g.s2[k], area = g.area[k];
    const auto now = Damping::field_stress(after, kn, ks, x1, x2);
    const auto e = Damping::field_stress(q, 1.0, 1.0, x1, x2);  // B q: the CP's elongations
    field_work -= 0.5 * area * (now[0] * e[0] + now[1] * e[1] + now[2] * e[2]);
    add_cp_force(x1, x2, -area * now[0], -area * now[1], -area * now[2], fn, f1, f2, mn, m1, m2);
  }
  if constexpr (AdvanceFields) {
    for (std::uint32_t k = begin; k < end; ++k)
      g.spring_state[k] = L::damping_active(p, g.history[k])
                              ? Damping::field_branch_stresses(elongations, kn, ks, g.s1[k], g.s2[k])
                              : typename G::SpringState{};
    g.field_form[c] = 0;
  }
  g.add_field_work(c, field_work);
  add_to_lane(resultant, lane, {fn, f1, f2, mn, m1, m2});
}

/// The field of old contact `oc` of group `old` (frame `old_frame`) moved to a new contact of origin `origin` and
/// frame (n, t1, t2) in elongation form, the form begin_contact takes it in (complete() turns it back): each branch's
/// generalised elongation is that of the same rigid relative motion at the new origin.
template <class G>
typename G::Field moved_field(const G& old, std::size_t oc, const ContactFrame& old_frame, const Vec3& origin, const Vec3& n,
                              const Vec3& t1, const Vec3& t2) {
  typename G::Field field{};
  const Vec3 shift = origin - old_frame.origin;
  const auto elongations = old.field_elongations(oc);
  for (std::size_t i = 0; i < field.size(); ++i) {
    const auto& h = elongations[i];
    const Vec3 e0 = h[0] * old_frame.n + h[1] * old_frame.t1 + h[2] * old_frame.t2;
    const Vec3 r = h[3] * old_frame.n + h[4] * old_frame.t1 + h[5] * old_frame.t2;
    const Vec3 e = e0 + r.cross(shift);
    field[i] = {e.dot(n), e.dot(t1), e.dot(t2), r.dot(n), r.dot(t1), r.dot(t2)};
  }
  return field;
}

}  // namespace blockdem
