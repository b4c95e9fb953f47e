// Damping ratio of the proportional schemes against eq. 10 and eq. 11 written out by hand.

#include <doctest/doctest.h>

#include "../approx.hpp"

#include <cmath>

#include "blockdem/core/units.hpp"
#include "blockdem/damping/mass_proportional.hpp"
#include "blockdem/damping/rayleigh.hpp"
#include "blockdem/damping/stiffness_proportional.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_damping_ratio {

TEST_CASE("mass-proportional: zeta* at the centre frequency, falling as 1/f (the paper's MassProp, 4 % at 7.5 Hz)") {
  const auto mass = damping::MassProportional::from_damping_ratio(0.04, 7.5);
  CHECK(mass.alpha == test::approx(2.0 * 0.04 * two_pi * 7.5));
  CHECK(mass.damping_ratio(angular_frequency(7.5)) == test::approx(0.04));
  CHECK(mass.damping_ratio(angular_frequency(15.0)) == test::approx(0.02));
  CHECK(mass.damping_ratio(angular_frequency(1.0)) == test::approx(0.3));
}

TEST_CASE("stiffness-proportional: zeta = beta omega / 2 and the eq. 11 timestep factor") {
  const auto stiff = damping::StiffnessProportional::from_damping_ratio(0.05, 10.0);
  CHECK(stiff.damping_ratio(angular_frequency(10.0)) == test::approx(0.05));
  CHECK(stiff.damping_ratio(angular_frequency(40.0)) == test::approx(0.2));
  // zeta_max = 0.75 at omega_max: sqrt(1 + 0.5625) - 0.75 = 0.5
  const double omega_max = 0.75 / (0.5 * stiff.beta);
  CHECK(stiff.timestep_factor(omega_max) == test::approx(0.5).epsilon(1e-14));
  CHECK(stiff.timestep_factor(0.0) == 1.0);
}

TEST_CASE("rayleigh: passes through both anchor points, minimum sqrt(alpha beta) at sqrt(alpha / beta) (eq. 10)") {
  const auto r = damping::Rayleigh::from_two_frequencies(0.05, 1.0, 0.05, 40.0);
  CHECK(r.damping_ratio(angular_frequency(1.0)) == test::approx(0.05).epsilon(1e-14));
  CHECK(r.damping_ratio(angular_frequency(40.0)) == test::approx(0.05).epsilon(1e-14));
  const double w_min = std::sqrt(r.alpha / r.beta);
  CHECK(w_min == test::approx(two_pi * std::sqrt(40.0)));
  CHECK(r.damping_ratio(w_min) == test::approx(std::sqrt(r.alpha * r.beta)));
  const auto unequal = damping::Rayleigh::from_two_frequencies(0.02, 2.0, 0.06, 20.0);
  CHECK(unequal.damping_ratio(angular_frequency(2.0)) == test::approx(0.02).epsilon(1e-14));
  CHECK(unequal.damping_ratio(angular_frequency(20.0)) == test::approx(0.06).epsilon(1e-14));
  CHECK_THROWS_AS(damping::Rayleigh::from_two_frequencies(0.05, 40.0, 0.05, 1.0), InvalidArgument);
  CHECK_THROWS_AS(damping::Rayleigh::from_two_frequencies(0.05, 0.0, 0.05, 1.0), InvalidArgument);
  CHECK_THROWS_AS(damping::Rayleigh::from_two_frequencies(-0.01, 1.0, 0.05, 2.0), InvalidArgument);
}

}  // namespace test_damping_ratio
