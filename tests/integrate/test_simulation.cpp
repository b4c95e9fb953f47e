// Validation of the explicit integrator with every damping policy on systems with analytical answers
// (issue 3, tests 1-5). Each test names its reference.

#include <doctest/doctest.h>

#include "../approx.hpp"
#include "../area_frame.hpp"
#include "../shipped.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "blockdem/contact/laws.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/maxwell_fit.hpp"
#include "blockdem/damping/policies.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "fixtures.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_simulation {

namespace {

constexpr std::uint8_t vertical_only = model::Fixity::translation_x | model::Fixity::translation_y | model::Fixity::all_rotations;

/// A 1 x 1 x 1 m block of 2000 kg on 4 elastic CPs of 0.25 m^2, vertical translation only, tuned to f_hz:
/// omega = sqrt(k_n A / m).
template <class Damping>
test::Decay vibrate(Damping damping, double f_hz, double cycles = 40, double steps_per_cycle = 400) {
  auto s = test::block_on_base(1, 1, 1);
  s.model.gravity = Vec3::Zero();
  s.model.bodies.fixity[s.block] = vertical_only;
  s.model.bodies.velocity[s.block] = Vec3(0, 0, 1e-3);
  const double omega = two_pi * f_hz;
  const double kn = 2000.0 * omega * omega;
  Simulation<Damping, contact::Elastic> sim(s.model, damping, [&](int, int) { return contact::Elastic::Parameters(kn, kn); });
  sim.set_timestep(1.0 / (f_hz * steps_per_cycle));
  std::vector<double> t, z;
  const double z0 = s.model.bodies.position[s.block].z();
  const auto n = static_cast<long long>(cycles * steps_per_cycle);
  for (long long i = 0; i < n; ++i) {
    sim.step();
    t.push_back(sim.time());
    z.push_back(s.model.bodies.position[s.block].z() - z0);
  }
  return test::measure_decay(t, z);
}

}  // namespace

TEST_CASE("simulation: a block on an elastic joint vibrates at sqrt(k A / m) (SDOF, analytical)") {
  for (double f : {0.5, 3.0, 20.0, 100.0}) {
    const auto d = vibrate(damping::None{}, f);
    CAPTURE(f);
    CHECK(d.frequency_hz == test::approx(f).epsilon(0.005));
    CHECK(d.damping_ratio < 1e-4);
  }
}

namespace {
/// The free-decay case of each policy with a damping ratio zeta(omega): the policy, the cycles measured at f (Hz),
/// and whether zeta is compared at the nominal frequency f or at the measured one.
template <class Damping>
struct DecayCase {
  const char* what;
  Damping policy;
  double (*cycles)(double f);
  bool at_nominal_frequency;
};
template <class Damping>
DecayCase<Damping> decay_case() {
  if constexpr (std::is_same_v<Damping, damping::MassProportional>) {
    return {"mass-proportional, 2 % at 5 Hz (eq. 10 with beta = 0)", damping::MassProportional::from_damping_ratio(0.02, 5.0),
            [](double f) { return f < 1 ? 6.0 : 40.0; }, true};
  } else if constexpr (std::is_same_v<Damping, damping::StiffnessProportional>) {
    return {"stiffness-proportional, 2 % at 10 Hz (eq. 10 with alpha = 0)",
            damping::StiffnessProportional::from_damping_ratio(0.02, 10.0), [](double f) { return f > 50 ? 6.0 : 40.0; }, false};
  } else if constexpr (std::is_same_v<Damping, damping::Rayleigh>) {
    return {"Rayleigh, 3 % at 1 and 40 Hz (eq. 10)", damping::Rayleigh::from_two_frequencies(0.03, 1.0, 0.03, 40.0),
            [](double) { return 10.0; }, false};
  } else if constexpr (std::is_same_v<Damping, damping::Maxwell<3>>) {
    damping::MaxwellFitOptions options;
    options.damping_ratio = 0.04;
    return {"Maxwell<3>, fitted to 4 % over 1-40 Hz (eq. 19 at the measured frequency)",
            damping::to_policy<3>(damping::fit_maxwell(options)), [](double) { return 12.0; }, false};
  } else {
    static_assert(test::unlisted<Damping>, "a new policy with a damping ratio: give it a free-decay case here");
  }
}
/// The policies with a damping ratio zeta(omega) (not None, nor Local, which is not viscous).
template <class Damping>
struct HasDampingRatio : std::bool_constant<requires(const Damping& d) { d.damping_ratio(1.0); }> {};
}  // namespace

TEST_CASE_TEMPLATE_DEFINE("simulation: the damping ratio measured from free decay matches each policy's zeta(f) within 5 %", Damping,
                          damping_ratio_case) {
  const double frequencies[] = {0.5, 2.0, 8.0, 30.0, 100.0};
  const auto c = decay_case<Damping>();
  INFO(c.what);
  for (double f : frequencies) {
    CAPTURE(f);
    const auto d = vibrate(c.policy, f, c.cycles(f));
    const double at = c.at_nominal_frequency ? f : d.frequency_hz;
    CHECK(d.damping_ratio == test::approx(c.policy.damping_ratio(two_pi * at)).epsilon(0.05));
  }
}
TEST_CASE_TEMPLATE_APPLY(damping_ratio_case, test::Select<HasDampingRatio, damping::ShippedPolicies>);

namespace {
/// Runs a vertical-only block at `factor` times the predicted critical timestep; returns max |z| / initial peak.
template <class Damping>
double growth_at(Damping damping, double factor, long long steps = 100000) {
  auto s = test::block_on_base(1, 1, 1);
  s.model.gravity = Vec3::Zero();
  s.model.bodies.fixity[s.block] = vertical_only;
  s.model.bodies.velocity[s.block] = Vec3(0, 0, 1e-3);
  const double omega = 2e5;  // rad/s: well above every Maxwell corner frequency, as in a DEM model (dt ~ 1e-5 s)
  const double kn = 2000.0 * omega * omega;
  Simulation<Damping, contact::Elastic> sim(s.model, damping, [&](int, int) { return contact::Elastic::Parameters(kn, kn); });
  sim.set_timestep(factor * sim.critical_timestep(), TimestepCheck::unchecked);
  const double z0 = s.model.bodies.position[s.block].z();
  const double initial = 1e-3 / omega;
  double largest = 0;
  for (long long i = 0; i < steps; ++i) {
    try {
      sim.step();
    } catch (const RunawayError&) {
      break;  // beyond 100 m/s: the run guard stopped it, as it stops every diverging run
    }
    largest = std::max(largest, std::abs(s.model.bodies.position[s.block].z() - z0));
    if (!(largest < 1e6 * initial)) break;
  }
  return largest / initial;
}
}  // namespace

