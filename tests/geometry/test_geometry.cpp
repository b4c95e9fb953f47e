// Convex polyhedra: mass properties against closed forms; validation errors name the block; generators.

#include <doctest/doctest.h>

#include <string>

#include "../approx.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/geometry/mass_properties.hpp"
#include "blockdem/model/model.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_geometry {

TEST_CASE("geometry: mass properties of a box and a tetrahedron (closed forms)") {
  const auto box = geometry::make_box(Vec3(1, 2, 3), Vec3(3, 3, 6));  // 2 x 1 x 3
  const auto m = geometry::mass_properties(box);
  CHECK(m.volume == test::approx(6.0));
  CHECK((m.centroid - Vec3(2, 2.5, 4.5)).norm() < 1e-12);
  // I_xx = V (b^2 + c^2) / 12 per unit density
  CHECK(m.inertia(0, 0) == test::approx(6.0 * (1 + 9) / 12.0));
  CHECK(m.inertia(1, 1) == test::approx(6.0 * (4 + 9) / 12.0));
  CHECK(m.inertia(2, 2) == test::approx(6.0 * (4 + 1) / 12.0));
  CHECK(std::abs(m.inertia(0, 1)) < 1e-12);
  geometry::ConvexPolyhedron tet;  // the unit corner tetrahedron: V = 1/6, centroid (1/4, 1/4, 1/4)
  tet.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  tet.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  tet.validate("tetrahedron");
  const auto t = geometry::mass_properties(tet);
  CHECK(t.volume == test::approx(1.0 / 6.0));
  CHECK((t.centroid - Vec3(0.25, 0.25, 0.25)).norm() < 1e-12);
  // About the centroid: I_xx = V (3/80)(b^2 + c^2)... for the corner tetrahedron I_xx = 1/80, I_xy = 1/480 (Tonon 2005)
  CHECK(t.inertia(0, 0) == test::approx(1.0 / 80.0));
  CHECK(t.inertia(0, 1) == test::approx(1.0 / 480.0));
}

TEST_CASE("geometry: invalid polyhedra are rejected with the block's name") {
  auto expect = [](const geometry::ConvexPolyhedron& p, const std::string& what) {
    try {
      p.validate("voussoir 7");
      FAIL("accepted");
    } catch (const InvalidArgument& e) {
      const std::string m = e.what();
      CHECK(m.find("voussoir 7") != std::string::npos);
      CHECK(m.find(what) != std::string::npos);
    }
  };
  auto open = geometry::make_box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  open.faces.pop_back();
  expect(open, "open");
  auto inward = geometry::make_box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  for (auto& f : inward.faces) std::reverse(f.begin(), f.end());
  expect(inward, "convex");
  auto dent = geometry::make_box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  dent.vertices[6] = Vec3(0.5, 0.5, 0.4);  // a top corner pushed below the top: not convex, top not planar
  expect(dent, "block 'voussoir 7'");
  model::Model m;
  CHECK_THROWS_AS(m.add_block(geometry::make_box(Vec3(0, 0, 0), Vec3(1, 1, 1)), 0.0, "brick"), InvalidArgument);
}

TEST_CASE("geometry: the arch and wall generators give valid blocks of the right total volume") {
  const double r = 1.0, t = 0.15, d = 0.5;
  double volume = 0;
  for (const auto& b : geometry::semicircular_arch(40, r, t, d)) {
    b.shape.validate(b.name);
    if (!b.support) volume += geometry::mass_properties(b.shape).volume;
  }
  // A ring of 40 straight-sided voussoirs: (pi/40) * ... the polygonal ring area is 40 (R_e^2 - R_i^2) sin(pi/40)/2
  const double ring = 40 * 0.5 * ((r + t / 2) * (r + t / 2) - (r - t / 2) * (r - t / 2)) * std::sin(3.141592653589793 / 40);
  CHECK(volume == test::approx(ring * d).epsilon(1e-12));
  double wall = 0;
  int units = 0;
  for (const auto& b : geometry::running_bond_wall(6, 5, 0.24, 0.12, 0.055)) {
    b.shape.validate(b.name);
    if (!b.support) {
      wall += geometry::mass_properties(b.shape).volume;
      ++units;
    }
  }
  CHECK(units == 3 * 5 + 3 * 6);  // odd courses: two halves and 4 whole units
  CHECK(wall == test::approx(6 * 5 * 0.24 * 0.12 * 0.055).epsilon(1e-12));
}

}  // namespace test_geometry
