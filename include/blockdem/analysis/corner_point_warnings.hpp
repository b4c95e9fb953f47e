#pragma once
// Where bonded joints carry bending on the corners of their faces only. A face-to-face joint gets a contact point at
// each corner of its overlap unless its pair of groups has a contact-point grid (model::ContactSettings,
// contact_point_area_by_tag; "contact_point_spacing" in a model file). Four corner points resist bending with
// I = A b^2 / 4 against A b^2 / 12 for a uniform distribution: a bonded joint's elastic cracking moment is three
// times a fine grid's (docs/study.md, "How many contact points a joint needs"). The study says so in its report.

#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "blockdem/analysis/structure.hpp"
#include "blockdem/contact/laws.hpp"
#include "blockdem/core/number_text.hpp"
#include "blockdem/integrate/contact_view.hpp"
#include "blockdem/model/contact_detection.hpp"

namespace blockdem::analysis {

/// Whether a joint law bonds the blocks it joins: a tensile strength or a cohesion that cracking or slip must break.
inline bool bonds(const contact::JointLaw& law) {
  return std::visit(
      [](const auto& p) {
        if constexpr (requires { p.tensile_strength; }) return p.tensile_strength > 0 || p.cohesion > 0;
        else return false;
      },
      law);
}

/// One warning per pair of groups whose joints bond and stand on the corners of their faces only (`contacts` as
/// the simulation detects them: the structure's grid per pair filled in), naming the pair, its bonded joints and
/// their contact points in `sim` (anything with visit_contacts(f(const ContactView&))); none where the grid is set.
template <class Sim>
std::vector<std::string> corner_point_warnings(const Structure& s, const model::ContactSettings& contacts, const Sim& sim) {
  const auto& tag = s.model.bodies.joint_tag;
  struct Count {
    std::set<std::pair<std::size_t, std::size_t>> joints;
    std::size_t points = 0;
  };
  std::map<std::pair<std::size_t, std::size_t>, Count> corner_only;
  sim.visit_contacts([&](const ContactView& c) {
    if (c.never_bonded || c.block_a >= tag.size() || c.block_b >= tag.size()) return;
    auto a = static_cast<std::size_t>(tag[c.block_a]), b = static_cast<std::size_t>(tag[c.block_b]);
    if (a > b) std::swap(a, b);
    if (!s.laws.has(a, b) || !bonds(s.laws.law(a, b)) ||
        contacts.contact_point_area(static_cast<int>(a), static_cast<int>(b)) > 0)
      return;
    auto& count = corner_only[{a, b}];
    count.joints.insert({c.block_a, c.block_b});
    ++count.points;
  });
  std::vector<std::string> warnings;
  for (const auto& [pair, count] : corner_only) {
    const std::size_t joints = count.joints.size();
    warnings.push_back("joints between '" + s.laws.name(pair.first) + "' and '" + s.laws.name(pair.second) + "': " +
                       std::to_string(joints) + (joints == 1 ? " bonded joint (" : " bonded joints (") +
                       std::to_string(count.points) + " contact points) on the corners of their faces only, which gives " +
                       "a joint three times the cracking moment of a fine grid of points (docs/study.md, how many " +
                       "contact points a joint needs); give the pair a \"contact_point_spacing\" (cross_vault: --max-cp-area)");
  }
  return warnings;
}

}  // namespace blockdem::analysis