namespace {
/// The policies whose timestep factor the growth test checks, each with the factor expected at omega_max = 2e5 rad/s
/// where the test states it.
template <class Damping>
struct StabilityCase {
  const char* what;
  Damping policy;
  std::optional<double> factor;
};
template <class Damping>
constexpr bool in_stability_test() {
  if constexpr (std::is_same_v<Damping, damping::None> || std::is_same_v<Damping, damping::Local> ||
                std::is_same_v<Damping, damping::StiffnessProportional> || std::is_same_v<Damping, damping::Maxwell<3>>)
    return true;
  else if constexpr (std::is_same_v<Damping, damping::MassProportional>) return false;  // factor 1: None's limit (eq. 1)
  else if constexpr (std::is_same_v<Damping, damping::Rayleigh>) return false;  // StiffnessProportional's factor (eq. 11)
  else static_assert(test::unlisted<Damping>, "a new policy: say whether the growth test checks its timestep factor");
}
template <class Damping>
struct InStabilityTest : std::bool_constant<in_stability_test<Damping>()> {};
template <class Damping>
StabilityCase<Damping> stability_case() {
  if constexpr (std::is_same_v<Damping, damping::None>) {
    return {"no damping (eq. 1)", {}, std::nullopt};
  } else if constexpr (std::is_same_v<Damping, damping::Local>) {
    return {"local damping 0.8 (factor 1 / sqrt(1.8): the force of a mode that turns every step is amplified)", {},
            1 / std::sqrt(1.8)};
  } else if constexpr (std::is_same_v<Damping, damping::StiffnessProportional>) {
    return {"stiffness-proportional, zeta = 0.3 at omega_max (eq. 11: factor 0.744)", {2 * 0.3 / 2e5}, std::sqrt(1.09) - 0.3};
  } else {
    static_assert(std::is_same_v<Damping, damping::Maxwell<3>>);
    damping::MaxwellFitOptions options;
    options.damping_ratio = 0.04;
    return {"Maxwell<3>, 4 % over 1-40 Hz (eq. 20: factor 1 / sqrt(1.39))", damping::to_policy<3>(damping::fit_maxwell(options)),
            std::nullopt};
  }
}
}  // namespace

TEST_CASE_TEMPLATE_DEFINE("simulation: stable at 0.95 and unstable at 1.1 times the critical timestep (eq. 1, 11, 20)", Damping,
                          stability_case_test) {
  const auto c = stability_case<Damping>();
  INFO(c.what);
  if (c.factor) CHECK(c.policy.timestep_factor(2e5) == test::approx(*c.factor));
  CHECK(growth_at(c.policy, 0.95) < 10);
  CHECK(growth_at(c.policy, 1.1) > 1e3);
}
TEST_CASE_TEMPLATE_APPLY(stability_case_test, test::Select<InStabilityTest, damping::ShippedPolicies>);

TEST_CASE("simulation: an undamped elastic run conserves energy and is time reversible") {
  // A block free in all six degrees of freedom, spinning and bouncing on elastic joints without gravity.
  auto s = test::block_on_base(0.6, 0.4, 1.0);
  s.model.gravity = Vec3(0, 0, -9.81);
  auto& b = s.model.bodies;
  b.velocity[s.block] = Vec3(2e-3, -1e-3, 3e-3);
  b.angular_velocity[s.block] = Vec3(1e-3, 2e-3, -1.5e-3);
  const double kn = 1e7;  // soft enough that the block turns by ~1e-3 rad, far above rounding
  model::ContactSettings contacts;
  contacts.tolerance = 0.01;  // no re-detection during the run: this test is about the scheme
  Simulation<damping::None, contact::Elastic> sim(s.model, damping::None{},
                                                  [&](int, int) { return contact::Elastic::Parameters(kn, 0.4 * kn); },
                                                  contacts);
  sim.set_timestep(0.1 * 2.0 / sim.estimated_omega_max());  // small, so that rounding, not the scheme, shows
  const Vec3 x0 = b.position[s.block];
  const Mat3 r0 = b.rotation[s.block];
  const auto n = 100000;
  double worst = 0;
  double excursion = 0;
  double turn = 0;
  for (int i = 0; i < n; ++i) {
    sim.step();
    excursion = std::max(excursion, (b.position[s.block] - x0).norm());
    turn = std::max(turn, (b.rotation[s.block] - r0).norm());
    if (i % 1000 == 999) worst = std::max(worst, sim.energy().balance_error);
  }
  CHECK(worst < 1e-3);  // total energy (kinetic + elastic - gravity work) within 0.1 %
  sim.reverse();
  for (int i = 0; i < n; ++i) sim.step();
  // Back to the start, relative to how far the block went.
  CHECK((b.position[s.block] - x0).norm() / excursion < 1e-9);
  CHECK((b.rotation[s.block] - r0).norm() / turn < 1e-9);  // (not angularDistance: its acos floor is 1e-8)
  CHECK(sim.detections() == 1);
}

