// General contacts (vertex-face, edge-face, edge-edge on the common plane) against rigid-block mechanics: cubes
// dropped on an edge, on a corner and edge across edge; the sliding and toppling blocks of the 3DEC verification
// set after Wyllie and Mah; a stocky block rocked to 30 degrees and Housner's restitution (issue 25).

#include <doctest/doctest.h>

#include "../approx.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <set>
#include <vector>

#include "blockdem/analysis/rocking.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/geometry/queries.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "rocking_reference.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_general_contacts {

namespace {
using MC = contact::MohrCoulomb;

enum class Landing { edge, corner, edge_across_edge };

/// A unit cube (2000 kg/m^3) turned to land on an edge or a corner, `drop` m above a fixed floor, or on the
/// horizontal edge of a fixed cube turned the other way (edge across edge, at right angles).
struct Drop {
  model::Model model;
  std::size_t lower = 0, cube = 0;
};

Drop cube_drop(Landing landing, double drop) {
  Drop d;
  const auto cube = geometry::make_box(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5));
  Mat3 turn = Eigen::AngleAxisd(pi / 4 + 0.05, Vec3::UnitY()).toRotationMatrix();  // an edge along y, not quite plumb
  if (landing == Landing::corner)  // the body diagonal nearly vertical: a corner down
    turn = (Eigen::AngleAxisd(pi / 4, Vec3::UnitX()) * Eigen::AngleAxisd(std::atan(1 / std::sqrt(2.0)) + 0.05, Vec3::UnitY()))
               .toRotationMatrix();
  if (landing == Landing::edge_across_edge) {
    turn = Eigen::AngleAxisd(pi / 4, Vec3::UnitY()).toRotationMatrix();  // an edge along y, down
    d.lower = d.model.add_block(cube.transformed(Eigen::AngleAxisd(pi / 4, Vec3::UnitX()).toRotationMatrix(),
                                                 Vec3(0, 0, -std::sqrt(0.5))),  // an edge along x, up, at z = 0
                                2000, "lower cube", 0, model::Motion::fixed);
  } else {
    d.lower = d.model.add_block(geometry::make_box(Vec3(-3, -3, -0.5), Vec3(3, 3, 0)), 2000, "floor", 0, model::Motion::fixed);
  }
  const auto turned = cube.transformed(turn, Vec3::Zero());
  double lowest = 0;
  for (const auto& v : turned.vertices) lowest = std::min(lowest, v.z());
  d.cube = d.model.add_block(cube.transformed(turn, Vec3(0, 0, drop - lowest)), 2000, "cube", 1);
  d.model.gravity = Vec3(0, 0, -9.81);
  return d;
}

/// A prism 1 m deep along y over a section in the x-z plane (x, z), moved by `shift`.
geometry::ConvexPolyhedron section_prism(const std::vector<Eigen::Vector2d>& section, const Vec3& shift = Vec3::Zero()) {
  std::vector<Vec3> base;
  for (const auto& p : section) base.push_back(Vec3(p.x(), 0, p.y()) + shift);
  return geometry::make_prism(base, Vec3(0, 1, 0));
}

/// Undamped dry joints (no tension, friction 45 deg), stiff: the only losses are slip and what re-detection does.
MC::Parameters dry(double kn = 1e9, double phi_deg = 45) { return MC::Parameters(kn, kn, 0, 0, phi_deg * pi / 180); }
}  // namespace

