// Contact points over re-detections: which keep their joint's history and which start as new contacts, for rigid
// blocks and for the nodes of deformable ones alike. A CP found at the first detection is part of a bonded joint;
// one found again keeps its history; one that the joint's new polygon adds takes the state of the joint where it
// is (its closest old CP); one where the pair had no contact (an impact, a new pair after sliding) never was
// bonded and starts from the law's failed state, marked contact::never_bonded.

#include <doctest/doctest.h>

#include "blockdem/contact/elastic.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "fixtures.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_contact_history {

namespace {

/// A bonded joint: tension 0.1 MPa, cohesion 0.2 MPa, 30 degrees.
auto bonded = [](int, int) { return contact::MohrCoulomb::Parameters(1e10, 4e9, 1e5, 2e5, 0.5236); };
using Sim = Simulation<damping::None, contact::MohrCoulomb>;

struct Counts {
  long long points = 0, failed = 0, never_bonded = 0;
};
Counts count(const Sim& sim) {
  Counts c;
  sim.visit_contact_histories([&](std::size_t, std::size_t, const auto& h) {
    ++c.points;
    c.failed += h.failed != 0;
    c.never_bonded += h.failed == contact::never_bonded;
  });
  return c;
}

/// A deformable 0.3 m box (max edge 0.15 m) `gap` above a fixed base, and a second one of the same mesh stacked on
/// it with the same gap.
model::Model stack(double gap) {
  model::Model m;
  m.add_block(geometry::make_box(Vec3(-1, -1, -0.5), Vec3(1, 1, 0)), 2000, "base", 0, model::Motion::fixed);
  const auto lower = m.add_block(geometry::make_box(Vec3(-0.15, -0.15, gap), Vec3(0.15, 0.15, gap + 0.3)), 2000, "lower", 1);
  const auto upper = m.add_block(geometry::make_box(Vec3(-0.15, -0.15, 2 * gap + 0.3), Vec3(0.15, 0.15, 2 * gap + 0.6)), 2000, "upper", 1);
  m.make_deformable(lower, 0.15, model::IsotropicElastic(5e9, 0.2));
  m.make_deformable(upper, 0.15, model::IsotropicElastic(5e9, 0.2));
  return m;
}

}  // namespace

TEST_CASE("node contacts: found at the start they are bonded, and a re-detection after the blocks deform keeps them so") {
  auto m = stack(0.0);
  Sim sim(m, damping::None{}, bonded);
  const auto start = count(sim);
  REQUIRE(start.points > 0);
  CHECK(start.failed == 0);
  for (int i = 0; i < 2000; ++i) sim.step();  // the stack loads its joints and vibrates under its weight
  sim.redetect();
  const auto again = count(sim);
  MESSAGE("node CPs: " << start.points << " at the start, " << again.points << " after a re-detection, " << again.failed << " failed");
  CHECK(again.points == start.points);
  CHECK(again.failed == 0);  // every CP found again: none comes back as a new (failed) contact
  CHECK(again.never_bonded == 0);
}

TEST_CASE("node contacts: CPs that appear during the run start failed, as rigid blocks' do, and stay marked") {
  // The stack dropped from 2 mm: the joints close during the run, so they never were bonded. The law keeps the
  // mark (contact::never_bonded) through its updates, so that damage counts can leave such contacts out.
  auto m = stack(2e-3);
  Sim sim(m, damping::None{}, bonded);
  REQUIRE(count(sim).points == 0);
  while (count(sim).points == 0 && sim.steps() < 20000) sim.step();
  for (int i = 0; i < 200; ++i) sim.step();
  const auto landed = count(sim);
  MESSAGE("node CPs after the landing: " << landed.points << ", failed " << landed.failed << " (" << sim.detections() << " detections)");
  REQUIRE(landed.points > 0);
  CHECK(landed.failed == landed.points);
  CHECK(landed.never_bonded == landed.points);
  long long marked = 0;
  sim.visit_contacts([&](const auto& c) { marked += c.never_bonded && c.damage == 0; });
  CHECK(marked == landed.points);  // output: new contacts, not damage
}

