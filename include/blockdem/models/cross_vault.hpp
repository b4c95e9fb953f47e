#pragma once
// The full-scale brick cross vault of the LNEC shake-table test (paper Sect. 2 and 3.2, Fig. 1, 6; Tables 1-2) as a
// parametric generator: the four webs of two intersecting barrel vaults in brick courses trimmed at the groins, the
// corner infill, piers, tie anchors, slab and steel frame, each block tagged with its component; materials, the
// joint law of every component pair, the steel ties and the monitor points of the test. A plain description that
// build_rigid_model() turns into a model::Model and check_assembly() checks (overlaps, contacts, masses).
//
// Frame: origin at the centre of the plan on the slab's top face, x east-west (transverse), y north-south (the
// excitation direction, paper Sect. 2), z up. Barrel A has its axis along y and forms the north and south webs,
// barrel B has its axis along x and forms the east and west webs; they intersect on the diagonal planes x = +-y.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "blockdem/contact/elastic.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/contact/softening.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/geometry/clip.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/mass_properties.hpp"
#include "blockdem/geometry/polygon.hpp"
#include "blockdem/geometry/queries.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem::models {

using Vec2 = Eigen::Vector2d;

namespace detail {
/// A number for a message: up to 6 significant digits, no trailing zeros.
inline std::string num(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}
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
using JointLaw = std::variant<contact::ElastoSoftening::Parameters, contact::MohrCoulomb::Parameters, contact::Elastic::Parameters>;
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

struct MonitorPoint {
  std::string name;
  Vec3 position;          // m, world
  std::size_t block = 0;  // the block it is attached to
};

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

namespace detail {

/// The intrados of a barrel in its cross-section (u across, w above the springing), parameter s in [-1, 1] from
/// the springing at u = -span/2 through the crown (s = 0) to u = +span/2; the normal points to the extrados.
struct ArchProfile {
  VaultProfile kind = VaultProfile::segmental;
  double a = 0, f = 0;           // m, half span and rise
  double radius = 0, centre_w = 0, springing_angle = 0;  // segmental: circle of radius R centred at (0, w_c)