TEST_CASE("general contacts: a cube on an edge, on a corner and edge across edge gets CPs on the edge, at the corner "
          "and at the crossing, where face-to-face detection finds none") {
  model::ContactSettings general, faces;
  faces.kinds = model::ContactKinds::faces;
  {
    const auto d = cube_drop(Landing::edge, 4e-4);
    const auto c = model::detect_contacts(d.model.bodies, general);
    REQUIRE(c.size() == 2);  // the two ends of the edge, 0.4 mm above the floor
    for (const auto& k : c) {
      CHECK(k.gap == test::approx(4e-4).epsilon(1e-9));
      CHECK((k.normal - Vec3::UnitZ()).norm() < 1e-12);
      CHECK(std::abs(std::abs(k.position.y()) - 0.5) < 1e-9);
      CHECK(k.area > 0);
    }
    CHECK(model::detect_contacts(d.model.bodies, faces).empty());
  }
  {
    const auto d = cube_drop(Landing::corner, 4e-4);
    const auto c = model::detect_contacts(d.model.bodies, general);
    REQUIRE(c.size() == 1);
    CHECK(c[0].gap == test::approx(4e-4).epsilon(1e-9));
    double lowest = 1e9;
    Vec3 corner = Vec3::Zero();
    for (const auto& v : d.model.bodies.world_shape(d.cube).vertices)
      if (v.z() < lowest) lowest = v.z(), corner = v;
    CHECK((c[0].position - corner).head<2>().norm() < 1e-9);
    CHECK(model::detect_contacts(d.model.bodies, faces).empty());
  }
  {
    const auto d = cube_drop(Landing::edge_across_edge, 4e-4);
    const auto c = model::detect_contacts(d.model.bodies, general);
    REQUIRE(c.size() == 1);  // the crossing of the two edges, on the z axis
    CHECK(c[0].gap == test::approx(4e-4).epsilon(1e-9));
    CHECK((c[0].normal - Vec3::UnitZ()).norm() < 1e-9);
    CHECK(c[0].position.head<2>().norm() < 1e-9);
    CHECK(model::detect_contacts(d.model.bodies, faces).empty());
  }
}

