// Contact detection: face-to-face contacts, tributary areas, subdivision, gaps, separation and interpenetration.

#include <doctest/doctest.h>

#include "../approx.hpp"
#include "blockdem/contact/elastic.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "blockdem/model/contact_detection.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_contact_detection {

namespace {
model::Model two_boxes(double lift, double shift = 0) {
  model::Model m;
  m.add_block(geometry::make_box(Vec3(-1, -1, -0.5), Vec3(1, 1, 0)), 2000, "base", 0, model::Motion::fixed);
  m.add_block(geometry::make_box(Vec3(-0.5 + shift, -0.5, lift), Vec3(0.5 + shift, 0.5, 1 + lift)), 2000, "top");
  return m;
}
}  // namespace

TEST_CASE("detection: a box on a box gets CPs at the corners of the overlap, a quarter of the area each") {
  const auto m = two_boxes(0.0004);
  const auto c = model::detect_contacts(m.bodies, model::ContactSettings{});
  REQUIRE(c.size() == 4);
  for (const auto& k : c) {
    CHECK(k.area == test::approx(0.25));
    CHECK(k.gap == test::approx(0.0004));
    CHECK((k.normal - Vec3(0, 0, 1)).norm() < 1e-12);
    CHECK(std::abs(std::abs(k.position.x()) - 0.5) < 1e-12);
  }
  // Half the top box hangs over the edge at x = 1: the overlap is 0.5 x 1.
  const auto half = model::detect_contacts(two_boxes(0, 1.0).bodies, model::ContactSettings{});
  double area = 0;
  for (const auto& k : half) area += k.area;
  CHECK(area == test::approx(0.5));
}

TEST_CASE("detection: subdivision bounds the area of every CP and keeps the total") {
  model::ContactSettings s;
  s.max_contact_point_area = 0.01;
  const auto c = model::detect_contacts(two_boxes(0).bodies, s);
  double total = 0, largest = 0;
  for (const auto& k : c) {
    total += k.area;
    largest = std::max(largest, k.area);
  }
  CHECK(total == test::approx(1.0));
  CHECK(largest <= 0.01 * (1 + 1e-9));
  CHECK(c.size() == 121);  // a 10 x 10 grid of cells has 11 x 11 vertices
}

TEST_CASE("detection: blocks apart beyond the tolerance have no contact, interpenetration at the start is an error") {
  CHECK(model::detect_contacts(two_boxes(0.002).bodies, model::ContactSettings{}).empty());
  auto m = two_boxes(-0.01);
  try {
    Simulation<damping::None, contact::Elastic> sim(m, damping::None{}, [](int, int) { return contact::Elastic::Parameters(1e9, 1e9); });
    FAIL("accepted");
  } catch (const InvalidArgument& e) {
    const std::string what = e.what();
    CHECK(what.find("'base' and 'top' interpenetrate") != std::string::npos);
  }
}

TEST_CASE("detection: every joint of an arch is found, with zero gaps") {
  model::Model m;
  for (const auto& b : geometry::semicircular_arch(20, 1.0, 0.15, 0.5))
    m.add_block(b.shape, 2000, b.name, 0, b.support ? model::Motion::fixed : model::Motion::free);
  const auto c = model::detect_contacts(m.bodies, model::ContactSettings{});
  CHECK(c.size() == 21 * 4);  // 19 joints between voussoirs and 2 springings, 4 corners each
  for (const auto& k : c) CHECK(std::abs(k.gap) < 1e-12);
}

