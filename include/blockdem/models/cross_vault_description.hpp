#pragma once
// The description of the LNEC cross vault (paper Sect. 2 and 3.2, Tables 1-2): its components, materials, the joint
// law of every component pair, the options of the generator (models/cross_vault_generator.hpp), the monitor points of
// the test, and CrossVault, the plain list of tagged blocks, ties and monitor points that the generator fills.
//
// Frame: origin at the centre of the plan on the slab's top face, x east-west (transverse), y north-south (the
// excitation direction, paper Sect. 2), z up. Barrel A has its axis along y and forms the north and south webs,
// barrel B has its axis along x and forms the east and west webs; they intersect on the diagonal planes x = +-y.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "blockdem/contact/elastic.hpp"
#include "blockdem/contact/laws.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/contact/softening.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/number_text.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "blockdem/model/model.hpp"
#include "blockdem/model/monitor_point.hpp"

namespace blockdem::models {

using Vec2 = Eigen::Vector2d;

namespace detail {
using blockdem::num;  // core/number_text.hpp
}  // namespace detail

/// What a block belongs to; also its joint tag in the rigid model (the contact law is chosen per pair of tags).
enum class Component : std::uint8_t { vault, infill, fixed_pier, movable_pier, slab, anchor, steel_frame };
inline constexpr std::size_t component_count = 7;
inline constexpr std::array<Component, component_count> all_components{
    Component::vault, Component::infill, Component::fixed_pier, Component::movable_pier,
    Component::slab,  Component::anchor, Component::steel_frame};
inline constexpr std::array<std::string_view, component_count> component_names{
    "vault", "infill", "fixed_pier", "movable_pier", "slab", "anchor", "steel_frame"};
constexpr std::string_view name(Component c) { return component_names[static_cast<std::size_t>(c)]; }
constexpr std::size_t index(Component c) { return static_cast<std::size_t>(c); }

/// The profile of both barrels through the springings (+-span/2, 0) and the crown (0, rise).
enum class VaultProfile : std::uint8_t {
  segmental,   ///< a circular arc (rise <= span/2); radius (span^2/4 + rise^2) / (2 rise)
  elliptical,  ///< half an ellipse with semi-axes span/2 and rise (any rise), vertical at the springings
};

/// The joint law of a pair of components (paper Sect. 3.1-3.2, Fig. 5). The laws themselves live in contact/.
enum class JointKind : std::uint8_t {
  Softening,            ///< elasto-softening unit-mortar interface (Fig. 5C): within vault and infill, masonry to structure
  MohrCoulombFriction,  ///< dry friction joint (Fig. 5B): the movable piers on the slab
  ElasticSteel,         ///< linear elastic (Fig. 5A): steel frame and auxiliary parts
};
inline constexpr std::array<std::string_view, 3> joint_kind_names{"softening", "mohr_coulomb_friction", "elastic_steel"};
constexpr std::string_view name(JointKind k) { return joint_kind_names[static_cast<std::size_t>(k)]; }

struct Material {
  std::string name;
  double density = 0;         // kg/m^3
  double youngs_modulus = 0;  // Pa
  double poisson_ratio = 0;
};

/// Parameters of a joint law, per unit area of joint. Unused fields stay 0 (e.g. strengths of ElasticSteel).
struct JointParameters {
  JointKind kind = JointKind::ElasticSteel;
  double normal_stiffness = 0;             // Pa/m
  double shear_stiffness = 0;              // Pa/m
  double tensile_strength = 0;             // Pa
  double cohesion = 0;                     // Pa
  double friction_angle = 0;               // rad
  double compressive_strength = 0;         // Pa (Softening only)
  double residual_compressive_strength = 0;  // Pa (Softening only): what a crushed joint still carries
  double fracture_energy_tension = 0;      // N/m, G_f^I (Softening only)
  double fracture_energy_shear = 0;        // N/m, G_f^II
  double fracture_energy_compression = 0;  // N/m, G_c
};

/// The joint law of the contact library for a joint of the model, for Simulation<Damping, ElastoSoftening,
/// MohrCoulomb, Elastic>: Softening -> contact::ElastoSoftening (residual friction = peak, no residual tension or
/// cohesion), MohrCoulombFriction -> contact::MohrCoulomb, ElasticSteel -> contact::Elastic.
using JointLaw = contact::JointLaw;
inline JointLaw joint_law(const JointParameters& p) {
  switch (p.kind) {
    case JointKind::Softening: {
      contact::ElastoSoftening::Strengths s;
      s.tensile = p.tensile_strength;
      s.cohesion = p.cohesion;
      s.friction_angle = p.friction_angle;
      s.compressive = p.compressive_strength;
      s.residual_compressive = p.residual_compressive_strength;
      return contact::ElastoSoftening::Parameters(
          {p.normal_stiffness, p.shear_stiffness}, s,
          {p.fracture_energy_tension, p.fracture_energy_shear, p.fracture_energy_compression});
    }
    case JointKind::MohrCoulombFriction:
      return contact::MohrCoulomb::Parameters(p.normal_stiffness, p.shear_stiffness, p.tensile_strength, p.cohesion,
                                              p.friction_angle);
    case JointKind::ElasticSteel:
      break;
  }
  return contact::Elastic::Parameters(p.normal_stiffness, p.shear_stiffness);
}

/// Where a monitor point sits: on the vault's extrados or intrados above/below a plan position, or on the top face
/// of its component (pier, anchor, slab, infill) at a plan position.
enum class MonitorLevel : std::uint8_t { extrados, intrados, top };

struct MonitorSpec {
  std::string name;
  Component component = Component::vault;  // the point is attached to the nearest block of this component
  double x = 0, y = 0;                     // m, plan position
  MonitorLevel level = MonitorLevel::extrados;
};

struct CrossVaultOptions {
  // The vault (paper Sect. 2).
  double plan_size = 3.5;       // m, side of the square plan (outer faces of the piers and webs)
  double span = 2.9;            // m, net span of each barrel at the intrados (springing to springing)
  double rise = 1.2;            // m, intrados crown above the springing
  double thickness = 0.12;      // m, of the single-ring vault: the units' 0.12 m width, no joint through it
  VaultProfile profile = VaultProfile::segmental;
  double unit_height = 0.045;   // m, along the arc (course height without joint)
  double unit_length = 0.23;    // m, along the barrel axis
  double joint_thickness = 0.01;  // m, mortar; blocks are units extended by half a joint on each side
  double infill_rise_fraction = 0.5;  // the corner infill reaches this fraction of the rise above the springing
  double min_block_fraction = 0.3;    // vault pieces cut at a groin smaller than this fraction of a whole block are merged into their neighbour in the course
  double min_infill_fraction = 0.05;  // infill pieces smaller than this fraction of a whole vault block are dropped

