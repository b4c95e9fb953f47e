#pragma once
// The contacts of one joint law, in struct-of-arrays storage. A contact is the interface between two blocks (one
// common plane, as in 3DEC); its contact points (CPs, the sub-contacts) lie on that plane. What is common to the
// CPs of a contact is stored and computed once per contact: the block pair, the joint parameters, the contact
// frame (n, t1, t2) and its origin, fixed in block A; the relative motion of the two blocks, reduced to an affine
// map of the CP's plane coordinates; the resultant force and moments. Per CP remain two plane coordinates, the
// area, the law's history, the damping policy's spring state and the traction.

#include <array>
#include <cstdint>
#include <vector>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"

namespace blockdem {

/// The energy of one CP (J), added to the three totals: the law's stored energy and, for policies with springs of
/// their own (Maxwell), what the branches still store, which the loop had counted as work done on them (dissipated):
/// it moves from viscous to elastic. `slip` and `viscous` are the CP's accumulated dissipation.
template <contact::ContactLaw Law, damping::DampingPolicy Damping>
void add_contact_point_energy(const Damping& damping, const typename Law::Parameters& p, const typename Law::History& h,
                              const std::array<typename Damping::ContactState, 3>& spring, double area, double slip,
                              double viscous, double& elastic_total, double& slip_total, double& viscous_total) {
  double stored = Law::stored_energy(p, h);
  if constexpr (requires { damping.stored_energy(spring[0], 1.0); }) {
    const double branches = damping.stored_energy(spring[0], Law::normal_stiffness(p)) +
                            damping.stored_energy(spring[1], Law::shear_stiffness(p)) +
                            damping.stored_energy(spring[2], Law::shear_stiffness(p));
    stored += branches;
    viscous_total -= area * branches;
  }
  elastic_total += area * stored;
  slip_total += slip;
  viscous_total += viscous;
}

namespace detail {
/// The per-contact branch state of policies with a contact-field form (damping::Maxwell::ContactField), else none.
template <class Damping>
struct ContactFieldOf {
  using type = damping::NoState;
  using sum = damping::NoState;
  static constexpr bool present = false;
};
template <class Damping>
  requires requires { typename Damping::ContactField; }
struct ContactFieldOf<Damping> {
  using type = typename Damping::ContactField;
  using sum = typename Damping::Generalised;
  static constexpr bool present = true;
};
}  // namespace detail

template <contact::ContactLaw Law, damping::DampingPolicy Damping>
struct ContactGroup {
  using Parameters = typename Law::Parameters;
  using History = typename Law::History;
  using SpringState = std::array<typename Damping::ContactState, 3>;  // normal, shear 1, shear 2
  using Traction = std::array<double, 3>;                             // Pa: normal (compression +), t1, t2

  std::vector<Parameters> properties;  // the parameter sets of this group; contacts refer to them by index

  // Per contact.
  std::vector<std::uint32_t> body_a, body_b;
  std::vector<std::uint16_t> property;
  std::vector<Vec3> origin_a;            // m, the origin of the contact plane in A's body frame (from A's centroid)
  std::vector<Vec3> normal_a, tangent_a; // n and t1 in A's body frame (they turn with A); t2 = n x t1
  std::vector<std::uint32_t> first_point;  // the CPs of contact c are first_point[c] .. first_point[c + 1] - 1
  std::vector<Vec3> force;               // N, world frame, on B (A gets the opposite)
  std::vector<Vec3> moment;              // N m, world frame: [2c] on A about A's centroid, [2c + 1] on B about B's
  // Policies with a contact-field form (Maxwell): while field_form[c] is 1, the branch state of contact c is
  // field[c] and its CPs' spring_state is unused; once a CP has released its branches, the CPs' spring_state.
  static constexpr bool has_field = detail::ContactFieldOf<Damping>::present;
  using Field = typename detail::ContactFieldOf<Damping>::type;
  using FieldSum = typename detail::ContactFieldOf<Damping>::sum;  // sum over the branches of a field
  std::vector<Field> field;
  std::vector<std::uint8_t> field_form;
  std::vector<double> field_viscous;  // J, the viscous work of the branches while in the field form, accumulated
  // The CPs' area moments sum a, sum a x1, sum a x2, sum a x1^2, sum a x2^2, sum a x1 x2 (m^2, m^3, m^4): the
  // contact's stiffness on its generalised elongation, from which the field's work per step follows (complete()).
  std::vector<std::array<double, 6>> area_moments;

