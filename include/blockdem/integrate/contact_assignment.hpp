#pragma once
// Contact assignment for the contacts between rigid blocks: the candidates of a detection (model/contact_detection)
// become contacts of the group of their joint law, one contact per block pair on one common plane, its frame at the
// area centroid of its contact points along a principal axis of their areas. At a re-detection every contact point
// inherits the state of the old contacts by one rule (integrate/contact_history.hpp), and a Maxwell field moves
// with its contact (integrate/maxwell_field.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <variant>
#include <vector>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/type_list.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/integrate/contact_frame.hpp"
#include "blockdem/integrate/contact_group.hpp"
#include "blockdem/integrate/contact_history.hpp"
#include "blockdem/integrate/maxwell_field.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem {

/// Dissipation carried over from old contact points to new ones, and that of old ones dropped (J).
struct CarriedDissipation {
  double slip = 0, viscous = 0;
};

/// The assignment of detected contact points to the rigid contact groups of a simulation, with the scratch of a
/// detection (old contacts by block pair, which old CPs have been taken over).
template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
class ContactAssignment {
 public:
  using Groups = std::tuple<ContactGroup<Laws, Damping>...>;
  using Properties = std::variant<typename Laws::Parameters...>;

  /// Distributes `candidates` over `groups`, one contact per block pair (detection emits the CPs of a pair together,
  /// on one common plane); `properties(tag_a, tag_b)` chooses the law and its parameters. With keep_history, a CP
  /// within the matching distance of an old CP of the same block pair takes over its history and damping state
  /// (Inheritance). Adds the dissipation of the old CPs that were not taken over to `retired`.
  template <class PropertyFunction>
  void assign(Groups& groups, const model::RigidBodies& b, const std::vector<model::ContactCandidate>& candidates,
              PropertyFunction& properties, const Damping& damping, const model::ContactSettings& settings,
              bool keep_history, CarriedDissipation& retired) {
    Groups old = std::move(groups);
    groups = Groups{};
    // Property sets are kept (property indices stay valid); new ones are appended.
    std::apply([&](auto&... g) { ((g.properties = std::get<std::remove_cvref_t<decltype(g)>>(old).properties), ...); }, groups);
    const double match = std::max(settings.tolerance, 0.25 * std::sqrt(settings.largest_contact_point_area()));
    // Old contacts by block pair, and which of their CPs have been taken over. Energy dissipated at CPs that will
    // not be taken over is kept in the totals.
    std::apply([&](auto&... g) {
      ((taken_over_[law_index<typename std::remove_cvref_t<decltype(g)>::LawType>()].assign(g.size(), 0)), ...);
      ((old_contacts_[law_index<typename std::remove_cvref_t<decltype(g)>::LawType>()] = contacts_by_pair(g)), ...);
    }, old);
    CarriedDissipation carried, before;
    std::apply([&](const auto&... g) {
      ((before.slip += std::accumulate(g.slip_dissipation.begin(), g.slip_dissipation.end(), 0.0),
        before.viscous += std::accumulate(g.viscous_dissipation.begin(), g.viscous_dissipation.end(), 0.0) +
                          field_viscous_work(g)), ...);
    }, old);
    std::map<std::pair<int, int>, Properties> chosen;
    // With contact fields (Maxwell), the contacts in the field form first and those whose CPs keep their own branch
    // states after them, so that the contact pass's tiles of four are of one form (at most one mixed tile a group).
    constexpr int passes = damping::ContactFieldDamping<Damping> ? 2 : 1;
    for (int pass = 0; pass < passes; ++pass) {
      for (std::size_t begin = 0, end = 0; begin < candidates.size(); begin = end) {
        const auto& c = candidates[begin];
        end = begin + 1;
        while (end < candidates.size() && candidates[end].a == c.a && candidates[end].b == c.b) ++end;
        const int ta = b.joint_tag[c.a], tb = b.joint_tag[c.b];
        auto it = chosen.find({ta, tb});
        if (it == chosen.end()) it = chosen.emplace(std::make_pair(ta, tb), properties(ta, tb)).first;
        std::visit([&](const auto& params) {
          add_contact(groups, b, params, candidates.data() + begin, candidates.data() + end, old, damping, keep_history,
                      match, carried, passes == 2 ? pass : -1);
        }, it->second);
      }
    }
    retired.slip += before.slip - carried.slip;
    retired.viscous += before.viscous - carried.viscous;
    std::apply([&](auto&... g) { (g.complete(b.size()), ...); }, groups);
  }

