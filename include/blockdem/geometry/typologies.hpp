#pragma once
// Generators of common masonry typologies as lists of named convex blocks: a dry-stack wall in running bond with
// openings, lintels, bonded return walls and a foundation wide enough to catch what falls; a semicircular barrel
// vault of voussoirs in staggered rings on two abutments. docs/generators.md describes them and their options.

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/number_text.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/generators.hpp"

namespace blockdem::geometry {

/// An opening through the wall: the units of courses sill_course .. head_course - 1 (0-based) between the jambs x0
/// and x1 are cut away, and a lintel fills course head_course over them.
struct WallOpening {
  double x0 = 0, x1 = 0;  // m, the jambs, from the wall's left end (x = 0)
  int sill_course = 0;    // the lowest course cut away (0: a door)
  int head_course = 0;    // the lintel's course, the first above the opening
};

/// What the wall stands on: a foundation block, or a thin floor slab; either is as wide as what can fall on it.
enum class Foundation { block, floor };

/// A wall along x in running bond (each course shifted by half a unit on the one below), its outer face on y = 0,
/// its inner face on y = thickness, standing on z = 0. Units are given with their joints (joints have no thickness).
struct WallOptions {
  double length = 2.0;             // m along x, a multiple of unit_length / 2, in [unit_length, 1000]
  int courses = 20;                // 1..10000
  double thickness = 0.12;         // m along y, in (0, 100]: one unit through
  double unit_length = 0.25;       // m along x, in (0, 100]
  double unit_height = 0.075;      // m along z, in (0, 100]
  std::vector<WallOpening> openings;
  double lintel_bearing = 0.125;   // m: how far each lintel runs past each jamb, in (0, 100]
  double return_length = 0;        // m: return walls at both ends, running along +y this far past the inner face;
                                   // 0: none, else in [unit_length / 2, 1000]
  Foundation foundation = Foundation::block;
  double foundation_depth = 0;     // m; 0: twice the thickness (block) or half a unit height (floor)

  double height() const { return courses * unit_height; }  // m
  /// The thickness of the foundation (m) and how far it runs past the masonry in x and y (m): the wall's height
  /// plus its thickness, so that the wall toppled either way lands on it.
  double foundation_thickness() const {
    return foundation_depth > 0 ? foundation_depth : foundation == Foundation::block ? 2 * thickness : 0.5 * unit_height;
  }
  double foundation_margin() const { return height() + thickness; }
  /// The masonry's reach at the ends: the returns' width, which the openings must keep clear of.
  double end_width() const { return return_length > 0 ? thickness : 0.0; }

