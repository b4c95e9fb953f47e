// The frame of mass-proportional damping (damping/frame.hpp): relative to the table, a block the table carries along
// feels no damping force; relative to the ground, the table drags it with alpha m v_table. Both against the
// single-degree-of-freedom system they stand for, integrated independently.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include "blockdem/contact/elastic.hpp"
#include "blockdem/damping/mass_proportional.hpp"
#include "blockdem/damping/rayleigh.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "blockdem/motion/base_motion.hpp"
#include "fixtures.hpp"

using namespace blockdem;

namespace test_damping_frame {

namespace {

// A flat block 1 x 1 x 0.1 m (200 kg) on the table, joined by elastic springs, without gravity and turning
// fixed: its sliding on the table is a single degree of freedom, u = x_block - x_table, of stiffness ks A.
constexpr double shear_stiffness = 1e7;                       // Pa/m, over A = 1 m^2
constexpr double mass = 200.0;                                // kg
const double omega = std::sqrt(shear_stiffness * 1.0 / mass);  // 223.6 rad/s, 35.6 Hz
constexpr double alpha = 10.0;                                 // 1/s: 2.2 % at 35.6 Hz

test::BlockOnBase flat_block() {
  auto s = test::block_on_base(1.0, 1.0, 0.1, 2000.0, model::Motion::base);
  s.model.gravity = Vec3::Zero();
  s.model.bodies.fixity[s.block] = model::Fixity::all_rotations;
  return s;
}

using Sim = Simulation<damping::MassProportional, contact::Elastic>;

Sim simulation(test::BlockOnBase& s, damping::Frame frame) {
  Sim sim(s.model, damping::MassProportional{alpha}, [](int, int) { return contact::Elastic::Parameters(1e10, shear_stiffness); });
  sim.set_damping_frame(frame);
  return sim;
}

/// u(t) of the block relative to the table: m u'' = -k u - m a_table - alpha m (u' + v_table in the ground's frame).
std::vector<double> reference(const motion::SineVelocity& table, damping::Frame frame, const std::vector<double>& times) {
  using State = std::array<double, 2>;
  const bool absolute = frame == damping::Frame::absolute;
  auto rhs = [&](const State& x, State& dxdt, double t) {
    const double drag = absolute ? table.velocity(t) : 0.0;
    dxdt[0] = x[1];
    dxdt[1] = -omega * omega * x[0] - table.acceleration(t) - alpha * (x[1] + drag);
  };
  boost::numeric::odeint::runge_kutta4<State> stepper;
  State x{0.0, 0.0};
  double t = 0.0;
  const double h = 1e-6;
  std::vector<double> u;
  for (const double target : times) {
    while (t + h <= target) {
      stepper.do_step(rhs, x, t, h);
      t += h;
    }
    if (target > t) {
      stepper.do_step(rhs, x, t, target - t);
      t = target;
    }
    u.push_back(x[0]);
  }
  return u;
}

}  // namespace

TEST_CASE("damping frame: on a table at constant velocity, a block carried along feels no mass-proportional damping in the table's frame and is dragged with alpha m v in the ground's") {
  const Vec3 v0(0.2, 0.0, 0.0);
  for (const auto frame : {damping::Frame::table, damping::Frame::absolute}) {
    const std::string frame_name = damping::name(frame);
    CAPTURE(frame_name);
    auto s = flat_block();
    s.model.base_motion = motion::BaseMotion::constant(v0);
    s.model.bodies.velocity[s.block] = v0;
    auto sim = simulation(s, frame);
    const auto steps = static_cast<long long>(3.0 / sim.timestep());  // 3 s: 15 times the decay time 2 / alpha
    for (long long k = 0; k < steps; ++k) sim.step();
    const double drag = alpha * mass * v0.x();  // 40 N
    const double force = s.model.bodies.force[s.block].x();  // the springs' force on the block
    const EnergyReport e = sim.energy();
    CHECK(e.balance_error < 1e-6);
    if (frame == damping::Frame::table) {
      CHECK(std::abs(force) < 1e-9 * drag);
      CHECK(std::abs(s.model.bodies.velocity[s.block].x() - v0.x()) < 1e-12);
      CHECK(e.viscous < 1e-12);
    } else {
      // The springs hold the block against the drag: steady, their force is the drag's, and so is the power the
      // table's drive spends through them (alpha m v^2, dissipated).
      CHECK(force == doctest::Approx(drag).epsilon(1e-6));
      CHECK(e.viscous == doctest::Approx(drag * v0.x() * sim.time()).epsilon(0.01));
    }
  }
}

TEST_CASE("damping frame: under a sine motion of the table the block's sliding is the single-degree-of-freedom system of its frame: -m a_table in the table's, and the drag alpha m v_table besides in the ground's") {
  motion::SineVelocity table;
  table.amplitude = 0.1;  // m/s
  table.period = 0.2;     // s: 5 Hz, below the block's 35.6 Hz
  table.cycles = 3;
  table.start = 0.01;
  std::vector<double> u_table_frame, u_absolute;
  for (const auto frame : {damping::Frame::table, damping::Frame::absolute}) {
    const std::string frame_name = damping::name(frame);
    CAPTURE(frame_name);
    auto s = flat_block();
    s.model.base_motion = motion::BaseMotion(table);
    auto sim = simulation(s, frame);
    const double offset = s.model.bodies.position[s.block].x() - s.model.bodies.position[s.base].x();
    std::vector<double> times, u;
    while (sim.time() < 1.0) {
      sim.step();
      times.push_back(sim.time());
      u.push_back(s.model.bodies.position[s.block].x() - s.model.bodies.position[s.base].x() - offset);
    }
    const auto expected = reference(table, frame, times);
    double peak = 0.0, error = 0.0;
    for (std::size_t k = 0; k < u.size(); ++k) {
      peak = std::max(peak, std::abs(expected[k]));
      error = std::max(error, std::abs(u[k] - expected[k]));
    }
    CHECK(peak > 1e-4);
    CHECK(error < 0.01 * peak);
    // The books close to the scheme's error in the base's work (about 4e-6 J in either frame): 2e-4 of the 0.045 J
    // the table's frame exchanges, 1e-6 of the 6.3 J the drag makes the ground's.
    const EnergyReport e = sim.energy();
    CHECK(std::abs(e.kinetic + e.elastic + e.viscous + e.slip - e.gravity_work - e.base_work - e.contact_update) < 1e-5);
    (frame == damping::Frame::table ? u_table_frame : u_absolute) = expected;
  }
  // The two frames differ by the drag: a third of the inertial force at 5 Hz with alpha = 10 1/s.
  double peak = 0.0, difference = 0.0;
  for (std::size_t k = 0; k < u_table_frame.size(); ++k) {
    peak = std::max(peak, std::abs(u_table_frame[k]));
    difference = std::max(difference, std::abs(u_table_frame[k] - u_absolute[k]));
  }
  CHECK(difference > 0.1 * peak);
}

TEST_CASE("damping frame: Rayleigh's mass term takes the frame, and a table at rest gives bitwise the same run in both") {
  // The block's displacement and velocity relative to the table after 2000 steps, sliding along y at first.
  auto run = [](damping::Frame frame, bool moving) {
    auto s = flat_block();
    if (moving) s.model.base_motion = motion::BaseMotion::constant(Vec3(0.1, 0.0, 0.0));
    s.model.bodies.velocity[s.block] = Vec3(moving ? 0.1 : 0.0, 0.05, 0.0);
    const Vec3 offset = s.model.bodies.position[s.block] - s.model.bodies.position[s.base];
    Simulation<damping::Rayleigh, contact::Elastic> sim(s.model, damping::Rayleigh{alpha, 1e-5},
                                                        [](int, int) { return contact::Elastic::Parameters(1e10, shear_stiffness); });
    sim.set_damping_frame(frame);
    for (int k = 0; k < 2000; ++k) sim.step();
    const auto& b = s.model.bodies;
    return std::pair{Vec3(b.position[s.block] - b.position[s.base] - offset), Vec3(b.velocity[s.block] - b.velocity[s.base])};
  };
  const auto [u_table, v_table] = run(damping::Frame::table, false);
  const auto [u_absolute, v_absolute] = run(damping::Frame::absolute, false);
  for (int c = 0; c < 3; ++c) {
    CHECK(u_table[c] == u_absolute[c]);
    CHECK(v_table[c] == v_absolute[c]);
  }
  CHECK(std::hypot(omega * u_table.y(), v_table.y()) > 1e-3);  // still sliding (0.05 m/s at first, 0.005 now)
  // Moving, the table's frame sees the relative motion it saw at rest (a Galilean change of frame); the ground's
  // lags the block behind the table by about alpha v / omega^2 = 2e-5 m.
  const auto [u_moving_table, v_moving_table] = run(damping::Frame::table, true);
  const auto [u_moving_absolute, v_moving_absolute] = run(damping::Frame::absolute, true);
  CHECK(u_moving_table.y() == doctest::Approx(u_table.y()).epsilon(1e-6));
  CHECK(std::abs(u_moving_table.x()) < 1e-12);
  CHECK(u_moving_absolute.x() < -5e-6);
  (void)v_moving_table;
  (void)v_moving_absolute;
}

}  // namespace test_damping_frame