  /// Copies the contacts and their histories (not the damping states: they start at zero) of another policy's
  /// groups, for a simulation continued with another damping policy.
  template <class OtherGroups>
  static void copy_histories(const OtherGroups& from, Groups& to, const Damping& damping, std::size_t blocks) {
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      (copy_group(std::get<I>(from), std::get<I>(to), damping, blocks), ...);
    }(std::index_sequence_for<Laws...>{});
  }

 private:
  template <contact::ContactLaw L>
  static constexpr std::size_t law_index() { return index_in<L, Laws...>(); }

  static std::uint64_t pair_key(std::size_t a, std::size_t b) { return (std::uint64_t{a} << 32) | std::uint64_t{b}; }

  /// The viscous work of a group's fields (J; 0 without fields).
  template <class G>
  static double field_viscous_work(const G& g) {
    double w = 0.0;
    if constexpr (G::has_field)
      for (std::size_t c = 0; c < g.contacts(); ++c) w += g.field_work(c);
    return w;
  }

  template <class G>
  static std::unordered_map<std::uint64_t, std::uint32_t> contacts_by_pair(const G& g) {
    std::unordered_map<std::uint64_t, std::uint32_t> index;
    index.reserve(g.contacts());
    for (std::size_t c = 0; c < g.contacts(); ++c) index.emplace(pair_key(g.body_a[c], g.body_b[c]), static_cast<std::uint32_t>(c));
    return index;
  }

  /// Adds the contact of the CPs [first, last) (one block pair) to the group of the law of `params`. form_pass 0:
  /// only contacts that will be in the field form; 1: only the others; -1: every contact.
  template <class Params>
  void add_contact(Groups& groups, const model::RigidBodies& b, const Params& params, const model::ContactCandidate* first,
                   const model::ContactCandidate* last, const Groups& old, const Damping& damping, bool keep_history,
                   double match, CarriedDissipation& carried, int form_pass) {
    using L = std::tuple_element_t<index_in<Params, typename Laws::Parameters...>(), std::tuple<Laws...>>;
    using G = ContactGroup<L, Damping>;
    auto& g = std::get<G>(groups);
    const std::size_t a = first->a, bb = first->b;
    const G* o = nullptr;
    std::size_t oc = 0;
    if (keep_history) {
      const auto& index = old_contacts_[law_index<L>()];
      if (const auto it = index.find(pair_key(a, bb)); it != index.end()) {
        o = &std::get<G>(old);
        oc = it->second;
      }
    }
    bool in_field_form = false;
    if constexpr (G::has_field) in_field_form = o ? o->field_form[oc] != 0 : damping.contact_field;
    if (form_pass >= 0 && in_field_form != (form_pass == 0)) return;
    // Property index: reuse an identical parameter set.
    std::size_t p = 0;
    while (p < g.properties.size() && !(g.properties[p] == params)) ++p;
    if (p == g.properties.size()) {
      if (p >= 65535) throw InvalidArgument("simulation: more than 65535 different contact property sets");
      g.properties.push_back(params);
    }
    // The frame of the CPs' areas: the origin at their centroid, t1 along a principal axis (AreaMoments). The
    // plane coordinates stay small, and a Maxwell field's stiffness is diagonal (damping::Maxwell::contact_stiffness).
    Vec3 origin = Vec3::Zero();
    double total_area = 0;
    for (auto c = first; c != last; ++c) {
      origin += c->area * c->position;
      total_area += c->area;
    }
    origin /= total_area;
    const Vec3 n = first->normal;
    Vec3 t1 = first->tangent;
    {
      const Vec3 t2 = n.cross(t1);
      AreaMoments moments;
      for (auto c = first; c != last; ++c) {
        const Vec3 d = c->position - origin;
        moments.add(d.dot(t1), d.dot(t2), c->area);
      }
      const double turn = moments.principal_turn();
      t1 = (std::cos(turn) * t1 + std::sin(turn) * t2).normalized();
    }
    const Vec3 t2 = n.cross(t1);
    const ContactFrame old_frame = o ? contact_frame(b, *o, oc) : ContactFrame{};
    const contact::ShearTurn turn = o ? shear_turn(old_frame.t1, old_frame.t2, t1, t2) : contact::ShearTurn{};
    // A branch field (Maxwell) continues on the new contact, moved to its origin and frame; a contact whose CPs
    // had their own branch states passes them on CP by CP (below).
    typename G::Field field{};
    double field_viscous = 0;
    if constexpr (G::has_field) {
      if (o) {
        field_viscous = o->field_work(oc);
        carried.viscous += field_viscous;
        if (in_field_form) field = moved_field(*o, oc, old_frame, origin, n, t1, t2);
      }
    }
    const Mat3& ra = b.rotation[a];
    g.begin_contact(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(bb), static_cast<std::uint16_t>(p),
                    ra.transpose() * (origin - b.position[a]), ra.transpose() * n, ra.transpose() * t1, in_field_form, field,
                    field_viscous);
    for (auto c = first; c != last; ++c) {
      const Vec3 d = c->position - origin;
      Inheritance from = keep_history ? Inheritance::new_contact : Inheritance::first_detection;
      std::uint32_t source = 0;
      if (o) {
        auto& taken = taken_over_[law_index<L>()];
        // The nearest old CP not yet taken, within the matching distance. The old CP sits on A where it was
        // detected; the new one at a vertex of the current overlap, so near it within the contact plane (along the
        // normal they differ by the overlap).
        const std::uint32_t none = o->first_point[oc + 1];
        std::uint32_t k = none, closest = none;
        double nearest = match, closest_distance = std::numeric_limits<double>::infinity();
        for (std::uint32_t j = o->first_point[oc]; j < none; ++j) {
          Vec3 e = old_frame.point(o->s1[j], o->s2[j]) - c->position;
          e -= e.dot(n) * n;
          if (e.norm() < closest_distance) {
            closest_distance = e.norm();
            closest = j;
          }
          if (taken[j]) continue;
          if (e.norm() <= nearest) {
            nearest = e.norm();
            k = j;
          }
        }
        if (k != none) {
          taken[k] = 1;
          from = Inheritance::same_point;
          source = k;
        } else if (closest != none) {
          from = Inheritance::same_joint;
          source = closest;
        }
      }
      const bool inherits = from == Inheritance::same_point || from == Inheritance::same_joint;
      const typename L::History h = inherited_history<L>(from, inherits ? &o->history[source] : nullptr, c->gap, turn);
      typename G::SpringState spring{};
      double slip = 0, viscous = 0;
      if (from == Inheritance::same_point) {
        // The shear springs' states follow the new tangent directions, like the law's shear stresses.
        if (!in_field_form) spring = inherited_spring_state(o->spring_state[source], turn);
        slip = o->slip_dissipation[source];
        viscous = o->viscous_dissipation[source];
        carried.slip += slip;
        carried.viscous += viscous;
      }
      g.add_point(d.dot(t1), d.dot(t2), c->area, h, spring, slip, viscous);
    }
  }

  template <class From, class To>
  static void copy_group(const From& from, To& to, const Damping& damping, std::size_t blocks) {
    to.properties = from.properties;
    to.body_a = from.body_a;
    to.body_b = from.body_b;
    to.property = from.property;
    to.origin_a = from.origin_a;
    to.normal_a = from.normal_a;
    to.tangent_a = from.tangent_a;
    to.first_point = from.first_point;
    to.force = from.force;
    to.moment = from.moment;
    to.s1 = from.s1;
    to.s2 = from.s2;
    to.area = from.area;
    to.history = from.history;
    to.spring_state.assign(from.size(), typename To::SpringState{});
    if constexpr (To::has_field) {
      to.field.assign((from.contacts() + lane_count - 1) / lane_count, typename To::FieldRecord{});
      to.field_form.assign(to.field.size() * lane_count, 0);
      std::fill_n(to.field_form.begin(), from.contacts(), damping.contact_field ? 1 : 0);
    }
    to.slip_dissipation.assign(from.size(), 0.0);
    to.viscous_dissipation.assign(from.size(), 0.0);
    to.complete(blocks);
  }

  std::array<std::vector<std::uint8_t>, sizeof...(Laws)> taken_over_;  // old CPs already matched, during a detection
  std::array<std::unordered_map<std::uint64_t, std::uint32_t>, sizeof...(Laws)> old_contacts_;  // by block pair, idem
};

}  // namespace blockdem