  // Supports and auxiliary parts: the paper gives the slab plan (4.4 x 4.9 m) and the tie section; the rest is
  // assumed (Fig. 1 is a drawing that the text does not carry).
  double pier_height = 1.0;     // m, slab top to the underside of the tie anchor (assumed)
  double anchor_height = 0.2;   // m, tie anchor block on top of each pier; its top is the springing level (assumed)
  double slab_length_x = 4.4;   // m (paper)
  double slab_length_y = 4.9;   // m (paper; the longer side along the excitation, assumed)
  double slab_thickness = 0.3;  // m (assumed)
  double steel_profile_depth = 0.16;   // m, UPN 160 envelope (assumed)
  double steel_profile_width = 0.065;  // m
  bool fixed_piers_west = true;  // fixed masonry piers at x < 0 (NW, SW), movable steel piers at x > 0 (assumed)

  // Steel ties: three couples of phi 32 bars (paper Sect. 2, 3.2).
  double tie_area = 8e-4;         // m^2
  double tie_density = 7800;      // kg/m^3
  double tie_modulus = 200e9;     // Pa
  double tie_pretension = 0;      // N
  double tie_spacing = 0.15;      // m, between the two bars of a couple (assumed)

  // Materials (Tables 1 and 2).
  double masonry_density = 1800;  // kg/m^3 (assumed: not given in the paper)
  double unit_modulus = 6200e6;   // Pa, E_b (Table 1)
  double unit_poisson = 0.25;     // (Table 1)
  double mortar_modulus = 370.05e6;      // Pa, E_m (Table 1)
  double tensile_strength = 0.3e6;       // Pa, f_t (Table 1)
  double compressive_strength = 9.1e6;   // Pa, f_c (Table 1)
  // Pa, f_c,r: what a joint crushed through still carries (not in the paper, whose law softens to 0). It matters
  // only past the paper's levels, where blocks pound and crush their joints: with 0 they pass through each other.
  double residual_compressive_strength = 0;
  double cohesion = 0.3e6;               // Pa, c (Table 1)
  double friction_angle_deg = 38;        // phi (Table 1)

