// The masonry typologies of geometry/typologies.hpp: block counts worked out by hand for small walls (with an
// opening, with bonded returns), volumes against the wall less its openings and the barrel vault's ring, no two
// blocks overlapping, every block touching another, the corner bond and the vault's stagger.

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "blockdem/geometry/mass_properties.hpp"
#include "blockdem/geometry/queries.hpp"
#include "blockdem/geometry/typologies.hpp"
#include "../approx.hpp"

using namespace blockdem;

// Named: this file may share a unity translation unit.
namespace test_typologies {

namespace {

struct Box {
  Vec3 lo, hi;
};

Box bounds(const geometry::ConvexPolyhedron& p) {
  Box b{p.vertices.front(), p.vertices.front()};
  for (const auto& v : p.vertices) {
    b.lo = b.lo.cwiseMin(v);
    b.hi = b.hi.cwiseMax(v);
  }
  return b;
}

const geometry::NamedBlock& find(const std::vector<geometry::NamedBlock>& blocks, const std::string& name) {
  for (const auto& b : blocks)
    if (b.name == name) return b;
  FAIL("no block named " << name);
  return blocks.front();
}

int count_group(const std::vector<geometry::NamedBlock>& blocks, const std::string& group) {
  int n = 0;
  for (const auto& b : blocks) n += b.group == group ? 1 : 0;
  return n;
}

/// Volume of the blocks that are not supports, m^3.
double masonry_volume(const std::vector<geometry::NamedBlock>& blocks) {
  double v = 0;
  for (const auto& b : blocks)
    if (!b.support) v += geometry::mass_properties(b.shape).volume;
  return v;
}

/// Every shape valid, every name distinct, no two blocks overlapping (separation >= -1e-12 m), every block touching
/// another (separation <= 1e-9 m with at least one).
void check_assembly(const std::vector<geometry::NamedBlock>& blocks) {
  std::vector<int> touching(blocks.size(), 0);
  double deepest = 0;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    CHECK_NOTHROW(blocks[i].shape.validate(blocks[i].name));
    CHECK_FALSE(blocks[i].group.empty());
    for (std::size_t j = i + 1; j < blocks.size(); ++j) {
      CHECK(blocks[i].name != blocks[j].name);
      const double s = geometry::separation(blocks[i].shape, blocks[j].shape);
      deepest = std::min(deepest, s);
      if (s <= 1e-9) ++touching[i], ++touching[j];
    }
  }
  CHECK(deepest >= -1e-12);
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    INFO(blocks[i].name);
    CHECK(touching[i] > 0);
  }
}

geometry::WallOptions small_wall(double length, int courses) {
  geometry::WallOptions o;
  o.length = length;
  o.courses = courses;
  o.thickness = 0.12;
  o.unit_length = 0.25;
  o.unit_height = 0.075;
  return o;
}

}  // namespace

TEST_CASE("typologies: a plain wall in running bond, 4 units long and 4 courses high") {
  const auto o = small_wall(1.0, 4);
  const auto blocks = geometry::masonry_wall(o);
  // Even courses (0-based) 4 whole units; odd ones a half at each end and 3 whole: 2 * 4 + 2 * 5, and the foundation.
  CHECK(blocks.size() == 19u);
  CHECK(count_group(blocks, "wall") == 18);
  CHECK(count_group(blocks, "foundation") == 1);
  CHECK(blocks.back().name == "foundation");
  CHECK(blocks.back().support);
  CHECK(masonry_volume(blocks) == test::approx(1.0 * 0.3 * 0.12).epsilon(1e-9));
  const auto c2u1 = bounds(find(blocks, "c2 u1").shape), c2u5 = bounds(find(blocks, "c2 u5").shape);
  CHECK(c2u1.hi.x() == test::approx(0.125));
  CHECK(c2u5.lo.x() == test::approx(0.875));
  // The foundation reaches the wall's height plus its thickness past its faces and ends: the toppled wall lands on it.
  const auto f = bounds(blocks.back().shape);
  CHECK(f.lo.y() == test::approx(-0.42));
  CHECK(f.hi.y() == test::approx(0.12 + 0.42));
  CHECK(f.lo.x() == test::approx(-0.42));
  CHECK(f.hi.x() == test::approx(1.42));
  CHECK(f.hi.z() == 0.0);
  CHECK(f.lo.z() == test::approx(-0.24));  // a block: twice the thickness deep
  check_assembly(blocks);
  auto floor = o;
  floor.foundation = geometry::Foundation::floor;
  CHECK(bounds(geometry::masonry_wall(floor).back().shape).lo.z() == test::approx(-0.0375));
}

