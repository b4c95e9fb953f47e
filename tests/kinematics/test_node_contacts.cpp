// Node contacts over re-detections: which CPs keep their joint's history and which start as new contacts. The
// reference is the rule for rigid blocks (Simulation::assign_contacts): a CP found at the first detection is part of
// a bonded joint; one that appears during the run (an impact, a slide) never was and starts from the law's failed
// state; one that is found again keeps its history.

#include <doctest/doctest.h>

#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/integrate/simulation.hpp"

using namespace blockdem;

namespace {

/// A bonded joint: tension 0.1 MPa, cohesion 0.2 MPa, 30 degrees.
auto bonded = [](int, int) { return contact::MohrCoulomb::Parameters(1e10, 4e9, 1e5, 2e5, 0.5236); };
using Sim = Simulation<damping::None, contact::MohrCoulomb>;

struct Counts {
  long long points = 0, failed = 0;
};
Counts count(const Sim& sim) {
  Counts c;
  sim.visit_contact_histories([&](std::size_t, std::size_t, const auto& h) {
    ++c.points;
    c.failed += h.failed != 0;
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
}

TEST_CASE("node contacts: CPs that appear during the run start failed, as rigid blocks' do") {
  // The stack dropped from 2 mm: the joints close during the run, so they never were bonded.
  auto m = stack(2e-3);
  Sim sim(m, damping::None{}, bonded);
  REQUIRE(count(sim).points == 0);
  while (count(sim).points == 0 && sim.steps() < 20000) sim.step();
  for (int i = 0; i < 200; ++i) sim.step();
  const auto landed = count(sim);
  MESSAGE("node CPs after the landing: " << landed.points << ", failed " << landed.failed << " (" << sim.detections() << " detections)");
  REQUIRE(landed.points > 0);
  CHECK(landed.failed == landed.points);
}
