// The run guard (integrate/run_guard.hpp): a run that diverges or throws a block off stops with RunawayError naming
// the block or node, the time and the value, within a few hundred steps; a sound run is never stopped.

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "fixtures.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_run_guard {

namespace {

using Sim = Simulation<damping::None, contact::MohrCoulomb>;

/// A stiff joint whose strengths are far above any stress here: elastic in shear.
Sim::PropertyFunction stiff_joint() {
  return [](int, int) { return contact::MohrCoulomb::Parameters(1e10, 1e10, 1e12, 1e12, 0.6); };
}

/// Steps until RunawayError or `steps`; returns the steps taken before the error (or -1) and its message.
std::pair<long long, std::string> run_until_stopped(Sim& sim, long long steps) {
  for (long long i = 0; i < steps; ++i) {
    try {
      sim.step();
    } catch (const RunawayError& e) {
      return {sim.steps(), e.what()};
    }
  }
  return {-1, {}};
}

}  // namespace

/// A block that slides on the base's shear springs only (x and y free), nudged along x.
test::BlockOnBase sliding_block() {
  auto s = test::block_on_base(1, 1, 1);
  s.model.bodies.fixity[s.block] = model::Fixity::translation_z | model::Fixity::all_rotations;
  s.model.bodies.velocity[s.block] = Vec3(1e-3, 0, 0);
  return s;
}

TEST_CASE("run guard: a timestep forced to 1.5 times the critical one is stopped within a few hundred steps") {
  auto s = sliding_block();
  Sim sim(s.model, damping::None{}, stiff_joint());
  sim.set_timestep(1.5 * sim.critical_timestep(), TimestepCheck::unchecked);
  const auto [steps, message_] = run_until_stopped(sim, 5000);
  const std::string& message = message_;  // (a name a lambda can capture: CAPTURE below)
  CAPTURE(message);
  CHECK(steps > 0);
  CHECK(steps <= 300);
  CHECK(message.find("block 'block' (1)") != std::string::npos);
  CHECK(message.find("the run diverged") != std::string::npos);
  CHECK(message.find("t = ") == 0);
}

TEST_CASE("run guard: the same block at 0.9 times the critical timestep runs on") {
  auto s = sliding_block();
  Sim sim(s.model, damping::None{}, stiff_joint());
  sim.set_timestep(0.9 * sim.critical_timestep());
  CHECK(run_until_stopped(sim, 5000).first == -1);
}

TEST_CASE("run guard: a block thrown at 150 m/s is stopped at the next check, with its speed") {
  auto s = test::block_on_base(1, 1, 1);
  s.model.bodies.position[s.block].z() += 0.5;  // in flight, clear of the base
  s.model.bodies.velocity[s.block] = Vec3(0, 0, 150);
  Sim sim(s.model, damping::None{}, stiff_joint());
  const auto [steps, message_] = run_until_stopped(sim, 100);
  const std::string& message = message_;  // (a name a lambda can capture: CAPTURE below)
  CAPTURE(message);
  CHECK(steps == sim.run_guard().check_interval);
  CHECK(message.find("block 'block' (1) moves at 150 m/s (velocity), beyond 100 m/s") != std::string::npos);
  // A bound raised past it lets it fly.
  auto t = test::block_on_base(1, 1, 1);
  t.model.bodies.position[t.block].z() += 0.5;
  t.model.bodies.velocity[t.block] = Vec3(0, 0, 150);
  Sim free_flight(t.model, damping::None{}, stiff_joint());
  free_flight.set_run_guard(RunGuard{200, 1});
  CHECK(run_until_stopped(free_flight, 100).first == -1);
}

TEST_CASE("run guard: a node whose velocity is not finite is named with its block") {
  auto s = test::block_on_base(1, 1, 1);
  s.model.make_deformable(s.block, 0.5, model::IsotropicElastic(30e9, 0.2));
  Sim sim(s.model, damping::None{}, stiff_joint());
  s.model.deformable.nodes.velocity[3] = Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  const auto [steps, message_] = run_until_stopped(sim, 100);
  const std::string& message = message_;  // (a name a lambda can capture: CAPTURE below)
  CAPTURE(message);
  CHECK(steps > 0);
  CHECK(message.find("of block 'block'") != std::string::npos);
  CHECK(message.find("node ") != std::string::npos);
}