TEST_CASE("simulation: contact points that a re-detection finds in overlap start touching, and the block rebounds with the energy it came with") {
  // A block falls flat onto its base, undamped, without gravity. Checked every 400 steps (2 mm of fall), its contact
  // is first found 0.8 mm deep. Loaded at that overlap, the new CPs would hold 1/2 kn d^2 A (32 J here) that no force
  // stored, and the block would leave with that much more kinetic energy than it came with. They start touching
  // instead (the laws are incremental, as in 3DEC): no energy appears, and the block leaves with what it came with.
  auto s = test::block_on_base(1.0, 1.0, 0.5);  // 1,000 kg on a 1 m^2 face
  auto& b = s.model.bodies;
  s.model.gravity = Vec3::Zero();
  b.position[s.block].z() += 3.2e-3;
  const double v0 = 0.5;
  b.velocity[s.block] = Vec3(0, 0, -v0);
  const double kn = 1e8;
  model::ContactSettings contacts;
  contacts.redetection_check_interval = 400;
  Simulation<damping::None, contact::MohrCoulomb> sim(s.model, damping::None{}, [&](int, int) {
    return contact::MohrCoulomb::Parameters(kn, kn, 0, 0, pi / 6);
  }, contacts);
  REQUIRE(sim.contact_points() == 0);
  sim.set_timestep(1e-5);
  const double mass = 1000.0, kinetic0 = 0.5 * mass * v0 * v0;
  const double bottom0 = b.position[s.block].z() - 3.2e-3;  // the block's bottom face where it started, less the lift
  double depth = 0;
  while (sim.contact_points() == 0 && sim.steps() < 2000) {
    depth = bottom0 - b.position[s.block].z();  // overlap where the step about to be taken detects (before it moves)
    sim.step();
  }
  REQUIRE(sim.contact_points() > 0);
  MESSAGE("found " << 1e3 * depth << " mm deep; the balance's term for re-detection " << sim.energy().contact_update << " J");
  CHECK(depth > 5e-4);
  CHECK(std::abs(sim.energy().contact_update) < 1e-9 * kinetic0);
  double lowest = b.position[s.block].z();
  // The bounce, then clear of the base until a check drops the open CPs.
  while ((sim.contact_points() > 0 || b.velocity[s.block].z() < 0) && sim.steps() < 20000) {
    sim.step();
    lowest = std::min(lowest, b.position[s.block].z());
  }
  REQUIRE(sim.contact_points() == 0);
  const auto e = sim.energy();
  const double kinetic = 0.5 * mass * b.velocity[s.block].squaredNorm();
  MESSAGE("rebound " << b.velocity[s.block].z() << " m/s: kinetic " << kinetic << " J against " << kinetic0
                     << " J; balance error " << e.balance_error);
  // The spring stood from the detection on: the block went down v0 sqrt(m / (kn A)) = 1.58 mm below where it was
  // found, and came back with its speed (within the leapfrog's half step at the detection, 1/2 dt v F).
  const double compression = v0 * std::sqrt(mass / kn);
  CHECK(bottom0 - lowest - depth == doctest::Approx(compression).epsilon(0.02));
  CHECK(kinetic == doctest::Approx(kinetic0).epsilon(0.01));
  CHECK(e.balance_error < 2e-3);
}

TEST_CASE("simulation: a block in free fall is detected again as its clearance halves, and lands without overlap") {
  // A 0.4 m cube dropped from 1 m above its base. Re-detected every half tolerance (0.5 mm) of its fall, it would be
  // detected some 2,000 times before it lands; with the redetection distance half its clearance it is detected each
  // time that clearance has halved (about log2(1 m / 1 mm) = 10 times), and still before it touches.
  auto s = test::block_on_base(0.4, 0.4, 0.4);
  auto& b = s.model.bodies;
  b.position[s.block].z() += 1.0;
  Simulation<damping::None, contact::Elastic> sim(s.model, damping::None{}, [](int, int) { return contact::Elastic::Parameters(1e9, 1e9); });
  REQUIRE(sim.contact_points() == 0);
  const double dt = 1e-5;
  sim.set_timestep(dt);
  double bottom = 1.0;
  while (sim.contact_points() == 0 && sim.steps() < 100000) {
    bottom = b.position[s.block].z() - 0.2;  // the gap when the step about to be taken detects
    sim.step();
  }
  REQUIRE(sim.contact_points() > 0);
  MESSAGE("landed after " << sim.steps() << " steps and " << sim.detections() << " detections, found at a gap of "
                          << 1e3 * bottom << " mm, at " << -b.velocity[s.block].z() << " m/s");
  CHECK(sim.detections() < 40);
  CHECK(bottom > -b.velocity[s.block].norm() * dt);  // found before it overlaps by more than a step's fall
  CHECK(bottom < model::ContactSettings{}.tolerance);
}

namespace {
/// Energy balance error after a damped free vibration (vertical only) with the given policy.
template <class Damping>
double balance_after_decay(Damping damping) {
  auto s = test::block_on_base(1, 1, 1);
  s.model.bodies.fixity[s.block] = vertical_only;
  s.model.bodies.velocity[s.block] = Vec3(0, 0, 1e-2);
  const double omega = two_pi * 10.0;
  Simulation<Damping, contact::Elastic> sim(s.model, damping,
                                            [&](int, int) { return contact::Elastic::Parameters(2000 * omega * omega, 2000 * omega * omega); });
  sim.set_timestep(1.0 / (10.0 * 400));
  for (int i = 0; i < 8000; ++i) sim.step();  // 20 cycles
  const auto e = sim.energy();
  CHECK(e.viscous > 0);
  return e.balance_error;
}
}  // namespace

namespace {
/// The viscous policies of the energy-balance test, each with its coefficients.
template <class Damping>
constexpr bool in_balance_test() {
  if constexpr (std::is_same_v<Damping, damping::MassProportional> || std::is_same_v<Damping, damping::StiffnessProportional> ||
                std::is_same_v<Damping, damping::Rayleigh> || std::is_same_v<Damping, damping::Maxwell<3>>)
    return true;
  else if constexpr (std::is_same_v<Damping, damping::None>) return false;  // no viscous work (the undamped balance: above)
  else if constexpr (std::is_same_v<Damping, damping::Local>) return false;  // not viscous: it settles a model
  else static_assert(test::unlisted<Damping>, "a new policy: say whether the energy-balance test runs it");
}
template <class Damping>
struct InBalanceTest : std::bool_constant<in_balance_test<Damping>()> {};
template <class Damping>
Damping balance_policy() {
  if constexpr (std::is_same_v<Damping, damping::MassProportional>) return damping::MassProportional::from_damping_ratio(0.05, 10);
  else if constexpr (std::is_same_v<Damping, damping::StiffnessProportional>) return damping::StiffnessProportional::from_damping_ratio(0.05, 10);
  else if constexpr (std::is_same_v<Damping, damping::Rayleigh>) return damping::Rayleigh::from_two_frequencies(0.03, 1, 0.03, 40);
  else {
    static_assert(std::is_same_v<Damping, damping::Maxwell<3>>);
    damping::MaxwellFitOptions options;
    options.damping_ratio = 0.05;
    return damping::to_policy<3>(damping::fit_maxwell(options));
  }
}
}  // namespace

TEST_CASE_TEMPLATE_DEFINE("simulation: the energy balance closes with every damping policy (viscous dissipation accounted)", Damping,
                          balance_case) {
  CHECK(balance_after_decay(balance_policy<Damping>()) < 1e-3);
}
TEST_CASE_TEMPLATE_APPLY(balance_case, test::Select<InBalanceTest, damping::ShippedPolicies>);

