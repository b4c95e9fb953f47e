// Results do not depend on the number of threads: forces are gathered per block in a fixed order (no atomics).

#include <doctest/doctest.h>

#include <vector>

#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/damping/maxwell_fit.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "../threads.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_threads {

namespace {
std::vector<Vec3> run_wall(int courses, int units, int steps) {
  model::Model m;
  for (const auto& b : geometry::running_bond_wall(courses, units, 0.24, 0.12, 0.055))
    m.add_block(b.shape, 1800, b.name, 0, b.support ? model::Motion::fixed : model::Motion::free);
  m.gravity = Vec3(2.0, 0, -9.81);  // a horizontal push so that blocks slide and rock
  damping::MaxwellFitOptions o;
  Simulation<damping::Maxwell<3>, contact::MohrCoulomb> sim(m, damping::to_policy<3>(damping::fit_maxwell(o)), [](int, int) {
    return contact::MohrCoulomb::Parameters(1e9, 4e8, 0, 0, 0.5);
  });
  for (int i = 0; i < steps; ++i) sim.step();
  std::vector<Vec3> out = m.bodies.position;
  for (const auto& w : m.bodies.angular_velocity) out.push_back(w);
  return out;
}
}  // namespace

TEST_CASE("threads: one and two threads give bitwise identical results") {
  CHECK(test::differences_between_one_and_two_threads([] { return run_wall(12, 20, 300); }) == 0);
}

TEST_CASE("threads: bitwise identical also when the block loops run in parallel (more than 1024 blocks)") {
  CHECK(test::differences_between_one_and_two_threads([] { return run_wall(22, 50, 100); }) == 0);
}

}  // namespace test_threads