  std::vector<MonitorSpec> monitors;  // empty: default_monitors()

  double half_plan() const { return 0.5 * plan_size; }
  double pier_width() const { return 0.5 * (plan_size - span); }
  double course_height() const { return unit_height + joint_thickness; }
  double block_length() const { return unit_length + joint_thickness; }
  double springing_level() const { return pier_height + anchor_height; }
  double infill_height() const { return infill_rise_fraction * rise; }  // above the springing

  void validate() const {
    auto check = [](bool ok, const std::string& what) {
      if (!ok) throw InvalidArgument("cross vault: " + what);
    };
    auto positive = [&](double v, const char* field, const char* unit) {
      check(v > 0 && std::isfinite(v), std::string(field) + " must be > 0 " + unit + ", got " + detail::num(v));
    };
    positive(plan_size, "plan size", "m");
    positive(span, "span", "m");
    positive(rise, "rise", "m");
    positive(thickness, "thickness", "m");
    positive(unit_height, "unit height", "m");
    positive(unit_length, "unit length", "m");
    positive(joint_thickness, "joint thickness", "m");
    check(span < plan_size, "span must be < plan size = " + detail::num(plan_size) + " m (the piers take the rest), got " + detail::num(span));
    if (profile == VaultProfile::segmental)
      check(rise <= 0.5 * span, "rise must be in (0, span/2 = " + detail::num(0.5 * span) +
                                    "] m for a segmental profile, got " + detail::num(rise) + " (use the elliptical profile for a higher rise)");
    check(thickness < 0.5 * span, "thickness must be < span/2 = " + detail::num(0.5 * span) + " m, got " + detail::num(thickness));
    {
      // The extrados meets the springing plane at u_e from the centre line; it must stay inside the plan.
      const double a = 0.5 * span, f = rise;
      double u_e = a + thickness;
      if (profile == VaultProfile::segmental) {
        const double radius = (a * a + f * f) / (2 * f), c = radius - f;
        u_e = std::sqrt((radius + thickness) * (radius + thickness) - c * c);
      }
      check(u_e < half_plan(), "the extrados reaches the springing " + detail::num(u_e) + " m from the centre, beyond half the plan size " +
                                   detail::num(half_plan()) + " m: enlarge the plan or thin the ring");
    }
    check(course_height() < 0.25 * span, "unit height + joint must be < span/4 m");
    // Smaller bricks make millions of blocks (0.02 m: 37 000 blocks, built and checked in about a second).
    check(course_height() >= 0.02 && block_length() >= 0.02,
          "unit height + joint and unit length + joint must be >= 0.02 m, got " + detail::num(course_height()) + " and " +
              detail::num(block_length()));
    check(infill_rise_fraction >= 0 && infill_rise_fraction < 1, "infill rise fraction must be in [0, 1), got " + detail::num(infill_rise_fraction));
    check(min_block_fraction >= 0 && min_block_fraction < 0.5, "min block fraction must be in [0, 0.5), got " + detail::num(min_block_fraction));
    check(min_infill_fraction >= 0 && min_infill_fraction < 1, "min infill fraction must be in [0, 1), got " + detail::num(min_infill_fraction));
    positive(pier_height, "pier height", "m");
    positive(anchor_height, "anchor height", "m");
    positive(slab_thickness, "slab thickness", "m");
    check(slab_length_x >= plan_size + 2 * steel_profile_width && slab_length_y >= plan_size + 2 * steel_profile_width,
          "the slab (" + detail::num(slab_length_x) + " x " + detail::num(slab_length_y) +
              " m) must hold the plan plus the steel profiles (" + detail::num(plan_size + 2 * steel_profile_width) + " m)");
    positive(steel_profile_depth, "steel profile depth", "m");
    positive(steel_profile_width, "steel profile width", "m");
    check(steel_profile_depth <= anchor_height, "steel profile depth must be <= anchor height (the beam between the fixed piers sits at the anchors)");
    check(steel_profile_depth <= pier_width(), "steel profile depth must be <= pier width = " + detail::num(pier_width()) + " m");
    positive(tie_area, "tie area", "m^2");
    positive(tie_density, "tie density", "kg/m^3");
    positive(tie_modulus, "tie modulus", "Pa");
    check(tie_pretension >= 0, "tie pretension must be >= 0 N");
    check(tie_spacing > 0 && tie_spacing < pier_width(), "tie spacing must be in (0, pier width = " + detail::num(pier_width()) + ") m");
    positive(masonry_density, "masonry density", "kg/m^3");
    check(unit_modulus > mortar_modulus && mortar_modulus > 0, "unit and mortar moduli must satisfy E_b > E_m > 0 (eq. 7)");
    check(unit_poisson > -1 && unit_poisson < 0.5, "unit Poisson ratio must be in (-1, 0.5)");
    check(tensile_strength >= 0 && cohesion >= 0 && compressive_strength > 0, "strengths must be >= 0 (compressive > 0) Pa");
    check(friction_angle_deg >= 0 && friction_angle_deg < 90, "friction angle must be in [0, 90) degrees");
    check(residual_compressive_strength >= 0 && residual_compressive_strength < compressive_strength,
          "residual compressive strength must be in [0, compressive strength " + detail::num(compressive_strength) +
              ") Pa, got " + detail::num(residual_compressive_strength));
    for (const auto& m : monitors) check(!m.name.empty(), "every monitor point needs a name");
  }
};

/// The optical targets OC1-OC4 and accelerometers of the test (paper Sect. 2, Fig. 2a). OC1 and ACC18 are at the
/// crown and ACC14 on the south-east pier (paper Sect. 5); the other positions are assumed, since Fig. 2a is a
/// drawing the text does not carry: OC2-OC4 at mid-web on the south, east and north webs, ACC2 on the slab, ACC6
/// and ACC12 on the north-west and north-east piers.
inline std::vector<MonitorSpec> default_monitors(const CrossVaultOptions& o) {
  const double web = 0.5 * (0.5 * o.span);     // mid-way between crown and springing line
  const double pier = o.half_plan() - 0.5 * o.pier_width();
  const Component west = o.fixed_piers_west ? Component::fixed_pier : Component::movable_pier;
  const Component east = o.fixed_piers_west ? Component::movable_pier : Component::fixed_pier;
  return {
      {"OC1", Component::vault, 0, 0, MonitorLevel::extrados},
      {"OC2", Component::vault, 0, -web, MonitorLevel::extrados},
      {"OC3", Component::vault, web, 0, MonitorLevel::extrados},
      {"OC4", Component::vault, 0, web, MonitorLevel::extrados},
      {"ACC2", Component::slab, 0, 0, MonitorLevel::top},
      {"ACC6", west, -pier, pier, MonitorLevel::top},
      {"ACC12", east, pier, pier, MonitorLevel::top},
      {"ACC14", east, pier, -pier, MonitorLevel::top},
      {"ACC18", Component::vault, 0, 0, MonitorLevel::extrados},
  };
}

struct CrossVaultBlock {
  geometry::ConvexPolyhedron shape;  // world coordinates, m
  Component component = Component::vault;
  std::size_t material = 0;          // index into CrossVault::materials
  model::Motion motion = model::Motion::free;
  std::string name;
};

/// A steel tie between two blocks, to become a truss element (one translational DOF per end) in a later issue.
struct Tie {
  std::string name;
  Vec3 end_a, end_b;          // m
  std::size_t block_a = 0, block_b = 0;
  double area = 0;            // m^2
  double density = 0;         // kg/m^3
  double youngs_modulus = 0;  // Pa
  double pretension = 0;      // N
  double length() const { return (end_b - end_a).norm(); }
  double mass() const { return density * area * length(); }
};

using MonitorPoint = model::MonitorPoint;

struct CrossVault {
  CrossVaultOptions options;
  std::vector<CrossVaultBlock> blocks;
  std::vector<Material> materials;
  std::array<std::array<JointParameters, component_count>, component_count> joints{};
  std::vector<Tie> ties;
  std::vector<MonitorPoint> monitor_points;

