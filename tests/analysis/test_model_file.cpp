// The model file (analysis/model_file.hpp): a small structure read back field by field against the numbers written
// in it and the laws of the paper (eq. 4-7, Table 1), and the table of bad files, each refused with the file, line,
// column, field and what is allowed.

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <variant>

#include "blockdem/analysis/model_file.hpp"
#include "../approx.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_model_file {

namespace {

/// Two bricks on a table: brick A on the table, brick B on A, a steel tie from A to the table.
const std::string two_bricks = R"({
  "blockdem_model": 1,
  "name": "two bricks",
  "units": "SI",
  "gravity": [0, 0, -9.81],
  "materials": {"brick": {"density": 1800, "youngs_modulus": 5e9, "poisson_ratio": 0.2}, "steel": {"density": 7800}},
  "groups": ["wall", "table"],
  "joints": [
    {"between": ["wall", "wall"], "law": "softening", "preset": "paper_table1", "contact_point_spacing": 0.03},
    {"between": ["*", "table"], "law": "mohr_coulomb", "normal_stiffness": 1e10, "shear_stiffness": 5e9, "friction_angle_deg": 30}
  ],
  "blocks": [
    {"name": "A", "group": "wall", "material": "brick", "box": [[0, 0, 0], [0.25, 0.12, 0.075]]},
    {"name": "B", "group": "wall", "material": "brick",
     "vertices": [[0, 0, 0.075], [0.25, 0, 0.075], [0.25, 0.12, 0.075], [0, 0.12, 0.075],
                  [0, 0, 0.15], [0.25, 0, 0.15], [0.25, 0.12, 0.15], [0, 0.12, 0.15]],
     "faces": [[0, 1, 2, 3], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]},
    {"name": "table", "group": "table", "material": "steel", "motion": "base", "box": [[-0.5, -0.5, -0.2], [0.75, 0.62, 0]]}
  ],
  "ties": [{"name": "tie", "ends": [{"block": "A", "point": [0.1, 0.06, 0.05]}, {"block": 2, "point": [0.1, 0.06, -0.1]}],
            "area": 1e-4, "youngs_modulus": 2e11, "density": 7800}],
  "monitors": [{"name": "top", "block": "B", "point": [0.125, 0.06, 0.15]}, {"name": "A", "block": "A"},
               {"name": "near", "point": [0.2, 0.1, 0.14]}],
  "excitation": {"record": "", "axis": "y", "pga_g": 0.3, "window_s": [0, 5]},
  "study": {"levels_percent": [50, 100], "rest_s": 0.5, "damping": {"scheme": "mass", "zeta": 0.04, "frequency_hz": 5}}
})";