  explicit ArchProfile(const CrossVaultOptions& o) : kind(o.profile), a(0.5 * o.span), f(o.rise) {
    if (kind == VaultProfile::segmental) {
      radius = (a * a + f * f) / (2 * f);
      centre_w = f - radius;
      springing_angle = std::asin(std::min(1.0, a / radius));
    }
  }
  Vec2 point(double s) const {
    if (kind == VaultProfile::segmental) {
      const double t = s * springing_angle;
      return {radius * std::sin(t), centre_w + radius * std::cos(t)};
    }
    const double t = s * 0.5 * pi;
    return {a * std::sin(t), f * std::cos(t)};
  }
  Vec2 normal(double s) const {
    if (kind == VaultProfile::segmental) {
      const double t = s * springing_angle;
      return {std::sin(t), std::cos(t)};
    }
    const double t = s * 0.5 * pi;
    return Vec2(std::sin(t) / a, std::cos(t) / f).normalized();
  }
};

/// The faceted ring: courses of equal length along the mid-thickness curve; the first and last course end on the
/// springing plane w = 0 (their outer corner where the extrados chord meets it).
inline void faceted_ring(const CrossVaultOptions& o, const ArchProfile& profile, std::vector<Vec2>& intrados,
                         std::vector<Vec2>& extrados) {
  const int samples = 8192;
  std::vector<double> s(samples + 1), length(samples + 1, 0.0);
  Vec2 previous = Vec2::Zero();
  for (int j = 0; j <= samples; ++j) {
    s[static_cast<std::size_t>(j)] = -1.0 + 2.0 * j / samples;
    const Vec2 m = profile.point(s[static_cast<std::size_t>(j)]) + 0.5 * o.thickness * profile.normal(s[static_cast<std::size_t>(j)]);
    if (j > 0) length[static_cast<std::size_t>(j)] = length[static_cast<std::size_t>(j - 1)] + (m - previous).norm();
    previous = m;
  }
  const double total = length.back();
  const int courses = std::max(3, static_cast<int>(std::lround(total / o.course_height())));
  intrados.assign(static_cast<std::size_t>(courses + 1), Vec2::Zero());
  extrados.assign(static_cast<std::size_t>(courses + 1), Vec2::Zero());
  std::size_t j = 0;
  for (int k = 0; k <= courses; ++k) {
    double sk = -1.0;
    if (k == courses) {
      sk = 1.0;
    } else if (k > 0) {
      const double target = total * k / courses;
      while (j + 1 < length.size() && length[j + 1] < target) ++j;
      const double t = (target - length[j]) / (length[j + 1] - length[j]);
      sk = s[j] + t * (s[j + 1] - s[j]);
    }
    intrados[static_cast<std::size_t>(k)] = profile.point(sk);
    extrados[static_cast<std::size_t>(k)] = profile.point(sk) + o.thickness * profile.normal(sk);
  }
  // Springings exactly on w = 0; the outer corner of the end courses where their extrados chord meets w = 0.
  for (const auto& [end, next] : {std::pair<std::size_t, std::size_t>{0, 1},
                                  std::pair<std::size_t, std::size_t>{static_cast<std::size_t>(courses), static_cast<std::size_t>(courses - 1)}}) {
    intrados[end] = Vec2(end == 0 ? -profile.a : profile.a, 0.0);
    const Vec2 e0 = extrados[end], e1 = extrados[next];
    if (e0.y() > 0) extrados[end] = e0 + (e0 - e1) * (e0.y() / (e1.y() - e0.y()));
    extrados[end].y() = 0.0;
  }
}

/// The area of a section polygon (m^2, unsigned).
inline double polygon_area(const std::vector<Vec2>& p) { return std::abs(geometry::polygon_area(p)); }

inline double volume(const geometry::ConvexPolyhedron& p) {
  if (p.vertices.empty()) return 0;
  double v = 0;
  const Vec3 o = p.centroid_of_vertices();
  for (const auto& face : p.faces) {
    const Vec3 a = p.vertices[static_cast<std::size_t>(face[0])] - o;
    for (std::size_t i = 1; i + 1 < face.size(); ++i)
      v += a.dot((p.vertices[static_cast<std::size_t>(face[i])] - o).cross(p.vertices[static_cast<std::size_t>(face[i + 1])] - o));
  }
  return v / 6.0;
}

/// A prism over the section polygon (u, w) of a barrel along v in [v_lo, v_hi], in the frame of the north web
/// (x = u, y = v, z = springing + w), clipped to the north web's side of the groins, y >= |x|.
inline geometry::ConvexPolyhedron north_web_piece(const std::vector<Vec2>& section, double v_lo, double v_hi, double z0) {
  std::vector<Vec3> base;
  for (const auto& q : section) base.emplace_back(q.x(), v_lo, z0 + q.y());
  const auto prism = geometry::make_prism(base, Vec3(0, v_hi - v_lo, 0));
  return geometry::clip(prism, {{Vec3(1, -1, 0), 0.0}, {Vec3(-1, -1, 0), 0.0}});
}

/// Rotations about z taking the north web onto the north, east, south and west webs.
inline Mat3 web_rotation(int web) {
  Mat3 r;
  switch (web) {
    case 1: r << 0, 1, 0, -1, 0, 0, 0, 0, 1; break;   // (x, y) -> (y, -x): east
    case 2: r << -1, 0, 0, 0, -1, 0, 0, 0, 1; break;  // south
    case 3: r << 0, -1, 0, 1, 0, 0, 0, 0, 1; break;   // (x, y) -> (-y, x): west
    default: r = Mat3::Identity();
  }
  return r;
}
inline constexpr std::array<std::string_view, 4> web_names{"N", "E", "S", "W"};

inline std::string corner_name(double x, double y) { return std::string(y > 0 ? "N" : "S") + (x > 0 ? "E" : "W"); }

}  // namespace detail

/// Builds the cross vault. Throws InvalidArgument naming the option and its range if the options are invalid, and
/// naming the block if a generated block is not a valid convex polyhedron.
inline CrossVault make_cross_vault(const CrossVaultOptions& options = {}) {
  options.validate();
  const auto& o = options;
  CrossVault v;
  v.options = o;
  if (v.options.monitors.empty()) v.options.monitors = default_monitors(o);
  const detail::ArchProfile profile(o);
  v.radius = o.profile == VaultProfile::segmental ? profile.radius : 0.0;
  detail::faceted_ring(o, profile, v.intrados_section, v.extrados_section);
  const auto& in = v.intrados_section;
  const auto& ex = v.extrados_section;
  const int courses = static_cast<int>(in.size()) - 1;
  v.courses = courses;
  const double Y = o.half_plan();
  if (ex.back().x() > Y)
    throw InvalidArgument("cross vault: the extrados at the springing lies " + detail::num(ex.back().x()) +
                          " m from the centre, beyond half the plan size " + detail::num(Y) +
                          " m; enlarge the plan or thin the ring");
  const double z0 = o.springing_level();
  const double L = o.block_length();

  // Materials (Tables 1 and 2).
  enum : std::size_t { masonry, rolling_pier, tie_anchor, concrete, back_frame };
  v.materials = {{"masonry (brick units, Table 1)", o.masonry_density, o.unit_modulus, o.unit_poisson},
                 {"rolling piers (Table 2)", 5570, 200e9, 0.3},
                 {"tie anchors (Table 2)", 2000, 200e9, 0.3},
                 {"concrete (Table 2)", 2000, 25e9, 0.3},
                 {"back frame steel (Table 2)", 10685, 200e9, 0.3}};

  // Joint laws per component pair (Sect. 3.2).
  JointParameters softening;
  softening.kind = JointKind::Softening;
  const auto stiffness = contact::joint_stiffness_from_eq7(o.unit_modulus, o.mortar_modulus, o.joint_thickness, o.unit_poisson);
  softening.normal_stiffness = stiffness.normal;  // eq. 7
  softening.shear_stiffness = stiffness.shear;    // eq. 7
  softening.tensile_strength = o.tensile_strength;
  softening.cohesion = o.cohesion;
  softening.friction_angle = o.friction_angle_deg * pi / 180.0;
  softening.compressive_strength = o.compressive_strength;
  softening.residual_compressive_strength = o.residual_compressive_strength;
  softening.fracture_energy_tension = contact::fracture_energy_tension_eq4(o.tensile_strength);
  softening.fracture_energy_shear = contact::fracture_energy_shear_eq5(softening.fracture_energy_tension);
  softening.fracture_energy_compression = contact::fracture_energy_compression_eq6(o.compressive_strength);
  JointParameters friction;
  friction.kind = JointKind::MohrCoulombFriction;
  friction.normal_stiffness = 10e9;  // 10 GPa/m
  friction.shear_stiffness = 0.01e9;
  friction.friction_angle = 1.0 * pi / 180.0;
  JointParameters elastic;
  elastic.kind = JointKind::ElasticSteel;
  elastic.normal_stiffness = elastic.shear_stiffness = 100e9;  // 100 GPa/m
  for (const auto a : all_components)
    for (const auto b : all_components) {
      auto is = [&](Component c) { return a == c || b == c; };
      const JointParameters* p = &elastic;
      if (is(Component::steel_frame))
        p = &elastic;
      else if (is(Component::movable_pier) && is(Component::slab))
        p = &friction;
      else if (is(Component::vault) || is(Component::infill))
        p = &softening;
      v.joints[index(a)][index(b)] = *p;
    }

  auto add = [&](geometry::ConvexPolyhedron shape, Component c, std::size_t material, std::string name,
                 model::Motion motion = model::Motion::free) {
    shape.validate(name);
    v.blocks.push_back({std::move(shape), c, material, motion, std::move(name)});
  };

  // --- The vault: courses along the barrel axis, bed joints in the radial planes of the faceted profile, head joints
  // normal to the axis from the outer face inward, staggered by half a block course to course. Pieces are clipped to
  // their web by the diagonal planes, and pieces smaller than min_block_fraction of a whole block are merged into
  // their neighbour in the course (the union of adjacent pieces of a course is again convex).
  struct Piece {
    double lo, hi, volume;
    int course;
  };
  std::vector<std::vector<Vec2>> sections(static_cast<std::size_t>(courses));
  std::vector<Piece> pieces;
  for (int k = 0; k < courses; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    auto& section = sections[ku];
    section = {in[ku], ex[ku], ex[ku + 1], in[ku + 1]};
    double u_min = 1e300;
    for (const auto& q : section) u_min = std::min(u_min, std::abs(q.x()));
    if (in[ku].x() < 0 && in[ku + 1].x() > 0) u_min = 0;
    const double whole = detail::polygon_area(section) * L;
    std::vector<double> cuts{Y};
    for (double c = Y - (k % 2 == 1 ? 0.5 * L : L);; c -= L) {
      cuts.push_back(c);
      if (c <= u_min) break;
    }
    std::vector<Piece> course;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      const double lo = cuts[i + 1], hi = cuts[i];
      const double vol = detail::volume(detail::north_web_piece(section, lo, hi, z0));
      if (vol <= 1e-12 * whole) continue;
      const double small = o.min_block_fraction * whole;
      if (!course.empty() && (vol < small || course.back().volume < small)) {
        course.back().lo = lo;
        course.back().volume += vol;
        ++v.vault_slivers_merged;
      } else {
        course.push_back({lo, hi, vol, k});
      }
    }
    pieces.insert(pieces.end(), course.begin(), course.end());
  }
  v.vault_slivers_merged *= 4;
  for (int web = 0; web < 4; ++web) {
    const Mat3 r = detail::web_rotation(web);
    std::vector<int> in_course(static_cast<std::size_t>(courses), 0);
    for (const auto& p : pieces) {
      const auto shape = detail::north_web_piece(sections[static_cast<std::size_t>(p.course)], p.lo, p.hi, z0);
      add(shape.transformed(r, Vec3::Zero()), Component::vault, masonry,
          "vault " + std::string(detail::web_names[static_cast<std::size_t>(web)]) + " course " + std::to_string(p.course + 1) +
              " block " + std::to_string(++in_course[static_cast<std::size_t>(p.course)]));
    }
  }

