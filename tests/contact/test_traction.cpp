// The contact pass stores no traction per CP: output takes it back from the joint law's history
// (ContactLaw::traction) and the damping policy's spring state (DampingPolicy::held_stress). Reference: what
// update() and spring_stress() returned on the step, over random paths through every regime. Also the other way
// round: the damping switch update() returns (Response::damping_active, which the contact pass uses) is the one
// the history holds (ContactLaw::damping_active, which output, release and redetection use).

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "blockdem/contact/elastic.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/contact/softening.hpp"
#include "blockdem/core/random.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/maxwell_fit.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/damping/rayleigh.hpp"
#include "blockdem/damping/stiffness_proportional.hpp"

using namespace blockdem;

namespace {

constexpr double degree = pi / 180.0;

/// Runs `paths` random displacement paths of 250 steps through each parameter set; returns how many steps the
/// history's traction differed from what update() returned (normal: by more than 1e-12 relative, rounding of the
/// secant; shear: at all) or its damping switch did, and counts the steps that slipped, cracked or crushed in
/// `inelastic` and those after which the damping was off in `inactive`.
template <class Law>
long long traction_mismatches(const std::vector<typename Law::Parameters>& sets, int paths, long long& inelastic,
                              long long& inactive) {
  SplitMix64 random(20261121);
  long long mismatches = 0;
  for (int path = 0; path < paths; ++path) {
    const auto& p = sets[static_cast<std::size_t>(path) % sets.size()];
    typename Law::History h{};
    const double drift = random.uniform() < 0.3 ? -0.4 : 0.0;
    for (int i = 0; i < 250; ++i) {
      auto increment = [&](double bias) {
        if (random.uniform() < 1.0 / 3.0) return 0.0;
        return std::pow(10.0, -8.0 + 4.5 * random.uniform()) * (random.uniform_symmetric() + bias);
      };
      const double dn = increment(drift);
      const contact::Shear ds{increment(0), increment(0)};
      const contact::Response r = Law::update(p, h, dn, ds);
      const contact::Traction t = Law::traction(p, h);
      const bool same = std::abs(t[0] - r.normal_stress) <= 1e-12 * std::abs(r.normal_stress) &&
                        t[1] == r.shear_stress[0] && t[2] == r.shear_stress[1] &&
                        r.damping_active == Law::damping_active(p, h);
      if (!same && ++mismatches < 4) {
        CAPTURE(path);
        CAPTURE(i);
        CAPTURE(r.normal_stress);
        CAPTURE(t[0]);
        CAPTURE(r.damping_active);
        CHECK(same);
      }
      inelastic += r.dissipated > 0;
      inactive += !r.damping_active;
    }
  }
  return mismatches;
}

/// Random steps (increments, timestep 0 a tenth of the time, the joint inactive a fifth): whenever the joint is
/// active, held_stress(state) must be the stress spring_stress just returned, exactly (the same sum in the same
/// order); when inactive spring_stress returns 0. Returns the mismatches and counts the non-zero stresses.
template <class Damping>
long long held_mismatches(const Damping& policy, double dt, long long& nonzero) {
  SplitMix64 random(7);
  long long mismatches = 0;
  for (int path = 0; path < 200; ++path) {
    typename Damping::ContactState state{};
    for (int i = 0; i < 200; ++i) {
      const double du = 1e-6 * random.uniform_symmetric();
      const double step = random.uniform() < 0.1 ? 0.0 : dt;
      const bool active = random.uniform() > 0.2;
      double dissipated = 0;
      const double returned = policy.spring_stress(state, 1e10, du, step, active, dissipated);
      const double held = active ? Damping::held_stress(state) : 0.0;
      if (held != returned && ++mismatches < 4) {
        CAPTURE(path);
        CAPTURE(i);
        CAPTURE(returned);
        CHECK(held == returned);
      }
      nonzero += returned != 0.0;
    }
  }
  return mismatches;
}

}  // namespace

TEST_CASE("every joint law: the traction and damping switch its history holds are what its last update returned (random paths)") {
  long long inelastic = 0, inactive = 0;
  CHECK(traction_mismatches<contact::Elastic>({{1e10, 4e9}, {3.9e10, 1.6e10}}, 400, inelastic, inactive) == 0);
  CHECK(inactive == 0);
  const std::vector<contact::MohrCoulomb::Parameters> mohr_coulomb{
      {1e10, 4e9, 0, 0, 0.6},                                   // dry joint
      {1e10, 4e9, 0.3e6, 0.3e6, 38 * degree, 0.05e6, 0.1e6, 30 * degree},  // bonded, residual strengths
      {3.9e10, 1.6e10, 0.1e6, 0.0, 0.0}};                       // no friction
  inelastic = inactive = 0;
  CHECK(traction_mismatches<contact::MohrCoulomb>(mohr_coulomb, 1200, inelastic, inactive) == 0);
  CHECK(inelastic > 1200 * 250 / 20);  // the paths slip and open, not only the elastic range
  CHECK(inactive > 1200 * 250 / 20);   // both values of the switch are checked
  CHECK(inactive < 1200 * 250);
  using contact::ElastoSoftening;
  const auto table1 = ElastoSoftening::Parameters::from_material();
  const contact::JointStiffness k{table1.normal_stiffness, table1.shear_stiffness};
  const ElastoSoftening::FractureEnergies g{table1.tension_fracture_energy, table1.shear_fracture_energy,
                                             table1.compression_fracture_energy};
  const std::vector<ElastoSoftening::Parameters> softening{
      table1, ElastoSoftening::Parameters(k, {0.3e6, 0.3e6, 38 * degree, 9.1e6, 0.05e6, 0.1e6, 30 * degree}, g),
      ElastoSoftening::Parameters(k, {0.1e6, 0.2e6, 0.0, 2e6, 0, 0, 0.0}, {5.0, 20.0, 500.0})};
  inelastic = inactive = 0;
  CHECK(traction_mismatches<ElastoSoftening>(softening, 1200, inelastic, inactive) == 0);
  CHECK(inelastic > 1200 * 250 / 20);  // cracked, crushed and slipped
  CHECK(inactive > 1200 * 250 / 20);
  CHECK(inactive < 1200 * 250);
}

TEST_CASE("every damping policy with spring states: the viscous stress the state holds is what spring_stress returned") {
  long long nonzero = 0;
  CHECK(held_mismatches(damping::None{}, 1e-5, nonzero) == 0);
  CHECK(nonzero == 0);
  CHECK(held_mismatches(damping::StiffnessProportional::from_damping_ratio(0.05, 10), 1e-5, nonzero) == 0);
  CHECK(nonzero > 30000);
  nonzero = 0;
  CHECK(held_mismatches(damping::Rayleigh::from_two_frequencies(0.03, 1, 0.03, 40), 1e-5, nonzero) == 0);
  CHECK(nonzero > 30000);
  nonzero = 0;
  auto maxwell = damping::to_policy<3>(damping::fit_maxwell(damping::MaxwellFitOptions{}));
  maxwell.prepare(1e-5);
  CHECK(held_mismatches(maxwell, 1e-5, nonzero) == 0);
  CHECK(nonzero > 30000);
}
