// The typologies of analysis/typologies.hpp written as model files and read back as `blockdem run` reads them; a
// free-standing dry-stack wall with a window pushed out of plane collapses at the multiplier of its rigid overturning
// mechanism worked out by hand (docs/generators.md), and with return walls it stands there; a barrel vault pushed
// across its span collapses at the multiplier of the arch of its ring.

#include <doctest/doctest.h>

#include <algorithm>
#include <sstream>
#include <string>

#include "blockdem/analysis/model_file.hpp"
#include "blockdem/analysis/model_file_writer.hpp"
#include "blockdem/analysis/pushover.hpp"
#include "blockdem/analysis/arch.hpp"
#include "blockdem/analysis/typologies.hpp"
#include "blockdem/geometry/polyhedron_check.hpp"
#include "blockdem/io/obj_geometry.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "../approx.hpp"

using namespace blockdem;

// Named: this file may share a unity translation unit.
namespace test_typology_pushover {

namespace {

/// The model file of a description, its study and pushover, as written and read back.
analysis::ModelFile as_file(const analysis::ModelDescription& d, const analysis::StudyOptions& study, const analysis::PushoverOptions* push,
                            const char* source) {
  std::ostringstream text;
  analysis::write_model_file(text, d, study, push);
  return analysis::parse_model_file(text.str(), source);
}

/// Every pair of groups whose blocks touch as built has a joint law (what `blockdem check` verifies).
void check_laws_of_touching_pairs(const analysis::ModelFile& file) {
  const auto& s = file.structure;
  auto settings = s.contacts;
  settings.kinds = file.study.contacts;
  s.laws.fill(settings);
  const auto contacts = model::detect_contacts(s.model.bodies, settings);
  CHECK_FALSE(contacts.empty());
  for (const auto& c : contacts) {
    const auto a = static_cast<std::size_t>(s.model.bodies.joint_tag[c.a]), b = static_cast<std::size_t>(s.model.bodies.joint_tag[c.b]);
    INFO(s.laws.name(a) << " - " << s.laws.name(b));
    CHECK(s.laws.has(a, b));
  }
}

/// The wall of the physics test: 6 units of 0.25 x 0.12 x 0.075 m per course (1.5 m long), 10 courses (0.75 m high),
/// a window 0.5 m wide from x = 0.5 to 1.0 m over courses 1-4 (0.3 m high, sill 0.075 m above the base), a stone
/// lintel in course 5 from x = 0.375 to 1.125 m; bricks of 1800 kg/m^3, the lintel 2200; dry joints of 35 degrees.
analysis::WallStudyOptions window_wall() {
  analysis::WallStudyOptions o;
  o.wall.length = 1.5;
  o.wall.courses = 10;
  o.wall.thickness = 0.12;
  o.wall.unit_length = 0.25;
  o.wall.unit_height = 0.075;
  o.wall.lintel_bearing = 0.125;
  o.wall.openings = {{0.5, 1.0, 1, 5}};
  return o;
}

/// The rigid overturning of the part of the wall above bed joint k about the joint's outer edge, under its weight W
/// and lambda W out of plane: lambda_k = (t/2) / (z_G - z_k), z_G the height of the part's centre of mass (a uniform
/// thickness: every part's centre of mass lies at mid-thickness). The part is the masonry above the joint less the
/// units under an opening that carry nothing (whole units below the sill within the jambs, then whole units under
/// those, course by course): they are left standing as the rest turns. The multiplier is the least over the joints.
struct HandMechanism {
  double lambda = 1e300;
  int joint = -1;
  double centre_of_mass = 0;  // m, z_G of the part that turns
};
HandMechanism hand_mechanism(const analysis::WallStudyOptions& o) {
  const auto& w = o.wall;
  const double h = w.unit_height, l = w.unit_length, H = w.height(), brick = analysis::unit_density(o.unit),
               stone = analysis::unit_density(o.lintel);
  HandMechanism best;
  for (int k = 0; k < w.courses; ++k) {
    const double zk = k * h;
    double mass = 0, moment = 0;  // per metre of thickness: kg/m, kg
    auto add = [&](double density, double width, double z0, double z1) {
      if (z1 <= z0) return;
      mass += density * width * (z1 - z0);
      moment += density * width * (z1 - z0) * 0.5 * (z0 + z1);
    };
    add(brick, w.length, zk, H);
    for (const auto& op : w.openings) {
      add(-brick, op.x1 - op.x0, std::max(zk, op.sill_course * h), op.head_course * h);  // the opening
      if (op.head_course >= k)  // the lintel: stone instead of brick
        add(stone - brick, op.x1 - op.x0 + 2 * w.lintel_bearing, op.head_course * h, (op.head_course + 1) * h);
      // The unloaded units under the opening, between the sill and the joint: from the first joint at or inside
      // each jamb (odd courses' joints shifted by half a unit) to the last.
      double a = op.x0, b = op.x1;
      for (int c = op.sill_course - 1; c >= k; --c) {
        const double offset = c % 2 == 1 ? 0.5 * l : 0.0;
        a = offset + std::ceil((a - offset) / l - 1e-9) * l;
        b = offset + std::floor((b - offset) / l + 1e-9) * l;
        if (b <= a) break;
        add(-brick, b - a, c * h, (c + 1) * h);
      }
    }
    const double lambda = 0.5 * w.thickness / (moment / mass - zk);
    if (lambda < best.lambda) best = {lambda, k, moment / mass};
  }
  return best;
}

}  // namespace

TEST_CASE("typology pushover: the wall and vault descriptions read back as model files with their groups, laws, table and monitor points") {
  auto o = window_wall();
  o.wall.return_length = 0.5;
  const auto push = analysis::wall_pushover(o);
  const auto wall = as_file(analysis::wall_description(o), o, &push, "wall.json");
  const auto& s = wall.structure;
  CHECK(s.groups() == std::vector<std::string>{"wall", "lintel", "return", "foundation"});
  REQUIRE(s.table.has_value());
  CHECK(s.model.bodies.name[*s.table] == "foundation");
  CHECK(s.model.bodies.motion[*s.table] == model::Motion::base);
  REQUIRE(s.monitors.size() == 1u);
  CHECK(s.monitors[0].name == "top");
  CHECK(s.model.bodies.name[s.monitors[0].block].rfind("c10 u", 0) == 0);
  CHECK(s.contacts.tolerance == test::approx(0.075e-3));
  CHECK(wall.study.axis == 'y');
  CHECK(wall.study.contacts == model::ContactKinds::general);
  REQUIRE(wall.pushover.has_value());
  CHECK(wall.pushover->axis == 'y');
  CHECK(wall.pushover->collapse_displacement == test::approx(0.03));
  CHECK(s.model.total_mass() == test::approx(1800 * (1.5 * 0.75 + 2 * 0.5 * 0.75 - 0.5 * 0.3 - 0.75 * 0.075) * 0.12 +
                                             2200 * 0.75 * 0.075 * 0.12).epsilon(1e-9));
  check_laws_of_touching_pairs(wall);

  analysis::BarrelVaultStudyOptions v;
  v.vault.rings = 15;
  const auto vault_push = analysis::barrel_vault_pushover(v);
  const auto vault = as_file(analysis::barrel_vault_description(v), v, &vault_push, "vault.json");
  CHECK(vault.structure.groups() == std::vector<std::string>{"vault", "abutment"});
  REQUIRE(vault.structure.table.has_value());
  CHECK(vault.structure.model.bodies.name[*vault.structure.table] == "abutment right");
  REQUIRE(vault.structure.monitors.size() == 1u);
  CHECK(vault.structure.model.bodies.name[vault.structure.monitors[0].block].rfind("ring 8 u", 0) == 0);  // the key ring
  CHECK(vault.study.axis == 'x');
  CHECK(vault.pushover->axis == 'x');
  check_laws_of_touching_pairs(vault);
}

TEST_CASE("typology pushover: a free-standing dry wall with a window, pushed out of plane, overturns at the hand multiplier of its "
          "mechanism, and with return walls it stands there") {
  // The hand calculation (docs/generators.md), per metre of thickness: the part above bed joint k is the wall's
  // rectangle above z_k less the window, with the lintel's extra 400 kg/m^3, less (for the base joint only) the two
  // units of course 0 under the window, which carry nothing and stay. It overturns about the joint's outer edge at
  // lambda_k = 0.06 / (z_G - z_k). The base governs: z_G = 0.41250 m, lambda_0 = 0.14545 (0.15066 if the unloaded
  // units turned with the rest); the sill joint 0.16232, joint 2 0.18417, ...; the wall without its window t/h = 0.16.
  // Friction (tan 35 degrees = 0.70) keeps every joint from sliding; the running bond makes the rest rock as one body.
  auto o = window_wall();
  const auto hand = hand_mechanism(o);
  CHECK(hand.joint == 0);
  CHECK(hand.centre_of_mass == test::approx(0.4125).epsilon(1e-9));
  CHECK(hand.lambda == test::approx(0.06 / 0.4125).epsilon(1e-9));

  // The pushover as `blockdem run` runs the written file, the bisection coarsened: from [0, 0.4] to 0.01 (8 trials).
  auto push = analysis::wall_pushover(o);
  push.upper = 0.4;
  push.resolution = 0.01;
  const auto file = as_file(analysis::wall_description(o), o, &push, "window_wall.json");
  REQUIRE(file.pushover.has_value());
  auto parsed = *file.pushover;
  parsed.progress = false;  // (not a field of the file)
  const auto r = analysis::run_pushover(file.structure, parsed, file.study.contacts == model::ContactKinds::general);
  CHECK_FALSE(r.falls_under_weight);
  CHECK_FALSE(r.stands_at_upper);
  // Tolerance: the bracket's half-width (0.00625 / 2) plus 2 % of the hand value: the joints' stiffness (1e10 Pa/m)
  // lets the wall lean a little before it rocks, and a trial near the limit ends at the collapse displacement or
  // the step limit. (Bisected to 0.001, blockdem brackets the multiplier in [0.14531, 0.14609]: +0.2 %.)
  CHECK(r.collapse_multiplier == test::approx(hand.lambda).epsilon((0.5 * (r.upper - r.lower) + 0.02 * hand.lambda) / hand.lambda));
  CHECK(r.upper - r.lower <= 0.01);

  // The same wall with return walls of 0.5 m bonded at both ends stands where the free wall fell: its overturning drags
  // the returns, which stand in their own plane. (Bisected to 0.005 in [0, 1] it collapses at 0.56, in 340 s.)
  o.wall.return_length = 0.5;
  auto returns_push = analysis::wall_pushover(o);
  returns_push.upper = r.upper;
  const auto with_returns = as_file(analysis::wall_description(o), o, &returns_push, "window_wall_returns.json");
  auto returns_parsed = *with_returns.pushover;
  returns_parsed.progress = false;
  const auto rr = analysis::run_pushover(with_returns.structure, returns_parsed, true);
  CHECK_FALSE(rr.falls_under_weight);
  CHECK(rr.stands_at_upper);
}

TEST_CASE("typology pushover: a barrel vault pushed across its span collapses at the multiplier of the arch of its ring") {
  // Rings of units along y, staggered, move as one arch across the span: the vault's multiplier is the arch's. The
  // 40-voussoir semicircular arch of t/R = 0.15 with joints of 40 degrees collapses at lambda = 0.1426 (docs/arch.md;
  // De Lorenzis et al. 2007 for the method): here R = 1 m (span 1.85 m, thickness 0.15 m), 0.5 m long in units of
  // 0.25 m, abutments as the arch's supports. Bisected in [0, 0.3] to 0.01; tolerance the bracket's half-width plus
  // 2 % (the contact tolerance and the density differ from the arch's; bisected to 0.005 it gives 0.1422).
  analysis::BarrelVaultStudyOptions v;
  v.vault.span = 1.85;
  v.vault.thickness = 0.15;
  v.vault.rings = 40;
  v.vault.length = 0.5;
  v.vault.unit_length = 0.25;
  v.joints.friction_angle_deg = 40;
  auto push = analysis::barrel_vault_pushover(v);
  push.upper = 0.3;
  push.resolution = 0.01;
  const auto file = as_file(analysis::barrel_vault_description(v), v, &push, "barrel_vault.json");
  auto parsed = *file.pushover;
  parsed.progress = false;
  const auto r = analysis::run_pushover(file.structure, parsed, true);
  CHECK_FALSE(r.falls_under_weight);
  CHECK_FALSE(r.stands_at_upper);
  const double arch = 0.142578125;
  CHECK(r.collapse_multiplier == test::approx(arch).epsilon((0.5 * (r.upper - r.lower) + 0.02 * arch) / arch));
}

TEST_CASE("typology pushover: the arch exported to OBJ and read back collapses at the generated arch's multiplier") {
  // `blockdem export arch.json arch.obj`, then a model file taking the OBJ's blocks: the same voussoirs (volumes and
  // centroids to 1e-9, tests/geometry/test_geometry_import.cpp) and the same pushover bracket as the arch generated.
  analysis::ArchOptions a;
  a.voussoirs = 20;
  auto d = analysis::arch_description(a);
  auto push = analysis::arch_pushover(a);
  push.upper = 0.5;
  push.resolution = 0.01;
  push.progress = false;
  std::vector<geometry::ImportedBlock> blocks;
  for (const auto& b : d.blocks) blocks.push_back(geometry::imported_block(b.shape, b.name));
  std::ostringstream obj;
  io::write_obj(obj, blocks, "arch");
  auto e = d;
  const auto back = io::read_obj(obj.str(), "arch.obj");
  REQUIRE(back.size() == d.blocks.size());
  std::vector<geometry::BlockIssue> issues;
  for (std::size_t i = 0; i < back.size(); ++i) {
    const auto shape = geometry::check_polyhedron(back[i], issues);
    REQUIRE(shape);
    e.blocks[i].shape = *shape;
  }
  CHECK(issues.empty());
  analysis::StudyOptions study;
  study.axis = 'x';
  const auto generated = as_file(d, study, &push, "arch.json"), imported = as_file(e, study, &push, "arch_obj.json");
  auto p = *generated.pushover;
  p.progress = false;
  const auto rg = analysis::run_pushover(generated.structure, p, true), ri = analysis::run_pushover(imported.structure, p, true);
  CHECK_FALSE(rg.stands_at_upper);
  CHECK(ri.lower == rg.lower);
  CHECK(ri.upper == rg.upper);
  CHECK(ri.collapse_multiplier == rg.collapse_multiplier);
}

}  // namespace test_typology_pushover