  // What the generator chose and did.
  int courses = 0;                   // per barrel, springing to springing
  double radius = 0;                 // m, intrados radius (segmental profile; 0 otherwise)
  std::size_t vault_slivers_merged = 0;   // groin pieces merged into their neighbour
  std::size_t infill_pieces_dropped = 0;
  double infill_volume_dropped = 0;  // m^3
  std::vector<Vec2> intrados_section, extrados_section;  // the faceted profile (u, w above springing), N + 1 points each

  const JointParameters& joint(Component a, Component b) const { return joints[index(a)][index(b)]; }
  /// The joint between two blocks of the rigid model, from their joint tags (= component indices).
  const JointParameters& joint(int tag_a, int tag_b) const {
    return joints[static_cast<std::size_t>(tag_a)][static_cast<std::size_t>(tag_b)];
  }
  /// The components of the two blocks of a contact point, and its joint.
  std::pair<Component, Component> components(const model::ContactCandidate& c) const {
    return {blocks[c.a].component, blocks[c.b].component};
  }
  const JointParameters& joint(const model::ContactCandidate& c) const { return joint(blocks[c.a].component, blocks[c.b].component); }
  double springing_level() const { return options.springing_level(); }
  std::size_t count(Component c) const {
    return static_cast<std::size_t>(std::count_if(blocks.begin(), blocks.end(), [&](const auto& b) { return b.component == c; }));
  }
  /// Height of the faceted extrados (or intrados) above the plan point (x, y), m (world z).
  double extrados_level(double x, double y) const { return surface_level(extrados_section, x, y); }
  double intrados_level(double x, double y) const { return surface_level(intrados_section, x, y); }

 private:
  double surface_level(const std::vector<Vec2>& section, double x, double y) const {
    // Inside y >= |x| (north/south webs) the surface is barrel A's, a function of x; elsewhere barrel B's, of y.
    const double u = std::abs(x) <= std::abs(y) ? x : y;
    if (u <= section.front().x() || u >= section.back().x()) return springing_level();
    for (std::size_t k = 0; k + 1 < section.size(); ++k)
      if (u <= section[k + 1].x()) {
        const double t = (u - section[k].x()) / (section[k + 1].x() - section[k].x());
        return springing_level() + section[k].y() + t * (section[k + 1].y() - section[k].y());
      }
    return springing_level();
  }
};

}  // namespace blockdem::models