  // --- The infill in the four corners up to the infill height: over each half of a corner (split by the groin
  // diagonal) one prism per vault course below that height, its underside that course's extrados facet so that
  // infill and vault meet face to face, bounded by the diagonal, the outer face of the plan and the infill's top;
  // and one prism beyond the extrados of the springing, on the tie anchor.
  const double h = o.infill_height();
  if (h > 0) {
    const double brick = o.course_height() * o.thickness * L;
    std::vector<std::pair<std::vector<Vec2>, int>> slices;  // section in (u, w), side (+1: u > 0)
    auto slice = [&](const Vec2& lower, const Vec2& upper, int side) {
      const double eps = 1e-12;
      if (lower.y() >= h - eps) return false;
      std::vector<Vec2> poly{lower, Vec2(lower.x(), h)};
      if (upper.y() < h - eps) {
        poly.emplace_back(upper.x(), h);
        poly.push_back(upper);
      } else if (upper.y() <= h + eps) {
        poly.push_back(upper);
      } else {
        poly.push_back(lower + (upper - lower) * ((h - lower.y()) / (upper.y() - lower.y())));
      }
      slices.emplace_back(std::move(poly), side);
      return true;
    };
    for (int side : {1, -1}) {
      const std::size_t outer = side > 0 ? static_cast<std::size_t>(courses) : 0;
      if (Y - std::abs(ex[outer].x()) > 1e-9) {
        const double u0 = ex[outer].x(), u1 = side * Y;
        slices.push_back({{Vec2(u0, 0), Vec2(u1, 0), Vec2(u1, h), Vec2(u0, h)}, side});
      }
      for (int k = 0; k < courses; ++k) {
        const auto lower = side > 0 ? static_cast<std::size_t>(courses - k) : static_cast<std::size_t>(k);
        const auto upper = side > 0 ? lower - 1 : lower + 1;
        if (!slice(ex[lower], ex[upper], side)) break;
      }
    }
    for (int web = 0; web < 4; ++web) {
      const Mat3 r = detail::web_rotation(web);
      int counter[2] = {0, 0};
      for (const auto& [poly, side] : slices) {
        std::vector<Vec3> base;
        double u_min = 1e300;
        for (const auto& q : poly) u_min = std::min(u_min, std::abs(q.x()));
        for (const auto& q : poly) base.emplace_back(q.x(), u_min, z0 + q.y());
        auto shape = geometry::clip(geometry::make_prism(base, Vec3(0, Y - u_min, 0)),
                                    side > 0 ? Vec3(1, -1, 0) : Vec3(-1, -1, 0), 0.0);
        const double vol = detail::volume(shape);
        if (vol < o.min_infill_fraction * brick) {
          ++v.infill_pieces_dropped;
          v.infill_volume_dropped += vol;
          continue;
        }
        shape = shape.transformed(r, Vec3::Zero());
        const Vec3 c = shape.centroid_of_vertices();
        add(std::move(shape), Component::infill, masonry,
            "infill " + detail::corner_name(c.x(), c.y()) + " " + std::string(detail::web_names[static_cast<std::size_t>(web)]) +
                " web " + std::to_string(++counter[side > 0 ? 0 : 1]));
      }
    }
  }