TEST_CASE("node contacts: points a late re-detection finds in overlap start touching, and store no energy") {
  // A deformable box falls onto a fixed base at 0.5 m/s, without gravity, checked every 400 steps (2 mm of fall):
  // its nodes are found some 0.8 mm deep. Their new contact points start touching (gap 0), not loaded by the
  // overlap, which would have stored 1/2 kn d^2 A in them from no force and launched the box back.
  model::Model m;
  m.add_block(geometry::make_box(Vec3(-1, -1, -0.5), Vec3(1, 1, 0)), 2000, "base", 0, model::Motion::fixed);
  const auto box = m.add_block(geometry::make_box(Vec3(-0.15, -0.15, 3.2e-3), Vec3(0.15, 0.15, 0.3032)), 2000, "box", 1);
  m.make_deformable(box, 0.15, model::IsotropicElastic(5e9, 0.2));
  m.gravity = Vec3::Zero();
  for (auto& v : m.deformable.nodes.velocity) v = Vec3(0, 0, -0.5);
  model::ContactSettings contacts;
  contacts.redetection_check_interval = 400;
  Sim sim(m, damping::None{}, bonded, contacts);
  REQUIRE(count(sim).points == 0);
  sim.set_timestep(1e-5);
  while (count(sim).points == 0 && sim.steps() < 2000) sim.step();
  REQUIRE(count(sim).points > 0);
  double deepest = 0;
  for (const auto& x : m.deformable.nodes.position) deepest = std::min(deepest, x.z());
  double lowest_gap = 1;
  sim.visit_contact_histories([&](std::size_t, std::size_t, const auto& h) { lowest_gap = std::min(lowest_gap, h.gap); });
  const auto e = sim.energy();
  MESSAGE("found " << 1e3 * -deepest << " mm deep (" << count(sim).points << " node CPs); lowest gap " << lowest_gap
                   << " m; the balance's term for re-detection " << e.contact_update << " J");
  CHECK(-deepest > 5e-4);
  CHECK(lowest_gap == 0.0);
  CHECK(std::abs(e.contact_update) < 1e-9 * e.kinetic);
}

TEST_CASE("contact history: a rigid block turned on its joint keeps the bond at the corners its new polygon adds") {
  // A 1 m cube on a bonded joint, turned 10 degrees about the vertical and detected again: its four corner CPs
  // move by some 0.09 m, beyond the matching distance (1 mm), so all four are new CPs of the same joint. Each
  // takes the state of the closest old one: bonded, not a new contact.
  auto s = test::block_on_base(1, 1, 1);
  s.model.gravity = Vec3::Zero();
  Sim sim(s.model, damping::None{}, bonded);
  REQUIRE(count(sim).points == 4);
  auto& b = s.model.bodies;
  b.orientation[s.block] = (Quaternion(Eigen::AngleAxisd(10.0 * pi / 180, Vec3::UnitZ())) * b.orientation[s.block]).normalized();
  b.rotation[s.block] = b.orientation[s.block].toRotationMatrix();
  sim.redetect();
  const auto turned = count(sim);
  CHECK(turned.points == 4);
  CHECK(turned.failed == 0);
  CHECK(turned.never_bonded == 0);
}

TEST_CASE("contact history: a block rattling on a pier of its own size keeps its energy over many re-detections") {
  // A tie anchor on its steel pier, as in the cross vault: two equal 0.3 m faces that nearly coincide, on a stiff
  // elastic joint (100 GPa/m), the anchor shaken in shear and about the vertical and detected again every few steps.
  // Where two nearly parallel edges of the faces cross, their overlap has a vertex at offset / angle along them
  // (offset and angle of the order of the elastic shear displacement): it jumps by centimetres from one detection to
  // the next, and a CP there would take the stress of another (its closest old CP) with another area, energy out of
  // nothing at every detection. The detection keeps the overlap's corners only, which stay where they are.
  model::Model m;
  m.gravity = Vec3(0, 0, -9.81);
  m.add_block(geometry::make_box(Vec3(-0.15, -0.15, -1), Vec3(0.15, 0.15, 0)), 5570, "pier", 0, model::Motion::fixed);
  const auto anchor = m.add_block(geometry::make_box(Vec3(-0.15, -0.15, 0), Vec3(0.15, 0.15, 0.2)), 2000, "anchor", 1);
  auto steel = [](int, int) { return contact::Elastic::Parameters(100e9, 100e9); };
  model::ContactSettings settings;
  settings.redetection_distance = 1e-6;  // m: detected again every step or two
  Simulation<damping::None, contact::Elastic> sim(m, damping::None{}, steel, settings);
  sim.set_timestep(0.2 * sim.critical_timestep());
  m.bodies.velocity[anchor] = Vec3(0.02, -0.015, 0);
  m.bodies.angular_velocity[anchor] = Vec3(0.01, 0.02, 0.05);
  for (int i = 0; i < 20000; ++i) sim.step();
  const auto e = sim.energy();
  const double motion = 0.5 * 36.0 * (0.02 * 0.02 + 0.015 * 0.015);  // J, the kinetic energy given (the anchor's 36 kg)
  CHECK(sim.detections() > 5000);
  CHECK(std::abs(e.contact_update) < 1e-2 * motion);  // 35 times the motion's energy with the crossing vertices
  CHECK(e.balance_error < 1e-3);  // 8.9 with them
}

}  // namespace test_contact_history
