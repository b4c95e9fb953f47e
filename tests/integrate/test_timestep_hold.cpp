// Holding the timestep against contacts that appear during a run (Simulation::hold_timestep()): a light block that
// lands next to a heavy one gains a contact stiffer, for its mass, than anything the timestep was chosen for. The
// reference values are the SDOF limit omega = sqrt(k_n A / m) of eq. 1-2 for a block on a fixed base (translation
// along z only: the bound's row is exactly that), and energy conservation of the undamped bounce.

#include <doctest/doctest.h>

#include "../approx.hpp"

#include <algorithm>
#include <cmath>

#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "fixtures.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_timestep_hold {

namespace {

using Sim = Simulation<damping::None, contact::MohrCoulomb>;

constexpr std::uint8_t vertical_only = model::Fixity::translation_x | model::Fixity::translation_y | model::Fixity::all_rotations;
constexpr double kn = 1e9;       // Pa/m, normal and shear
constexpr double gap = 5e-3;     // m, the light block's fall onto the base
constexpr double side = 0.1;     // m, of the light block (2 kg at 2000 kg/m^3, 0.01 m^2 on the base)

/// A 1 m cube of 2000 kg on its base and a 0.1 m cube of 2 kg held `gap` above the base, 1 m away: both move
/// along z only. Alone on its joint, the heavy one has omega^2 = k_n A / m = 5e5 rad^2/s^2, the light one 5e6 once
/// it lands: ten times more, so the timestep set before the landing is too large for it by sqrt(10) / 0.8.
struct Landing {
  test::BlockOnBase s = test::block_on_base(1, 1, 1);
  std::size_t light = 0;
  Landing() {
    light = s.model.add_block(geometry::make_box(Vec3(1.5 - side / 2, -side / 2, gap), Vec3(1.5 + side / 2, side / 2, gap + side)),
                              2000.0, "light", 1);
    s.model.bodies.fixity[s.block] = vertical_only;
    s.model.bodies.fixity[light] = vertical_only;
  }
};

Sim make(model::Model& m) {
  // No tension: a contact point found at a gap stays open until the block lands on it.
  return Sim(m, damping::None{}, [](int, int) { return contact::MohrCoulomb::Parameters(kn, kn, 0, 0, 0.6); });
}

struct Bounce {
  double impact_speed = 0;  // m/s, the largest speed before the landing
  double largest_speed = 0; // m/s, after it
  bool finite = true;
};

/// Steps through the landing and `after` steps beyond it.
Bounce land(Sim& sim, std::size_t light, long long after) {
  const auto& b = sim.model().bodies;
  Bounce r;
  while (b.position[light].z() - side / 2 > 1e-4 && sim.steps() < 100000) {  // position: the centroid
    sim.step();
    r.impact_speed = std::max(r.impact_speed, b.velocity[light].norm());
  }
  for (long long i = 0; i < after; ++i) {
    sim.step();
    r.finite = r.finite && std::isfinite(b.velocity[light].z());
    r.largest_speed = std::max(r.largest_speed, b.velocity[light].norm());
    if (!(r.largest_speed < 1e3)) break;
  }
  return r;
}

}  // namespace