TEST_CASE("simulation: bad input names the parameter, the block or the allowed range") {
  auto s = test::block_on_base(1, 1, 1);
  Simulation<damping::None, contact::Elastic> sim(s.model, damping::None{}, [](int, int) { return contact::Elastic::Parameters(1e9, 1e9); });
  CHECK_THROWS_WITH_AS(sim.set_timestep(2 * sim.critical_timestep()), doctest::Contains("exceeds the critical timestep"), InvalidArgument);
  CHECK_THROWS_WITH_AS(sim.set_timestep(-1), doctest::Contains("timestep must be > 0"), InvalidArgument);
  CHECK_THROWS_WITH_AS(contact::Elastic::Parameters(0, 1e9), doctest::Contains("normal stiffness must be > 0 Pa/m"), InvalidArgument);
  CHECK_THROWS_WITH_AS(contact::MohrCoulomb::Parameters(1e9, -1, 0, 0, 0.5), doctest::Contains("shear stiffness must be > 0 Pa/m"), InvalidArgument);
  CHECK_THROWS_WITH_AS(contact::MohrCoulomb::Parameters(1e9, 1e9, 0, 0, 2.0), doctest::Contains("friction angle must be in [0, 90)"), InvalidArgument);
  model::ContactSettings bad;
  bad.tolerance = 0;
  CHECK_THROWS_WITH_AS((Simulation<damping::None, contact::Elastic>(s.model, damping::None{}, [](int, int) { return contact::Elastic::Parameters(1e9, 1e9); }, bad)),
                       doctest::Contains("tolerance must be > 0"), InvalidArgument);
}

TEST_CASE("simulation: Maxwell branches act while the joint is closed and release their stress while it is open") {
  // A block dropped onto a dry joint (no tension) from 1 mm: in contact the branches carry stress; thrown off again,
  // the open joint's branches hold none (DESIGN.md §4: a dashpot never acts across an open joint).
  auto s = test::block_on_base(1, 1, 1);
  s.model.gravity = Vec3(0, 0, -9.81);
  s.model.bodies.velocity[s.block] = Vec3(0, 0, -0.05);
  damping::MaxwellFitOptions options;
  model::ContactSettings contacts;
  contacts.tolerance = 0.01;
  Simulation<damping::Maxwell<3>, contact::MohrCoulomb> sim(
      s.model, damping::to_policy<3>(damping::fit_maxwell(options)),
      [](int, int) { return contact::MohrCoulomb::Parameters(1e8, 1e8, 0, 0, 0.6); }, contacts);
  const auto& g = sim.group<contact::MohrCoulomb>();
  auto branch_stress = [&] {
    double sum = 0;
    for (std::size_t c = 0; c < g.contacts(); ++c)
      for (std::uint32_t k = g.first_point[c]; k < g.first_point[c + 1]; ++k)
        for (const auto& direction : g.spring_at(c, k))
          for (double b : direction) sum += std::abs(b);
    return sum;
  };
  double closed_max = 0;
  bool saw_open = false;
  for (int i = 0; i < 20000; ++i) {
    sim.step();
    const bool open = g.history[0].gap > 0 && g.history[1].gap > 0 && g.history[2].gap > 0 && g.history[3].gap > 0;
    if (!open) closed_max = std::max(closed_max, branch_stress());
    if (open) {
      saw_open = true;
      CHECK(branch_stress() == 0.0);
    }
    if (i == 100) s.model.bodies.velocity[s.block].z() = 0.2;  // throw it up: the joint opens
  }
  CHECK(saw_open);
  CHECK(closed_max > 0);
}

TEST_CASE("simulation: Maxwell branches in the contact-field form give the motion of every CP's own branches") {
  // Reference: the same run with every CP keeping its own branch states (Maxwell::contact_field = false). A slender
  // block settles on a dry joint, the contact carrying one field per branch; a redetection moves the field to the
  // new contact; then the block is set rocking, an edge lifts, the open CPs release their branches and the contact
  // goes over to per-CP states.
  struct Result {
    Vec3 position;
    Quaternion orientation;
    EnergyReport energy;
    bool field_settled = false, field_redetected = false, field_rocking = true;
    std::vector<double> normal_stress;  // Pa, at each CP, settled (the output's tractions)
  };
  auto run = [](bool field_form) {
    auto s = test::block_on_base(0.4, 0.4, 1.0);
    s.model.gravity = Vec3(0, 0, -9.81);
    damping::MaxwellFitOptions options;
    auto policy = damping::to_policy<3>(damping::fit_maxwell(options));
    policy.contact_field = field_form;
    model::ContactSettings contacts;
    contacts.tolerance = 0.01;
    Simulation<damping::Maxwell<3>, contact::MohrCoulomb> sim(
        s.model, policy, [](int, int) { return contact::MohrCoulomb::Parameters(1e9, 4e8, 0, 0, 0.6); }, contacts);
    const auto& g = sim.group<contact::MohrCoulomb>();
    Result r;
    for (int i = 0; i < 4000; ++i) {
      if (i == 1000) {
        sim.synchronize();
        // Turning about the centre of its base (no slip there): one side presses in, the other lifts.
        const Vec3 w(0.05, 0.3, 0);
        s.model.bodies.angular_velocity[s.block] = w;
        s.model.bodies.velocity[s.block] = w.cross(s.model.bodies.position[s.block]);
      }
      sim.step();
      if (i == 400) r.field_settled = g.field_form[0] != 0;
      if (i == 500) sim.redetect();
      if (i == 900) {
        r.field_redetected = g.field_form[0] != 0;
        sim.synchronize();
        sim.visit_contacts([&](const auto& v) { r.normal_stress.push_back(v.normal_stress); });
      }
    }
    r.field_rocking = g.field_form[0] != 0;
    r.position = s.model.bodies.position[s.block];
    r.orientation = s.model.bodies.orientation[s.block];
    r.energy = sim.energy();
    return r;
  };
  const auto field = run(true);
  const auto point = run(false);
  CHECK(field.field_settled);
  CHECK(field.field_redetected);
  CHECK_FALSE(field.field_rocking);  // the joint opened
  CHECK_FALSE(point.field_settled);
  REQUIRE(field.normal_stress.size() == point.normal_stress.size());
  for (std::size_t k = 0; k < field.normal_stress.size(); ++k)
    CHECK(field.normal_stress[k] == test::approx(point.normal_stress[k]).epsilon(1e-9));
  const auto start = test::block_on_base(0.4, 0.4, 1.0).model.bodies.position[1];
  CHECK((point.position - start).norm() > 1e-4);  // it rocked
  CHECK((field.position - point.position).norm() == test::approx(0.0).scale((point.position - start).norm()).epsilon(1e-9));
  CHECK(field.orientation.angularDistance(point.orientation) < 1e-10);
  CHECK(field.energy.viscous > 0);
  CHECK(field.energy.viscous == test::approx(point.energy.viscous).epsilon(1e-8));
  CHECK(field.energy.elastic == test::approx(point.energy.elastic).epsilon(1e-8));
}