  void validate() const {
    auto check = [](bool ok, const std::string& what) {
      if (!ok) throw InvalidArgument("wall: " + what);
    };
    check(unit_length > 0 && unit_length <= 100, "unit_length must be in (0, 100] m, got " + num(unit_length));
    check(unit_height > 0 && unit_height <= 100, "unit_height must be in (0, 100] m, got " + num(unit_height));
    check(thickness > 0 && thickness <= 100, "thickness must be in (0, 100] m, got " + num(thickness));
    check(courses >= 1 && courses <= 10000, "courses must be in 1..10000, got " + std::to_string(courses));
    const double halves = 2 * length / unit_length;
    check(length >= unit_length && length <= 1000, "length must be in [unit_length " + num(unit_length) + ", 1000] m, got " + num(length));
    check(std::abs(halves - std::round(halves)) <= 1e-9 * halves,
          "length must be a multiple of unit_length / 2 = " + num(0.5 * unit_length) + " m (running bond), got " + num(length));
    check(lintel_bearing > 0 && lintel_bearing <= 100, "lintel_bearing must be in (0, 100] m, got " + num(lintel_bearing));
    check(return_length == 0 || (return_length >= 0.5 * unit_length && return_length <= 1000),
          "return_length must be 0 (no returns) or in [unit_length / 2 = " + num(0.5 * unit_length) + ", 1000] m, got " + num(return_length));
    check(return_length == 0 || length >= 2 * thickness + unit_length,
          "length must be at least 2 thickness + unit_length = " + num(2 * thickness + unit_length) + " m with return walls, got " + num(length));
    check(foundation_depth >= 0 && foundation_depth <= 100, "foundation_depth must be in [0, 100] m (0: the default), got " + num(foundation_depth));
    for (std::size_t k = 0; k < openings.size(); ++k) {
      const auto& o = openings[k];
      const std::string which = "openings[" + std::to_string(k) + "]: ";
      const double lo = end_width() + lintel_bearing, hi = length - end_width() - lintel_bearing;
      check(o.x0 >= lo - 1e-12 && o.x1 > o.x0 && o.x1 <= hi + 1e-12,
            which + "needs " + num(lo) + " <= x0 < x1 <= " + num(hi) + " m (the lintel's bearing" +
                (return_length > 0 ? " and the return walls" : "") + " inside the wall), got x0 " + num(o.x0) + ", x1 " + num(o.x1));
      check(o.sill_course >= 0 && o.sill_course < o.head_course && o.head_course < courses,
            which + "needs 0 <= sill_course < head_course <= courses - 1 = " + std::to_string(courses - 1) + " (the lintel's course), got " +
                std::to_string(o.sill_course) + " and " + std::to_string(o.head_course));
      for (std::size_t j = 0; j < k; ++j) {
        const auto& p = openings[j];
        const bool apart_x = o.x0 - lintel_bearing >= p.x1 + lintel_bearing - 1e-12 || p.x0 - lintel_bearing >= o.x1 + lintel_bearing - 1e-12;
        const bool apart_z = o.sill_course > p.head_course || p.sill_course > o.head_course;
        check(apart_x || apart_z, which + "it or its lintel overlaps openings[" + std::to_string(j) + "] or its lintel");
      }
    }
  }
};

namespace detail {

struct Span {
  double begin, end;
};

/// The units of one course over [begin, end], with bond joints at offset + k unit (k integer), less the gaps
/// (openings, lintels). A piece shorter than a quarter unit at the end of a stretch of masonry joins its neighbour:
/// a closer rather than a sliver. Throws if the gaps leave a stretch narrower than that, naming it.
inline std::vector<Span> course_units(double begin, double end, double offset, double unit, std::vector<Span> gaps, const std::string& course) {
  const double eps = 1e-9 * unit, min_piece = 0.25 * unit;
  std::sort(gaps.begin(), gaps.end(), [](const Span& a, const Span& b) { return a.begin < b.begin; });
  std::vector<Span> stretches;
  double at = begin;
  for (const auto& g : gaps) {
    if (g.begin > at + eps) stretches.push_back({at, g.begin});
    at = std::max(at, g.end);
  }
  if (end > at + eps) stretches.push_back({at, end});
  std::vector<Span> units;
  for (const auto& s : stretches) {
    if (s.end - s.begin < min_piece - eps)
      throw InvalidArgument("wall: the openings leave masonry from x = " + num(s.begin) + " to " + num(s.end) + " m in " + course +
                            ", narrower than a quarter unit: move the openings");
    std::vector<double> cuts{s.begin};
    for (double k = std::ceil((s.begin - offset) / unit); offset + k * unit < s.end - eps; k += 1)
      if (offset + k * unit > s.begin + eps) cuts.push_back(offset + k * unit);
    cuts.push_back(s.end);
    if (cuts.size() > 2 && cuts[1] - cuts[0] < min_piece - eps) cuts.erase(cuts.begin() + 1);
    if (cuts.size() > 2 && cuts[cuts.size() - 1] - cuts[cuts.size() - 2] < min_piece - eps) cuts.erase(cuts.end() - 2);
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) units.push_back({cuts[k], cuts[k + 1]});
  }
  return units;
}

}  // namespace detail

