// The table's motion: a record integrated exactly (constant and linear acceleration against their closed forms),
// held before its start and after its end; whole sine cycles against their closed form; sums along several
// directions; one component sampled bit for bit as itself; bad input named.

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "../approx.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/base_motion.hpp"
#include "blockdem/motion/synthetic.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_base_motion {
using namespace blockdem::motion;

namespace {
Record linear_record(double a0, double slope, double dt, std::size_t n) {
  Record record;
  record.dt = dt;
  for (std::size_t i = 0; i < n; ++i) record.acceleration.push_back(a0 + slope * record.time(i));
  return record;
}
}  // namespace

TEST_CASE("base motion: at rest and constant") {
  const BaseMotion rest;
  CHECK(rest.velocity(3.0) == Vec3::Zero());
  CHECK(BaseMotion::at_rest().acceleration(-1.0) == Vec3::Zero());
  CHECK(rest.end() == -std::numeric_limits<double>::infinity());
  const auto moving = BaseMotion::constant(Vec3(0.1, -0.2, 0.3));
  CHECK(moving.velocity(-5.0) == Vec3(0.1, -0.2, 0.3));
  CHECK(moving.final_velocity() == Vec3(0.1, -0.2, 0.3));
  CHECK(moving.acceleration(1.0) == Vec3::Zero());
  CHECK((moving.displacement(3.0, 1.0) - Vec3(0.2, -0.4, 0.6)).norm() < 1e-15);
  CHECK_THROWS_AS(BaseMotion::constant(Vec3(std::nan(""), 0, 0)), InvalidArgument);
}

TEST_CASE("base motion: a record of linear acceleration gives the exact velocity at its samples, held outside it") {
  // a = 2 - 3 s for s = t - start in [0, 2]: v = v0 + 2 s - 1.5 s^2, u = v0 s + s^2 - s^3 / 2 (trapezoid and the
  // cubic displacement rule are exact for it, motion/integration.hpp).
  const double start = 1.5, v0 = 0.25, dt = 0.01;
  const BaseMotion m(linear_record(2.0, -3.0, dt, 201), {}, Vec3(0, 2, 0), start, v0);
  REQUIRE(m.records().size() == 1);
  const auto& r = m.records().front();
  CHECK(r.direction() == Vec3::UnitY());
  CHECK(r.end() == test::approx(3.5));
  CHECK(m.end() == test::approx(3.5));
  for (int i = 0; i <= 200; i += 25) {
    const double s = dt * i, t = start + s;
    CHECK(m.velocity(t).y() == test::approx(v0 + 2 * s - 1.5 * s * s).epsilon(1e-12));
    CHECK(m.acceleration(t).y() == test::approx(2 - 3 * s).epsilon(1e-12));
    CHECK(r.displacement(t) == doctest::Approx(v0 * s + s * s - 0.5 * s * s * s).epsilon(1e-12));  // 0 at the start
    CHECK(m.velocity(t).x() == 0.0);
  }
  const double v_end = v0 + 2 * 2.0 - 1.5 * 4.0;
  CHECK(r.final_velocity() == test::approx(v_end).epsilon(1e-12));
  CHECK(m.final_velocity().y() == test::approx(v_end).epsilon(1e-12));
  // Before the start: the initial velocity, no acceleration; after the end: the final velocity, no acceleration.
  CHECK(m.velocity(0.0).y() == v0);
  CHECK(m.acceleration(0.0).y() == 0.0);
  CHECK(m.velocity(10.0).y() == r.final_velocity());
  CHECK(m.acceleration(10.0).y() == 0.0);
  CHECK(r.displacement(4.5) == test::approx(v0 * 2 + 4 - 4 + v_end * 1.0).epsilon(1e-12));
  // From time 0: the travel before the start at v0 is counted too.
  CHECK(m.displacement(3.5).y() == test::approx(v0 * start + v0 * 2 + 4 - 4).epsilon(1e-12));
}

TEST_CASE("base motion: a rectangular acceleration pulse is two samples (Newmark's input)") {
  Record pulse;
  pulse.dt = 0.2;
  pulse.acceleration = {3.0, 3.0};
  const BaseMotion m(pulse, {}, Vec3::UnitX(), 1.0);
  CHECK(m.velocity(1.0).x() == 0.0);
  CHECK(m.velocity(1.1).x() == test::approx(0.3));
  CHECK(m.velocity(1.2).x() == test::approx(0.6));
  CHECK(m.velocity(7.0).x() == test::approx(0.6));
}