namespace {

/// A slender block settles on its base, is set rocking at step 1000 (one edge lifts, the joint slides) and rocks
/// until step 3000. Every 100 steps: the forces the output gives at the CPs (area x traction, the traction taken
/// back from the law's history and the damping state) must add up to the contact's force on B from the contact
/// pass (1e-9 of the block's weight). Returns how many checks ran in a contact whose CPs kept their own branch
/// states (a Maxwell field released) and how many with some viscous stress at a CP.
template <class Damping, class Law>
std::array<int, 2> tractions_add_up(Damping policy, typename Law::Parameters joint) {
  auto s = test::block_on_base(0.4, 0.4, 1.0);
  s.model.gravity = Vec3(0, 0, -9.81);
  const double weight = 0.16 * 2000 * 9.81;
  model::ContactSettings contacts;
  contacts.tolerance = 0.01;
  Simulation<Damping, Law> sim(s.model, policy, [&](int, int) { return joint; }, contacts);
  const auto& g = sim.template group<Law>();
  std::array<int, 2> seen{0, 0};
  for (int i = 0; i < 3000; ++i) {
    if (i == 1000) {
      sim.synchronize();
      const Vec3 w(0.05, 0.3, 0);
      s.model.bodies.angular_velocity[s.block] = w;
      s.model.bodies.velocity[s.block] = w.cross(s.model.bodies.position[s.block]) + Vec3(0.05, 0, 0);
    }
    sim.step();
    if (i % 100 != 99) continue;
    sim.synchronize();
    std::vector<Vec3> sum(g.contacts(), Vec3::Zero());
    std::vector<std::size_t> contact_of;
    for (std::size_t c = 0; c < g.contacts(); ++c)
      for (std::uint32_t k = g.first_point[c]; k < g.first_point[c + 1]; ++k) contact_of.push_back(c);
    std::size_t k = 0;
    bool viscous = false;
    sim.visit_contacts([&](const auto& v) {
      sum[contact_of.at(k)] += v.force;
      const auto law = Law::traction(g.properties[g.property[contact_of[k]]], g.history[k]);
      viscous = viscous || std::abs(v.normal_stress - law[0]) > 1e-6 * std::abs(law[0]) + 1e-3;
      ++k;
    });
    REQUIRE(k == g.history.size());
    for (std::size_t c = 0; c < g.contacts(); ++c) {
      INFO("step " << i << ", contact " << c);
      CHECK((sum[c] - g.force[c]).norm() <= 1e-9 * weight);
    }
    if constexpr (std::remove_cvref_t<decltype(g)>::has_field) seen[0] += g.contacts() > 0 && g.field_form[0] == 0;
    seen[1] += viscous;
  }
  CHECK((s.model.bodies.position[s.block] - test::block_on_base(0.4, 0.4, 1.0).model.bodies.position[1]).norm() > 1e-4);  // it rocked
  return seen;
}

/// Each policy of the traction test on a dry Mohr-Coulomb joint (Maxwell<3>: fitted to the default 3 % over 1-40 Hz).
/// Not Local: it is for settling, and takes out the rocking the test sets off (the block moves 0.07 mm, not 0.1).
template <class Damping>
struct InTractionTest : std::bool_constant<!std::is_same_v<Damping, damping::Local>> {};
template <class Damping>
Damping traction_policy() {
  if constexpr (std::is_same_v<Damping, damping::None>) return {};
  else if constexpr (std::is_same_v<Damping, damping::MassProportional>) return damping::MassProportional::from_damping_ratio(0.05, 5);
  else if constexpr (std::is_same_v<Damping, damping::StiffnessProportional>) return damping::StiffnessProportional::from_damping_ratio(0.05, 20);
  else if constexpr (std::is_same_v<Damping, damping::Rayleigh>) return damping::Rayleigh::from_two_frequencies(0.03, 1, 0.03, 40);
  else if constexpr (std::is_same_v<Damping, damping::Maxwell<3>>) return damping::to_policy<3>(damping::fit_maxwell(damping::MaxwellFitOptions{}));
  else static_assert(test::unlisted<Damping>, "a new policy: give it parameters for the traction test here");
}

}  // namespace

TEST_CASE_TEMPLATE_DEFINE("output: the CP tractions, taken back from the joint histories and damping states, add up to the contact forces",
                          Damping, traction_sum_case) {
  // Reference: the contact pass's own resultant of the same stresses (the tractions are no longer stored per CP).
  const contact::MohrCoulomb::Parameters dry(1e9, 4e8, 0, 0, 0.6);
  const auto seen = tractions_add_up<Damping, contact::MohrCoulomb>(traction_policy<Damping>(), dry);
  if constexpr (damping::PerSpringDamping<Damping>) CHECK(seen[1] > 10);  // viscous stresses at the CPs were checked
  else CHECK(seen[1] == 0);
  if constexpr (damping::ContactFieldDamping<Damping>) CHECK(seen[0] > 5);  // also after the field was released
}
TEST_CASE_TEMPLATE_APPLY(traction_sum_case, test::Select<InTractionTest, damping::ShippedPolicies>);

TEST_CASE("output: the CP tractions add up to the contact forces also for the other laws and Maxwell's per-CP form") {
  damping::MaxwellFitOptions options;
  const auto maxwell = damping::to_policy<3>(damping::fit_maxwell(options));
  auto per_cp = maxwell;
  per_cp.contact_field = false;
  const contact::MohrCoulomb::Parameters dry(1e9, 4e8, 0, 0, 0.6);
  CHECK(tractions_add_up<damping::None, contact::Elastic>({}, {1e9, 4e8})[1] == 0);
  CHECK(tractions_add_up<damping::Maxwell<3>, contact::MohrCoulomb>(per_cp, dry)[1] > 10);
  CHECK(tractions_add_up<damping::Maxwell<3>, contact::ElastoSoftening>(maxwell, contact::ElastoSoftening::Parameters::from_material())[1] > 10);
}