/// The message of the InvalidArgument that reading `text` throws ("" if none).
std::string refusal(const std::string& text) {
  try {
    (void)analysis::parse_model_file(text, "bad.json");
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "";
}

/// `two_bricks` with its first `from` replaced by `to`.
std::string changed(const std::string& from, const std::string& to) {
  std::string text = two_bricks;
  const auto at = text.find(from);
  REQUIRE_MESSAGE(at != std::string::npos, from);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("model file: two bricks on a table read back as written (blocks, masses, groups, laws of eq. 4-7, ties, monitors, study)") {
  const auto file = analysis::parse_model_file(two_bricks, "two_bricks.json");
  const auto& s = file.structure;
  const auto& b = s.model.bodies;
  REQUIRE(b.size() == 3);
  CHECK(s.name == "two bricks");
  CHECK(s.groups() == std::vector<std::string>{"wall", "table"});
  // A brick 0.25 x 0.12 x 0.075 m of 1800 kg/m^3, and a tie of 1e-4 m^2 x 0.15 m of steel, half of it lumped on A.
  const double brick = 1800 * 0.25 * 0.12 * 0.075;
  CHECK(b.mass[0] == test::approx(brick + 0.5 * 7800 * 1e-4 * 0.15).epsilon(1e-12));
  CHECK(b.mass[1] == test::approx(brick).epsilon(1e-12));
  CHECK(b.position[1].z() == test::approx(0.1125).epsilon(1e-12));  // B's faces were given in any orientation
  CHECK(b.motion[2] == model::Motion::base);
  CHECK(b.joint_tag[0] == 0);
  CHECK(b.joint_tag[2] == 1);
  CHECK(s.model.deformable.trusses.size() == 1);
  CHECK(s.model.deformable.trusses[0].length0 == test::approx(0.15).epsilon(1e-12));
  // Mortar joints of Table 1 with eq. 7's stiffness and eq. 4-6's fracture energies; the wildcard pair for the table.
  const auto& mortar = std::get<contact::ElastoSoftening::Parameters>(s.laws.law(0, 0));
  const auto k = contact::joint_stiffness_from_eq7(6200e6, 370.05e6, 0.010, 0.25);
  CHECK(mortar.normal_stiffness == test::approx(k.normal).epsilon(1e-14));
  CHECK(mortar.tensile_strength == test::approx(0.3e6).epsilon(1e-14));
  CHECK(mortar.tension_fracture_energy == test::approx(contact::fracture_energy_tension_eq4(0.3e6)).epsilon(1e-14));
  CHECK(mortar.compression_fracture_energy == test::approx(contact::fracture_energy_compression_eq6(9.1e6)).epsilon(1e-14));
  CHECK(s.laws.contact_point_area(0, 0) == test::approx(0.03 * 0.03).epsilon(1e-14));
  const auto& friction = std::get<contact::MohrCoulomb::Parameters>(s.laws.law(0, 1));
  CHECK(friction.friction_angle == test::approx(30 * pi / 180).epsilon(1e-14));
  CHECK(s.laws.has(1, 1));  // "*" covers the table with itself too
  // Monitor points: a point on B, A's centroid, and the block nearest to a point (B).
  REQUIRE(s.monitors.size() == 3);
  CHECK(s.monitors[0].block == 1);
  CHECK(s.monitors[1].position.x() == test::approx(0.125).epsilon(1e-12));
  CHECK(s.monitors[2].block == 1);
  CHECK(s.table == std::optional<std::size_t>(2));
  // The study.
  const auto& o = file.study;
  CHECK(o.axis == 'y');
  CHECK(o.levels == std::vector<double>{50, 100});
  CHECK(o.rest == 0.5);
  CHECK(o.damping == analysis::DampingScheme::mass);
  CHECK(o.frequency_hz == 5);
  CHECK(o.settling == analysis::Settling::automatic);
  CHECK_FALSE(o.window_default);
  CHECK(o.window_end == 5);
  CHECK(file.scale.kind == analysis::RecordScale::Kind::pga);
  CHECK(file.scale.target_g == 0.3);
  CHECK_NOTHROW(s.validate());
  CHECK_NOTHROW(o.validate());
}

TEST_CASE("model file: a PGA target sets the record level so that the 100 % level has that PGA") {
  motion::Record r;
  r.name = "sine";
  r.dt = 0.01;
  for (int i = 0; i < 500; ++i) r.acceleration.push_back(2.0 * std::sin(0.1 * i));  // PGA 2 m/s^2
  const double peak = motion::peak_values(r).pga;
  const double level = analysis::record_level_for({analysis::RecordScale::Kind::pga, 0.3, 0}, r, "test");
  // At 100 % the study applies the record times 100 / record_level: its PGA is the target.
  CHECK(peak * 100 / level == test::approx(0.3 * standard_gravity).epsilon(1e-12));
}

// Each row: what is changed in `two_bricks`, and what the message must say (the place and the rule).
TEST_CASE("model file: every bad file is refused with its line, column, field and what is allowed") {
  struct Row {
    std::string from, to, says;
  };
  const Row rows[] = {
      {R"("blockdem_model": 1)", R"("blockdem_model": 2)", "bad.json:2:21: blockdem_model: this blockdem reads version 1"},
      {R"("blockdem_model": 1,)", "", "bad.json:1:1: the file: \"blockdem_model\" is missing"},
      {R"("units": "SI")", R"("units": "mm")", "bad.json:4:12: units: the model file is in SI units only"},
      {R"("gravity": [0, 0, -9.81])", R"("gravity": [0, -9.81])", "gravity: expected three numbers [x, y, z], got 2 values"},
      {R"("gravity": [0, 0, -9.81])", R"("gravity": [0, 0, -9810])", "gravity[2]: must be in [-1000, 1000] m/s^2, got -9810"},
      {R"("name": "two bricks",)", R"("nmae": "two bricks",)", "bad.json:3:11: : unknown key \"nmae\" (allowed: blockdem_model, name"},
      {R"("density": 1800,)", R"("density": -1800,)", "materials.brick.density: must be in (0, 100000] kg/m^3, got -1800"},
      {R"("density": 1800,)", R"("densty": 1800,)", "unknown key \"densty\" (allowed: density, youngs_modulus, poisson_ratio)"},
      {R"("poisson_ratio": 0.2)", R"("poisson_ratio": 0.5)", "materials.brick.poisson_ratio: must be in (-1, 0.5), got 0.5"},
      {R"("groups": ["wall", "table"],)", R"("groups": ["wall", "wall"],)", "groups[1]: \"wall\" is listed twice"},
      {R"("groups": ["wall", "table"],)", R"("groups": ["wall", "*"],)", "groups[1]: a group needs a name (not \"\" or \"*\")"},
      {R"("law": "softening")", R"("law": "plastic")", "joints[0].law: unknown value \"plastic\" (allowed: elastic, mohr_coulomb, softening)"},
      {R"(["wall", "wall"])", R"(["wall", "roof"])", "joints[0].between[1]: no group \"roof\" (groups: wall, table)"},
      {R"(["wall", "wall"])", R"(["wall"])", "joints[0].between: expected 2 values, got 1"},
      {R"("friction_angle_deg": 30)", R"("friction_angle_deg": 95)", "joints[1].friction_angle_deg: must be in [0, 89] degrees, got 95"},
      {R"("friction_angle_deg": 30)", "\"cohesion\": 0", "joints[1]: \"friction_angle_deg\" is missing"},
      {R"("friction_angle_deg": 30)", R"("friction_angle_deg": 30, "friction_angle_rad": 0.5)", "give friction_angle_deg or friction_angle_rad, not both"},
      {R"("friction_angle_deg": 30)", R"("friction_angle_deg": 30, "compressive_strength": 5e6)",
       "joints[1].compressive_strength: the law mohr_coulomb takes no \"compressive_strength\""},
      {R"("normal_stiffness": 1e10)", R"("normal_stiffness": 0)", "joints[1].normal_stiffness: must be in (0, 1e+16] Pa/m, got 0"},
      {R"("preset": "paper_table1")", R"("preset": "lourenco")", "joints[0].preset: unknown value \"lourenco\" (allowed: paper_table1)"},
      {R"("preset": "paper_table1")", R"("tensile_strength": 0.3e6)", "joints[0]: \"compressive_strength\" is missing"},
      {R"("preset": "paper_table1")", R"("preset": "paper_table1", "fracture_energy_tension": 1)",
       "fracture energy G_f^I must be >"},
      {R"("contact_point_spacing": 0.03)", R"("contact_point_spacing": -0.03)", "joints[0].contact_point_spacing: must be in [0, 100] m"},
      {R"({"between": ["*", "table"])", R"({"between": ["wall", "wall"])", "a second law for the pair \"wall\", \"wall\" (the first at bad.json:9:5)"},
      {R"("material": "brick", "box")", R"("material": "brik", "box")", "blocks[0].material: no material \"brik\" (materials: brick, steel)"},
      {R"("motion": "base")", R"("motion": "moving")", "blocks[2].motion: unknown value \"moving\" (allowed: free, fixed, base)"},
      {R"("box": [[0, 0, 0], [0.25, 0.12, 0.075]])", R"("box": [[0, 0, 0], [0.25, 0.12, 0]])",
       "blocks[0].box: the second corner must exceed the first along x, y and z"},
      {R"("box": [[0, 0, 0], [0.25, 0.12, 0.075]])", R"("box": [[0, 0, 0], [0.25, 0.12, 0.075]], "vertices": [])",
       "blocks[0].box: give a box or vertices and faces, not both"},
      {R"([3, 0, 4, 7]])", R"([3, 0, 4, 8]])", "blocks[1].faces[5][3]: must be in [0, 7], got 8"},
      {R"([3, 0, 4, 7]])", R"([3, 0, 4, 6.5]])", "blocks[1].faces[5]: a vertex index must be an integer, got 6.5"},
      {R"([0, 0, 0.15], [0.25, 0, 0.15])", R"([0, 0, 0.15], [0.25, 0, 0.2])", "blocks[1]: block 'B': face"},
      {R"({"name": "A", "group": "wall", "material": "brick",)", R"({"name": "A", "group": "wall", "material": "brick", "deformable": {"max_edge": 0.05},)",
       ""},  // a deformable brick of a material with E and nu: accepted
      {R"("steel": {"density": 7800})", R"("steel": {"density": 7800}, "x": {"density": 1})", ""},  // an unused material: accepted
      {R"("motion": "base",)", R"("motion": "base", "deformable": {"max_edge": 0.1},)", "blocks[2].deformable: only a free block can be deformable"},
      {R"({"block": 2, "point")", R"({"block": 3, "point")", "ties[0].ends[1].block: no block 3 (blocks are numbered 0..2)"},
      {R"({"block": 2, "point")", R"({"block": "floor", "point")", "ties[0].ends[1].block: no block named \"floor\""},
      {R"("area": 1e-4)", R"("area": 0)", "ties[0].area: must be in (0, 100] m^2, got 0"},
      {R"("density": 7800}])", R"("density": 7800, "pretension": -1}])", "ties[0].pretension: must be in [0, 1e+12] N, got -1"},
      {R"({"name": "A", "block": "A"})", R"({"name": "top", "block": "A"})", "monitors[1].name: two monitor points are named \"top\""},
      {R"({"name": "A", "block": "A"})", R"({"name": "A,B", "block": "A"})", "monitors[1].name: a monitor point's name must be non-empty, without commas"},
      {R"({"name": "A", "block": "A"})", R"({"name": "A"})", "monitors[1]: \"point\" is missing"},
      {R"("excitation": {)", R"("table": "A", "excitation": {)", "table: the table must be a block with \"motion\": \"base\""},
      {R"("axis": "y")", R"("axis": "w")", "excitation.axis: unknown value \"w\" (allowed: x, y, z)"},
      {R"("pga_g": 0.3)", R"("pga_g": 0.3, "sa_g": 0.5)", "excitation: give one of record_level_percent, pga_g and sa_g"},
      {R"("pga_g": 0.3)", R"("sa_g": 0.5)", "excitation: \"sa_period_s\" is missing"},
      {R"("window_s": [0, 5])", R"("window_s": [5, 5])", "excitation.window_s[1]: must be in (5, 100000] s, got 5"},
      {R"("window_s": [0, 5])", R"("window_s": [0, 5], "baseline": "mean,lowpass:3")", "excitation.baseline:"},
      {R"("levels_percent": [50, 100])", R"("levels_percent": [])", "study.levels_percent: expected between 1 and any number of values, got 0"},
      {R"("levels_percent": [50, 100])", R"("levels_percent": [50, 2000])", "study.levels_percent[1]: must be in (0, 1000] %, got 2000"},
      {R"("scheme": "mass")", R"("scheme": "viscous")", "study.damping.scheme: unknown value \"viscous\" (allowed: none, mass, stiffness, rayleigh, maxwell)"},
      {R"("zeta": 0.04)", R"("zeta": 0.6)", "study.damping.zeta: must be in [0, 0.5), got 0.6"},
      {R"("rest_s": 0.5)", R"("rest_s": 0.5, "analysis": "modal")", "study.analysis: unknown value \"modal\" (allowed: levels, pushover)"},
      {R"("rest_s": 0.5)", R"("rest_s": 0.5, "pushover": {"axis": "x"})", "study.pushover: goes with \"analysis\": \"pushover\""},
      {R"("rest_s": 0.5)", R"("rest_s": 0.5, "analysis": "pushover", "pushover": {"axis": "z"})", "study.pushover.axis: unknown value \"z\" (allowed: x, -x, y, -y)"},
      {R"("preset": "paper_table1")", R"("preset": "paper_table1", "normal_stiffness": 1e10, "shear_stiffness": 4e9, "unit_modulus": 5e9)",
       "joints[0]: give the stiffnesses or the unit and mortar of eq. 7"},
      {R"("preset": "paper_table1")", R"("tensile_strength": 1e5, "compressive_strength": 5e6, "cohesion": 1e5, "friction_angle_deg": 30, "unit_modulus": 5e9)",
       "joints[0]: \"mortar_modulus\" is missing (eq. 7 needs"},
      {R"("scheme": "mass")", R"("scheme": "maxwell", "branches": 2.5)", "study.damping.branches: must be a whole number, got 2.5"},
      {R"("study": {)", R"("study": {"timestep": {"target_dt_s": 1},)", "study.timestep.target_dt_s: must be in [0, 0.01) s, got 1"},
      {R"("study": {)", R"("study": {"settle": {"method": "viscous"},)", "study.settle.method: unknown value \"viscous\" (allowed: auto, inertial, local)"},
      {R"("study": {)", R"("study": {"settle": {"method": "local"},)", ""},
      {"\"blocks\": [", "\"blocks\": [1, ", "blocks[0]: expected an object { ... }, got a number"},
      {R"("monitors": [)", R"("monitors": [}, )", "bad.json:22:16: expected a value"},
  };
  int refused = 0;
  for (const auto& row : rows) {
    CAPTURE(row.to);
    const std::string message = refusal(changed(row.from, row.to));
    if (row.says.empty()) {
      CHECK(message == "");
      continue;
    }
    ++refused;
    CHECK_MESSAGE(message.find(row.says) != std::string::npos, "message: " << message);
    CHECK(message.starts_with("bad.json:"));  // every refusal names the file and the place
  }
  CHECK(refused >= 30);
}

}  // namespace test_model_file
