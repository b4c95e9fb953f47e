// The critical timestep of a model of rigid blocks (eq. 1): the block Gershgorin bound on omega_max against the
// eigenfrequencies of systems solved by hand and against the integrator's own stability limit.

#include <doctest/doctest.h>

#include "../approx.hpp"

#include <algorithm>
#include <cmath>

#include "blockdem/contact/elastic.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "fixtures.hpp"

using namespace blockdem;

namespace {

using Sim = Simulation<damping::None, contact::Elastic>;

constexpr std::uint8_t vertical_only = model::Fixity::translation_x | model::Fixity::translation_y | model::Fixity::all_rotations;

/// Steps until the largest block displacement from the start exceeds 1e6 times `initial` or `steps` are done;
/// returns that largest displacement over `initial`.
double growth(Sim& sim, double initial, long long steps = 20000) {
  const auto& b = sim.model().bodies;
  const auto x0 = b.position;
  double largest = 0;
  for (long long i = 0; i < steps && largest < 1e6 * initial; ++i) {
    sim.step();
    for (std::size_t k = 0; k < b.size(); ++k) largest = std::max(largest, (b.position[k] - x0[k]).norm());
  }
  return largest / initial;
}

/// Two 1 m cubes of 2000 kg stacked on a fixed base, vertical translation only, each joint 1 m^2 of k_n = k_s:
/// masses m, springs k = k_n (base to 1, 1 to 2). omega^2 = (k / m) (3 +- sqrt 5) / 2.
struct Stack {
  model::Model model;
  double k = 2e9, m = 2000;
  Stack() {
    model.gravity = Vec3::Zero();
    model.add_block(geometry::make_box(Vec3(-2, -2, -0.5), Vec3(2, 2, 0)), 2000.0, "base", 0, model::Motion::fixed);
    for (int i = 0; i < 2; ++i) {
      const std::size_t b = model.add_block(geometry::make_box(Vec3(-0.5, -0.5, i), Vec3(0.5, 0.5, i + 1.0)), 2000.0, "cube", 1);
      model.bodies.fixity[b] = vertical_only;
    }
    model.bodies.velocity[2] = Vec3(0, 0, 1e-3);
  }
  double omega_max() const { return std::sqrt(k / m * (3 + std::sqrt(5.0)) / 2); }
};

}  // namespace

TEST_CASE("timestep: for two stacked blocks eq. 1's estimate per block is below omega_max, the bound above it") {
  Stack s;
  Sim sim(s.model, damping::None{}, [&](int, int) { return contact::Elastic::Parameters(s.k, s.k); });
  // Per block: sqrt(2 k / m) (the lower block on its two joints). Bound: rows 2k/m + k/m and k/m + k/m.
  CHECK(sim.estimated_omega_max() == test::approx(std::sqrt(2 * s.k / s.m)).epsilon(1e-9));
  CHECK(sim.frequency_bound().omega_max() == test::approx(std::sqrt(3 * s.k / s.m)).epsilon(1e-9));
  CHECK(sim.bounded_frequency());
  CHECK(sim.critical_timestep() == test::approx(2 / std::sqrt(3 * s.k / s.m)).epsilon(1e-9));
  CHECK(sim.timestep() == test::approx(Sim::bound_safety_factor * sim.critical_timestep()).epsilon(1e-12));

  // The integrator's limit is 2 / omega_max (1.618 sqrt(k / m)): the estimate's timestep is beyond it.
  const double initial = 1e-3 / s.omega_max();
  auto run_at = [&](double dt) {
    Stack t;
    Sim run(t.model, damping::None{}, [&](int, int) { return contact::Elastic::Parameters(t.k, t.k); });
    run.set_timestep(dt, TimestepCheck::unchecked);
    return growth(run, initial);
  };
  CHECK(run_at(0.99 * 2 / sim.estimated_omega_max()) > 1e3);
  CHECK(run_at(1.01 * 2 / s.omega_max()) > 1e3);
  CHECK(run_at(0.99 * 2 / s.omega_max()) < 10);
  CHECK(run_at(sim.critical_timestep()) < 10);
}

TEST_CASE("timestep: for one free block on its base the bound is omega_max, the integrator's limit to 2 %") {
  // Six degrees of freedom, translation and rocking coupled (the CPs lie below the centroid): the bound is the
  // largest eigenvalue of its 6 x 6 mass-normalised stiffness, so the scheme is stable just below and unstable just
  // above the critical timestep.
  auto run_at = [](double factor) {
    auto s = test::block_on_base(0.6, 0.4, 1.0);
    s.model.gravity = Vec3::Zero();
    auto& b = s.model.bodies;
    b.velocity[s.block] = Vec3(2e-4, -1e-4, 3e-4);
    b.angular_velocity[s.block] = Vec3(1e-4, 2e-4, -1.5e-4);
    model::ContactSettings contacts;
    contacts.tolerance = 0.01;
    Sim sim(s.model, damping::None{}, [](int, int) { return contact::Elastic::Parameters(1e9, 0.4e9); }, contacts);
    sim.set_timestep(factor * sim.critical_timestep(), TimestepCheck::unchecked);
    return growth(sim, 1e-4 * sim.timestep(), 5000);
  };
  CHECK(run_at(0.98) < 1e3);
  CHECK(run_at(1.02) > 1e5);
}

TEST_CASE("timestep: partial density scaling by the bound brings every block's row to the target") {
  Stack s;
  Sim sim(s.model, damping::None{}, [&](int, int) { return contact::Elastic::Parameters(s.k, s.k); });
  const double target = 2 * sim.timestep();
  const auto r = sim.scale_density_to(target);
  CHECK(sim.timestep() == target);
  CHECK(r.scaled_blocks == 2);
  // Both rows at most omega_t^2 with omega_t = 2 safety / target; each block's scaled with the other's real mass,
  // so the final bound lies below: the lower cube needs s with 2k/(m s) + k/(m sqrt s) = omega_t^2.
  const double omega_t = 2 * Sim::bound_safety_factor / target;
  CHECK(sim.frequency_bound().omega_max() <= omega_t);
  const double x = (std::sqrt(1 + 8 * omega_t * omega_t * s.m / s.k) - 1) / 4;  // 1 / sqrt(s): 2 x^2 + x = omega_t^2 m / k
  CHECK(s.model.bodies.mass[1] == test::approx(s.m / (x * x)).epsilon(1e-6));
  CHECK(std::abs(sim.density_scaling_mass(target, [](double) { return 1.0; })) < 1e-9 * s.m);  // nothing left to add
}