TEST_CASE("general contacts: blocks that touch along a line where four joints meet (a groin) get no CPs until one "
          "presses its edge into the other") {
  // In the x-z plane, 1 m deep along y: A left of x = 0 below a face that rises 2 in 1 to the left from the line (the
  // y axis), B right of x = 0 above a level face. Their faces on x = 0 lie in one plane and meet at the line end to
  // end, like the courses of two webs at a groin; B's face there meets A's steep face at 27 deg. Every plane through
  // the line between them has the same gap, up to rounding or the joints' closure as a vault settles.
  const Vec3 n_steep = Vec3(2, 0, 1).normalized();  // A's steep face, outward
  const auto pair = [&](const Vec3& shift) {
    model::Model m;
    m.add_block(section_prism({{-1, -1}, {0, -1}, {0, 0}, {-1, 2}}), 2000, "A", 0, model::Motion::fixed);
    m.add_block(section_prism({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, shift), 2000, "B", 0);
    return m;
  };
  model::ContactSettings general, faces;
  faces.kinds = model::ContactKinds::faces;
  // B 2 um off along the normal of A's steep face: that face's plane has the larger gap (2 um against 1.8 um on
  // x = 0), but the face-to-face plane x = 0, within a hundredth of the tolerance of it, is the common plane, and
  // the faces there only meet at the line: no CP. Edge CPs on A's steep face would tie B to A like a bed joint.
  for (const double opening : {0.0, 2e-6}) {
    const auto m = pair(opening * n_steep);
    CHECK(model::detect_contacts(m.bodies, general).empty());
    CHECK(model::detect_contacts(m.bodies, faces).empty());
  }
  // B pressed into A 0.1 mm to the left and 0.1 mm up: 45 um into the plane of A's steep face and 100 um into the
  // plane x = 0, so the steep face's plane is the common plane by far, and B's edge gets its CPs there.
  const auto pressed = pair(Vec3(-1e-4, 0, 1e-4));
  const auto c = model::detect_contacts(pressed.bodies, general);
  REQUIRE(!c.empty());
  double deepest = 0;
  for (const auto& k : c) {
    CHECK((k.normal - n_steep).norm() < 1e-9);
    CHECK(k.area > 0);
    deepest = std::min(deepest, k.gap);
  }
  CHECK(deepest == test::approx(-1e-4 / std::sqrt(5.0)).epsilon(1e-6));  // B's edge, 45 um into A
  CHECK(model::detect_contacts(pressed.bodies, faces).empty());
}

TEST_CASE("general contacts: blocks that meet edge to edge with a third block between them, face to face with "
          "both, get no CPs (without it, or an edge on a face, they do)") {
  // Three wedges around the y axis in the x-z plane, as blocks of neighbouring webs meet at a vault's crown line: A
  // from 90 to 135 deg, C from 45 to 90 deg, B from 0 to 45 deg. A and B touch along the axis only, an edge of each,
  // with no face-to-face plane between them (A's face on x = 0 meets B's diagonal face at 45 deg); C fills the wedge
  // between them and meets both face to face, and carries what passes there.
  const auto a = section_prism({{0, 0}, {0, 1}, {-1, 1}});
  const auto c = section_prism({{0, 0}, {1, 1}, {0, 1}});
  const auto b = section_prism({{0, 0}, {1, 0}, {1, 1}});
  model::ContactSettings general;
  const auto pairs = [&](bool with_c) {
    model::Model m;
    m.add_block(a, 2000, "A", 0);
    m.add_block(b, 2000, "B", 0, model::Motion::fixed);
    if (with_c) m.add_block(c, 2000, "C", 0);
    std::set<std::pair<std::size_t, std::size_t>> found;
    for (const auto& k : model::detect_contacts(m.bodies, general)) found.insert({k.a, k.b});
    return found;
  };
  const std::set<std::pair<std::size_t, std::size_t>> with_c{{0, 2}, {1, 2}};  // A-C and B-C, not A-B
  CHECK(pairs(true) == with_c);
  const std::set<std::pair<std::size_t, std::size_t>> alone{{0, 1}};  // A and B alone: their edges' contact
  CHECK(pairs(false) == alone);
}

TEST_CASE("general contacts: a cube dropped on an edge, on a corner and edge across edge neither passes into what it "
          "lands on nor makes energy") {
  // Reference: energy conservation, kinetic + elastic + slip = work of gravity, with the energy that re-detection
  // adds or removes counted as error (not as a term), over 0.5 s: the 5 cm drop, the impact and the bounces after.
  // Measured: edge 0.10 %, corner 0.59 % (it tumbles off its corner, 80 J of slip), edge across edge 0.007 %;
  // deepest overlap 2.3, 3.3 and 5.9 mm.
  for (const Landing landing : {Landing::edge, Landing::corner, Landing::edge_across_edge}) {
    CAPTURE(static_cast<int>(landing));
    auto d = cube_drop(landing, 0.05);
    Simulation<damping::None, MC> sim(d.model, damping::None{}, [](int, int) { return dry(); });
    const double scale = d.model.bodies.mass[d.cube] * 9.81 * 0.05;  // J, the drop's potential energy
    double deepest = 0, worst = 0, fell = 0;
    for (int k = 0; sim.time() < 0.5; ++k) {
      sim.step();
      if (k % 5) continue;
      fell = std::max(fell, sim.energy().gravity_work);
      deepest = std::max(deepest, -geometry::separation(d.model.bodies.world_shape(d.lower), d.model.bodies.world_shape(d.cube)));
      const auto e = sim.energy();
      worst = std::max(worst, std::abs(e.kinetic + e.elastic + e.slip - e.gravity_work));
    }
    CHECK(fell > 0.9 * scale);  // it fell
    CHECK(deepest < 0.01);                           // 1 % of its size
    CHECK(deepest > 1e-4);                           // it did land
    CHECK(worst < 0.01 * scale);
  }
}

namespace {
/// The block of the 3DEC verification after Wyllie and Mah: 10 m wide (down the slope), `height` m high, 2 m deep,
/// 2000 kg/m^3 on a plane inclined at 40 degrees (gravity 10 m/s^2 turned by 40 degrees), joints k_n = k_s = 10 MPa/m
/// without cohesion or tension. The plane runs 300 m down the slope.
struct Slope {
  model::Model model;
  std::size_t block = 0;
  model::ContactSettings contacts;
};

Slope block_on_slope(double height) {
  Slope s;
  const double slope = 40 * pi / 180;
  s.model.add_block(geometry::make_box(Vec3(-20, -5, -5), Vec3(300, 5, 0)), 2000, "slope", 0, model::Motion::fixed);
  s.block = s.model.add_block(geometry::make_box(Vec3(0, -1, 0), Vec3(10, 1, height)), 2000, "block", 1);
  s.model.gravity = 10 * Vec3(std::sin(slope), 0, -std::cos(slope));
  // The soft joints overlap by centimetres under a 25 m block on its edge: a tolerance of 5 cm (0.5 % of the width)
  // keeps its contact through the rotation, and steps of 1 ms move it less than that at 30 m/s.
  s.contacts.tolerance = 0.05;
  return s;
}
}  // namespace

TEST_CASE("general contacts: the Wyllie and Mah block on a 40 degree slope stands at h = 10 m with 40.1 deg, slides at "
          "h = 5 m with 20 deg, topples at h = 25 m with 40 deg and goes on toppling down the slope") {
  const double g = 10, slope = 40 * pi / 180;
  SUBCASE("stable: b/h = 1 > tan 40 (no toppling), tan 40.1 > tan 40 (no sliding); at 39.9 deg it slides") {
    for (const double phi : {40.1, 39.9}) {
      CAPTURE(phi);
      auto s = block_on_slope(10);
      Simulation<damping::Local, MC> sim(s.model, damping::Local{}, [=](int, int) { return dry(1e7, phi); }, s.contacts);
      const Vec3 x0 = s.model.bodies.position[s.block];
      const bool settled = sim.solve_to_equilibrium(1e-6, 5000);
      const double moved = (s.model.bodies.position[s.block] - x0).norm();
      MESSAGE("phi ", phi, ": settled ", settled, ", moved ", moved, " m");
      CHECK(settled == (phi > 40));
      CHECK((phi > 40 ? moved < 0.2 : moved > 1.0));  // 40.1: the joint's elastic overlap and a short slip
    }
  }
  SUBCASE("sliding: b/h = 2, tan 20 < tan 40: it slides at g (sin 40 - cos 40 tan 20) = 3.640 m/s^2, unturned") {
    // Measured: 16.396 m in 3 s against 16.389 m (+0.04 %).
    auto s = block_on_slope(5);
    Simulation<damping::None, MC> sim(s.model, damping::None{}, [](int, int) { return dry(1e7, 20); }, s.contacts);
    sim.set_timestep(1e-3);
    const Vec3 x0 = s.model.bodies.position[s.block];
    const Quaternion q0 = s.model.bodies.orientation[s.block];
    while (sim.time() < 3.0) sim.step();
    const double a = g * (std::sin(slope) - std::cos(slope) * std::tan(20 * pi / 180));
    CHECK((s.model.bodies.position[s.block] - x0).x() == test::approx(0.5 * a * sim.time() * sim.time()).epsilon(0.01));
    CHECK(s.model.bodies.orientation[s.block].angularDistance(q0) < 0.01);
  }
  SUBCASE("toppling: b/h = 0.4 < tan 40: it turns over its lower edge onto its side, and on down the slope") {
    auto s = block_on_slope(25);
    Simulation<damping::None, MC> sim(s.model, damping::None{}, [](int, int) { return dry(1e7, 40); }, s.contacts);
    sim.set_timestep(1e-3);
    const Vec3 x0 = s.model.bodies.position[s.block];
    const Quaternion q0 = s.model.bodies.orientation[s.block];
    double turned = 0, deepest = 0, balance = 0;
    int lost = 0;
    for (int k = 0; sim.time() < 12.0; ++k) {
      sim.step();
      if (k % 10) continue;
      const Quaternion q = s.model.bodies.orientation[s.block] * q0.conjugate();
      turned = std::max(turned, std::abs(2 * std::atan2(q.y(), q.w())));
      const double separation = geometry::separation(s.model.bodies.world_shape(0), s.model.bodies.world_shape(s.block));
      deepest = std::max(deepest, -separation);
      lost += separation < 0 && sim.contact_points() == 0;  // overlapping the slope with no contact: fell through
      balance = std::max(balance, sim.energy().balance_error);
    }
    CHECK(turned > pi / 2);  // over onto its side, and beyond
    CHECK((s.model.bodies.position[s.block] - x0).x() > 50);  // down the slope
    CHECK(lost == 0);
    // The soft joints' overlap where the 25 m block lands on its side at ~13 m/s: its kinetic energy (1.6e8 J)
    // into springs of 10 MPa/m over its 25 x 2 m face gives sqrt(2 E / (k A)) = 0.8 m. Measured 0.92 m; it turns
    // 198 degrees and goes 103 m down the slope in 12 s, the energy balance within 1.6e-4.
    CHECK(deepest < 1.0);
    CHECK(balance < 1e-3);
  }
}

TEST_CASE("general contacts: a stocky block (b/h = 1) rocked to 30 degrees keeps its contact and its impact follows "
          "Housner's restitution 1 - 1.5 sin^2(alpha) = 0.25") {
  // Housner's impact is inelastic, about the new edge, without sliding: a friction angle of 80 degrees, and dashpots
  // in the joint's springs. Their ratio, 4 x critical of the block bouncing on its base, is CALIBRATED to Housner's
  // value at the default timestep: the match tests that the impact is resolved about the new edge, not the damping.
  // Measured: 29.4 deg, 0.2533 (1.3 % above 0.25); 0.283 with dashpots at 2 x critical. At 0.03 of the default
  // timestep the same dashpots give 0.243 and 0.253: part of the default's figure is the timestep's error (the tests
  // below). The undamped springs are checked against an independent model below.
  analysis::RockingOptions o;
  o.width = 1;
  o.depth = 0.5;
  o.height = 1;
  o.friction_angle_deg = 80;
  o.contact_damping_ratio = 4;
  o.duration = 2.0;
  motion::Record pulse;  // a half-sine base acceleration of 2.35 g over 0.3 s
  pulse.dt = 1e-3;
  for (int i = 0; i <= 300; ++i) pulse.acceleration.push_back(2.35 * 9.81 * std::sin(pi * i / 300.0));
  o.base_acceleration = pulse;
  const auto r = analysis::analyse_rocking(o);
  CHECK(r.max_rotation * 180 / pi == doctest::Approx(30).epsilon(0.1));
  CHECK_FALSE(r.overturned);
  CHECK(r.max_penetration < 0.01);  // 1 % of its size
  REQUIRE(!r.restitution.empty());
  CHECK(r.housner_restitution == test::approx(0.25));
  CHECK(r.restitution.front() == test::approx(r.housner_restitution).epsilon(0.1));
}

namespace {

/// The half-sine base acceleration of the Housner test above: 2.35 g over 0.3 s, sampled at 1 ms.
std::vector<double> housner_pulse() {
  std::vector<double> a;
  for (int i = 0; i <= 300; ++i) a.push_back(2.35 * 9.81 * std::sin(pi * i / 300.0));
  return a;
}

/// The stocky block of the Housner test above, undamped, at `factor` of the default timestep.
analysis::RockingResult stocky_block(double factor) {
  analysis::RockingOptions o;
  o.width = 1;
  o.depth = 0.5;
  o.height = 1;
  o.friction_angle_deg = 80;
  o.duration = 2.0;
  o.timestep_factor = factor;
  o.base_acceleration.dt = 1e-3;
  o.base_acceleration.acceleration = housner_pulse();
  return analysis::analyse_rocking(o);
}

/// The independent reference of the same block (tests/integrate/rocking_reference.hpp: two corner springs with
/// Coulomb friction, Boost.Odeint's Runge-Kutta at 1e-6 s, none of the DEM's detection, joint law or central
/// differences).
test::RockingReference::Result stocky_reference() {
  test::RockingReference ref;
  ref.base_acceleration = housner_pulse();
  return ref.run();
}

/// The DEM's largest rotation within 0.1 % of the reference's, its first restitution within `restitution_tolerance`.
void check_against_reference(double factor, double restitution_tolerance) {
  const auto dem = stocky_block(factor);
  const auto exact = stocky_reference();
  REQUIRE(!exact.restitution.empty());
  REQUIRE(!dem.restitution.empty());
  MESSAGE("timestep " << dem.timestep << " s: largest rotation DEM " << dem.max_rotation << " rad, reference "
          << exact.max_rotation << " rad; first restitution DEM " << dem.restitution.front() << ", reference "
          << exact.restitution.front());
  CHECK(dem.max_rotation == test::approx(exact.max_rotation).epsilon(1e-3));
  CHECK(dem.restitution.front() == test::approx(exact.restitution.front()).epsilon(restitution_tolerance));
}

}  // namespace

TEST_CASE("general contacts: at a timestep that resolves the impact, the stocky block's undamped rocking and landing "
          "match an independent ODE of the same block on its springs") {
  // Measured at 0.03 of the default timestep (2.6e-5 s): largest rotation 0.518434 against 0.518606 rad, restitution
  // 0.1843 against 0.1826 (the reference converged to 4 digits between 4e-6 and 1e-6 s; the DEM between 0.1 and 0.01
  // of its default: 0.1846, 0.1843, 0.1842). The DEM's four contact points are the reference's two edges.
  check_against_reference(0.03, 0.02);
}

TEST_CASE("general contacts: from 0.4 to 1 of the default timestep the stocky block's undamped landing never gives "
          "back more than it came with, and its median restitution is the ODE's within 20 %") {
  // At the default timestep the landing edge's springs are resolved by about two steps, and how the landing shares its
  // energy between the rocking and the block's bounce on its springs (both undamped, in the DEM and in the reference)
  // turns on where the steps fall: the first restitution is ill-conditioned more than biased. Measured over these 61
  // fractions: median 0.212 against the reference's 0.183 (16 % above); 55 in 0.167-0.323; four of 0.70-0.95 (at 0.77,
  // 0.88, 0.96 and 1 of the default); two landings below about 0.165, whose rebound stays under the 0.01 rad where the
  // restitution is measured. The largest rotation before the landing is right at every fraction (0.03 %, checked to
  // 0.1 %); at 0.03 of the default the landing converges (the test above). Studies of rocking and overturning without
  // damping want half the timestep or less (docs/rocking_block.md).
  const auto exact = stocky_reference();
  REQUIRE(!exact.restitution.empty());
  std::vector<double> restitution;
  for (int i = 0; i <= 60; ++i) {
    const auto dem = stocky_block(0.4 + 0.01 * i);
    CHECK(dem.max_rotation == test::approx(exact.max_rotation).epsilon(1e-3));
    if (!dem.restitution.empty()) restitution.push_back(dem.restitution.front());
  }
  const double e = exact.restitution.front();
  REQUIRE(restitution.size() >= 55);
  std::sort(restitution.begin(), restitution.end());
  MESSAGE(restitution.size() << " landings measured: smallest " << restitution.front() << ", median "
          << restitution[restitution.size() / 2] << ", largest " << restitution.back() << "; reference " << e);
  CHECK(restitution.back() <= 1.0);
  CHECK(restitution[restitution.size() / 2] == test::approx(e).epsilon(0.2));
  CHECK(std::count_if(restitution.begin(), restitution.end(), [&](double x) { return x > 2 * e; }) <= 6);
}

TEST_CASE("general contacts: a block turned past 20 degrees on its edge keeps its edge's contact points and their "
          "histories (face-face to edge-face), which face-to-face detection loses") {
  for (const auto kinds : {model::ContactKinds::general, model::ContactKinds::faces}) {
    CAPTURE(static_cast<int>(kinds));
    model::Model m;
    m.add_block(geometry::make_box(Vec3(-3, -1, -0.5), Vec3(3, 1, 0)), 2000, "base", 0, model::Motion::fixed);
    // A 1 x 0.5 x 1 m block leaning 18 degrees on its edge x = 0, z = 0 (0.1 mm into the base).
    const Mat3 lean = Eigen::AngleAxisd(18 * pi / 180, Vec3::UnitY()).toRotationMatrix();
    const auto block = m.add_block(geometry::make_box(Vec3(-1, -0.25, 0), Vec3(0, 0.25, 1)).transformed(lean, Vec3(0, 0, -1e-4)),
                                   2000, "block", 1);
    m.gravity = Vec3::Zero();
    model::ContactSettings settings;
    settings.kinds = kinds;
    Simulation<damping::None, MC> sim(m, damping::None{}, [](int, int) { return dry(); }, settings);
    REQUIRE(sim.contact_points() == 2);
    // Shear the edge's joint a little: the block moves 2 x 0.2 um along x.
    m.bodies.velocity[block] = Vec3(0.01, 0, 0);
    const double dt = 2e-5;
    sim.set_timestep(dt);
    sim.step();
    sim.step();
    m.bodies.velocity[block] = Vec3::Zero();
    sim.synchronize();
    std::vector<ContactView> before, after;
    sim.visit_contacts([&](const ContactView& v) { before.push_back(v); });
    REQUIRE(before.size() == 2);
    CHECK(before[0].shear_stress > 100);  // Pa: k_s times the slip of the step
    // Turn it 5 degrees further about that edge, to 23 degrees, and detect again.
    const Quaternion turn(Eigen::AngleAxisd(5 * pi / 180, Vec3::UnitY()));
    const Vec3 pivot(before[0].position.x(), 0, before[0].position.z());
    m.bodies.orientation[block] = (turn * m.bodies.orientation[block]).normalized();
    m.bodies.rotation[block] = rotation_matrix(m.bodies.orientation[block]);
    m.bodies.position[block] = pivot + turn * (m.bodies.position[block] - pivot);
    sim.redetect();
    sim.visit_contacts([&](const ContactView& v) { after.push_back(v); });
    if (kinds == model::ContactKinds::faces) {
      CHECK(after.empty());  // 23 degrees between the faces: no face-to-face contact
      continue;
    }
    REQUIRE(after.size() == 2);
    for (const auto& v : before) {
      const auto& w = (after[0].position - v.position).norm() < (after[1].position - v.position).norm() ? after[0] : after[1];
      CHECK((w.position - v.position).norm() < 1e-5);  // at the same place on the edge (turned about the CP, 50 um off it)
      CHECK(w.shear_stress == test::approx(v.shear_stress).epsilon(1e-9));
      CHECK(w.normal_stress == test::approx(v.normal_stress).epsilon(1e-9));
      CHECK_FALSE(w.never_bonded);
    }
  }
}

}  // namespace test_general_contacts
