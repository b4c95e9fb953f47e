// The 3DEC deck reader and writer (io/threedec_geometry.hpp) and the COMPAS JSON reader (io/compas_geometry.hpp):
// 3DEC 7 and 3DEC 5 syntax, a written arch read back bit for bit, COMPAS 1.x and 2.x assemblies, and malformed
// input refused with its line (and column and path, for JSON).

#include <doctest/doctest.h>

#include <bit>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/geometry/imported_block.hpp"
#include "blockdem/io/compas_geometry.hpp"
#include "blockdem/io/json.hpp"
#include "blockdem/io/threedec_geometry.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_geometry_files {

namespace {

/// The block as the library's polyhedron, checked: closed, planar, convex and its faces counter-clockwise seen from
/// outside (an inward face fails the convexity test of validate).
void check_outward_polyhedron(const geometry::ImportedBlock& b) {
  geometry::ConvexPolyhedron p{b.vertices, b.faces};
  CHECK_NOTHROW(p.validate(b.name));
}

bool same_bits(const Vec3& a, const Vec3& b) {
  for (int k = 0; k < 3; ++k)
    if (std::bit_cast<std::uint64_t>(a[k]) != std::bit_cast<std::uint64_t>(b[k])) return false;
  return true;
}

/// Each face of `a` and `b` as the same corners, bit for bit, in the same order.
bool same_faces_by_coordinates(const geometry::ImportedBlock& a, const geometry::ImportedBlock& b) {
  if (a.faces.size() != b.faces.size()) return false;
  for (std::size_t f = 0; f < a.faces.size(); ++f) {
    if (a.faces[f].size() != b.faces[f].size()) return false;
    for (std::size_t k = 0; k < a.faces[f].size(); ++k)
      if (!same_bits(a.vertices[static_cast<std::size_t>(a.faces[f][k])], b.vertices[static_cast<std::size_t>(b.faces[f][k])])) return false;
  }
  return true;
}

// The unit cube of the 3DEC manual: each face clockwise seen from outside.
constexpr const char* cube_3dec7 = R"(model new
block create polyhedron &
  face (0,0,0) (1,0,0) (1,1,0) (0,1,0) &
  face (0,0,0) (0,0,1) (1,0,1) (1,0,0) &
  face (0,0,0) (0,1,0) (0,1,1) (0,0,1) &
  face (1,0,0) (1,0,1) (1,1,1) (1,1,0) &
  face (0,1,0) (1,1,0) (1,1,1) (0,1,1) &
  face (0,0,1) (0,1,1) (1,1,1) (1,0,1)
)";

constexpr const char* cube_3dec5 = R"(new
poly face 0,0,0 1,0,0 1,1,0 0,1,0 &
 face 0,0,0 0,0,1 1,0,1 1,0,0 &
 face 0,0,0 0,1,0 0,1,1 0,0,1 &
 face 1,0,0 1,0,1 1,1,1 1,1,0 &
 face 0,1,0 1,1,0 1,1,1 0,1,1 &
 face 0,0,1 0,1,1 1,1,1 1,0,1
)";

/// A COMPAS mesh's data for the box lo..hi (faces counter-clockwise seen from outside), vertex keys k0, k0 + step, ...
std::string compas_box(const Vec3& lo, const Vec3& hi, const std::string& extra = "", int k0 = 0, int step = 1) {
  const auto box = geometry::make_box(lo, hi);
  std::string s = "{" + extra + "\"vertex\": {";
  for (std::size_t i = 0; i < box.vertices.size(); ++i) {
    const auto& x = box.vertices[i];
    s += (i ? ", \"" : "\"") + std::to_string(k0 + step * static_cast<int>(i)) + "\": {\"x\": " + io::JsonObject::number(x.x()) +
         ", \"y\": " + io::JsonObject::number(x.y()) + ", \"z\": " + io::JsonObject::number(x.z()) + "}";
  }
  s += "}, \"face\": {";
  for (std::size_t f = 0; f < box.faces.size(); ++f) {
    s += (f ? ", \"" : "\"") + std::to_string(f) + "\": [";
    for (std::size_t k = 0; k < box.faces[f].size(); ++k) s += (k ? ", " : "") + std::to_string(k0 + step * box.faces[f][k]);
    s += "]";
  }
  return s + "}, \"facedata\": {}, \"edgedata\": {}, \"max_vertex\": 7, \"max_face\": 5}";
}

}  // namespace

