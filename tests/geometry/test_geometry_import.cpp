// Geometry import: OBJ read and written back, each block's checks (every defect named, with its block) and the
// assembly's (overlaps by pair and depth, blocks touching nothing, names given twice).

#include <doctest/doctest.h>

#include <sstream>
#include <string>
#include <vector>

#include "blockdem/analysis/model_file_geometry.hpp"
#include "blockdem/geometry/assembly_check.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/geometry/mass_properties.hpp"
#include "blockdem/geometry/polyhedron_check.hpp"
#include "blockdem/io/obj_geometry.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_geometry_import {

using Severity = geometry::BlockIssue::Severity;

/// The unit cube as a CAD program exports it: each face two triangles with corners of its own (not shared), some
/// the top's two wound inward.
const char* cad_cube = R"(# exported
mtllib cube.mtl
o Cube
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
vn 0 0 -1
usemtl stone
s off
f 1//1 3//1 2//1
f 1//1 4//1 3//1
f 5 7 6
f 5 8 7
f 1 2 6
f 1 6 5
f 2 3 7
f 2 7 6
f 3 4 8
f 3 8 7
f 4 1 5
f 4 5 8
)";

std::vector<geometry::BlockIssue> issues_of(const std::string& obj, std::optional<geometry::ConvexPolyhedron>* shape = nullptr) {
  const auto blocks = io::read_obj(obj, "test.obj");
  REQUIRE(blocks.size() == 1);
  std::vector<geometry::BlockIssue> issues;
  auto s = geometry::check_polyhedron(blocks[0], issues);
  if (shape) *shape = s;
  return issues;
}

bool says(const std::vector<geometry::BlockIssue>& issues, Severity s, const std::string& text) {
  for (const auto& i : issues)
    if (i.severity == s && i.what.find(text) != std::string::npos) return true;
  return false;
}

TEST_CASE("geometry import: a CAD cube (triangles, inward faces) becomes the unit cube with six faces") {
  std::optional<geometry::ConvexPolyhedron> shape;
  const auto issues = issues_of(cad_cube, &shape);
  REQUIRE(shape);
  CHECK(shape->vertices.size() == 8);
  CHECK(shape->faces.size() == 6);
  const auto m = geometry::mass_properties(*shape);
  CHECK(m.volume == doctest::Approx(1.0).epsilon(1e-12));
  CHECK((m.centroid - Vec3(0.5, 0.5, 0.5)).norm() < 1e-12);
  CHECK(says(issues, Severity::warning, "inward normals: 2 of 12 faces pointed inward; turned outward"));
  CHECK(says(issues, Severity::note, "12 faces on 6 planes"));
  for (const auto& i : issues) CHECK(i.block == "Cube");
  CHECK(issues.front().origin == "test.obj:3");
}

TEST_CASE("geometry import: every face inward is turned outward, said so, and the block is usable") {
  std::string inward = "o Box\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nv 0 0 1\nv 2 0 1\nv 2 1 1\nv 0 1 1\n"
                       "f 1 2 3 4\nf 8 7 6 5\nf 5 6 2 1\nf 6 7 3 2\nf 7 8 4 3\nf 8 5 1 4\n";
  std::optional<geometry::ConvexPolyhedron> shape;
  const auto issues = issues_of(inward, &shape);
  REQUIRE(shape);
  CHECK(says(issues, Severity::warning, "every face pointed inward; turned outward"));
  CHECK(geometry::mass_properties(*shape).volume == doctest::Approx(2.0).epsilon(1e-12));
}