TEST_CASE("typologies: a wall with a window and its lintel, 6 units long and 6 courses high") {
  auto o = small_wall(1.5, 6);
  o.openings.push_back({0.5, 1.0, 1, 4});  // courses 1-3 cut between x = 0.5 and 1.0 m; the lintel in course 4
  o.lintel_bearing = 0.125;
  const auto blocks = geometry::masonry_wall(o);
  // By course (0-based): 0: 6 whole units; 1 and 3 (joints at 0.125 + k 0.25): a half, a whole and the half split
  // at the jamb on each side, 3 + 3; 2 (joints on the jambs): 2 + 2; 4, the lintel's course (from 0.375 to 1.125 m):
  // a whole and a half on each side, 2 + 2; 5: 7 (two halves and 5 whole). 33 units, the lintel, the foundation.
  CHECK(count_group(blocks, "wall") == 6 + 6 + 4 + 6 + 4 + 7);
  CHECK(count_group(blocks, "lintel") == 1);
  CHECK(blocks.size() == 35u);
  const auto lintel = bounds(find(blocks, "lintel 1").shape);
  CHECK(lintel.lo.x() == test::approx(0.375));
  CHECK(lintel.hi.x() == test::approx(1.125));
  CHECK(lintel.lo.z() == test::approx(4 * 0.075));
  CHECK(lintel.hi.z() == test::approx(5 * 0.075));
  CHECK(lintel.hi.y() == test::approx(0.12));
  // The units split at the jambs: course 2 (1-based), x from 0.375 to 0.5 m and from 1.0 to 1.125 m.
  CHECK(bounds(find(blocks, "c2 u3").shape).hi.x() == test::approx(0.5));
  CHECK(bounds(find(blocks, "c2 u4").shape).lo.x() == test::approx(1.0));
  const double wall = 1.5 * 6 * 0.075 * 0.12, window = 0.5 * 3 * 0.075 * 0.12;
  CHECK(masonry_volume(blocks) == test::approx(wall - window).epsilon(1e-9));
  check_assembly(blocks);
  // A jamb 2.5 cm past a joint leaves no sliver: that piece joins its neighbour (a unit and a tenth).
  auto off = o;
  off.openings[0].x0 = 0.4;
  const auto shifted = geometry::masonry_wall(off);
  double shortest = 1;
  for (const auto& b : shifted)
    if (!b.support) shortest = std::min(shortest, bounds(b.shape).hi.x() - bounds(b.shape).lo.x());
  CHECK(shortest >= 0.25 * 0.25);
  CHECK(masonry_volume(shifted) == test::approx(wall - 0.6 * 3 * 0.075 * 0.12).epsilon(1e-9));
  check_assembly(shifted);
}

