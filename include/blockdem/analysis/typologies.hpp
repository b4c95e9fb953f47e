#pragma once
// The masonry typologies of geometry/typologies.hpp as model files describe them (model_file_writer.hpp): a wall or
// a barrel vault of dry-jointed units on a foundation that a record shakes, with the seismic study along the
// typology's weak axis and its equivalent-static pushover. `blockdem run` runs the files as written.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "blockdem/analysis/model_file_writer.hpp"
#include "blockdem/analysis/pushover_options.hpp"
#include "blockdem/analysis/study_options.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/number_text.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/geometry/queries.hpp"
#include "blockdem/geometry/typologies.hpp"

namespace blockdem::analysis {

/// What the units (or lintels) are made of; each kind has its density.
enum class MasonryUnit { brick, stone };
inline constexpr const char* name(MasonryUnit u) { return u == MasonryUnit::brick ? "brick" : "stone"; }
inline constexpr double unit_density(MasonryUnit u) { return u == MasonryUnit::brick ? 1800.0 : 2200.0; }  // kg/m^3
inline constexpr double foundation_density = 2400;  // kg/m^3, concrete (a base block: its mass does not enter the run)

/// Dry joints: Mohr-Coulomb friction without cohesion or tension (paper Fig. 5B), for every pair of groups that
/// touch or may come to touch as the structure falls.
struct DryJointOptions {
  double friction_angle_deg = 35;  // (0, 89]
  double normal_stiffness = 1e10;  // Pa/m, [1e6, 1e15]
  double shear_stiffness = 0;      // Pa/m; 0: half the normal stiffness

  contact::MohrCoulomb::Parameters law() const {
    return {normal_stiffness, shear_stiffness > 0 ? shear_stiffness : 0.5 * normal_stiffness, 0, 0, friction_angle_deg * pi / 180.0};
  }
  void validate(const std::string& context) const {
    auto check = [&](bool ok, const std::string& what) {
      if (!ok) throw InvalidArgument(context + ": " + what);
    };
    check(friction_angle_deg > 0 && friction_angle_deg <= 89, "friction_angle_deg must be in (0, 89] degrees, got " + num(friction_angle_deg));
    // Beyond these the timestep and the joints' overlap leave the range where a run means anything.
    check(normal_stiffness >= 1e6 && normal_stiffness <= 1e15, "normal_stiffness must be in [1e6, 1e15] Pa/m, got " + num(normal_stiffness));
    check(shear_stiffness == 0 || (shear_stiffness >= 1e6 && shear_stiffness <= 1e15),
          "shear_stiffness must be 0 (half the normal) or in [1e6, 1e15] Pa/m, got " + num(shear_stiffness));
  }
};

/// A wall study: the wall, its materials and joints, and the study (study_options.hpp), shaken out of plane (along
/// y) by default, with general contacts (units that rock far and fall).
struct WallStudyOptions : StudyOptions {
  geometry::WallOptions wall;
  MasonryUnit unit = MasonryUnit::brick;
  MasonryUnit lintel = MasonryUnit::stone;
  DryJointOptions joints;

  WallStudyOptions() {
    context = "wall study";
    axis = 'y';
    contacts = model::ContactKinds::general;
  }
  void validate() const {
    wall.validate();
    joints.validate(context);
    StudyOptions::validate();
  }
};

/// A barrel vault study: shaken across the span (along x) by default, general contacts.
struct BarrelVaultStudyOptions : StudyOptions {
  geometry::BarrelVaultOptions vault;
  MasonryUnit unit = MasonryUnit::brick;
  DryJointOptions joints;

