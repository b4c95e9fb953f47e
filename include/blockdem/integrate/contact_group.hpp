#pragma once
// The contacts of one joint law, in struct-of-arrays storage. A contact is the interface between two blocks (one
// common plane, as in 3DEC); its contact points (CPs, the sub-contacts) lie on that plane. What is common to the
// CPs of a contact is stored and computed once per contact: the block pair, the joint parameters, the contact
// frame (n, t1, t2) and its origin, fixed in block A (the origin at the area centroid of the CPs, t1 along a
// principal axis of their areas: AreaMoments); the relative motion of the two blocks, reduced to an affine
// map of the CP's plane coordinates; the resultant force and moments. Per CP remain two plane coordinates, the
// area, the law's history and the damping policy's spring state; the traction is not stored but taken back from
// those two (traction_at).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/lanes.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/io/checkpoint.hpp"

namespace blockdem {

/// The energy of one CP (J), added to the three totals: the law's stored energy and, for policies with springs of
/// their own (Maxwell), what the branches still store, which the loop had counted as work done on them (dissipated):
/// it moves from viscous to elastic. `slip` and `viscous` are the CP's accumulated dissipation.
template <contact::ContactLaw Law, damping::DampingPolicy Damping>
void add_contact_point_energy(const Damping& damping, const typename Law::Parameters& p, const typename Law::History& h,
                              const std::array<typename Damping::ContactState, 3>& spring, double area, double slip,
                              double viscous, double& elastic_total, double& slip_total, double& viscous_total) {
  double stored = Law::stored_energy(p, h);
  if constexpr (damping::SpringEnergyDamping<Damping>) {
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

/// The area moments of a contact's CPs at plane coordinates (x1, x2) from the origin along (t1, t2): the contact
/// frame is chosen with them (the origin at the centroid, t1 along a principal axis) and a Maxwell field's
/// stiffness follows from them.
struct AreaMoments {
  double area = 0;                                // sum a, m^2
  double first_1 = 0, first_2 = 0;                // sum a x1, sum a x2, m^3
  double second_11 = 0, second_22 = 0, second_12 = 0;  // sum a x1^2, sum a x2^2, sum a x1 x2, m^4

  void add(double x1, double x2, double a) {
    area += a;
    first_1 += a * x1;
    first_2 += a * x2;
    second_11 += a * x1 * x1;
    second_22 += a * x2 * x2;
    second_12 += a * x1 * x2;
  }
  double centroid_1() const { return first_1 / area; }
  double centroid_2() const { return first_2 / area; }
  /// The turn theta (rad) of t1 about n, t1' = cos(theta) t1 + sin(theta) t2, that makes t1' a principal axis of
  /// the areas: with the moments about the centroid (parallel axes), tan(2 theta) = 2 I12 / (I11 - I22), and then
  /// sum a x1' x2' = 0 about the centroid.
  double principal_turn() const {
    const double i11 = second_11 - first_1 * centroid_1(), i22 = second_22 - first_2 * centroid_2(),
                 i12 = second_12 - first_1 * centroid_2();
    return 0.5 * std::atan2(2.0 * i12, i11 - i22);
  }
};

namespace detail {
/// The per-contact branch state of policies with a contact-field form, else none.
template <class Damping>
struct ContactFieldOf {
  using type = damping::NoState;
  using sum = damping::NoState;
  using record = damping::NoState;
  static constexpr bool present = false;
};
template <class Damping>
  requires damping::ContactFieldDamping<Damping>
struct ContactFieldOf<Damping> {
  using type = typename Damping::ContactField;
  using sum = typename Damping::Generalised;
  using record = typename Damping::FieldLanes;
  static constexpr bool present = true;
};
}  // namespace detail

template <contact::ContactLaw Law, damping::DampingPolicy Damping>
struct ContactGroup {
  using LawType = Law;
  using Parameters = typename Law::Parameters;
  using History = typename Law::History;
  using SpringState = std::array<typename Damping::ContactState, 3>;  // normal, shear 1, shear 2
  using Traction = contact::Traction;                                 // Pa: normal (compression +), t1, t2

  std::vector<Parameters> properties;  // the parameter sets of this group; contacts refer to them by index

  // Per contact.
  std::vector<std::uint32_t> body_a, body_b;
  std::vector<std::uint16_t> property;
  std::vector<Vec3> origin_a;            // m, the origin of the contact plane in A's body frame (from A's centroid)
  std::vector<Vec3> normal_a, tangent_a; // n and t1 in A's body frame (they turn with A); t2 = n x t1
  std::vector<std::uint32_t> first_point;  // the CPs of contact c are first_point[c] .. first_point[c + 1] - 1
  std::vector<Vec3> force;               // N, world frame, on B (A gets the opposite)
  std::vector<Vec3> moment;              // N m, world frame: [2c] on A about A's centroid, [2c + 1] on B about B's
  // Policies with a contact-field form (Maxwell): while field_form[c] is 1, the branch state of contact c is its
  // field's forces (field_forces) and its CPs' spring_state is unused; once a CP has released its branches, the
  // CPs' spring_state. The field's stiffness is the diagonal of the contact's stiffness G on its generalised
  // elongation (complete(); diagonal because the frame is the CPs' principal one); its work the branches' viscous
  // work while in the field form, kept also after. Four contacts to a record, one per lane (contact c in
  // field[c / 4], lane c % 4), as the contact pass advances them; field_form has four entries per record too, 0
  // past the last contact, so that the contact pass reads a record's four in one load.
  static constexpr bool has_field = detail::ContactFieldOf<Damping>::present;
  using Field = typename detail::ContactFieldOf<Damping>::type;
  using FieldSum = typename detail::ContactFieldOf<Damping>::sum;  // sum over the branches of a field
  using FieldRecord = typename detail::ContactFieldOf<Damping>::record;
  std::vector<FieldRecord> field;
  std::vector<std::uint8_t> field_form;

  // Per contact point.
  std::vector<double> s1, s2;            // m, coordinates on the contact plane from the origin along t1, t2
  std::vector<double> area;              // m^2
  std::vector<History> history;
  std::vector<SpringState> spring_state;
  // No traction per CP: the contact pass would write 24 bytes per CP-step for output only (6-10 % of an Elastic
  // step). traction_at() asks the law's history and the damping state, which hold it.
  std::vector<double> slip_dissipation;     // J, accumulated
  std::vector<double> viscous_dissipation;  // J, accumulated

  // Gather lists: for block i, entries first[i] .. first[i + 1] - 1 of `entry`, each 2 * contact + side (0: A, 1: B).
  std::vector<std::uint32_t> first;
  std::vector<std::uint32_t> entry;

  std::size_t contacts() const { return body_a.size(); }
  std::size_t size() const { return area.size(); }  // contact points

  /// Every array, for checkpoints (io/checkpoint.hpp), as they are: the gather lists too, and the fields in their
  /// force form (complete() is not called again: it would take the forces for elongations).
  void save_state(io::CheckpointWriter& out) const { visit_state(*this, out); }
  void load_state(io::CheckpointReader& in) { visit_state(*this, in); }
  template <class Self, class Archive>
  static void visit_state(Self& g, Archive& ar) {
    ar("contact property sets", g.properties);
    ar("contact blocks A", g.body_a);
    ar("contact blocks B", g.body_b);
    ar("contact property indices", g.property);
    ar("contact origins", g.origin_a);
    ar("contact normals", g.normal_a);
    ar("contact tangents", g.tangent_a);
    ar("contacts' first CPs", g.first_point);
    ar("contact forces", g.force);
    ar("contact moments", g.moment);
    ar("contact fields", g.field);
    ar("contact field forms", g.field_form);
    ar("CP plane coordinates 1", g.s1);
    ar("CP plane coordinates 2", g.s2);
    ar("CP areas", g.area);
    ar("CP histories", g.history);
    ar("CP spring states", g.spring_state);
    ar("CP slip dissipation", g.slip_dissipation);
    ar("CP viscous dissipation", g.viscous_dissipation);
    ar("gather list heads", g.first);
    ar("gather list entries", g.entry);
  }

  void clear() { *this = ContactGroup{}; }

  /// Opens contact c (call before adding its CPs). A branch field f is given in elongation form (h_i, see
  /// field_elongations); complete() turns it into the force form the contact pass advances.
  void begin_contact(std::uint32_t a, std::uint32_t b, std::uint16_t p, const Vec3& origin, const Vec3& normal,
                     const Vec3& tangent, bool in_field_form = false, const Field& f = Field{}, double viscous = 0.0) {
    if constexpr (has_field) {
      const std::size_t c = contacts();
      if (c % lane_count == 0) {
        field.push_back(FieldRecord{});
        field_form.resize(field_form.size() + lane_count, 0);
      }
      set_field_forces(c, f);
      field_lanes(c).work.set(c % lane_count, 2.0 * viscous);
      field_form[c] = in_field_form ? 1 : 0;
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

  /// The branch field of contact c in elongation form: for each branch h_i = G^+ F_i (the field keeps F_i = G h_i,
  /// damping::Maxwell::ContactField), G = diag(g) the contact's stiffness. G is singular where the CPs do not span
  /// the plane (a line of CPs has no moment of area about it, one CP none at all); that component of h_i is then 0,
  /// and B h_i, the elongation at each CP, is that of the h_i given (a CP on the line does not move in a turn about
  /// it).
  auto field_elongations(std::size_t c) const {
    auto h = Damping::branch_forces(field_forces(c));
    const auto g = field_stiffness(c);
    for (auto& branch : h)
      for (std::size_t j = 0; j < 6; ++j) branch[j] = g[j] > 0.0 ? branch[j] / g[j] : 0.0;
    return h;
  }

  /// The record and the lane of contact c's field.
  const FieldRecord& field_lanes(std::size_t c) const { return field[c / lane_count]; }
  FieldRecord& field_lanes(std::size_t c) { return field[c / lane_count]; }
  /// Contact c's field: its branch forces (the last slot their sum, Damping::ContactField).
  Field field_forces(std::size_t c) const {
    Field f{};
    for (std::size_t i = 0; i < f.size(); ++i)
      for (std::size_t j = 0; j < 6; ++j) f[i][j] = field_lanes(c).forces[i][j][c % lane_count];
    return f;
  }
  void set_field_forces(std::size_t c, const Field& f) {
    for (std::size_t i = 0; i < f.size(); ++i)
      for (std::size_t j = 0; j < 6; ++j) field_lanes(c).forces[i][j].set(c % lane_count, f[i][j]);
  }
  /// The diagonal of contact c's stiffness G (Damping::FieldStiffness).
  auto field_stiffness(std::size_t c) const {
    typename Damping::FieldStiffness g{};
    for (std::size_t j = 0; j < 6; ++j) g[j] = field_lanes(c).stiffness[Damping::stiffness_slot(j)][c % lane_count];
    return g;
  }
  /// The viscous work of contact c's field (J), and adding to it.
  double field_work(std::size_t c) const { return 0.5 * field_lanes(c).work[c % lane_count]; }
  void add_field_work(std::size_t c, double work) {
    auto& w = field_lanes(c).work;
    w.set(c % lane_count, w[c % lane_count] + 2.0 * work);
  }

  /// The branch state of CP k of contact c, whichever form holds it.
  SpringState spring_at(std::size_t c, std::size_t k) const {
    if constexpr (has_field) {
      if (field_form[c]) {
        const auto& p = properties[property[c]];
        return Damping::field_branch_stresses(field_elongations(c), Law::normal_stiffness(p), Law::shear_stiffness(p), s1[k], s2[k]);
      }
    }
    return spring_state[k];
  }

  /// The traction (Pa, on B, in the contact frame) of CP k of contact c after the last contact pass: the joint
  /// law's (from its history) plus the damping's (from whichever form holds the branch state; none across a joint
  /// that is failed or open).
  Traction traction_at(std::size_t c, std::size_t k) const {
    const auto& p = properties[property[c]];
    Traction t = Law::traction(p, history[k]);
    if (!Law::damping_active(p, history[k])) return t;
    const SpringState spring = spring_at(c, k);
    for (std::size_t j = 0; j < 3; ++j) t[j] += Damping::held_stress(spring[j]);
    return t;
  }

  /// Adds a CP to the contact opened last.
  void add_point(double u, double v, double a, const History& h, const SpringState& spring, double slip, double viscous) {
    s1.push_back(u);
    s2.push_back(v);
    area.push_back(a);
    history.push_back(h);
    spring_state.push_back(spring);
    slip_dissipation.push_back(slip);
    viscous_dissipation.push_back(viscous);
    ++first_point.back();
  }

  /// Builds what follows from the contacts once they are all added: the gather lists for `blocks` blocks, in
  /// increasing contact order so that sums are reproducible, and for a branch field each contact's stiffness.
  /// A branch field needs each contact's origin at the area centroid of its CPs and t1 along a principal axis of
  /// their areas (InvalidArgument otherwise, naming the contact).
  void complete(std::size_t blocks) {
    if constexpr (has_field) {
      for (std::size_t c = 0; c < contacts(); ++c) {
        AreaMoments m;
        for (std::uint32_t k = first_point[c]; k < first_point[c + 1]; ++k) m.add(s1[k], s2[k], area[k]);
        const double a0 = m.area, a11 = m.second_11, a22 = m.second_22;
        // What is left of the first moments and the product of area is rounding: relative to the contact's size.
        const double tolerance = 1e-9, size = std::sqrt((a11 + a22) / std::max(a0, 1e-300)) + std::sqrt(a0);
        const double off_1 = std::abs(m.first_1) / (a0 * size), off_2 = std::abs(m.first_2) / (a0 * size),
                     off_12 = std::abs(m.second_12) / (a11 + a22 + a0 * a0);
        if (!(off_1 <= tolerance && off_2 <= tolerance && off_12 <= tolerance)) {
          char numbers[160];
          std::snprintf(numbers, sizeof numbers, "sum a x1 = %.3g, sum a x2 = %.3g (of A L), sum a x1 x2 = %.3g (of I); at most %.0e",
                        off_1, off_2, off_12, tolerance);
          throw InvalidArgument("contact group: contact " + std::to_string(c) + " (blocks " + std::to_string(body_a[c]) + ", " +
                                std::to_string(body_b[c]) + "): the Maxwell contact field needs the origin at the area " +
                                "centroid of the CPs and t1 along a principal axis of their areas; " + numbers);
        }
        const auto& p = properties[property[c]];
        const auto g = Damping::contact_stiffness(a0, a11, a22, Law::normal_stiffness(p), Law::shear_stiffness(p));
        BLOCKDEM_ASSERT(g[1] == g[2]);  // the record keeps one slot for both (Damping::stiffness_slot)
        for (std::size_t j = 0; j < 6; ++j)
          field_lanes(c).stiffness[Damping::stiffness_slot(j)].set(c % lane_count, g[j]);
        const Field h = field_forces(c);
        std::array<typename Damping::Generalised, std::tuple_size_v<Field>> forces{};  // F = G h (begin_contact: h)
        for (std::size_t b = 0; b < forces.size(); ++b)
          for (std::size_t j = 0; j < 6; ++j) forces[b][j] = g[j] * h[b][j];
        set_field_forces(c, Damping::field_of(forces));
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