TEST_CASE("typologies: return walls bonded at the corners, the wall's end unit through the corner in even courses, the return's in odd") {
  auto o = small_wall(1.5, 2);
  o.return_length = 0.5;
  const auto blocks = geometry::masonry_wall(o);
  // Course 0 (1-based c1): the wall's 6 units run from end to end; each return from y = 0.12 (the wall's inner face)
  // to 0.62 m, its joints at 0.125 + k 0.25: the 5 mm sliver joins its neighbour, 2 units per return.
  // Course 1 (c2): each return from y = 0 through the corner, joints at k 0.25: 3 units; the wall between the returns
  // from 0.12 to 1.38 m, joints at 0.125 + k 0.25, the slivers at both ends joined: 5 units.
  CHECK(count_group(blocks, "wall") == 6 + 5);
  CHECK(count_group(blocks, "return") == 2 * 2 + 2 * 3);
  CHECK(blocks.size() == 22u);
  const auto c1u1 = bounds(find(blocks, "c1 u1").shape);
  CHECK(c1u1.lo.x() == 0.0);
  const auto r1 = bounds(find(blocks, "return left c1 u1").shape);
  CHECK(r1.lo.y() == test::approx(0.12));
  CHECK(r1.hi.y() == test::approx(0.375));
  const auto r2 = bounds(find(blocks, "return left c2 u1").shape);
  CHECK(r2.lo.y() == 0.0);
  CHECK(r2.hi.y() == test::approx(0.25));
  CHECK(r2.hi.x() == test::approx(0.12));
  CHECK(bounds(find(blocks, "c2 u1").shape).lo.x() == test::approx(0.12));
  CHECK(bounds(find(blocks, "return right c2 u3").shape).hi.y() == test::approx(0.62));
  CHECK(bounds(find(blocks, "return right c2 u3").shape).lo.x() == test::approx(1.38));
  CHECK(masonry_volume(blocks) == test::approx((1.5 * 0.12 + 2 * 0.5 * 0.12) * 2 * 0.075).epsilon(1e-9));
  // The foundation past the returns' ends too.
  CHECK(bounds(blocks.back().shape).hi.y() == test::approx(0.62 + 2 * 0.075 + 0.12));
  check_assembly(blocks);
}

TEST_CASE("typologies: a wall with returns and two openings, one of them a door") {
  auto o = small_wall(3.0, 10);
  o.return_length = 0.75;
  o.openings = {{0.5, 1.0, 0, 7}, {1.75, 2.5, 3, 7}};
  const auto blocks = geometry::masonry_wall(o);
  CHECK(count_group(blocks, "lintel") == 2);
  const double wall = 3.0 * 0.12 * 0.75 + 2 * 0.75 * 0.12 * 0.75;
  const double openings = 0.5 * 7 * 0.075 * 0.12 + 0.75 * 4 * 0.075 * 0.12;
  CHECK(masonry_volume(blocks) == test::approx(wall - openings).epsilon(1e-9));
  check_assembly(blocks);
}

TEST_CASE("typologies: bad wall options name the field and its range") {
  auto o = small_wall(1.1, 4);
  CHECK_THROWS_WITH_AS(geometry::masonry_wall(o), doctest::Contains("length must be a multiple of unit_length / 2"), InvalidArgument);
  o = small_wall(1.5, 6);
  o.courses = 0;
  CHECK_THROWS_WITH_AS(geometry::masonry_wall(o), doctest::Contains("courses must be in 1..10000"), InvalidArgument);
  o = small_wall(1.5, 6);
  o.openings.push_back({0.05, 0.5, 1, 3});
  CHECK_THROWS_WITH_AS(geometry::masonry_wall(o), doctest::Contains("openings[0]: needs 0.125 <= x0 < x1"), InvalidArgument);
  o.openings = {{0.5, 1.0, 2, 6}};
  CHECK_THROWS_WITH_AS(geometry::masonry_wall(o), doctest::Contains("head_course <= courses - 1 = 5"), InvalidArgument);
  o.openings = {{0.25, 0.5, 1, 3}, {0.7, 1.0, 2, 4}};
  CHECK_THROWS_WITH_AS(geometry::masonry_wall(o), doctest::Contains("openings[1]: it or its lintel overlaps openings[0]"), InvalidArgument);
  o.openings = {{0.25, 0.5, 1, 3}, {0.76, 1.0, 1, 3}};  // piers of 1 cm between the lintels
  CHECK_THROWS_WITH_AS(geometry::masonry_wall(o), doctest::Contains("narrower than a quarter unit"), InvalidArgument);
  o = small_wall(1.5, 6);
  o.return_length = 0.05;
  CHECK_THROWS_WITH_AS(geometry::masonry_wall(o), doctest::Contains("return_length must be 0 (no returns) or in [unit_length / 2"), InvalidArgument);
}