TEST_CASE("geometry import: each defect is named, with the block, and makes it unusable") {
  const std::string corners = "o B\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
  std::optional<geometry::ConvexPolyhedron> shape;
  SUBCASE("open: a face missing") {
    const auto issues = issues_of(corners + "f 4 3 2 1\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n", &shape);
    CHECK_FALSE(shape);
    CHECK(says(issues, Severity::error, "not closed: 4 edges belong to one face only"));
  }
  SUBCASE("a face not planar") {
    const std::string bent = "o B\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1.2\nv 0 1 1\n";
    const auto issues = issues_of(bent + "f 4 3 2 1\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n", &shape);
    CHECK_FALSE(shape);
    CHECK(says(issues, Severity::error, "is not planar: a corner lies"));
  }
  SUBCASE("not convex: an L-shaped prism, the worst face named") {
    const std::string l = "o L\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nv 0 0 1\nv 2 0 1\nv 2 1 1\nv 1 1 1\nv 1 2 1\nv 0 2 1\n"
                          "f 6 5 4 3 2 1\nf 7 8 9 10 11 12\nf 1 2 8 7\nf 2 3 9 8\nf 3 4 10 9\nf 4 5 11 10\nf 5 6 12 11\nf 6 1 7 12\n";
    const auto issues = issues_of(l, &shape);
    CHECK_FALSE(shape);
    CHECK(says(issues, Severity::error, "not convex: corner"));
    CHECK(says(issues, Severity::error, "m outside the plane of face"));
    CHECK(issues.back().block == "L");
  }
  SUBCASE("no volume: a flat box") {
    const std::string flat = "o F\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
    const auto issues = issues_of(flat + "f 4 3 2 1\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n", &shape);
    CHECK_FALSE(shape);
    CHECK(!issues.empty());
    CHECK(issues.back().severity == Severity::error);
  }
}

TEST_CASE("geometry import: the arch written to OBJ and read back is the same arch (volumes and centroids to 1e-9)") {
  const auto arch = geometry::semicircular_arch(11, 2.0, 0.3, 0.5);
  std::vector<geometry::ImportedBlock> out;
  for (const auto& b : arch) out.push_back(geometry::imported_block(b.shape, b.name, b.support ? "support" : "arch"));
  std::ostringstream text;
  io::write_obj(text, out, "arch");
  const auto back = io::read_obj(text.str(), "arch.obj");
  REQUIRE(back.size() == arch.size());
  for (std::size_t i = 0; i < arch.size(); ++i) {
    CHECK(back[i].name == arch[i].name);
    CHECK(back[i].group == (arch[i].support ? "support" : "arch"));
    CHECK(back[i].vertices == arch[i].shape.vertices);  // bit for bit: numbers written in their shortest exact form
    std::vector<geometry::BlockIssue> issues;
    const auto shape = geometry::check_polyhedron(back[i], issues);
    REQUIRE(shape);
    CHECK(issues.empty());
    const auto a = geometry::mass_properties(arch[i].shape), b = geometry::mass_properties(*shape);
    CHECK(std::abs(a.volume - b.volume) <= 1e-9 * a.volume);
    CHECK((a.centroid - b.centroid).norm() <= 1e-9);
  }
}

TEST_CASE("geometry import: OBJ objects, groups and connected sets of faces") {
  const std::string two = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 5 0 0\nv 6 0 0\nv 5 1 0\nv 5 0 1\n";
  const std::string tets = "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n";
  SUBCASE("neither objects nor groups: one block per connected set") {
    const auto b = io::read_obj(two + tets, "t.obj");
    REQUIRE(b.size() == 2);
    CHECK(b[0].name == "block 1");
    CHECK(b[1].name == "block 2");
    CHECK(b[1].vertices.front() == Vec3(5, 0, 0));
  }
  SUBCASE("groups without objects: one block per group") {
    const auto b = io::read_obj(two + "g first\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\ng second\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf -3 -2 -1\n", "t.obj");
    REQUIRE(b.size() == 2);
    CHECK(b[0].name == "first");
    CHECK(b[1].name == "second");
    CHECK(b[1].faces.back() == std::vector<int>{1, 2, 3});  // negative indices count back from the last vertex
    CHECK(b[0].group.empty());
  }
  SUBCASE("objects with groups: the group is the block's layer") {
    const auto b = io::read_obj(two + "o tet A\ng layer 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\no tet B\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n", "t.obj");
    REQUIRE(b.size() == 2);
    CHECK(b[0].name == "tet A");
    CHECK(b[0].group == "layer 1");
    CHECK(b[1].group == "layer 1");
    CHECK(b[1].origin == "t.obj:15");
  }
}

