// The contact pass stores no traction per CP: output takes it back from the joint law's history
// (ContactLaw::traction) and the damping policy's spring state (DampingPolicy::held_stress). Reference: what
// update() and spring_stress() returned on the step, over random paths through every regime. Also the other way
// round: the damping switch update() returns (Response::damping_active, which the contact pass uses) is the one
// the history holds (ContactLaw::damping_active, which output, release and redetection use).

#include <doctest/doctest.h>

#include "../shipped.hpp"

#include <cmath>
#include <type_traits>
#include <vector>

#include "blockdem/contact/laws.hpp"
#include "blockdem/core/random.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/maxwell_fit.hpp"
#include "blockdem/damping/policies.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_traction {

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
    if (path % 3 == 2) Law::start_unbonded(h);  // a contact point found during the run
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

/// The parameter sets of each law the random paths run through, and how many paths.
template <class Law>
struct TractionCase {
  std::vector<typename Law::Parameters> sets;
  int paths = 0;
};
template <class Law>
TractionCase<Law> traction_case() {
  if constexpr (std::is_same_v<Law, contact::Elastic>) {
    return {{{1e10, 4e9}, {3.9e10, 1.6e10}}, 400};
  } else if constexpr (std::is_same_v<Law, contact::MohrCoulomb>) {
    return {{{1e10, 4e9, 0, 0, 0.6},                                             // dry joint
             {1e10, 4e9, 0.3e6, 0.3e6, 38 * degree, 0.05e6, 0.1e6, 30 * degree},  // bonded, residual strengths
             {3.9e10, 1.6e10, 0.1e6, 0.0, 0.0}},                                 // no friction
            1200};
  } else if constexpr (std::is_same_v<Law, contact::ElastoSoftening>) {
    using contact::ElastoSoftening;
    const auto table1 = ElastoSoftening::Parameters::from_material();
    const contact::JointStiffness k{table1.normal_stiffness, table1.shear_stiffness};
    const ElastoSoftening::FractureEnergies g{table1.tension_fracture_energy, table1.shear_fracture_energy,
                                              table1.compression_fracture_energy};
    return {{table1, ElastoSoftening::Parameters(k, {0.3e6, 0.3e6, 38 * degree, 9.1e6, 0.05e6, 0.1e6, 30 * degree}, g),
             ElastoSoftening::Parameters(k, {0.1e6, 0.2e6, 0.0, 2e6, 0, 0, 0.0}, {5.0, 20.0, 500.0})},
            1200};
  } else {
    static_assert(test::unlisted<Law>, "a new law: give it parameter sets for the random paths here");
  }
}

/// Each policy for the random steps (Maxwell<3>: fitted to the default 3 % over 1-40 Hz).
template <class Damping>
Damping held_policy() {
  if constexpr (std::is_same_v<Damping, damping::None> || std::is_same_v<Damping, damping::Local>) return {};
  else if constexpr (std::is_same_v<Damping, damping::MassProportional>) return damping::MassProportional::from_damping_ratio(0.05, 10);
  else if constexpr (std::is_same_v<Damping, damping::StiffnessProportional>) return damping::StiffnessProportional::from_damping_ratio(0.05, 10);
  else if constexpr (std::is_same_v<Damping, damping::Rayleigh>) return damping::Rayleigh::from_two_frequencies(0.03, 1, 0.03, 40);
  else if constexpr (std::is_same_v<Damping, damping::Maxwell<3>>) return damping::to_policy<3>(damping::fit_maxwell(damping::MaxwellFitOptions{}));
  else static_assert(test::unlisted<Damping>, "a new policy: give it parameters for the random steps here");
}

}  // namespace

TEST_CASE_TEMPLATE_DEFINE("every joint law: the traction and damping switch its history holds are what its last update returned (random paths)", Law, traction_law_case) {
  const auto c = traction_case<Law>();
  long long inelastic = 0, inactive = 0;
  CHECK(traction_mismatches<Law>(c.sets, c.paths, inelastic, inactive) == 0);
  const long long steps = 250LL * c.paths;
  if constexpr (std::is_same_v<Law, contact::Elastic>) {
    // Only its never-bonded paths (a third) open, and of their steps only those that open with shear held dissipate.
    CHECK(inelastic > 0);
    CHECK(inactive > steps / 20);
    CHECK(inactive < steps / 3);
  } else {
    CHECK(inelastic > steps / 20);  // the paths slip, crack, crush or open, not only the elastic range
    CHECK(inactive > steps / 20);   // both values of the switch are checked
    CHECK(inactive < steps);
  }
}
TEST_CASE_TEMPLATE_APPLY(traction_law_case, contact::ShippedLaws);

TEST_CASE_TEMPLATE_DEFINE("every damping policy: the viscous stress its spring state holds is what spring_stress returned", Damping,
                          held_policy_case) {
  auto policy = held_policy<Damping>();
  if constexpr (damping::PreparedDamping<Damping>) policy.prepare(1e-5);
  long long nonzero = 0;
  CHECK(held_mismatches(policy, 1e-5, nonzero) == 0);
  if constexpr (damping::PerSpringDamping<Damping>) CHECK(nonzero > 30000);
  else CHECK(nonzero == 0);  // no springs: no viscous stress at a CP
}
TEST_CASE_TEMPLATE_APPLY(held_policy_case, damping::ShippedPolicies);

}  // namespace test_traction