TEST_CASE("contact group: a Maxwell field kept as forces gives back the elongations at the CPs, also when G is singular") {
  // Reference: the CP elongations B(x1, x2) h of the field given to begin_contact. complete() keeps F = G h; the
  // elongations recovered from F must give the same B h at every CP of the contact: with four CPs (G regular, h
  // itself), with two (G singular: a turn about the line through them moves neither) and with one. The CPs are
  // placed in the frame of their areas (centroid, principal axes), as the simulation places them.
  using Group = ContactGroup<contact::Elastic, damping::Maxwell<3>>;
  std::vector<std::vector<std::array<double, 3>>> layouts{
      {{0.12, 0.05, 0.01}, {-0.12, 0.05, 0.02}, {-0.12, -0.05, 0.015}, {0.3, -0.2, 0.005}},
      {{0.12, 0.05, 0.01}, {-0.2, -0.03, 0.02}},
      {{0.1, -0.04, 0.01}}};
  for (auto& points : layouts) {
    test::to_area_frame(points);
    Group g;
    g.properties.push_back(contact::Elastic::Parameters(1e10, 4e9));
    Group::Field field{};
    for (std::size_t i = 0; i < field.size(); ++i)
      for (std::size_t j = 0; j < 6; ++j) field[i][j] = 1e-6 * std::sin(1.0 + 3.0 * static_cast<double>(i) + static_cast<double>(j));
    g.begin_contact(0, 1, 0, Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX(), true, field);
    for (const auto& [x1, x2, a] : points) g.add_point(x1, x2, a, {}, {}, 0.0, 0.0);
    g.complete(2);
    const auto h = g.field_elongations(0);
    for (std::size_t i = 0; i < field.size(); ++i)
      for (const auto& [x1, x2, a] : points) {
        damping::Maxwell<3>::Generalised given{};
        std::copy_n(field[i].begin(), 6, given.begin());
        const auto want = damping::Maxwell<3>::field_stress(given, 1.0, 1.0, x1, x2);
        const auto got = damping::Maxwell<3>::field_stress(h[i], 1.0, 1.0, x1, x2);
        for (std::size_t j = 0; j < 3; ++j) CHECK(got[j] == test::approx(want[j]).scale(1e-6).epsilon(1e-9));
      }
  }
}

TEST_CASE("contact group: area moments find the centroid and the principal axes of a turned, shifted rectangle") {
  // Reference: four equal CPs at the corners of a 0.4 x 0.1 m rectangle, turned by 0.3 rad and shifted to (1, -2):
  // the centroid is (1, -2), the principal axis along the long side is at 0.3 rad, and the polar moment about the
  // centroid is 4 a (0.2^2 + 0.05^2) (point areas).
  const double turn = 0.3, a = 0.01;
  AreaMoments m;
  for (const auto& [u, v] : std::vector<std::array<double, 2>>{{0.2, 0.05}, {-0.2, 0.05}, {-0.2, -0.05}, {0.2, -0.05}})
    m.add(1.0 + std::cos(turn) * u - std::sin(turn) * v, -2.0 + std::sin(turn) * u + std::cos(turn) * v, a);
  CHECK(m.centroid_1() == test::approx(1.0).epsilon(1e-14));
  CHECK(m.centroid_2() == test::approx(-2.0).epsilon(1e-14));
  CHECK(m.principal_turn() == test::approx(turn).epsilon(1e-12));
  const double i22 = m.second_22 - m.first_2 * m.centroid_2();
  const double i11 = m.second_11 - m.first_1 * m.centroid_1();
  CHECK(i11 + i22 == test::approx(4 * a * (0.2 * 0.2 + 0.05 * 0.05)).epsilon(1e-10));
}

TEST_CASE("contact group: a Maxwell field refuses CPs whose origin is not their area centroid or t1 not a principal axis") {
  // The field's stiffness is diagonal only in the frame of the CPs' areas: any other frame is an error naming the
  // contact, not a silently wrong force.
  using Group = ContactGroup<contact::Elastic, damping::Maxwell<3>>;
  const std::vector<std::vector<std::array<double, 3>>> layouts{
      {{0.2, 0.1, 0.01}, {-0.1, 0.1, 0.01}},                                          // centroid at x2 = 0.1
      {{0.1, 0.1, 0.01}, {-0.1, -0.1, 0.01}},                                         // centred, on a diagonal
      {{0.1, 0.05, 0.01}, {-0.1, 0.05, 0.01}, {-0.1, -0.05, 0.01}, {0.1, -0.05, 0.01}}};  // centred and principal
  for (std::size_t l = 0; l < layouts.size(); ++l) {
    Group g;
    g.properties.push_back(contact::Elastic::Parameters(1e10, 4e9));
    g.begin_contact(3, 7, 0, Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX(), true);
    for (const auto& [x1, x2, a] : layouts[l]) g.add_point(x1, x2, a, {}, {}, 0.0, 0.0);
    if (l < 2)
      CHECK_THROWS_WITH_AS(g.complete(8), doctest::Contains("contact 0 (blocks 3, 7)"), InvalidArgument);
    else
      CHECK_NOTHROW(g.complete(8));
  }
  // The same CPs in a group without a field: any frame.
  ContactGroup<contact::Elastic, damping::MassProportional> plain;
  plain.properties.push_back(contact::Elastic::Parameters(1e10, 4e9));
  plain.begin_contact(3, 7, 0, Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX());
  for (const auto& [x1, x2, a] : layouts[0]) plain.add_point(x1, x2, a, {}, {}, 0.0, 0.0);
  CHECK_NOTHROW(plain.complete(8));
}

// ---- density scaling of rigid-only models, static mass scaling ----

namespace {

using ElasticSettle = Simulation<damping::Local, contact::Elastic>;
const auto stiff_joint = [](int, int) { return contact::Elastic::Parameters(1e10, 4e9); };

/// Steps `steps` times; the times (s) and the block's height above the one it started from (m) after each step.
template <class Sim>
std::pair<std::vector<double>, std::vector<double>> record_height(Sim& sim, std::size_t block, int steps) {
  const auto& b = sim.model().bodies;
  const double z0 = b.position[block].z();
  std::vector<double> t, z;
  for (int i = 0; i < steps; ++i) {
    sim.step();
    t.push_back(sim.time());
    z.push_back(b.position[block].z() - z0);
  }
  return {t, z};
}

bool all_finite(const model::RigidBodies& b, std::size_t i) {
  return b.position[i].allFinite() && b.velocity[i].allFinite() && b.angular_velocity[i].allFinite() &&
         b.orientation[i].coeffs().allFinite() && b.force[i].allFinite() && b.moment[i].allFinite();
}

}  // namespace

TEST_CASE("density scaling: a rigid-only model switched to the mixed step by scaling steps on, its state finite") {
  // Regression: scale_density_to() set up the deformable state of a rigid-only model without its gather lists, and
  // the first step read past them (gather_rigid, integrate/node_pass.hpp).
  auto s = test::block_on_base(0.2, 0.2, 0.2);
  ElasticSettle sim(s.model, damping::Local{}, stiff_joint);
  REQUIRE_FALSE(sim.mixed());
  const auto r = sim.scale_density_to(4 * sim.timestep());
  CHECK(sim.mixed());
  CHECK(r.scaled_blocks == 1);
  CHECK(r.mass_increase_percent > 0);
  for (int i = 0; i < 1000; ++i) sim.step();
  CHECK(all_finite(s.model.bodies, s.block));
  CHECK(std::isfinite(sim.unbalanced_force_ratio()));
  CHECK(sim.steps() == 1000);
}