/// The wall of the options: its units (group "wall", named "c3 u5": the fifth unit from the left of the third course
/// from the bottom, both counted from 1), one lintel per opening (group "lintel", "lintel 1" over openings[0]), the
/// return walls ("return", "return left c2 u1", the first unit from the corner) and the foundation (group
/// "foundation", a support), in that order course by course, the foundation last. The returns are bonded to the
/// wall at the corners: in even courses (0-based) the wall's end unit runs through the corner, in odd courses the
/// return's. Courses and returns keep the bond's joints; a jamb or a lintel's end off a joint splits the unit there.
inline std::vector<NamedBlock> masonry_wall(const WallOptions& o) {
  o.validate();
  const double l = o.unit_length, h = o.unit_height, t = o.thickness, L = o.length, R = o.return_length;
  const bool returns = R > 0;
  std::vector<NamedBlock> blocks;
  auto add = [&](double x0, double x1, double y0, double y1, double z0, const std::string& name, const char* group) {
    blocks.push_back({make_box(Vec3(x0, y0, z0), Vec3(x1, y1, z0 + h)), name, false, group});
  };
  for (int c = 0; c < o.courses; ++c) {
    const double z0 = c * h;
    const std::string course = "c" + std::to_string(c + 1);
    const bool wall_through = c % 2 == 0;  // at the corners: the wall's end unit (even) or the return's (odd)
    std::vector<detail::Span> gaps;
    for (std::size_t k = 0; k < o.openings.size(); ++k) {
      const auto& op = o.openings[k];
      if (op.sill_course <= c && c < op.head_course) gaps.push_back({op.x0, op.x1});
      if (c == op.head_course) {
        gaps.push_back({op.x0 - o.lintel_bearing, op.x1 + o.lintel_bearing});
        blocks.push_back({make_box(Vec3(op.x0 - o.lintel_bearing, 0, z0), Vec3(op.x1 + o.lintel_bearing, t, z0 + h)),
                          "lintel " + std::to_string(k + 1), false, "lintel"});
      }
    }
    const double inset = returns && !wall_through ? t : 0.0;
    const auto units = detail::course_units(inset, L - inset, c % 2 == 0 ? 0.0 : 0.5 * l, l, gaps, "course " + std::to_string(c) + " (0-based)");
    for (std::size_t k = 0; k < units.size(); ++k)
      add(units[k].begin, units[k].end, 0, t, z0, course + " u" + std::to_string(k + 1), "wall");
    if (!returns) continue;
    // The returns' joints from the outer face (y = 0) in odd courses, shifted by half a unit in even ones.
    const auto along = detail::course_units(wall_through ? t : 0.0, t + R, c % 2 == 0 ? 0.5 * l : 0.0, l, {},
                                            "the returns' course " + std::to_string(c) + " (0-based)");
    const std::pair<const char*, double> sides[] = {{"left", 0.0}, {"right", L - t}};
    for (const auto& [side, x_side] : sides)
      for (std::size_t k = 0; k < along.size(); ++k)
        add(x_side, x_side + t, along[k].begin, along[k].end, z0,
            std::string("return ") + side + " " + course + " u" + std::to_string(k + 1), "return");
  }
  const double m = o.foundation_margin(), d = o.foundation_thickness();
  blocks.push_back({make_box(Vec3(-m, -m, -d), Vec3(L + m, t + R + m, 0)), "foundation", true, "foundation"});
  return blocks;
}

/// A semicircular barrel vault: the intrados a half cylinder of radius span / 2 about the y axis (centre at the
/// origin, springings on z = 0, x across the span), length along y from 0. The rise is the radius: the generator
/// makes semicircular vaults only.
struct BarrelVaultOptions {
  double span = 2.0;            // m, clear (the intrados' diameter), in (0, 1000]
  double thickness = 0.24;      // m, radial, in (0, span]
  double length = 1.0;          // m along y, a multiple of unit_length / 2, in [unit_length, 1000]
  int rings = 15;               // voussoirs across the span, one ring of units along y each, 2..2000
  double unit_length = 0.25;    // m along y, in (0, 100]
  bool running_bond = true;     // alternate rings shifted by half a unit along y (else joints straight through)
  double abutment_width = 0;    // m along x, centred under each springing; 0: twice the thickness; in [thickness, span + thickness)
  double abutment_height = 0;   // m; 0: the thickness; in (0, 1000]