TEST_CASE("base motion: whole cycles of sine velocity start and end at rest where they started") {
  const SineVelocity sine{0.2, 0.5, 3, Vec3(0, 0, 4), 1.0};
  const BaseMotion m(sine);
  CHECK(m.sines().front().direction == Vec3::UnitZ());
  CHECK(m.end() == test::approx(2.5));
  const double w = two_pi / 0.5;
  for (double t : {1.1, 1.37, 2.0, 2.49}) {
    CHECK(m.velocity(t).z() == test::approx(0.2 * std::sin(w * (t - 1.0))).epsilon(1e-9));
    CHECK(m.acceleration(t).z() == test::approx(0.2 * w * std::cos(w * (t - 1.0))).epsilon(1e-9));
    CHECK(m.displacement(t, 1.0).z() == doctest::Approx(0.2 / w * (1 - std::cos(w * (t - 1.0)))).epsilon(1e-12));
    // The acceleration is the derivative of the velocity, the velocity that of the displacement.
    const double h = 1e-6;
    const double dv = m.velocity(t + h).z() - m.velocity(t - h).z();
    const double du = m.displacement(t + h).z() - m.displacement(t - h).z();
    CHECK(dv / (2 * h) == doctest::Approx(m.acceleration(t).z()).epsilon(1e-6));
    CHECK(du / (2 * h) == doctest::Approx(m.velocity(t).z()).epsilon(1e-6));
  }
  CHECK(m.velocity(0.9) == Vec3::Zero());
  CHECK(m.velocity(2.6) == Vec3::Zero());
  CHECK(m.displacement(3.0).norm() == 0.0);
  CHECK(m.final_velocity() == Vec3::Zero());
  CHECK_THROWS_WITH_AS(BaseMotion(SineVelocity{0.2, 0.0, 1, Vec3::UnitX(), 0.0}), doctest::Contains("must be > 0"),
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(BaseMotion(SineVelocity{0.2, 1.0, 0, Vec3::UnitX(), 0.0}), doctest::Contains("at least 1"),
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(BaseMotion(SineVelocity{0.2, 1.0, 1, Vec3::Zero(), 0.0}), doctest::Contains("direction"),
                       InvalidArgument);
}

TEST_CASE("base motion: a sum moves the table by each part along its direction") {
  const RecordMotion along_x(ramp_record(1.0, 0.5, 2.0, 0.01), {}, Vec3::UnitX(), 0.5, -0.1);
  const SineVelocity along_y{0.05, 0.25, 8, Vec3::UnitY(), 0.0};
  const Vec3 drift(0, 0, 0.01);
  const auto m = BaseMotion(along_x) + BaseMotion(along_y) + BaseMotion::constant(drift);
  CHECK(m.records().size() == 1);
  CHECK(m.sines().size() == 1);
  CHECK(m.constant_velocity() == drift);
  for (double t : {0.0, 0.3, 0.77, 1.9, 2.6, 3.0}) {
    const Vec3 expected = along_x.velocity(t) * Vec3::UnitX() + along_y.velocity(t) * Vec3::UnitY() + drift;
    CHECK((m.velocity(t) - expected).norm() < 1e-15);
    CHECK((m.acceleration(t) - Vec3(along_x.acceleration(t), along_y.acceleration(t), 0)).norm() < 1e-15);
  }
  CHECK(m.end() == test::approx(2.5));
  CHECK((m.final_velocity() - Vec3(along_x.final_velocity(), 0, 0.01)).norm() < 1e-15);
  BaseMotion sum;
  sum += BaseMotion(along_y);
  sum += BaseMotion(along_y);
  CHECK(sum.velocity(0.1).y() == test::approx(2 * along_y.velocity(0.1)));
}

TEST_CASE("base motion: one component alone is sampled bit for bit as itself (a zero added would turn -0 into +0)") {
  // What keeps the vault study's numbers those of its first version, which sampled the record directly.
  const RecordMotion r(linear_record(-1.0, 0.0, 0.01, 101), {}, Vec3::UnitX(), 0.0);
  const BaseMotion m(r);
  for (double t : {0.005, 0.5, 0.999, 2.0}) {
    const Vec3 v = m.velocity(t), direct = r.velocity(t) * r.direction();
    CHECK(v.x() == direct.x());
    CHECK(std::signbit(v.y()) == std::signbit(direct.y()));
    CHECK(std::signbit(v.y()));  // -0: the velocity is negative
  }
  const BaseMotion pulse(SineVelocity{1e-3, 0.05, 1, Vec3::UnitY(), 0.2});
  const double u = (0.23 - 0.2) / 0.05;
  CHECK(pulse.velocity(0.23).y() == 1e-3 * std::sin(2 * pi * u));
}

TEST_CASE("base motion: bad records and directions are refused, naming what is wrong") {
  Record short_record;
  short_record.dt = 0.01;
  short_record.acceleration = {1.0};
  CHECK_THROWS_WITH_AS(BaseMotion(short_record, {}, Vec3::UnitX()), doctest::Contains("at least 2"), InvalidArgument);
  const auto record = linear_record(1.0, 0.0, 0.01, 10);
  CHECK_THROWS_WITH_AS(BaseMotion(record, {}, Vec3::Zero()), doctest::Contains("direction"), InvalidArgument);
  CHECK_THROWS_WITH_AS(BaseMotion(record, {}, Vec3::UnitX(), std::numeric_limits<double>::infinity()),
                       doctest::Contains("start time must be finite"), InvalidArgument);
}

}  // namespace test_base_motion
