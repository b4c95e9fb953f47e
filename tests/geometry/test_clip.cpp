// Clipping convex polyhedra by planes, prisms, point distance and the separating-axis separation of two blocks.

#include <doctest/doctest.h>

#include <cmath>

#include "../approx.hpp"
#include "blockdem/geometry/clip.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/mass_properties.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/geometry/queries.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_clip {

namespace {
geometry::ConvexPolyhedron unit_cube() { return geometry::make_box(Vec3(0, 0, 0), Vec3(1, 1, 1)); }
}  // namespace

TEST_CASE("clip: the unit cube cut by x + y + z <= 1.5 keeps half its volume and gets a regular hexagon as cap") {
  const auto p = geometry::clip(unit_cube(), Vec3(1, 1, 1), 1.5);
  p.validate("clipped cube");
  CHECK(p.vertices.size() == 10);  // 4 corners below the plane, 6 cut points
  CHECK(p.faces.size() == 7);
  CHECK(geometry::mass_properties(p).volume == test::approx(0.5));  // the plane halves the cube by symmetry
  // The cap: a regular hexagon of side sqrt(1/2), area (3 sqrt 3 / 2) s^2, outward normal along (1, 1, 1).
  const auto cap = p.faces.size() - 1;
  CHECK(p.face_area(cap) == test::approx(1.5 * std::sqrt(3.0) * 0.5));
  CHECK((p.face_normal(cap) - Vec3(1, 1, 1).normalized()).norm() < 1e-12);
}

TEST_CASE("clip: a plane through an edge of the cube leaves a triangular prism without slivers") {
  const auto p = geometry::clip(unit_cube(), Vec3(1, -1, 0), 0.0);  // keep y >= x: the diagonal plane through z-edges
  p.validate("half cube");
  CHECK(p.vertices.size() == 6);
  CHECK(p.faces.size() == 5);
  CHECK(geometry::mass_properties(p).volume == test::approx(0.5));
  CHECK(geometry::mass_properties(p).centroid.x() == test::approx(1.0 / 3.0));
}

TEST_CASE("clip: both sides of a cut add up to the whole, and share the cap") {
  const auto box = geometry::make_box(Vec3(-1, 0, 2), Vec3(3, 0.5, 2.25));
  const Vec3 n(0.3, -0.2, 1.0);
  const double offset = n.dot(Vec3(1.2, 0.2, 2.1));
  const auto below = geometry::clip(box, n, offset);
  const auto above = geometry::clip(box, -n, -offset);
  below.validate("below");
  above.validate("above");
  CHECK(geometry::mass_properties(below).volume + geometry::mass_properties(above).volume == test::approx(1.0 * 0.5 * 0.25 * 4));
  CHECK(below.face_area(below.faces.size() - 1) == test::approx(above.face_area(above.faces.size() - 1)));
  // A plane that misses leaves the block as it is, or takes all of it.
  CHECK(geometry::clip(box, Vec3(0, 0, 1), 10.0).vertices.size() == 8);
  CHECK(geometry::clip(box, Vec3(0, 0, 1), 1.0).vertices.empty());
  CHECK(geometry::clip(box, Vec3(0, 0, 1), 2.0).vertices.empty());  // touches the bottom face only
  CHECK_THROWS_AS(geometry::clip(box, Vec3::Zero(), 1.0), InvalidArgument);
}

TEST_CASE("prism: a triangle swept along a vector, either winding, has outward faces and area x height volume") {
  const std::vector<Vec3> ccw{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 1, 0)};
  const std::vector<Vec3> cw{Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(2, 0, 0)};
  for (const auto& base : {ccw, cw}) {
    const auto p = geometry::make_prism(base, Vec3(0.5, 0, 3));  // oblique: volume = base area x height
    p.validate("prism");
    CHECK(geometry::mass_properties(p).volume == test::approx(1.0 * 3));
  }
}

TEST_CASE("distance: zero inside and on the surface, Euclidean outside (face, edge and corner regions)") {
  const auto cube = unit_cube();
  CHECK(geometry::distance(cube, Vec3(0.5, 0.5, 0.5)) == 0.0);
  CHECK(geometry::distance(cube, Vec3(1, 0.5, 0.5)) == 0.0);
  CHECK(geometry::distance(cube, Vec3(1.5, 0.5, 0.5)) == test::approx(0.5));
  CHECK(geometry::distance(cube, Vec3(1.3, 1.4, 0.5)) == test::approx(0.5));                 // edge: hypot(0.3, 0.4)
  CHECK(geometry::distance(cube, Vec3(-0.2, -0.3, 1.6)) == test::approx(std::sqrt(0.49)));  // corner
}

TEST_CASE("separation: face axes for boxes, edge-edge axes for two crossed edges that face normals cannot separate") {
  const auto a = unit_cube();
  CHECK(geometry::separation(a, geometry::make_box(Vec3(1.1, 0, 0), Vec3(2, 1, 1))) == test::approx(0.1));
  CHECK(geometry::separation(a, geometry::make_box(Vec3(0.95, 0.2, 0.2), Vec3(2, 1, 1))) == test::approx(-0.05));
  CHECK(geometry::separation(a, geometry::make_box(Vec3(1, 0, 0), Vec3(2, 1, 1))) == doctest::Approx(0.0).epsilon(1e-15));
  // Cube A turned 45 degrees about y (top edge along y at z = sqrt(2)/2), cube B turned 45 degrees about x and
  // lifted so that its bottom edge, along x, lies a gap g above A's top edge: only the axis x cross y = z separates.
  const double g = 0.01, r = std::sqrt(0.5);
  const auto centred = geometry::make_box(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5));
  const auto turned_a = centred.transformed(Eigen::AngleAxisd(pi / 4, Vec3::UnitY()).toRotationMatrix(), Vec3::Zero());
  const auto turned_b = centred.transformed(Eigen::AngleAxisd(pi / 4, Vec3::UnitX()).toRotationMatrix(), Vec3(0, 0, 2 * r + g));
  CHECK(geometry::separation(turned_a, turned_b) == test::approx(g).epsilon(1e-9));
  const auto touching = centred.transformed(Eigen::AngleAxisd(pi / 4, Vec3::UnitX()).toRotationMatrix(), Vec3(0, 0, 2 * r - g));
  CHECK(geometry::separation(turned_a, touching) == test::approx(-g).epsilon(1e-9));
}

}  // namespace test_clip
