#pragma once
// The cross vault generator: make_cross_vault() lays the courses of the four webs, trimmed at the groins, the corner
// infill, piers, tie anchors, slab and steel frame (paper Sect. 2, Fig. 1, 6), and build_rigid_model() turns the
// description into a model::Model of rigid blocks.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/geometry/clip.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/polygon.hpp"
#include "blockdem/geometry/queries.hpp"
#include "blockdem/model/model.hpp"
#include "blockdem/models/cross_vault_description.hpp"
#include "blockdem/models/cross_vault_geometry.hpp"

namespace blockdem::models {

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

}  // namespace blockdem::models