  // --- Piers, tie anchors, slab, steel frame.
  const double w = o.pier_width();
  const double zp = o.pier_height;
  std::array<std::size_t, 4> anchor_block{};  // NE, NW, SE, SW
  const std::array<std::pair<double, double>, 4> corners{{{1, 1}, {-1, 1}, {1, -1}, {-1, -1}}};
  for (std::size_t i = 0; i < 4; ++i) {
    const auto [sx, sy] = corners[i];
    const double x0 = sx > 0 ? Y - w : -Y, y0 = sy > 0 ? Y - w : -Y;
    const bool fixed = (sx < 0) == o.fixed_piers_west;
    const std::string corner = detail::corner_name(sx, sy);
    add(geometry::make_box(Vec3(x0, y0, 0), Vec3(x0 + w, y0 + w, zp)), fixed ? Component::fixed_pier : Component::movable_pier,
        fixed ? masonry : rolling_pier, "pier " + corner + (fixed ? " (fixed, masonry)" : " (movable, steel)"));
    add(geometry::make_box(Vec3(x0, y0, zp), Vec3(x0 + w, y0 + w, z0)), Component::anchor, tie_anchor, "tie anchor " + corner);
    anchor_block[i] = v.blocks.size() - 1;
  }
  add(geometry::make_box(Vec3(-0.5 * o.slab_length_x, -0.5 * o.slab_length_y, -o.slab_thickness),
                         Vec3(0.5 * o.slab_length_x, 0.5 * o.slab_length_y, 0)),
      Component::slab, concrete, "slab", model::Motion::base);
  // UPN profiles on the outer faces of the fixed piers, from the slab to the top of the infill; a profile between
  // the two fixed piers' anchors (the fixed piers are connected by steel profiles instead of ties).
  {
    const double sx = o.fixed_piers_west ? -1.0 : 1.0;
    const double d = o.steel_profile_depth, t = o.steel_profile_width;
    const double c = Y - 0.5 * w;  // pier centre line
    const double top = z0 + std::max(h, 0.0);
    for (double sy : {1.0, -1.0}) {
      const std::string corner = detail::corner_name(sx, sy);
      const double xo = sx * Y, yo = sy * Y;
      add(geometry::make_box(Vec3(std::min(xo, xo + sx * t), sy * c - 0.5 * d, 0), Vec3(std::max(xo, xo + sx * t), sy * c + 0.5 * d, top)),
          Component::steel_frame, back_frame, "UPN " + corner + " " + (sx < 0 ? "west" : "east") + " face");
      add(geometry::make_box(Vec3(sx * c - 0.5 * d, std::min(yo, yo + sy * t), 0), Vec3(sx * c + 0.5 * d, std::max(yo, yo + sy * t), top)),
          Component::steel_frame, back_frame, "UPN " + corner + " " + (sy > 0 ? "north" : "south") + " face");
    }
    const double zb = zp + 0.5 * (o.anchor_height - d);
    const double xo = sx * Y;
    add(geometry::make_box(Vec3(std::min(xo, xo - sx * t), -(Y - w), zb), Vec3(std::max(xo, xo - sx * t), Y - w, zb + d)),
        Component::steel_frame, back_frame, std::string("steel profile between the fixed piers (") + (sx < 0 ? "west" : "east") + ")");
  }