TEST_CASE("contact detection: a block's redetection distance is half its clearance, half the tolerance in contact") {
  // Reference: the gap between axis-aligned boxes. A block on the base touches it (r = tolerance / 2); a block 0.3 m
  // above the first may move 0.15 m, as may the first toward it only r: together less than the gap.
  model::Model m;
  m.add_block(geometry::make_box(Vec3(-1, -1, -0.5), Vec3(1, 1, 0)), 2000, "base", 0, model::Motion::fixed);
  m.add_block(geometry::make_box(Vec3(0, 0, 0), Vec3(0.2, 0.2, 0.2)), 2000, "on base");
  m.add_block(geometry::make_box(Vec3(0, 0, 0.5), Vec3(0.2, 0.2, 0.7)), 2000, "above");
  m.add_block(geometry::make_box(Vec3(3, 0, 0), Vec3(3.2, 0.2, 0.2)), 2000, "aside");  // 2 m from the base's box
  model::ContactSettings settings;
  const auto& b = m.bodies;
  const auto d = model::redetection_distances(b, b.position, b.orientation, settings, [](std::size_t) { return false; });
  CHECK(d[0] == settings.redetection());
  CHECK(d[1] == settings.redetection());
  CHECK(d[2] == doctest::Approx(0.15).epsilon(1e-12));
  CHECK(d[3] == doctest::Approx(1.0).epsilon(1e-12));
  // Widened by the tolerance (a deformable block's box): 1 mm less clearance.
  const auto w = model::redetection_distances(b, b.position, b.orientation, settings, [](std::size_t i) { return i == 2; });
  CHECK(w[2] == doctest::Approx(0.5 * (0.3 - settings.tolerance)).epsilon(1e-12));
}

TEST_CASE("detection: a block on another of its own size, turned and shifted by less than the tolerance, has CPs at "
          "the four corners only") {
  // Two equal 0.3 m faces 0.1 mm apart, the upper turned 0.2 mrad and shifted 0.014 mm: their overlap also has a
  // vertex where each pair of nearly parallel edges crosses, offset / angle along them (here some 5 cm), a place
  // that jumps between detections. Below a quarter of the tolerance the overlap keeps its corners, each with a
  // quarter of the area.
  model::Model m;
  m.add_block(geometry::make_box(Vec3(-0.15, -0.15, -1), Vec3(0.15, 0.15, 0)), 5570, "pier", 0, model::Motion::fixed);
  const auto top = m.add_block(geometry::make_box(Vec3(-0.15, -0.15, 1e-4), Vec3(0.15, 0.15, 0.2001)), 2000, "anchor", 1);
  auto& b = m.bodies;
  b.orientation[top] = Quaternion(Eigen::AngleAxisd(2e-4, Vec3::UnitZ()));
  b.rotation[top] = b.orientation[top].toRotationMatrix();
  b.position[top] += Vec3(1e-5, -1e-5, 0);
  const auto c = model::detect_contacts(b, model::ContactSettings{});
  REQUIRE(c.size() == 4);
  double area = 0;
  for (const auto& k : c) {
    area += k.area;
    CHECK(k.area == test::approx(0.0225).epsilon(1e-3));
    CHECK(std::abs(std::abs(k.position.x()) - 0.15) < 1e-4);
    CHECK(std::abs(std::abs(k.position.y()) - 0.15) < 1e-4);
  }
  // The exact overlap of the two squares (clipped by hand: 0.0899900 m^2); the four corners leave out the slivers at
  // the crossings (9e-5 of it).
  CHECK(area == test::approx(0.0899900).epsilon(1.5e-4));
}

TEST_CASE("polygons: a vertex where the boundary hardly turns is dropped within the distance, a sliver's corners are kept") {
  using geometry::Polygon2;
  // A square with a vertex 1e-5 off the middle of its bottom edge: dropped at 1e-4, kept at 1e-6.
  const Polygon2 square{{0, 0}, {0.15, -1e-5}, {0.3, 0}, {0.3, 0.3}, {0, 0.3}};
  CHECK(geometry::drop_shallow_vertices(square, 1e-4, 0.35).size() == 4);
  CHECK(geometry::drop_shallow_vertices(square, 1e-6, 0.35).size() == 5);
  // A sliver 1e-5 wide: its corners turn by 90 degrees and stay, whatever the distance.
  const Polygon2 sliver{{0, 0}, {0.3, 0}, {0.3, 1e-5}, {0, 1e-5}};
  CHECK(geometry::drop_shallow_vertices(sliver, 1e-3, 0.35).size() == 4);
}

}  // namespace test_contact_detection
