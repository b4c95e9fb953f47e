// The joint test driver: the pre-compression lands on the requested normal stress (also on the hardening branch),
// every path conserves energy, and the monotonic paths pass through the analytical peaks.

#include <doctest/doctest.h>

#include "../approx.hpp"

#include "blockdem/analysis/joint_test.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_joint_test {
using analysis::JointPath;

TEST_CASE("joint test: the closure for a normal stress inverts the elastic line and the hardening parabola") {
  const auto p = contact::ElastoSoftening::Parameters::from_material();
  for (const double sigma : {-0.2e6, 0.5e6, 3.0e6, 5e6, 9.0e6}) {
    CAPTURE(sigma);
    contact::ElastoSoftening::History h{};
    const auto r = contact::ElastoSoftening::update(p, h, -analysis::closure_for_stress(p, sigma), {0, 0});
    CHECK(r.normal_stress == test::approx(sigma).epsilon(1e-12));
  }
}

TEST_CASE("joint test: each path reaches its analytical peak (f_t, c + sigma tan(phi), f_c) and closes its energy balance") {
  analysis::JointTestOptions o;
  o.steps = 4000;
  for (const auto path : {JointPath::tension, JointPath::shear, JointPath::compression, JointPath::cyclic_tension,
                          JointPath::cyclic_shear}) {
    CAPTURE(analysis::to_string(path));
    o.path = path;
    const auto r = analysis::run_joint_test(o);
    CHECK(r.final_damage > 0.999);
    CHECK(r.failed);
    CHECK(r.energy_balance_error < 1e-3);  // trapezoid-rule work against the law's accounting
    CHECK(r.peak_stress <= r.expected_peak * (1 + 1e-12));
    if (path == JointPath::tension || path == JointPath::shear || path == JointPath::compression)
      CHECK(r.peak_stress == test::approx(r.expected_peak).epsilon(1e-12));
    else
      CHECK(r.peak_stress > 0.99 * r.expected_peak);
  }
  o.path = JointPath::shear;
  o.normal_stress = 0.5e6;
  CHECK(analysis::run_joint_test(o).expected_peak == test::approx(0.3e6 + 0.5e6 * std::tan(38 * pi / 180)).epsilon(1e-12));
  CHECK_THROWS_WITH_AS(analysis::joint_path_from_string("bending"), doctest::Contains("is not one of tension, shear"),
                       InvalidArgument);
}

}  // namespace test_joint_test