  // --- Ties: three couples of bars at mid-height of the anchors, between the anchor centre lines: the two sides
  // across the excitation (north, south) and the side of the movable piers.
  {
    const double c = Y - 0.5 * w;
    const double z = zp + 0.5 * o.anchor_height;
    const double movable_x = o.fixed_piers_west ? c : -c;
    auto anchor = [&](double sx, double sy) {
      for (std::size_t i = 0; i < 4; ++i)
        if (corners[i].first == sx && corners[i].second == sy) return anchor_block[i];
      return anchor_block[0];
    };
    auto couple = [&](const std::string& side, const Vec3& a, const Vec3& b, const Vec3& offset, std::size_t ba, std::size_t bb) {
      for (int bar : {1, 2}) {
        const Vec3 shift = (bar == 1 ? -0.5 : 0.5) * o.tie_spacing * offset;
        v.ties.push_back({"tie " + side + " " + std::to_string(bar), a + shift, b + shift, ba, bb, o.tie_area,
                          o.tie_density, o.tie_modulus, o.tie_pretension});
      }
    };
    for (double sy : {1.0, -1.0})
      couple(sy > 0 ? "north" : "south", Vec3(-c, sy * c, z), Vec3(c, sy * c, z), Vec3(0, 1, 0), anchor(-1, sy), anchor(1, sy));
    const double sx = movable_x > 0 ? 1.0 : -1.0;
    couple(sx > 0 ? "east" : "west", Vec3(movable_x, -c, z), Vec3(movable_x, c, z), Vec3(1, 0, 0), anchor(sx, -1), anchor(sx, 1));
  }