TEST_CASE("density scaling: a scaled rigid block settles where the unscaled one does (statics do not depend on mass)") {
  // Reference: a 0.2 m box of 2000 kg/m^3 on elastic CPs over 0.04 m^2 sinks by its real weight over k_n A,
  // rho h g / k_n = 3.924e-7 m, scaled or not: the weight stays that of the real mass.
  struct Settled {
    Vec3 position;
    DensityScaling scaling;
  };
  const auto settle = [](bool scaled) {
    auto s = test::block_on_base(0.2, 0.2, 0.2);
    ElasticSettle sim(s.model, damping::Local{}, stiff_joint);
    Settled r;
    if (scaled) r.scaling = sim.scale_density_to(4 * sim.timestep());
    CHECK(sim.solve_to_equilibrium(1e-10, 200000));
    r.position = s.model.bodies.position[s.block];
    return r;
  };
  const Vec3 start = test::block_on_base(0.2, 0.2, 0.2).model.bodies.position[1];
  const auto unscaled = settle(false);
  const auto scaled = settle(true);
  const double sink = 2000 * 0.2 * 9.81 / 1e10;
  CHECK(start.z() - unscaled.position.z() == test::approx(sink).epsilon(1e-6));
  CHECK(start.z() - scaled.position.z() == test::approx(sink).epsilon(1e-6));
  CHECK((scaled.position - unscaled.position).norm() <= 1e-6 * sink);
  CHECK(unscaled.scaling.mass_increase_percent == 0);
  CHECK(scaled.scaling.mass_increase_percent > 0);
  CHECK(scaled.scaling.max_density_scaling_factor > 10);  // the target is four times the block's own limit
}

TEST_CASE("density scaling: a scaled rigid block vibrates at sqrt(k A / m_scaled) about its real-weight equilibrium") {
  // Reference: SDOF under gravity released at rest on an undeformed joint: z(t) = -d (1 - cos omega t) with
  // omega = sqrt(k_n A / m_scaled) (the inertia scaled) and d = m_real g / (k_n A) (the weight real), so the lowest
  // point is -2 d.
  auto s = test::block_on_base(1, 1, 1);
  s.model.bodies.fixity[s.block] = vertical_only;
  const double kn = 2000.0 * std::pow(two_pi * 100.0, 2);  // 100 Hz with the real mass
  Simulation<damping::None, contact::Elastic> sim(s.model, damping::None{}, [&](int, int) { return contact::Elastic::Parameters(kn, kn); });
  const auto r = sim.scale_density_to(4 * sim.timestep());
  const double mass = s.model.bodies.mass[s.block];
  CHECK(mass == test::approx(16 * 2000.0).epsilon(1e-6));  // (4 dt)^2: the translational limit is the block's
  CHECK(r.scaled_blocks == 1);
  const double f = std::sqrt(kn / mass) / two_pi;
  sim.set_timestep(1.0 / (400 * f));  // resolve the vibration: the masses are what is checked
  const auto [t, z] = record_height(sim, s.block, 20 * 400);
  const double d = 2000.0 * 9.81 / kn;
  CHECK(test::measure_decay(t, z).frequency_hz == test::approx(f).epsilon(0.005));
  CHECK(*std::min_element(z.begin(), z.end()) == test::approx(-2 * d).epsilon(0.005));
}

namespace {

/// A stack of four boxes of very different sizes and masses (1152 kg down to 0.13 kg, own limits 1.3e-4 to 1.8e-3 s)
/// on a fixed base, off centre so that the joints shear and the blocks tilt; elastic joints, no re-detection.
struct Stack {
  model::Model model;
  std::vector<std::size_t> blocks;
};

Stack box_stack() {
  Stack s;
  s.model.add_block(geometry::make_box(Vec3(-1, -1, -0.5), Vec3(1, 1, 0)), 2000, "base", 0, model::Motion::fixed);
  struct Box {
    double x, width, height;  // m
  };
  double z = 0;
  for (const Box& b : {Box{0.0, 1.2, 0.4}, Box{0.05, 0.1, 0.08}, Box{0.08, 0.5, 0.3}, Box{0.06, 0.04, 0.04}}) {
    s.blocks.push_back(s.model.add_block(
        geometry::make_box(Vec3(b.x - 0.5 * b.width, -0.5 * b.width, z), Vec3(b.x + 0.5 * b.width, 0.5 * b.width, z + b.height)),
        2000, "box " + std::to_string(s.blocks.size()), 1));
    z += b.height;
  }
  return s;
}

model::ContactSettings no_redetection() {
  model::ContactSettings c;
  c.tolerance = 0.01;
  return c;
}

const auto soft_joint = [](int, int) { return contact::Elastic::Parameters(1e9, 4e8); };

/// The median of the free blocks' own limits estimate_safety_factor 2 / max(sqrt(k / m), sqrt(k r^2 / I_min)) (s).
template <class Sim>
double median_own_limit(const Sim& sim) {
  const auto& b = sim.model().bodies;
  std::vector<double> kt, kr, kn, limits;
  sim.stiffnesses(kt, kr, kn);
  for (std::size_t i = 0; i < b.size(); ++i)
    if (b.motion[i] == model::Motion::free && kt[i] > 0)
      limits.push_back(Sim::estimate_safety_factor * 2.0 /
                       std::max(std::sqrt(kt[i] / b.mass[i]), std::sqrt(kr[i] / b.principal_inertia[i].minCoeff())));
  std::sort(limits.begin(), limits.end());
  return limits[limits.size() / 2];
}

}  // namespace