  // Per contact point.
  std::vector<double> s1, s2;            // m, coordinates on the contact plane from the origin along t1, t2
  std::vector<double> area;              // m^2
  std::vector<History> history;
  std::vector<SpringState> spring_state;
  std::vector<Traction> traction;        // Pa, on B: joint law plus damping, in the contact frame
  std::vector<double> slip_dissipation;     // J, accumulated
  std::vector<double> viscous_dissipation;  // J, accumulated

  // Gather lists: for block i, entries first[i] .. first[i + 1] - 1 of `entry`, each 2 * contact + side (0: A, 1: B).
  std::vector<std::uint32_t> first;
  std::vector<std::uint32_t> entry;

  std::size_t contacts() const { return body_a.size(); }
  std::size_t size() const { return area.size(); }  // contact points

  void clear() { *this = ContactGroup{}; }

  /// Opens contact c (call before adding its CPs).
  void begin_contact(std::uint32_t a, std::uint32_t b, std::uint16_t p, const Vec3& origin, const Vec3& normal,
                     const Vec3& tangent, bool in_field_form = false, const Field& f = Field{}, double viscous = 0.0) {
    if constexpr (has_field) {
      field.push_back(f);
      field_form.push_back(in_field_form ? 1 : 0);
      field_viscous.push_back(viscous);
    }
    body_a.push_back(a);
    body_b.push_back(b);
    property.push_back(p);
    origin_a.push_back(origin);
    normal_a.push_back(normal);
    tangent_a.push_back(tangent);
    if (first_point.empty()) first_point.push_back(0);
    first_point.push_back(first_point.back());
    force.push_back(Vec3::Zero());
    moment.push_back(Vec3::Zero());
    moment.push_back(Vec3::Zero());
  }

  /// The branch state of CP k of contact c, whichever form holds it.
  SpringState spring_at(const Damping& damping, std::size_t c, std::size_t k) const {
    if constexpr (has_field) {
      if (field_form[c]) {
        const auto& p = properties[property[c]];
        return damping.field_branch_stresses(field[c], Law::normal_stiffness(p), Law::shear_stiffness(p), s1[k], s2[k]);
      }
    }
    return spring_state[k];
  }

  /// Adds a CP to the contact opened last.
  void add_point(double u, double v, double a, const History& h, const SpringState& spring, double slip, double viscous) {
    s1.push_back(u);
    s2.push_back(v);
    area.push_back(a);
    history.push_back(h);
    spring_state.push_back(spring);
    traction.push_back({0.0, 0.0, 0.0});
    slip_dissipation.push_back(slip);
    viscous_dissipation.push_back(viscous);
    ++first_point.back();
  }

  /// Builds what follows from the contacts once they are all added: the gather lists for `blocks` blocks, in
  /// increasing contact order so that sums are reproducible, and the area moments of each contact's CPs.
  void complete(std::size_t blocks) {
    if constexpr (has_field) {
      area_moments.assign(contacts(), {});
      for (std::size_t c = 0; c < contacts(); ++c)
        for (std::uint32_t k = first_point[c]; k < first_point[c + 1]; ++k) {
          const double a = area[k], u = s1[k], v = s2[k];
          auto& m = area_moments[c];
          m = {m[0] + a, m[1] + a * u, m[2] + a * v, m[3] + a * u * u, m[4] + a * v * v, m[5] + a * u * v};
        }
    }
    first.assign(blocks + 1, 0);
    for (std::size_t c = 0; c < contacts(); ++c) {
      ++first[body_a[c] + 1];
      ++first[body_b[c] + 1];
    }
    for (std::size_t i = 0; i < blocks; ++i) first[i + 1] += first[i];
    entry.assign(first.back(), 0);
    std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
    for (std::size_t c = 0; c < contacts(); ++c) {
      entry[next[body_a[c]]++] = static_cast<std::uint32_t>(2 * c);
      entry[next[body_b[c]]++] = static_cast<std::uint32_t>(2 * c + 1);
    }
  }
};

}  // namespace blockdem