TEST_CASE("3dec deck: a unit cube in 3DEC 7 and in 3DEC 5 syntax reads to 8 vertices and 6 outward faces") {
  for (const char* text : {cube_3dec7, cube_3dec5}) {
    const auto deck = io::read_threedec_deck(text, "cube.3ddat");
    REQUIRE(deck.blocks.size() == 1);
    const auto& b = deck.blocks[0];
    CHECK(b.name == "block 1");
    CHECK(b.group.empty());
    CHECK(b.origin == "cube.3ddat:2");
    CHECK(b.vertices.size() == 8);
    REQUIRE(b.faces.size() == 6);
    for (const auto& f : b.faces) CHECK(f.size() == 4);
    check_outward_polyhedron(b);  // 3DEC's clockwise corners turned counter-clockwise
    CHECK(deck.skipped_commands == 1);  // model new / new
    CHECK(deck.not_followed.empty());
  }
}

TEST_CASE("3dec deck: comments, continuation lines, groups, abbreviations and corner forms") {
  const std::string text =
      "; a deck with two blocks\n"
      "model new            ; start\n"
      "BLOCK CRE POLYH face (0 0 0) (1 0 0) (1 1 0) (0 1 0) ...\n"
      "  face (0,0,0) (0,0,1) (1,0,1) (1,0,0) &   ; the front\n"
      "\n"
      "  ; a comment line inside the command\n"
      "  face 0,0,0 0,1,0 0,1,1 0,0,1 face 1,0,0 1,0,1 1,1,1 1,1,0&\n"
      "  face ( 0 , 1 , 0 ) (1,1,0) (1,1,1) (0,1,1) face (0,0,1) (0,1,1) (1,1,1) (1,0,1) group 'left wall' slot 'masonry'\n"
      "block contact jmodel assign 7\n"
      "blo cr poly face (0,0,1) (1,0,1) (1,1,1) (0,1,1) face (0,0,1) (0,0,2) (1,0,2) (1,0,1) &\n"
      "  face (0,0,1) (0,1,1) (0,1,2) (0,0,2) face (1,0,1) (1,0,2) (1,1,2) (1,1,1) &\n"
      "  face (0,1,1) (1,1,1) (1,1,2) (0,1,2) face (0,0,2) (0,1,2) (1,1,2) (1,0,2) gr \"top; course\"\n"
      "polyhedron face +0,0,2 1,0,2 1,1,2 0,1,2 face 0,0,2 0,0,3 1,0,3 1,0,2 face 0,0,2 0,1,2 0,1,3 0,0,3 &\n"
      "  face 1,0,2 1,0,3 1,1,3 1,1,2 face 0,1,2 1,1,2 1,1,3 0,1,3 face 0,0,3 0,1,3 1,1,3 1,0,3 group cap\n"
      "fish define load\n"
      "  block create polyhedron face [x] ; FISH, not a command\n"
      "end\n"
      "block cut joint-set dip 30\n"
      "program call 'more.3ddat'\n";
  const auto deck = io::read_threedec_deck(text, "wall.3ddat");
  REQUIRE(deck.blocks.size() == 3);
  CHECK(deck.blocks[0].name == "block 1");
  CHECK(deck.blocks[0].group == "left wall");
  CHECK(deck.blocks[0].origin == "wall.3ddat:3");
  CHECK(deck.blocks[1].name == "block 2");
  CHECK(deck.blocks[1].group == "top; course");  // ';' inside quotes is not a comment
  CHECK(deck.blocks[1].origin == "wall.3ddat:10");
  CHECK(deck.blocks[2].group == "cap");
  CHECK(deck.blocks[2].origin == "wall.3ddat:13");
  for (const auto& b : deck.blocks) {
    CHECK(b.vertices.size() == 8);
    CHECK(b.faces.size() == 6);
    check_outward_polyhedron(b);
  }
  CHECK(deck.blocks[2].vertices[3] == Vec3(0, 0, 2));  // "+0,0,2": the first face's corners come turned around
  CHECK(deck.skipped_commands == 5);  // model new, block contact, the FISH function, block cut, program call
  REQUIRE(deck.not_followed.size() == 2);
  CHECK(deck.not_followed[0] == "wall.3ddat:18: block cut joint-set dip 30");
  CHECK(deck.not_followed[1] == "wall.3ddat:19: program call 'more.3ddat'");
}