  BarrelVaultStudyOptions() {
    context = "barrel vault study";
    axis = 'x';
    contacts = model::ContactKinds::general;
  }
  void validate() const {
    vault.validate();
    joints.validate(context);
    StudyOptions::validate();
  }
};

namespace detail {

/// The description of generated blocks: groups in the order of `groups` (those no block has left out), every pair of
/// them but support-support given the dry law, supports on the table (motion "base"; the first is the table),
/// materials as `material_of` names them (name, density).
template <class MaterialOf>
ModelDescription describe_blocks(const std::vector<geometry::NamedBlock>& blocks, const std::vector<std::string>& groups,
                                 const DryJointOptions& joints, MaterialOf material_of) {
  ModelDescription d;
  std::vector<std::string> present;
  for (const auto& g : groups)
    for (const auto& b : blocks)
      if (b.group == g) {
        present.push_back(g);
        break;
      }
  d.laws = LawTable(present);
  auto group_index = [&](const std::string& g) {
    for (std::size_t i = 0; i < present.size(); ++i)
      if (present[i] == g) return i;
    throw InvalidArgument("typology: block group '" + g + "' is not among the description's groups");
  };
  const auto law = joints.law();
  for (std::size_t a = 0; a < present.size(); ++a)
    for (std::size_t b = a; b < present.size(); ++b) {
      bool supports_only = true;  // two supports never move against each other: no joint between them
      for (const auto& blk : blocks)
        if ((blk.group == present[a] || blk.group == present[b]) && !blk.support) supports_only = false;
      if (!supports_only) d.laws.set(a, b, law);
    }
  for (const auto& b : blocks) {
    const auto [material, rho] = material_of(b);
    std::size_t m = 0;
    while (m < d.materials.size() && d.materials[m].name != material) ++m;
    if (m == d.materials.size()) d.materials.push_back({material, rho, 0, 0});
    if (b.support && !d.table) d.table = d.blocks.size();
    d.blocks.push_back({b.name, group_index(b.group), m, b.support ? model::Motion::base : model::Motion::free, b.shape, 0.0});
  }
  return d;
}

/// The first free block that holds `point` (on its boundary counts), for a monitor point.
inline std::size_t block_at(const ModelDescription& d, const Vec3& point, double tolerance) {
  for (std::size_t i = 0; i < d.blocks.size(); ++i)
    if (d.blocks[i].motion == model::Motion::free && geometry::distance(d.blocks[i].shape, point) <= tolerance) return i;
  throw InvalidArgument("typology: no block holds the monitor point " + num(point.x()) + ", " + num(point.y()) + ", " + num(point.z()));
}

}  // namespace detail

/// The wall as a model file describes it: units of brick or stone (group "wall"), lintels ("lintel"), return walls
/// ("return"), all on a concrete foundation ("foundation") that is the table; dry joints between every pair of
/// groups; the monitor point "top" on the top of the wall at mid-length and mid-thickness (moving with the block
/// under it); a contact tolerance of a thousandth of the unit's smaller cross dimension.
inline ModelDescription wall_description(const WallStudyOptions& o) {
  o.validate();
  const auto& w = o.wall;
  const auto blocks = geometry::masonry_wall(w);
  ModelDescription d = detail::describe_blocks(blocks, {"wall", "lintel", "return", "foundation"}, o.joints, [&](const geometry::NamedBlock& b) {
    if (b.group == "foundation") return std::pair<std::string, double>("concrete", foundation_density);
    const MasonryUnit u = b.group == "lintel" ? o.lintel : o.unit;
    return std::pair<std::string, double>(name(u), unit_density(u));
  });
  d.name = "masonry wall " + num(w.length) + " x " + num(w.height()) + " m, " + num(w.thickness) + " m thick" +
           (w.openings.empty() ? "" : ", " + std::to_string(w.openings.size()) + (w.openings.size() == 1 ? " opening" : " openings")) +
           (w.return_length > 0 ? ", return walls " + num(w.return_length) + " m" : "");
  d.contact_tolerance = 1e-3 * std::min(w.unit_height, w.thickness);
  const Vec3 top(0.5 * w.length, 0.5 * w.thickness, w.height());
  d.monitors.push_back({"top", top, detail::block_at(d, top, 1e-9 * w.height())});
  return d;
}

/// The vault as a model file describes it: voussoirs of brick or stone (group "vault") on two concrete abutments
/// ("abutment") that move with the table (the right one is the table); dry joints; the monitor point "crown" at
/// mid-length on the ring's centreline at the crown; a contact tolerance of a thousandth of the thickness or the
/// voussoir's depth, whichever is smaller.
inline ModelDescription barrel_vault_description(const BarrelVaultStudyOptions& o) {
  o.validate();
  const auto& v = o.vault;
  const auto blocks = geometry::barrel_vault(v);
  ModelDescription d = detail::describe_blocks(blocks, {"vault", "abutment"}, o.joints, [&](const geometry::NamedBlock& b) {
    if (b.support) return std::pair<std::string, double>("concrete", foundation_density);
    return std::pair<std::string, double>(name(o.unit), unit_density(o.unit));
  });
  d.name = "semicircular barrel vault, span " + num(v.span) + " m, " + num(v.thickness) + " m thick, " + num(v.length) + " m long, " +
           std::to_string(v.rings) + " rings" + (v.running_bond ? " in running bond" : "");
  const double depth = 2 * v.inner_radius() * std::sin(0.5 * pi / v.rings);  // the intrados' chord of a voussoir
  d.contact_tolerance = 1e-3 * std::min({v.thickness, depth, 0.5 * v.unit_length});
  // The crown: the middle of the key voussoir's centreline chord (odd rings), or the crown joint (even rings).
  const double centreline = 0.5 * (v.inner_radius() + v.outer_radius());
  const Vec3 crown(0, 0.5 * v.length, v.rings % 2 == 1 ? centreline * std::cos(0.5 * pi / v.rings) : centreline);
  d.monitors.push_back({"crown", crown, detail::block_at(d, crown, 1e-9 * v.span)});
  return d;
}

/// The wall's pushover as `blockdem run` runs it (pushover.hpp): lambda g out of plane, along +y (towards the
/// returns, if any), bisected in [0, 1] to 0.005; collapse at a block moving a quarter of the thickness.
inline PushoverOptions wall_pushover(const WallStudyOptions& o) {
  o.validate();
  PushoverOptions p;
  p.axis = 'y';
  p.resolution = 0.005;
  p.collapse_displacement = 0.25 * o.wall.thickness;
  return p;
}

/// The vault's pushover: lambda g across the span, along +x, bisected in [0, 1] to 0.005; collapse at a voussoir
/// moving a quarter of the thickness (as the arch's, analysis/arch.hpp).
inline PushoverOptions barrel_vault_pushover(const BarrelVaultStudyOptions& o) {
  o.validate();
  PushoverOptions p;
  p.axis = 'x';
  p.resolution = 0.005;
  p.collapse_displacement = 0.25 * o.vault.thickness;
  return p;
}

}  // namespace blockdem::analysis