TEST_CASE("run guard: bad bounds name the field and its range") {
  auto s = test::block_on_base(1, 1, 1);
  Sim sim(s.model, damping::None{}, stiff_joint());
  CHECK_THROWS_WITH_AS(sim.set_run_guard(RunGuard{0, 16}), doctest::Contains("max speed must be > 0 m/s"), InvalidArgument);
  CHECK_THROWS_WITH_AS(sim.set_run_guard(RunGuard{100, 0}), doctest::Contains("check interval must be in 1..1000000"),
                       InvalidArgument);
}

TEST_CASE("run guard: a block that sinks into a joint far too soft for it stops at a quarter of the contact's size") {
  auto s = test::block_on_base(1, 1, 1);
  s.model.bodies.velocity[s.block] = Vec3(0, 0, -1);
  Sim sim(s.model, damping::None{}, [](int, int) { return contact::MohrCoulomb::Parameters(1e3, 1e3, 1e12, 1e12, 0.6); });
  sim.set_timestep(1e-3);
  const auto [steps, message_] = run_until_stopped(sim, 2000);
  const std::string& message = message_;  // (a name a lambda can capture: CAPTURE below)
  CAPTURE(message);
  // 1 m/s into a 1 m x 1 m joint whose springs (250 N at 0.25 m) hardly hold its weight (19.6 kN): the block falls
  // freely, d = t + g t^2 / 2, and is 0.25 m deep at t = (sqrt(1 + 2 g 0.25) - 1) / g = 0.146 s; caught at the next
  // check, at most 16 steps later.
  CHECK(steps > 0);
  const double g = s.model.gravity.norm(), deep = (std::sqrt(1 + 2 * g * 0.25) - 1) / g;
  CHECK(sim.time() >= deep);
  CHECK(sim.time() <= deep + 16.5e-3);
  CHECK(message.find("contact point") != std::string::npos);
  CHECK(message.find("block 'block' (1)") != std::string::npos);
  CHECK(message.find("(normal displacement), deeper than 0.25 times its contact's size") != std::string::npos);
}

TEST_CASE("run guard: a stress that is not finite in an element is named with its component and block") {
  auto s = test::block_on_base(1, 1, 1);
  s.model.make_deformable(s.block, 0.5, model::IsotropicElastic(30e9, 0.2));
  Sim sim(s.model, damping::None{}, stiff_joint());
  sim.set_run_guard(RunGuard{100, 1});
  s.model.deformable.tetrahedra.stress[2][3] = std::numeric_limits<double>::quiet_NaN();
  const auto [steps, message_] = run_until_stopped(sim, 100);
  const std::string& message = message_;  // (a name a lambda can capture: CAPTURE below)
  CAPTURE(message);
  CHECK(steps == 1);
  CHECK(message.find("is not finite") != std::string::npos);
  CHECK(message.find("also: the stress sigma_xy of tetrahedron 2 of block 'block' (1) is not finite") != std::string::npos);
}

TEST_CASE("run guard: a joint traction that is not finite is traced to its contact point and component") {
  auto s = sliding_block();
  Sim sim(s.model, damping::None{}, stiff_joint());
  sim.set_run_guard(RunGuard{100, 1});
  auto& g = sim.group<contact::MohrCoulomb>();
  REQUIRE(g.size() > 2);
  g.history[2].shear[1] = std::numeric_limits<double>::quiet_NaN();
  const auto [steps, message_] = run_until_stopped(sim, 100);
  const std::string& message = message_;  // (a name a lambda can capture: CAPTURE below)
  CAPTURE(message);
  CHECK(steps == 1);
  CHECK(message.find("velocity of block 'block' (1) is not finite") != std::string::npos);
  CHECK(message.find("also: the shear stress 2 of contact point 2 between block") != std::string::npos);
}

TEST_CASE("run guard: the overlap bound is checked") {
  auto s = test::block_on_base(1, 1, 1);
  Sim sim(s.model, damping::None{}, stiff_joint());
  CHECK_THROWS_WITH_AS(sim.set_run_guard(RunGuard{100, 16, 0}), doctest::Contains("max overlap must be in (0, 10]"),
                       InvalidArgument);
}

}  // namespace test_run_guard
