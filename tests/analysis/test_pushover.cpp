// The equivalent-static pushover (analysis/pushover.hpp) of model files against the rigid-body limits: a monolithic
// block of width b and height h on a fixed base overturns at lambda = b/h; a dry running-bond wall standing free,
// pushed out of plane, at t/h; and the 40-voussoir arch written as a model file collapses at the multiplier of
// `arch --find-collapse` (analysis/arch.hpp, an implementation of its own).

#include <doctest/doctest.h>

#include <sstream>
#include <string>

#include "blockdem/analysis/arch.hpp"
#include "blockdem/analysis/model_file.hpp"
#include "blockdem/analysis/model_file_writer.hpp"
#include "blockdem/analysis/pushover.hpp"
#include "blockdem/geometry/generators.hpp"
#include "../approx.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_pushover {

namespace {

/// A model file of dry blocks (Mohr-Coulomb, 40 degrees, no cohesion or tension) on a fixed base, pushed along
/// `axis`; `blocks` is the JSON text of the free blocks.
std::string dry_model(const std::string& blocks, const std::string& axis) {
  return R"({"blockdem_model": 1, "name": "dry blocks",
  "materials": {"stone": {"density": 2000}},
  "joints": [{"between": ["*", "*"], "law": "mohr_coulomb", "normal_stiffness": 1e10, "shear_stiffness": 5e9, "friction_angle_deg": 40}],
  "contacts": {"kinds": "general", "tolerance": 1e-4},
  "blocks": [{"name": "base", "group": "base", "material": "stone", "motion": "fixed", "box": [[-0.5, -0.5, -0.2], [1.5, 0.7, 0]]},
)" + blocks + R"(],
  "study": {"analysis": "pushover", "pushover": {"axis": ")" + axis + R"(", "resolution": 0.001}}})";
}

analysis::PushoverResult push(const std::string& text) {
  auto file = analysis::parse_model_file(text, "pushover.json");
  REQUIRE(file.pushover.has_value());
  auto o = *file.pushover;
  o.progress = false;
  return analysis::run_pushover(file.structure, o, true);
}

}  // namespace

TEST_CASE("pushover: a monolithic block of width b and height h on a fixed base overturns at lambda = b/h (within 1 %)") {
  // b = 0.3 m along the push, h = 1 m: the resultant of weight and lambda times weight, at h/2, leaves the base at
  // lambda = (b/2) / (h/2). Friction (tan 40 degrees = 0.84) holds it from sliding.
  const auto r = push(dry_model(R"({"name": "block", "group": "block", "material": "stone", "box": [[0, 0, 0], [0.3, 0.3, 1.0]]})", "x"));
  CHECK_FALSE(r.falls_under_weight);
  CHECK_FALSE(r.stands_at_upper);
  CHECK(r.collapse_multiplier == test::approx(0.3).epsilon(0.01));
  CHECK(r.upper - r.lower <= 0.001);
}

TEST_CASE("pushover: a dry running-bond wall standing free, pushed out of plane, overturns at t/h (within 5 %)") {
  // 4 units of 0.25 x 0.12 x 0.075 m per course, 8 courses: t/h = 0.12 / 0.6 = 0.2. Without tension in its bed
  // joints, the wall above any joint overturns about its edge at t / (its height): first the whole wall, at t/h.
  std::string blocks;
  for (const auto& b : geometry::running_bond_wall(8, 4, 0.25, 0.12, 0.075)) {
    if (b.support) continue;  // the file's base takes the foundation's place
    const auto& v = b.shape.vertices;
    Vec3 lo = v[0], hi = v[0];
    for (const auto& x : v) {
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
    blocks += (blocks.empty() ? "" : ",\n") + std::string(R"({"group": "wall", "material": "stone", "box": [)") +
              analysis::detail::json_vec3(lo) + ", " + analysis::detail::json_vec3(hi) + "]}";
  }
  const auto r = push(dry_model(blocks, "y"));
  CHECK_FALSE(r.falls_under_weight);
  CHECK(r.collapse_multiplier == test::approx(0.2).epsilon(0.05));
}

TEST_CASE("pushover: the 40-voussoir arch as a model file collapses at the multiplier of arch --find-collapse") {
  // The arch of analysis/arch.hpp (t/R = 0.15, R = 1 m, depth 0.5 m, dry joints of 40 degrees, k_n = 1e10 Pa/m,
  // 2000 kg/m^3, springings fixed; tolerance 1e-4 R; collapse at a quarter of the thickness) written as a model file.
  // As `arch --model` writes it.
  const analysis::ArchOptions arch;
  analysis::StudyOptions study;
  study.contacts = model::ContactKinds::general;
  const auto push = analysis::arch_pushover(arch);
  std::ostringstream text;
  analysis::write_model_file(text, analysis::arch_description(arch), study, &push);
  const auto file = analysis::parse_model_file(text.str(), "arch.json");
  REQUIRE(file.pushover);
  analysis::PushoverOptions o = *file.pushover;
  CHECK(o.resolution == 0.005);  // as --find-collapse
  CHECK(o.collapse_displacement == 0.25 * 0.15);
  o.progress = false;
  const auto r = analysis::run_pushover(file.structure, o, file.study.contacts == model::ContactKinds::general);
  // `arch --find-collapse`: 0.142578125 (8 halvings of [0, 1]; docs/arch.md). The same bisection on the same
  // blocks, laws and thresholds, with the study's simulation: the same bracket, or the next one.
  CHECK(r.collapse_multiplier == test::approx(0.142578125).epsilon(0.005 / 0.142578125));
}

}  // namespace test_pushover