  // --- Monitor points, each attached to the nearest block of its component.
  for (const auto& m : v.options.monitors) {
    Vec3 p(m.x, m.y, 0);
    if (m.level == MonitorLevel::extrados) p.z() = v.extrados_level(m.x, m.y);
    else if (m.level == MonitorLevel::intrados) p.z() = v.intrados_level(m.x, m.y);
    std::optional<std::size_t> best;
    double best_distance = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < v.blocks.size(); ++i) {
      const auto& b = v.blocks[i];
      if (b.component != m.component) continue;
      if (m.level == MonitorLevel::top) {  // the top face of the block under (x, y)
        double top = -1e300;
        for (const auto& q : b.shape.vertices) top = std::max(top, q.z());
        const double d = geometry::distance(b.shape, Vec3(m.x, m.y, top));
        if (d < best_distance) {
          best_distance = d;
          best = i;
          p.z() = top;
        }
        continue;
      }
      const double d = geometry::distance(b.shape, p);
      if (d < best_distance) {
        best_distance = d;
        best = i;
      }
    }
    if (!best) throw InvalidArgument("cross vault: monitor point '" + m.name + "': the model has no " + std::string(name(m.component)) + " block");
    v.monitor_points.push_back({m.name, p, *best});
  }
  return v;
}

/// The rigid-block model of the cross vault: one rigid block per block, density from its material, joint tag =
/// component index (choose the law with CrossVault::joint(tag_a, tag_b)), motion as generated (the slab follows the
/// table, everything else is free).
inline model::Model build_rigid_model(const CrossVault& v) {
  model::Model m;
  for (const auto& b : v.blocks)
    m.add_block(b.shape, v.materials[b.material].density, b.name, static_cast<int>(b.component), b.motion);
  return m;
}