  double inner_radius() const { return 0.5 * span; }
  double outer_radius() const { return 0.5 * span + thickness; }
  double abutment_x() const { return abutment_width > 0 ? abutment_width : 2 * thickness; }
  double abutment_z() const { return abutment_height > 0 ? abutment_height : thickness; }

  void validate() const {
    auto check = [](bool ok, const std::string& what) {
      if (!ok) throw InvalidArgument("barrel vault: " + what);
    };
    check(span > 0 && span <= 1000, "span must be in (0, 1000] m, got " + num(span));
    check(thickness > 0 && thickness <= span, "thickness must be in (0, span " + num(span) + "] m, got " + num(thickness));
    check(unit_length > 0 && unit_length <= 100, "unit_length must be in (0, 100] m, got " + num(unit_length));
    const double halves = 2 * length / unit_length;
    check(length >= unit_length && length <= 1000, "length must be in [unit_length " + num(unit_length) + ", 1000] m, got " + num(length));
    check(std::abs(halves - std::round(halves)) <= 1e-9 * halves,
          "length must be a multiple of unit_length / 2 = " + num(0.5 * unit_length) + " m, got " + num(length));
    check(rings >= 2 && rings <= 2000, "rings must be in 2..2000, got " + std::to_string(rings));
    check(abutment_width == 0 || (abutment_width >= thickness && abutment_width < span + thickness),
          "abutment_width must be 0 (twice the thickness) or in [thickness, span + thickness) m (the abutments may not meet), got " +
              num(abutment_width));
    check(abutment_x() < span + thickness, "the default abutment width, twice the thickness, makes the abutments meet: give abutment_width");
    check(abutment_height >= 0 && abutment_height <= 1000, "abutment_height must be in [0, 1000] m (0: the thickness), got " + num(abutment_height));
  }
};

/// The vault of the options: its voussoirs (group "vault", "ring 3 u2": the second unit along y of the third ring
/// from the right springing, x > 0), convex hexahedra with plane intrados and extrados (chords of the circles), then
/// the two abutments (group "abutment", supports): "abutment right" and "abutment left".
inline std::vector<NamedBlock> barrel_vault(const BarrelVaultOptions& o) {
  o.validate();
  const double ri = o.inner_radius(), re = o.outer_radius(), l = o.unit_length;
  std::vector<NamedBlock> blocks;
  for (int i = 0; i < o.rings; ++i) {
    const double a0 = pi * i / o.rings, a1 = pi * (i + 1) / o.rings;
    const double offset = o.running_bond && i % 2 == 1 ? 0.5 * l : 0.0;
    const auto units = detail::course_units(0, o.length, offset, l, {}, "ring " + std::to_string(i + 1));
    for (std::size_t k = 0; k < units.size(); ++k) {
      const double y0 = units[k].begin, y1 = units[k].end;
      auto at = [](double r, double a, double y) { return Vec3(r * std::cos(a), y, r * std::sin(a)); };
      blocks.push_back({make_hexahedron({at(ri, a0, y1), at(re, a0, y1), at(re, a0, y0), at(ri, a0, y0), at(ri, a1, y1), at(re, a1, y1),
                                         at(re, a1, y0), at(ri, a1, y0)}),
                        "ring " + std::to_string(i + 1) + " u" + std::to_string(k + 1), false, "vault"});
    }
  }
  const double centre = 0.5 * (ri + re), w = 0.5 * o.abutment_x(), hz = o.abutment_z();
  blocks.push_back({make_box(Vec3(centre - w, 0, -hz), Vec3(centre + w, o.length, 0)), "abutment right", true, "abutment"});
  blocks.push_back({make_box(Vec3(-centre - w, 0, -hz), Vec3(-centre + w, o.length, 0)), "abutment left", true, "abutment"});
  return blocks;
}

}  // namespace blockdem::geometry