TEST_CASE("static mass scaling: restore_real_masses() gives back the real masses and inertias exactly") {
  auto s = box_stack();
  ElasticSettle sim(s.model, damping::Local{}, soft_joint, no_redetection());
  const auto mass = s.model.bodies.mass;
  const auto inertia = s.model.bodies.principal_inertia;
  const double dt_real = sim.timestep();
  const double target = median_own_limit(sim);
  REQUIRE(target > dt_real);
  const auto r = sim.scale_masses_for_statics(target);
  CHECK(sim.static_masses());
  CHECK(sim.timestep() == target);
  CHECK(r.scaled_blocks == 4);
  CHECK(r.min_density_scaling_factor < 0.1);  // the big blocks lighter
  CHECK(r.max_density_scaling_factor > 5);    // the small ones heavier
  // Every free block now has the target as its own limit, translation and rotation alike.
  std::vector<double> kt, kr, kn;
  sim.stiffnesses(kt, kr, kn);
  const double omega = 2 * ElasticSettle::estimate_safety_factor / target;
  for (std::size_t i : s.blocks) {
    CHECK(std::sqrt(kt[i] / s.model.bodies.mass[i]) == test::approx(omega).epsilon(1e-8));
    CHECK(std::sqrt(kr[i] / s.model.bodies.principal_inertia[i].minCoeff()) == test::approx(omega).epsilon(1e-8));
  }
  CHECK(r.dt_critical == test::approx(target / ElasticSettle::estimate_safety_factor * damping::Local{}.timestep_factor(0)).epsilon(1e-8));
  for (int i = 0; i < 200; ++i) sim.step();
  sim.restore_real_masses();
  CHECK_FALSE(sim.static_masses());
  for (std::size_t i = 0; i < mass.size(); ++i) {
    CHECK(s.model.bodies.mass[i] == mass[i]);
    CHECK(s.model.bodies.principal_inertia[i] == inertia[i]);
  }
  CHECK(sim.timestep() == sim.default_timestep());
  CHECK(sim.timestep() == test::approx(dt_real).epsilon(0.01));  // the blocks moved a little since construction
  // A dynamic simulation continued from it: real masses, the rigid kernel, the real masses' timestep.
  Simulation<damping::None, contact::Elastic> dynamic(sim, damping::None{});
  CHECK_FALSE(dynamic.mixed());
  CHECK(dynamic.timestep() == dynamic.default_timestep());
  for (std::size_t i = 0; i < mass.size(); ++i) CHECK(s.model.bodies.mass[i] == mass[i]);
}

TEST_CASE("static mass scaling: a simulation with static masses is not continued before its real masses are back") {
  auto s = test::block_on_base(0.2, 0.2, 0.2);
  ElasticSettle sim(s.model, damping::Local{}, stiff_joint);
  sim.scale_masses_for_statics(2 * sim.timestep());
  CHECK_THROWS_WITH_AS((Simulation<damping::None, contact::Elastic>(sim, damping::None{})),
                       doctest::Contains("restore_real_masses"), InvalidArgument);
  CHECK_THROWS_WITH_AS(sim.scale_masses_for_statics(0), doctest::Contains("static mass scaling: the target timestep must be > 0 s"),
                       InvalidArgument);
  sim.restore_real_masses();
  CHECK_NOTHROW((Simulation<damping::None, contact::Elastic>(sim, damping::None{})));
}

TEST_CASE("static mass scaling: a stack of very different boxes settles in far fewer steps, to the same equilibrium") {
  // Reference: the unscaled settle of the same stack (statics do not depend on the masses; the weights stay real).
  // Unbalanced-force ratio 1e-5: 5050 steps unscaled, 140 with static mass scaling (all blocks at one frequency;
  // the count does not depend on the target, which only scales dt^2 / m). Positions compared at 1e-9, where the
  // runs differ only by the path dependence of the incremental shear springs of tilting blocks (~1e-4 of the
  // largest displacement).
  struct Settled {
    long long steps = 0;
    std::vector<Vec3> position;
    std::vector<Quaternion> orientation;
  };
  const auto settle = [](bool scaled) {
    auto s = box_stack();
    ElasticSettle sim(s.model, damping::Local{}, soft_joint, no_redetection());
    if (scaled) sim.scale_masses_for_statics(median_own_limit(sim));
    Settled r;
    CHECK(sim.solve_to_equilibrium(1e-5, 100000));
    r.steps = sim.steps();
    CHECK(sim.solve_to_equilibrium(1e-9, 100000));
    r.position = s.model.bodies.position;
    r.orientation = s.model.bodies.orientation;
    return r;
  };
  const auto start = box_stack().model;
  const auto unscaled = settle(false);
  const auto scaled = settle(true);
  MESSAGE("settling the stack to 1e-5: " << unscaled.steps << " steps unscaled, " << scaled.steps << " with static mass scaling");
  CHECK(10 * scaled.steps < unscaled.steps);
  double largest = 0;
  for (std::size_t i = 0; i < unscaled.position.size(); ++i)
    largest = std::max(largest, (unscaled.position[i] - start.bodies.position[i]).norm());
  CHECK(largest > 1e-3);  // the stack leans
  for (std::size_t i = 0; i < unscaled.position.size(); ++i) {
    CAPTURE(i);
    CHECK((scaled.position[i] - unscaled.position[i]).norm() <= 1e-3 * largest);
    CHECK(scaled.orientation[i].angularDistance(unscaled.orientation[i]) <= 1e-3 * 4e-3);  // of a tilt of 3.6e-3 rad
  }
}

TEST_CASE("static mass scaling: after restore_real_masses() a dynamic continuation vibrates at the real frequency") {
  // Reference: SDOF f = sqrt(k_n A / m_real) / 2 pi = 20 Hz (the settle ran with over 9 times the mass).
  auto s = test::block_on_base(1, 1, 1);
  s.model.bodies.fixity[s.block] = vertical_only;
  const double f = 20.0;
  const double kn = 2000.0 * std::pow(two_pi * f, 2);
  const auto joint = [&](int, int) { return contact::Elastic::Parameters(kn, kn); };
  ElasticSettle settle(s.model, damping::Local{}, joint);
  const double target = 3 * settle.timestep();
  settle.scale_masses_for_statics(target);
  // k / m_static = omega_t^2 with 2 safety / omega_t = target
  const double omega_t = 2 * ElasticSettle::estimate_safety_factor / target;
  CHECK(s.model.bodies.mass[s.block] == test::approx(kn / (omega_t * omega_t)).epsilon(1e-6));
  CHECK(s.model.bodies.mass[s.block] > 9 * 2000.0);
  CHECK(settle.solve_to_equilibrium(1e-9, 100000));
  settle.restore_real_masses();
  Simulation<damping::None, contact::Elastic> sim(settle, damping::None{});
  CHECK(sim.timestep() == sim.default_timestep());
  sim.set_timestep(1.0 / (400 * f));
  s.model.bodies.velocity[s.block] = Vec3(0, 0, 1e-4);
  const auto [t, z] = record_height(sim, s.block, 20 * 400);
  CHECK(test::measure_decay(t, z).frequency_hz == test::approx(f).epsilon(0.005));
}

}  // namespace test_simulation