TEST_CASE("3dec deck: a written arch reads back to the same vertices, bit for bit, and the same faces") {
  std::vector<geometry::ImportedBlock> blocks;
  for (const auto& b : geometry::semicircular_arch(9, 2.3, 0.37, 0.61))
    blocks.push_back(geometry::imported_block(b.shape, b.name, b.support ? "supports" : "voussoirs"));
  std::ostringstream out;
  io::write_threedec_deck(out, blocks, "arch of 9 voussoirs\nsecond title line");
  const std::string deck_text = out.str();
  CHECK(deck_text.starts_with("; arch of 9 voussoirs\n; second title line\n"));
  CHECK(deck_text.find("program call 'file.3ddat'") != std::string::npos);
  CHECK(deck_text.find("; voussoir 1\nblock create polyhedron &\n  face (") != std::string::npos);
  CHECK(deck_text.find("group 'supports'") != std::string::npos);

  const auto deck = io::read_threedec_deck(deck_text, "arch.3ddat");
  CHECK(deck.skipped_commands == 0);
  REQUIRE(deck.blocks.size() == blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const auto& a = blocks[i];
    const auto& b = deck.blocks[i];
    CAPTURE(i);
    CHECK(b.name == "block " + std::to_string(i + 1));
    CHECK(b.group == a.group);
    CHECK(b.vertices.size() == a.vertices.size());
    for (const auto& x : b.vertices) {  // every vertex read is one written, bit for bit
      bool found = false;
      for (const auto& y : a.vertices) found = found || same_bits(x, y);
      CHECK(found);
    }
    CHECK(same_faces_by_coordinates(a, b));
    check_outward_polyhedron(b);
  }
  // Read blocks list their vertices in the order their faces first use them: written and read again, they come back
  // exactly (vertices bit for bit, the same face indices).
  std::ostringstream again;
  io::write_threedec_deck(again, deck.blocks, "again");
  const auto second = io::read_threedec_deck(again.str(), "again.3ddat");
  REQUIRE(second.blocks.size() == deck.blocks.size());
  for (std::size_t i = 0; i < deck.blocks.size(); ++i) {
    REQUIRE(second.blocks[i].vertices.size() == deck.blocks[i].vertices.size());
    for (std::size_t v = 0; v < deck.blocks[i].vertices.size(); ++v) CHECK(same_bits(second.blocks[i].vertices[v], deck.blocks[i].vertices[v]));
    CHECK(second.blocks[i].faces == deck.blocks[i].faces);
  }
}

TEST_CASE("3dec deck: the writer refuses what a deck cannot hold") {
  const auto box = geometry::make_box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  std::ostringstream out;
  CHECK_THROWS_WITH_AS(io::write_threedec_deck(out, {geometry::imported_block(box, "b", "it's")}, "t"), doctest::Contains("quote"), InvalidArgument);
  auto open = geometry::imported_block(box, "open");
  open.faces.resize(3);
  CHECK_THROWS_WITH_AS(io::write_threedec_deck(out, {open}, "t"), doctest::Contains("3 faces (a block needs at least 4)"), InvalidArgument);
  auto far = geometry::imported_block(box, "far");
  far.vertices[2].x() = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH_AS(io::write_threedec_deck(out, {far}, "t"), doctest::Contains("not a finite point"), InvalidArgument);
  CHECK(out.str().empty());  // nothing written before the refusal
}

