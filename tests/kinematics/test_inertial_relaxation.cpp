// Inertial relaxation (integrate/inertial_relaxation.hpp): the static equilibrium of local damping and of the
// analytical solution, on deformable and rigid blocks, independent of the threads.

#include <doctest/doctest.h>

#include "../integrate/fixtures.hpp"
#include "../threads.hpp"

#include <cmath>
#include <vector>

#include "blockdem/contact/elastic.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/integrate/inertial_relaxation.hpp"
#include "blockdem/integrate/simulation.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_inertial_relaxation {

using Settle = Simulation<damping::Local, contact::Elastic>;

struct Relaxed {
  bool converged = false;
  long long steps = 0, restarts = 0;
  std::vector<double> state;  // node and block positions, then block orientations
};

/// Steps `sim` (static masses) to `tolerance` by inertial relaxation (local damping's coefficient 0) or local damping.
Relaxed relax(Settle& sim, model::Model& m, bool inertial, double tolerance, long long max_steps) {
  sim.scale_masses_for_statics(sim.estimate_safety_factor * 2 / sim.estimated_omega_max());
  InertialRelaxation relaxation;
  Relaxed r;
  for (long long n = 0; n < max_steps && !r.converged; ++n) {
    sim.step();
    if (inertial) relaxation.after_step(m, sim.timestep());
    if (n % 10 == 9) r.converged = sim.unbalanced_force_ratio() <= tolerance;
    r.steps = n + 1;
  }
  r.restarts = relaxation.restarts();
  for (const auto& x : m.deformable.nodes.position) r.state.insert(r.state.end(), x.data(), x.data() + 3);
  for (const auto& x : m.bodies.position) r.state.insert(r.state.end(), x.data(), x.data() + 3);
  for (const auto& q : m.bodies.orientation) r.state.insert(r.state.end(), {q.w(), q.x(), q.y(), q.z()});
  return r;
}

damping::Local local_damping(bool inertial) {
  damping::Local d;
  if (inertial) d.coefficient = 0;
  return d;
}

TEST_CASE("inertial relaxation: a deformable column settles as rho g H^2 / (2E) + rho g H / kn (1 %), as under local damping") {
  // A 0.4 x 0.4 x 2 m column (E 1 GPa, nu 0: uniaxial stress) on a fixed base, joint kn 1e10 Pa/m: its top sinks
  // 3.924e-5 m in itself and 3.92e-6 m on the joint. Tetrahedra of 0.2 m.
  const double rho = 2000, height = 2, young = 1e9, kn = 1e10, g = 9.81;
  const auto column = [&](bool inertial) {
    model::Model m;
    m.add_block(geometry::make_box(Vec3(-1, -1, -0.5), Vec3(1, 1, 0)), rho, "base", 0, model::Motion::fixed);
    const auto d = m.add_block(geometry::make_box(Vec3(-0.2, -0.2, 0), Vec3(0.2, 0.2, height)), rho, "column", 1);
    m.make_deformable(d, 0.2, model::IsotropicElastic(young, 0.0));
    model::ContactSettings contacts;
    contacts.tolerance = 0.01;
    Settle sim(m, local_damping(inertial), [&](int, int) { return contact::Elastic::Parameters(kn, 0.4 * kn); }, contacts);
    const auto before = m.deformable.nodes.position;
    const auto r = relax(sim, m, inertial, 1e-6, 100000);
    double sink = 0;
    int top = 0;
    for (std::size_t i = 0; i < before.size(); ++i)
      if (before[i].z() > height - 1e-9) {
        sink += before[i].z() - m.deformable.nodes.position[i].z();
        ++top;
      }
    return std::pair{r, sink / top};
  };
  const double expected = rho * g * height * height / (2 * young) + rho * g * height / kn;
  const auto [inertial, inertial_sink] = column(true);
  const auto [local, local_sink] = column(false);
  MESSAGE("column to 1e-6: inertial relaxation " << inertial.steps << " steps (" << inertial.restarts << " stops), local damping "
                                                  << local.steps << "; top sinks " << inertial_sink << " and " << local_sink
                                                  << " m, expected " << expected);
  REQUIRE(inertial.converged);
  REQUIRE(local.converged);
  CHECK(inertial.restarts > 0);
  CHECK(inertial_sink == doctest::Approx(expected).epsilon(0.01));
  CHECK(inertial_sink == doctest::Approx(local_sink).epsilon(1e-4));
}

TEST_CASE("inertial relaxation: a deformable block, a rigid block off centre on it and a rigid pillar come to local damping's rest") {
  // The model of the static mass scaling test (test_deformable.cpp): rotations take part too.
  const auto settle = [](bool inertial) {
    model::Model m = test::deformable_block_with_rigid_ones();
    model::ContactSettings contacts;
    contacts.tolerance = 0.01;
    Settle sim(m, local_damping(inertial), [](int, int) { return contact::Elastic::Parameters(1e9, 4e8); }, contacts);
    return relax(sim, m, inertial, 1e-9, 100000);
  };
  const auto inertial = settle(true);
  const auto local = settle(false);
  MESSAGE("deformable and rigid blocks to 1e-9: inertial relaxation " << inertial.steps << " steps (" << inertial.restarts
                                                                      << " stops), local damping " << local.steps);
  REQUIRE(inertial.converged);
  REQUIRE(local.converged);
  const double sink = 1.177e-5;  // m, of the small block (fixtures.hpp)
  REQUIRE(inertial.state.size() == local.state.size());
  double largest = 0;
  for (std::size_t i = 0; i < local.state.size(); ++i) largest = std::max(largest, std::abs(inertial.state[i] - local.state[i]));
  CHECK(largest <= 1e-5 * sink);
}

TEST_CASE("inertial relaxation: one and two threads give bitwise identical states (sums over fixed chunks)") {
  // 0.05 m tetrahedra: over 2,048 nodes, so that the sums take more than one chunk.
  const auto differences = test::differences_between_one_and_two_threads([] {
    model::Model m;
    m.add_block(geometry::make_box(Vec3(-1, -1, -0.5), Vec3(1, 1, 0)), 2000, "base", 0, model::Motion::fixed);
    const auto d = m.add_block(geometry::make_box(Vec3(-0.2, -0.2, 0), Vec3(0.2, 0.2, 0.4)), 2000, "cube", 1);
    m.add_block(geometry::make_box(Vec3(-0.1, -0.1, 0.4), Vec3(0.15, 0.1, 0.5)), 2000, "cap", 1);
    m.make_deformable(d, 0.05, model::IsotropicElastic(1e9, 0.2));
    REQUIRE(m.deformable.nodes.size() > 2048);
    model::ContactSettings contacts;
    contacts.tolerance = 0.01;
    Settle sim(m, local_damping(true), [](int, int) { return contact::Elastic::Parameters(1e10, 4e9); }, contacts);
    const auto r = relax(sim, m, true, 0, 1000);
    CHECK(r.restarts > 0);
    return r.state;
  });
  CHECK(differences == 0);
}

}  // namespace test_inertial_relaxation
