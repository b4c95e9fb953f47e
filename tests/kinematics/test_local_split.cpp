// Local damping of deformable blocks split into rigid-body motion and deformation (damping::Local with
// split_rigid_motion, integrate/local_split.hpp).

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <string>

#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/integrate/local_split.hpp"
#include "blockdem/integrate/simulation.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_local_split {

/// A block of width w and height h (depth 0.2 m) on a fixed base, deformable (20 GPa) or rigid, settled, then under
/// gravity tilted to tan(theta) = ratio for `duration` s from rest; returns the horizontal displacement of its
/// centre of mass, m.
double drift(bool deformable, bool split, double w, double h, double friction_deg, double ratio, double duration) {
  model::Model m;
  m.add_block(geometry::make_box(Vec3(-1, -0.5, -0.2), Vec3(1, 0.5, 0)), 2000, "base", 0, model::Motion::fixed);
  const auto block = m.add_block(geometry::make_box(Vec3(-0.5 * w, -0.1, 0), Vec3(0.5 * w, 0.1, h)), 2000, "block", 1);
  if (deformable) m.make_deformable(block, 0.1, model::IsotropicElastic(20e9, 0.2));
  const contact::MohrCoulomb::Parameters joint(1e10, 1e10, 0, 0, friction_deg * pi / 180);
  damping::Local local;
  local.split_rigid_motion = split;
  Simulation<damping::Local, contact::MohrCoulomb> sim(m, local, [&](int, int) { return joint; });
  REQUIRE(sim.solve_to_equilibrium(1e-6, 50000));
  const auto& nd = m.deformable.nodes;
  auto centre = [&] {
    if (!deformable) return m.bodies.position[block].x();
    double mass = 0, moment = 0;
    for (std::size_t i = 0; i < nd.size(); ++i) {
      mass += nd.mass[i];
      moment += nd.mass[i] * nd.position[i].x();
    }
    return moment / mass;
  };
  const double x0 = centre(), t0 = sim.time();
  m.gravity = 9.81 / std::sqrt(1 + ratio * ratio) * Vec3(ratio, 0, -1);
  while (sim.time() - t0 < duration) sim.step();
  return centre() - x0;
}

}  // namespace test_local_split

TEST_CASE("split local damping: a deformable block slides as a rigid one, 0.5 (1 - c) a t^2 (2 %)") {
  using namespace test_local_split;
  // Sliding: a = g (sin theta - mu cos theta); local damping takes c of the force while force and velocity agree,
  // so the block accelerates at (1 - c) a.
  const double mu = std::tan(20 * pi / 180), r = 2 * mu, g = 9.81 / std::sqrt(1 + r * r);
  const double expected = 0.5 * (1 - 0.8) * (g * r - mu * g) * 0.1 * 0.1;
  const double rigid = drift(false, true, 0.2, 0.2, 20, r, 0.1), split = drift(true, true, 0.2, 0.2, 20, r, 0.1);
  const double nodal = drift(true, false, 0.2, 0.2, 20, r, 0.1);
  MESSAGE("slide in 0.1 s: expected " << expected << " m, rigid " << rigid << ", deformable split " << split
          << ", deformable nodal " << nodal);
  CHECK(rigid == doctest::Approx(expected).epsilon(0.02));
  CHECK(split == doctest::Approx(expected).epsilon(0.02));
}

TEST_CASE("split local damping: its resultant and moment are the rigid block's damping, and it never adds energy") {
  model::Model m;
  const auto block = m.add_block(geometry::make_box(Vec3(0, 0, 0), Vec3(0.3, 0.2, 0.5)), 2000, "block", 0);
  m.make_deformable(block, 0.1, model::IsotropicElastic(10e9, 0.2));
  auto& nd = m.deformable.nodes;
  const auto& blk = m.deformable.blocks.front();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const double c = 0.8;
  for (int trial = 0; trial < 20; ++trial) {
    // A rigid motion plus noise in both the velocities and the forces.
    const Vec3 V(u(random), u(random), u(random)), W(u(random), u(random), u(random));
    for (std::uint32_t i = blk.first_node; i < blk.end_node; ++i) {
      nd.velocity[i] = V + W.cross(nd.position[i]) + 0.3 * Vec3(u(random), u(random), u(random));
      nd.force[i] = 100 * Vec3(u(random), u(random), u(random));
    }
    detail::SplitLocalDamping s;
    REQUIRE(detail::split_local_damping(blk, nd, c, s));
    // Independently: the block's resultant, moment, velocity and angular velocity about the centre of mass.
    double mass = 0;
    Vec3 centre = Vec3::Zero(), momentum = Vec3::Zero(), force = Vec3::Zero();
    for (std::uint32_t i = blk.first_node; i < blk.end_node; ++i) {
      mass += nd.mass[i];
      centre += nd.mass[i] * nd.position[i];
      momentum += nd.mass[i] * nd.velocity[i];
      force += nd.force[i];
    }
    centre /= mass;
    Mat3 inertia = Mat3::Zero();
    Vec3 angular_momentum = Vec3::Zero(), moment = Vec3::Zero(), d_sum = Vec3::Zero(), d_moment = Vec3::Zero();
    double power = 0, deformation_power = 0;
    for (std::uint32_t i = blk.first_node; i < blk.end_node; ++i) {
      const Vec3 r = nd.position[i] - centre;
      inertia += nd.mass[i] * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
      angular_momentum += nd.mass[i] * r.cross(nd.velocity[i]);
      moment += r.cross(nd.force[i]);
    }
    const Vec3 velocity = momentum / mass, omega = inertia.inverse() * angular_momentum;
    for (std::uint32_t i = blk.first_node; i < blk.end_node; ++i) {
      const Vec3 r = nd.position[i] - centre, d = s.force(nd, i);
      d_sum += d;
      d_moment += r.cross(d);
      power += d.dot(nd.velocity[i]);
      deformation_power += s.deformation(nd, i).dot(nd.velocity[i] - velocity - omega.cross(r));
    }
    const Vec3 rigid = detail::local_damping_force(c, force, velocity), turning = detail::local_damping_force(c, moment, omega);
    for (int k = 0; k < 3; ++k) {
      CHECK(d_sum[k] == doctest::Approx(rigid[k]).epsilon(1e-9).scale(force.norm()));
      CHECK(d_moment[k] == doctest::Approx(turning[k]).epsilon(1e-9).scale(moment.norm()));
    }
    CHECK(deformation_power <= 0);
    CHECK(power == doctest::Approx(rigid.dot(velocity) + turning.dot(omega) + deformation_power).epsilon(1e-9));
    CHECK(power <= 0);
  }
}