TEST_CASE("3dec deck: malformed input is refused with its line") {
  const std::string head = "model new\n; the cube\nblock create polyhedron &\n";  // the command starts on line 3
  const std::string faces = "face (0,0,0) (0,0,1) (1,0,1) (1,0,0) &\n face (0,0,0) (0,1,0) (0,1,1) (0,0,1) &\n"
                            " face (1,0,0) (1,0,1) (1,1,1) (1,1,0)";
  const auto read = [](const std::string& text) { return io::read_threedec_deck(text, "bad.3ddat"); };
  const std::pair<std::string, std::string> cases[] = {
      {head + " face (0,0,0) (1,0,0) &\n" + faces, "bad.3ddat:4: a face with 2 corners"},
      {head + " face (0,0,0) (1,0,0) (1,1.2.3,0) &\n" + faces, "bad.3ddat:4: '1.2.3' is not a number"},
      {head + " face (0,0,0) (1,0,0) (1,1e999,0) &\n" + faces, "bad.3ddat:4: '1e999' is not a number"},
      {head + " face (0,0,0) (1,0,0) (1,-inf,0) &\n" + faces, "bad.3ddat:4: '-inf' is not a number"},
      {head + " face (0,0,0) (1,0,0) (1,1,0 &\n", "bad.3ddat:4: a '(' with no ')'"},
      {head + " face (0,0,0) (1,0,0) (1,1) &\n" + faces, "bad.3ddat:4: a corner with 2 coordinates"},
      {head + " face 0,0,0 1,0,0 1,1 0,1,0 &\n" + faces, "bad.3ddat:4: a corner with 2 coordinates"},
      {head + " face &\n" + faces, "bad.3ddat:4: 'face' with no corners after it"},
      {head + faces + " face\n", "bad.3ddat:6: 'face' with no corners after it"},
      {head + faces + "\n", "bad.3ddat:3: a polyhedron with 3 faces (a block needs at least 4"},
      {head + " face (0,0,0) (1,0,0) (1,1,0) &\n" + faces + " group 'wall\n", "bad.3ddat:7: a quote with no closing quote"},
      {head + " face (0,0,0) (1,0,0) (1,1,0) &\n" + faces + " group\n", "bad.3ddat:7: 'group' with no name after it"},
      {head + " face (0,0,0) (1,0,0) (1,1,0) dip 30 &\n" + faces, "bad.3ddat:4: unexpected 'dip' in a polyhedron"},
      {"model new\nfish define f\n  x = 1\n", "bad.3ddat:2: a FISH function with no 'end'"},
  };
  for (const auto& c : cases) {  // not a structured binding: Clang 14 cannot capture one in the macros' lambdas
    CAPTURE(c.first);
    CHECK_THROWS_WITH_AS(read(c.first), doctest::Contains(c.second.c_str()), InputError);
  }
  CHECK_NOTHROW(read(head + " face (0,0,0) (1,0,0) (1,1,0) &\n" + faces));  // the cases' base is a valid deck
}