TEST_CASE("typologies: a semicircular barrel vault, its volume and the stagger of its rings") {
  geometry::BarrelVaultOptions o;
  o.span = 2.0;
  o.thickness = 0.24;
  o.length = 1.0;
  o.rings = 9;
  o.unit_length = 0.25;
  const auto blocks = geometry::barrel_vault(o);
  // Even rings (0-based) 4 whole units along y; odd ones a half at each end and 3 whole: 5 * 4 + 4 * 5; 2 abutments.
  CHECK(count_group(blocks, "vault") == 40);
  CHECK(count_group(blocks, "abutment") == 2);
  CHECK(blocks.size() == 42u);
  const double ri = 1.0, re = 1.24;
  // Plane intrados and extrados: the ring is the polygon of the chords, n/2 sin(pi/n) (Re^2 - Ri^2) per metre; it
  // tends to the half annulus pi/2 (Re^2 - Ri^2) as 1 - pi^2 / (6 n^2).
  const double polygon = 0.5 * o.rings * std::sin(pi / o.rings) * (re * re - ri * ri) * o.length;
  CHECK(masonry_volume(blocks) == test::approx(polygon).epsilon(1e-9));
  o.rings = 200;
  o.length = 0.25;
  const double fine = masonry_volume(geometry::barrel_vault(o)), half_annulus = 0.5 * pi * (re * re - ri * ri) * o.length;
  CHECK(fine == test::approx(half_annulus).epsilon(pi * pi / (6.0 * 200 * 200)));
  CHECK(fine < half_annulus);
  // The stagger: ring 2 (1-based) starts with a half unit, ring 1 with a whole; no joint runs through both.
  const auto r1 = bounds(find(blocks, "ring 1 u1").shape), r2 = bounds(find(blocks, "ring 2 u1").shape);
  CHECK(r1.hi.y() == test::approx(0.25));
  CHECK(r2.hi.y() == test::approx(0.125));
  CHECK(bounds(find(blocks, "ring 2 u5").shape).lo.y() == test::approx(0.875));
  // The springings rest on the abutments; the crown is at the outer radius.
  const auto right = bounds(find(blocks, "abutment right").shape);
  CHECK(right.hi.z() == 0.0);
  CHECK(right.lo.x() == test::approx(1.12 - 0.24));
  CHECK(right.hi.x() == test::approx(1.12 + 0.24));
  check_assembly(blocks);
  o.rings = 4;
  o.running_bond = false;
  o.length = 0.5;
  const auto straight = geometry::barrel_vault(o);
  CHECK(count_group(straight, "vault") == 8);
  CHECK(bounds(find(straight, "ring 2 u1").shape).hi.y() == test::approx(0.25));
  check_assembly(straight);
}

TEST_CASE("typologies: bad barrel vault options name the field and its range") {
  geometry::BarrelVaultOptions o;
  o.rings = 1;
  CHECK_THROWS_WITH_AS(geometry::barrel_vault(o), doctest::Contains("rings must be in 2..2000"), InvalidArgument);
  o = {};
  o.length = 0.3;
  CHECK_THROWS_WITH_AS(geometry::barrel_vault(o), doctest::Contains("length must be a multiple of unit_length / 2"), InvalidArgument);
  o = {};
  o.abutment_width = 2.5;
  CHECK_THROWS_WITH_AS(geometry::barrel_vault(o), doctest::Contains("abutment_width must be 0"), InvalidArgument);
}

}  // namespace test_typologies