TEST_CASE("geometry import: what OBJ text cannot be parsed is refused with its line") {
  CHECK_THROWS_WITH_AS(io::read_obj("v 0 0 0\nv 1 zero 0\n", "bad.obj"), doctest::Contains("bad.obj:2: vertex coordinate 'zero' is not a finite number"), InputError);
  CHECK_THROWS_WITH_AS(io::read_obj("v 0 0 0\nv 1 nan 0\n", "bad.obj"), doctest::Contains("bad.obj:2:"), InputError);
  CHECK_THROWS_WITH_AS(io::read_obj("v 0 0\n", "bad.obj"), doctest::Contains("bad.obj:1: a vertex needs three coordinates"), InputError);
  CHECK_THROWS_WITH_AS(io::read_obj("v 0 0 0\nv 1 0 0\nf 1 2\n", "bad.obj"), doctest::Contains("bad.obj:3: a face needs at least 3 corners"), InputError);
  CHECK_THROWS_WITH_AS(io::read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\n# c\nf 1 2 9\n", "bad.obj"),
                       doctest::Contains("bad.obj:5: face corner 9 refers to no vertex (3 vertices so far"), InputError);
  CHECK_THROWS_WITH_AS(io::read_obj("v 0 0 0\nf 1 0 1\n", "bad.obj"), doctest::Contains("face corner '0' is not a vertex number"), InputError);
  CHECK_THROWS_WITH_AS(io::read_obj("v 0 0 0 \\\n", "bad.obj"), doctest::Contains("bad.obj:1: the file ends in a line continued"), InputError);
}

TEST_CASE("geometry import: the assembly's checks name overlapping pairs with their depth, lone blocks and repeated names") {
  const auto a = geometry::make_box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const auto b = geometry::make_box(Vec3(0.99, 0, 0), Vec3(2, 1, 1));      // into a by 10 mm
  const auto c = geometry::make_box(Vec3(0, 0, 1), Vec3(1, 1, 2));          // on a
  const auto d = geometry::make_box(Vec3(5, 5, 5), Vec3(6, 6, 6));          // alone
  const auto e = geometry::make_box(Vec3(2, 0, 0), Vec3(3, 1, 1.0005));     // beside b, touching
  std::vector<geometry::AssemblyBlock> blocks{{&a, "a", "m.obj:1", true}, {&b, "b", "m.obj:9", true}, {&c, "c", "", true},
                                              {&d, "d", "", true}, {&e, "c", "", false}};
  std::vector<geometry::BlockIssue> issues;
  const auto r = geometry::check_assembly(blocks, 1e-3, issues);
  CHECK(r.deepest_overlap == doctest::Approx(0.01).epsilon(1e-9));
  CHECK(says(issues, Severity::error, "overlaps 'b' (m.obj:9) by 0.01 m, more than the contact tolerance 0.001 m"));
  CHECK(says(issues, Severity::error, "touches no other block (none within the contact tolerance 0.001 m): it would fall"));
  CHECK(says(issues, Severity::warning, "the name is given to 2 blocks"));
  std::size_t errors = 0;
  for (const auto& i : issues) errors += i.severity == Severity::error;
  CHECK(errors == 2);  // a-b and d; nothing else
}

TEST_CASE("geometry import: object patterns") {
  using analysis::detail::name_matches;
  CHECK(name_matches("*", "anything"));
  CHECK(name_matches("voussoir*", "voussoir 12"));
  CHECK_FALSE(name_matches("voussoir*", "support left"));
  CHECK(name_matches("support ?eft", "support left"));
  CHECK(name_matches("*left", "support left"));
  CHECK_FALSE(name_matches("c?", "c12"));
  CHECK(name_matches("", ""));
}

}  // namespace test_geometry_import