TEST_CASE("compas json: a COMPAS 1.x assembly of two boxes") {
  const std::string text = R"({"dtype": "compas_assembly.datastructures/Assembly", "value": {"attributes": {"name": "Assembly"},
  "data": {"node": {"0": {"block": )" + compas_box(Vec3(0, 0, 0), Vec3(1, 0.5, 0.25), R"("attributes": {"name": "Block"}, )") +
                           R"(, "is_support": true}, "1": {"block": )" + compas_box(Vec3(0, 0, 0.25), Vec3(1, 0.5, 0.5)) + R"(}}, "edge": {}}}})";
  const auto blocks = io::read_compas_json(text, "assembly.json");
  REQUIRE(blocks.size() == 2);
  CHECK(blocks[0].name == "node 0");  // COMPAS's default name "Block" says nothing
  CHECK(blocks[1].name == "node 1");
  CHECK(blocks[0].origin == "assembly.json:2");
  for (const auto& b : blocks) {
    CHECK(b.vertices.size() == 8);
    CHECK(b.faces.size() == 6);
    check_outward_polyhedron(b);
  }
  CHECK(blocks[1].vertices[6] == Vec3(1, 0.5, 0.5));
}

TEST_CASE("compas json: a COMPAS 2.x assembly with dtype and data, named blocks and keys that are not 0..n-1") {
  const std::string text = R"({"dtype": "compas_assembly.datastructures/Assembly", "data": {"attributes": {},
  "graph": {"dtype": "compas.datastructures/Graph", "data": {"attributes": {}, "node": {
    "0": {"block": {"dtype": "compas_assembly.datastructures/Block", "data": )" +
                           compas_box(Vec3(0, 0, 0), Vec3(2, 1, 1), "", 10, 20) + R"(, "name": "pier", "guid": "x"}},
    "1": {"block": {"dtype": "compas_assembly.datastructures/Block", "data": )" +
                           compas_box(Vec3(0, 0, 1), Vec3(2, 1, 2), R"("attributes": {"name": "lintel"}, )") + R"(}}},
    "edge": {"0": {"1": {}}}}}}})";
  const auto blocks = io::read_compas_json(text, "a2.json");
  REQUIRE(blocks.size() == 2);
  CHECK(blocks[0].name == "pier");
  CHECK(blocks[1].name == "lintel");
  const auto box = geometry::make_box(Vec3(0, 0, 0), Vec3(2, 1, 1));
  CHECK(blocks[0].vertices == box.vertices);
  CHECK(blocks[0].faces == box.faces);  // keys 10, 30, 50 ... mapped to 0, 1, 2 ...
}

TEST_CASE("compas json: a bare mesh, a wrapped mesh and an array of meshes") {
  const auto bare = io::read_compas_json(compas_box(Vec3(0, 0, 0), Vec3(1, 1, 1)), "mesh.json");
  REQUIRE(bare.size() == 1);
  CHECK(bare[0].name == "block 1");
  CHECK(bare[0].origin == "mesh.json:1");
  check_outward_polyhedron(bare[0]);
  const auto wrapped = io::read_compas_json(R"({"dtype": "compas.datastructures/Mesh", "value": )" +
                                                compas_box(Vec3(0, 0, 0), Vec3(1, 1, 1), R"("attributes": {"name": "Mesh"}, "dva": {"x": 0, "y": 0, "z": 0}, )") + "}",
                                            "m.json");
  REQUIRE(wrapped.size() == 1);
  CHECK(wrapped[0].name == "block 1");
  const auto list = io::read_compas_json("[" + compas_box(Vec3(0, 0, 0), Vec3(1, 1, 1)) + ",\n" + compas_box(Vec3(0, 0, 1), Vec3(1, 1, 2)) + "]", "l.json");
  REQUIRE(list.size() == 2);
  CHECK(list[1].name == "block 2");
  CHECK(list[1].origin == "l.json:2");
  // A coordinate a vertex leaves out is the mesh's default.
  const auto defaults = io::read_compas_json(R"({"default_vertex_attributes": {"x": 0, "y": 0, "z": 5}, "vertex": {"0": {"x": 1, "y": 2}},
    "face": {}})", "d.json");
  REQUIRE(defaults.size() == 1);
  CHECK(defaults[0].vertices[0] == Vec3(1, 2, 5));
}

TEST_CASE("compas json: errors name the line, column and path") {
  const std::string two_blocks = R"({"dtype": "compas_assembly.datastructures/Assembly", "data": {"graph": {"node": {
  "0": {"block": )" + compas_box(Vec3(0, 0, 0), Vec3(1, 1, 1)) + R"(},
  "3": {"block": {"vertex": {"0": {"x": 0, "y": 0, "z": 0}, "1": {"x": 1, "y": 0, "z": 0}, "2": {"x": 0, "y": 1, "z": 0}},
                  "face": {"7": [0, 1, 12]}}}}}}})";
  CHECK_THROWS_WITH_AS(io::read_compas_json(two_blocks, "a.json"),
                       doctest::Contains("a.json:4:40: data.graph.node.3.block.face.7[2]: no vertex \"12\" in this mesh"), InvalidArgument);
  const std::string text_coordinate = R"({"vertex": {"0": {"x": 0, "y": "1", "z": 0}}, "face": {}})";
  CHECK_THROWS_WITH_AS(io::read_compas_json(text_coordinate, "c.json"), doctest::Contains("c.json:1:32: vertex.0.y: expected a number, got a string"),
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(io::read_compas_json(R"([{"vertex": {"0": {"x": 0, "y": 1}}, "face": {}}])", "z.json"),
                       doctest::Contains("z.json:1:19: [0].vertex.0: no \"z\" coordinate"), InvalidArgument);
  CHECK_THROWS_WITH_AS(io::read_compas_json(R"({"vertex": {"0": {"x": 0, "y": 1, "z": 0}}, "face": {"0": [0, 0.5, 0]}})", "k.json"),
                       doctest::Contains("face.0[1]: expected a vertex key (an integer or a string), got the number 0.5"), InvalidArgument);
  CHECK_THROWS_WITH_AS(io::read_compas_json(R"({"vertex": {}, "face": {"0": [0, 1]}})", "f.json"),
                       doctest::Contains("f.json:1:30: face.0: a face with 2 vertices"), InvalidArgument);
  CHECK_THROWS_WITH_AS(io::read_compas_json(R"({"vertex": [], "face": {}})", "v.json"), doctest::Contains("v.json:1:12: vertex: expected an object"),
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(io::read_compas_json(R"({"dtype": "compas.geometry/Point", "data": {"x": 1}})", "p.json"),
                       doctest::Contains("p.json:1:1: no COMPAS mesh in the file (expected an object with \"vertex\" and \"face\""), InvalidArgument);
  CHECK_THROWS_WITH_AS(io::read_compas_json("{\"vertex\": {}, }", "j.json"), doctest::Contains("j.json:1:16"), InvalidArgument);
}

}  // namespace test_geometry_files