/// Volumes per component (m^3) of the exact (not faceted) geometry, for checking the generated blocks: the vault
/// ring in closed form for the segmental profile, by Gauss quadrature over the ring for the elliptical one; the
/// infill by Simpson's rule over the exact extrados; boxes exactly.
inline std::array<double, component_count> analytical_volumes(const CrossVaultOptions& o) {
  o.validate();
  std::array<double, component_count> volume{};
  const detail::ArchProfile profile(o);
  const double Y = o.half_plan(), t = o.thickness, h = o.infill_height();
  // Exact extrados height w at horizontal position u >= 0 (0 beyond the springing); and its u where w = 0.
  auto extrados_point = [&](double s) -> Vec2 { return profile.point(s) + t * profile.normal(s); };
  const double R = profile.radius, c = -profile.centre_w, Re = R + t;
  // u of the extrados on the springing plane (w = 0).
  const double u_springing = o.profile == VaultProfile::segmental ? std::sqrt(Re * Re - c * c) : extrados_point(1.0).x();
  auto extrados = [&](double u) {
    if (u >= u_springing) return 0.0;
    if (o.profile == VaultProfile::segmental) return std::sqrt(Re * Re - u * u) - c;
    double lo = 0, hi = 1;  // the extrados' u grows with s on [0, 1]
    for (int i = 0; i < 100; ++i) {
      const double mid = 0.5 * (lo + hi);
      (extrados_point(mid).x() < u ? lo : hi) = mid;
    }
    return extrados_point(0.5 * (lo + hi)).y();
  };
  if (o.profile == VaultProfile::segmental) {
    // Ring section {R <= r <= R + t, w >= 0} in polar coordinates about the centre (0, -c): the angle from the
    // vertical reaches theta(r) = acos(c / r). A web is the section swept from the groin |u| to the outer face Y:
    // V = int (Y - |u|) dA = Y A - int |u| dA, with A = 2 int r theta(r) dr and int |u| dA = 2 int (r^2 - c r) dr.
    auto area_primitive = [c](double r) { return 0.5 * r * r * std::acos(c / r) - 0.5 * c * std::sqrt(r * r - c * c); };
    auto moment_primitive = [c](double r) { return r * r * r / 3.0 - 0.5 * c * r * r; };
    const double area = 2 * (area_primitive(Re) - area_primitive(R));
    const double moment = 2 * (moment_primitive(Re) - moment_primitive(R));
    volume[index(Component::vault)] = 4 * (Y * area - moment);
  } else {
    // int over s in [0, 1] (u >= 0, doubled by symmetry), r in [0, t] of (Y - u) |d(x)/d(s, r)|, x = p(s) + r n(s);
    // 2-point Gauss in r (the integrand is a polynomial of degree 2 in r), 5-point Gauss on 4000 panels in s.
    const double gs[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
    const double gw[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665, 0.2369268850561891};
    const int panels = 4000;
    const double ds = 1.0 / panels, step = 1e-7;
    double web = 0;
    for (int i = 0; i < panels; ++i)
      for (int g = 0; g < 5; ++g) {
        const double s = (i + 0.5 + 0.5 * gs[g]) * ds;
        const Vec2 dp = (profile.point(std::min(1.0, s + step)) - profile.point(std::max(0.0, s - step))) /
                        (std::min(1.0, s + step) - std::max(0.0, s - step));
        const Vec2 dn = (profile.normal(std::min(1.0, s + step)) - profile.normal(std::max(0.0, s - step))) /
                        (std::min(1.0, s + step) - std::max(0.0, s - step));
        const Vec2 n = profile.normal(s);
        for (double r : {0.5 * t * (1 - 1 / std::sqrt(3.0)), 0.5 * t * (1 + 1 / std::sqrt(3.0))}) {
          const Vec2 ds_vec = dp + r * dn;
          const double jacobian = std::abs(ds_vec.x() * n.y() - ds_vec.y() * n.x());
          const double u = profile.point(s).x() + r * n.x();
          web += gw[g] * 0.5 * ds * 0.5 * t * (Y - u) * jacobian;
        }
      }
    volume[index(Component::vault)] = 4 * 2 * web;
  }
  if (h > 0) {
    // Where the exact extrados reaches the infill top: bisection on u in [0, u_springing].
    double lo = 0, hi = u_springing;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (extrados(mid) > h ? lo : hi) = mid;
    }
    const double u_top = 0.5 * (lo + hi);
    // Half a corner: int_{u_top}^{Y} (h - extrados(u)) (Y - u) du, split at the springing (kink of the extrados).
    auto simpson = [&](double a, double b) {
      const int n = 20000;
      const double dx = (b - a) / n;
      double sum = 0;
      for (int i = 0; i <= n; ++i) {
        const double u = a + i * dx;
        const double f = (h - extrados(u)) * (Y - u);
        sum += f * (i == 0 || i == n ? 1 : (i % 2 == 1 ? 4 : 2));
      }
      return sum * dx / 3;
    };
    volume[index(Component::infill)] = 8 * (simpson(u_top, u_springing) + simpson(u_springing, Y));
  }
  const double w = o.pier_width();
  volume[index(Component::fixed_pier)] = 2 * w * w * o.pier_height;
  volume[index(Component::movable_pier)] = 2 * w * w * o.pier_height;
  volume[index(Component::anchor)] = 4 * w * w * o.anchor_height;
  volume[index(Component::slab)] = o.slab_length_x * o.slab_length_y * o.slab_thickness;
  const double d = o.steel_profile_depth, s = o.steel_profile_width;
  volume[index(Component::steel_frame)] = 4 * d * s * (o.springing_level() + std::max(h, 0.0)) + s * d * 2 * (Y - w);
  return volume;
}

/// What check_assembly() found.
struct AssemblyCheck {
  std::vector<model::ContactCandidate> contacts;           // as detected, block pair ids a < b
  std::size_t contact_points = 0;
  std::size_t open_contact_points = 0;                     // gap beyond the contact tolerance
  std::array<std::size_t, 3> contact_points_by_joint{};   // by JointKind
  double max_penetration = 0;                              // m, deepest overlap of two blocks (separating axes)
  std::pair<std::size_t, std::size_t> deepest_pair{0, 0};
  bool vault_connected = false;                            // through vault-vault contacts
  std::size_t min_vault_neighbours = 0;                    // fewest vault blocks any vault block touches
  std::size_t vault_blocks_below_two_neighbours = 0;
  std::array<double, component_count> mass{};              // kg, of the blocks
  std::array<double, component_count> analytical_mass{};   // kg, analytical volume x density
  double tie_mass = 0;                                     // kg
  double detection_seconds = 0;
  double max_mass_error() const {  // largest |mass / analytical - 1| over the components present
    double e = 0;
    for (std::size_t c = 0; c < component_count; ++c)
      if (analytical_mass[c] > 0) e = std::max(e, std::abs(mass[c] / analytical_mass[c] - 1));
    return e;
  }
};

