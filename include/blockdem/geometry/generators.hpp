#pragma once
// Block assemblies used in tests and examples: a semicircular arch of voussoirs and a dry-stack wall in running bond.

#include <cmath>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"

namespace blockdem::geometry {

struct NamedBlock {
  ConvexPolyhedron shape;
  std::string name;
  bool support = false;  // a block meant to be fixed (springings, foundation)
  std::string group{};   // what the block is part of ("wall", "lintel", ...); empty: not grouped
};

/// A semicircular arch in the x-z plane (z up), centre of the circle at the origin, `radius` to the centreline,
/// `thickness` radially, `depth` along y, springing faces on z = 0; plus two support blocks under the springings.
inline std::vector<NamedBlock> semicircular_arch(int voussoirs, double radius, double thickness, double depth) {
  if (voussoirs < 2 || voussoirs > 10000) throw InvalidArgument("arch: voussoirs must be in 2..10000");
  if (!(radius > 0)) throw InvalidArgument("arch: radius must be > 0 m");
  if (!(thickness > 0 && thickness < 2 * radius)) throw InvalidArgument("arch: thickness must be in (0, 2 radius) m");
  if (!(depth > 0)) throw InvalidArgument("arch: depth must be > 0 m");
  const double ri = radius - 0.5 * thickness;
  const double re = radius + 0.5 * thickness;
  const double y0 = -0.5 * depth;
  const double y1 = 0.5 * depth;
  std::vector<NamedBlock> blocks;
  for (int i = 0; i < voussoirs; ++i) {
    // From the right springing (angle 0) to the left one (angle pi).
    const double a0 = pi * i / voussoirs;
    const double a1 = pi * (i + 1) / voussoirs;
    const Vec3 i0(ri * std::cos(a0), 0, ri * std::sin(a0)), e0(re * std::cos(a0), 0, re * std::sin(a0));
    const Vec3 i1(ri * std::cos(a1), 0, ri * std::sin(a1)), e1(re * std::cos(a1), 0, re * std::sin(a1));
    auto at = [](Vec3 p, double y) { p.y() = y; return p; };
    blocks.push_back({make_hexahedron({at(i0, y1), at(e0, y1), at(e0, y0), at(i0, y0),
                                       at(i1, y1), at(e1, y1), at(e1, y0), at(i1, y0)}),
                      "voussoir " + std::to_string(i + 1)});
  }
  const double h = thickness;  // support blocks: as deep as the ring is thick
  blocks.push_back({make_box(Vec3(ri - 0.5 * h, y0, -h), Vec3(re + 0.5 * h, y1, 0)), "support right", true});
  blocks.push_back({make_box(Vec3(-re - 0.5 * h, y0, -h), Vec3(-ri + 0.5 * h, y1, 0)), "support left", true});
  return blocks;
}

/// A dry-stack wall in running bond along x: `courses` courses of units `length` x `width` x `height` (x, y, z),
/// `units_per_course` units per course; every other course starts and ends with a half unit so the ends are
/// flush. A foundation block (support) lies under it, its top at z = 0.
inline std::vector<NamedBlock> running_bond_wall(int courses, int units_per_course, double length, double width,
                                                 double height) {
  if (courses < 1 || units_per_course < 1) throw InvalidArgument("wall: courses and units per course must be >= 1");
  if (!(length > 0 && width > 0 && height > 0)) throw InvalidArgument("wall: unit dimensions must be > 0 m");
  std::vector<NamedBlock> blocks;
  const double wall_length = units_per_course * length;
  for (int c = 0; c < courses; ++c) {
    const double z0 = c * height;
    // Even courses: n whole units; odd courses: a half unit at each end and n - 1 whole units between.
    std::vector<double> cuts{0.0};
    const double shift = (c % 2 == 1) ? 0.5 * length : 0.0;
    for (int u = 0; u < units_per_course; ++u)
      if (shift + u * length > 0.0) cuts.push_back(shift + u * length);
    cuts.push_back(wall_length);
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
      blocks.push_back({make_box(Vec3(cuts[k], 0, z0), Vec3(cuts[k + 1], width, z0 + height)),
                        "unit c" + std::to_string(c + 1) + "-" + std::to_string(k + 1)});
  }
  blocks.push_back({make_box(Vec3(-0.5 * length, -0.5 * width, -height), Vec3(wall_length + 0.5 * length, 1.5 * width, 0)),
                    "foundation", true});
  return blocks;
}

}  // namespace blockdem::geometry