TEST_CASE("timestep hold: a block that lands with a timestep too large for its new contact diverges unless held") {
  // The control: the same landing at the same timestep set unchecked (so not held) diverges; the checked run
  // lowers its timestep at the landing's re-detection to its margin 0.8 below the light block's limit, and stays
  // bounded through the first bounce. (At omega dt = 1.6 the impact is resolved by two steps: the block leaves the
  // joint at 0.47 m/s for one step, the speed the spring's one sample gave it, before the closure impulse at the
  // next sample takes back what the joint's opening within the step made: 0.30 m/s after, from 0.31 at the
  // impact; tests/integrate/test_impact_energy.cpp.)
  Landing unheld;
  auto free = make(unheld.s.model);
  const double dt = free.timestep();  // 0.8 of the heavy block's limit: 0.8 * 2 / sqrt(5e5)
  CHECK(dt == test::approx(0.8 * 2 / std::sqrt(kn * 1.0 / 2000.0)).epsilon(1e-9));
  free.set_timestep(dt, TimestepCheck::unchecked);
  const auto diverged = land(free, unheld.light, 40);  // the first bounce
  CHECK(free.timestep_hold().reductions == 0);
  CHECK(diverged.largest_speed > 5 * diverged.impact_speed);  // thrown off at omega dt = 5

  Landing held;
  auto sim = make(held.s.model);
  REQUIRE(sim.timestep() == dt);
  const auto bounce = land(sim, held.light, 40);
  const double limit = 2 / std::sqrt(kn * side * side / held.s.model.bodies.mass[held.light]);
  MESSAGE("timestep " << dt << " s -> " << sim.timestep() << " s after " << sim.timestep_hold().reductions << " reduction(s); impact "
                      << bounce.impact_speed << " m/s, largest speed after " << bounce.largest_speed << " m/s");
  CHECK(sim.timestep_hold().reductions == 1);
  CHECK(sim.timestep() == test::approx(0.8 * limit).epsilon(1e-9));
  CHECK(sim.timestep_hold().smallest_dt == sim.timestep());
  CHECK(bounce.finite);
  CHECK(bounce.largest_speed < 2 * bounce.impact_speed);
}

TEST_CASE("timestep hold: a run keeps the margin it was set with, and the bounce gives the impact's energy back") {
  // Set at a quarter of the heavy block's limit, the run is held at a quarter of the light block's after the
  // landing: the impact is resolved by some ten steps and the undamped elastic bounce returns the impact speed.
  Landing held;
  auto sim = make(held.s.model);
  sim.set_timestep(0.25 * sim.critical_timestep());
  const auto bounce = land(sim, held.light, 4000);
  const double limit = 2 / std::sqrt(kn * side * side / held.s.model.bodies.mass[held.light]);
  MESSAGE("impact " << bounce.impact_speed << " m/s, largest speed after " << bounce.largest_speed << " m/s; energy balance error "
                    << sim.energy().balance_error);
  CHECK(sim.timestep_hold().reductions == 1);
  CHECK(sim.timestep() == test::approx(0.25 * limit).epsilon(1e-9));
  CHECK(bounce.largest_speed == test::approx(bounce.impact_speed).epsilon(0.05));
}

TEST_CASE("timestep hold: a density-scaled run keeps its timestep and raises the landed block to the target") {
  // Density scaling to twice the heavy block's limit, then the landing: the light block's row k_n A / m must come
  // down to (2 * 0.8 / dt)^2, so its mass goes to k_n A (dt / 1.6)^2 (plus the bisection's 1e-9), and the bound's
  // critical timestep is back at dt / 0.8.
  Landing held;
  auto sim = make(held.s.model);
  const double target = 2 * sim.timestep();
  const auto scaling = sim.scale_density_to(target);
  REQUIRE(scaling.scaled_blocks == 1);  // the heavy block; the light one has no contact yet
  const double real = held.s.model.bodies.mass[held.light];
  const auto bounce = land(sim, held.light, 40);
  const auto& hold = sim.timestep_hold();
  const double mass = held.s.model.bodies.mass[held.light];
  MESSAGE("light block " << real << " kg -> " << mass << " kg at the landing; impact " << bounce.impact_speed
                         << " m/s, largest speed after " << bounce.largest_speed << " m/s; the raise added " << hold.kinetic_energy << " J");
  CHECK(sim.timestep() == target);
  CHECK(hold.raises == 1);
  CHECK(hold.raised_blocks == 1);
  CHECK(hold.raised_nodes == 0);
  CHECK(hold.reductions == 0);
  CHECK(mass == test::approx(kn * side * side * std::pow(target / 1.6, 2)).epsilon(1e-6));
  CHECK(hold.added_mass == test::approx(mass - real).epsilon(1e-12));
  CHECK(hold.kinetic_energy > 0);
  CHECK(sim.critical_timestep() >= target / 0.8 * (1 - 1e-6));
  CHECK(bounce.finite);
  CHECK(bounce.largest_speed < 2 * bounce.impact_speed);
}

}  // namespace test_timestep_hold