/// Checks the assembly: contact detection on the rigid model (every block taken as free, so that no pair is
/// skipped), the deepest overlap of any two blocks by the separating-axis test over all pairs whose boxes meet,
/// the contact graph of the vault, and the mass of each component against its analytical volume.
inline AssemblyCheck check_assembly(const CrossVault& v, const model::Model& m, const model::ContactSettings& settings) {
  AssemblyCheck r;
  auto bodies = m.bodies;
  std::fill(bodies.motion.begin(), bodies.motion.end(), model::Motion::free);
  const auto start = std::chrono::steady_clock::now();
  r.contacts = model::detect_contacts(bodies, settings);
  const auto& contacts = r.contacts;
  r.detection_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.contact_points = contacts.size();
  const std::size_t n = v.blocks.size();
  std::vector<std::vector<std::size_t>> neighbours(n);
  for (const auto& c : contacts) {
    if (c.gap > settings.tolerance) ++r.open_contact_points;
    ++r.contact_points_by_joint[static_cast<std::size_t>(v.joint(c).kind)];
    if (v.blocks[c.a].component == Component::vault && v.blocks[c.b].component == Component::vault) {
      neighbours[c.a].push_back(c.b);
      neighbours[c.b].push_back(c.a);
    }
  }
  std::vector<std::size_t> vault;
  for (std::size_t i = 0; i < n; ++i) {
    auto& nb = neighbours[i];
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
    if (v.blocks[i].component == Component::vault) vault.push_back(i);
  }
  if (!vault.empty()) {
    r.min_vault_neighbours = std::numeric_limits<std::size_t>::max();
    for (std::size_t i : vault) {
      r.min_vault_neighbours = std::min(r.min_vault_neighbours, neighbours[i].size());
      if (neighbours[i].size() < 2) ++r.vault_blocks_below_two_neighbours;
    }
    std::vector<bool> seen(n, false);
    std::vector<std::size_t> stack{vault.front()};
    seen[vault.front()] = true;
    std::size_t reached = 0;
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      ++reached;
      for (std::size_t j : neighbours[i])
        if (!seen[j]) {
          seen[j] = true;
          stack.push_back(j);
        }
    }
    r.vault_connected = reached == vault.size();
  }
  // Overlaps: sweep and prune along x over the world boxes, exact separation of every pair whose boxes meet.
  std::vector<Vec3> lo(n), hi(n);
  for (std::size_t i = 0; i < n; ++i) {
    lo[i] = Vec3::Constant(1e300);
    hi[i] = Vec3::Constant(-1e300);
    for (const auto& p : v.blocks[i].shape.vertices) {
      lo[i] = lo[i].cwiseMin(p);
      hi[i] = hi[i].cwiseMax(p);
    }
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lo[a].x() < lo[b].x(); });
  for (std::size_t u = 0; u < n; ++u)
    for (std::size_t w = u + 1; w < n && lo[order[w]].x() < hi[order[u]].x(); ++w) {
      const std::size_t a = order[u], b = order[w];
      if ((lo[a].array() >= hi[b].array()).any() || (lo[b].array() >= hi[a].array()).any()) continue;
      const double s = geometry::separation(v.blocks[a].shape, v.blocks[b].shape);
      if (-s > r.max_penetration) {
        r.max_penetration = -s;
        r.deepest_pair = std::minmax(a, b);
      }
    }
  const auto reference = analytical_volumes(v.options);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& b = v.blocks[i];
    r.mass[index(b.component)] += v.materials[b.material].density * detail::volume(b.shape);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = index(v.blocks[i].component);
    if (r.analytical_mass[c] == 0) r.analytical_mass[c] = reference[c] * v.materials[v.blocks[i].material].density;
  }
  for (const auto& t : v.ties) r.tie_mass += t.mass();
  return r;
}

/// Axis-aligned bounding box of the blocks of one component: {min corner, max corner}, m. Empty component: zeros.
inline std::array<Vec3, 2> bounding_box(const CrossVault& v, Component c) {
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  bool any = false;
  for (const auto& b : v.blocks)
    if (b.component == c)
      for (const auto& p : b.shape.vertices) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
        any = true;
      }
  if (!any) return {Vec3::Zero(), Vec3::Zero()};
  return {lo, hi};
}

}  // namespace blockdem::models
