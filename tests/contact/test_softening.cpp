// The elasto-softening joint (paper Sect. 3.1, Fig. 5C, eq. 4-7; DESIGN.md §6): eq. 4-7 against hand-computed values,
// the dissipated energy of each mode against its fracture energy, peaks against the strengths, cyclic paths against
// the secant and the initial stiffness, energy closure, and a property test over random displacement paths.

#include <doctest/doctest.h>

#include "../approx.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "blockdem/contact/softening.hpp"
#include "blockdem/core/random.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/maxwell_fit.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "../integrate/fixtures.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_softening {
using contact::ElastoSoftening;
using Parameters = ElastoSoftening::Parameters;
using History = ElastoSoftening::History;

namespace {

constexpr double degree = pi / 180.0;

/// Table 1 with eq. 4-7.
Parameters table1(double cap_shear_factor = 9.0) { return Parameters::from_material({}, cap_shear_factor); }

/// One contact point driven along a displacement path; work done on the joint by the trapezoid rule.
struct Driver {
  Parameters p;
  History h{};
  double sigma = 0;            // Pa, compression positive
  contact::Shear tau{0, 0};    // Pa, traction of A on B
  double work = 0;             // J/m^2, trapezoid rule
  double dissipated = 0;       // J/m^2, sum of the law's per-step values
  double min_step_dissipation = 0;

  explicit Driver(const Parameters& params) : p(params) {}

  contact::Response step(double du_normal, contact::Shear du_shear = {0, 0}) {
    const contact::Response r = ElastoSoftening::update(p, h, du_normal, du_shear);
    // The joint resists closing with sigma and slip with -tau: dW = -sigma du_n - tau . du_s.
    work += -0.5 * (sigma + r.normal_stress) * du_normal -
            0.5 * ((tau[0] + r.shear_stress[0]) * du_shear[0] + (tau[1] + r.shear_stress[1]) * du_shear[1]);
    sigma = r.normal_stress;
    tau = r.shear_stress;
    dissipated += r.dissipated;
    min_step_dissipation = std::min(min_step_dissipation, r.dissipated);
    return r;
  }
  /// A straight leg of the path in n equal steps.
  void leg(double du_normal, contact::Shear du_shear, int n) {
    for (int i = 0; i < n; ++i) step(du_normal / n, {du_shear[0] / n, du_shear[1] / n});
  }
  double stored() const { return ElastoSoftening::stored_energy(p, h); }
};

}  // namespace

// ---- eq. 4-7 ----

TEST_CASE("softening: eq. 7 joint stiffnesses for Table 1 (hand-computed)") {
  // k_n = E_b E_m / (t_m (E_b - E_m)) = 6200 * 370.05 / (0.010 * 5829.95) MPa/m = 39 353.853 806 6 MPa/m;
  // k_s = k_n / (2 (1 + 0.25)) = 15 741.541 522 7 MPa/m.
  const auto k = contact::joint_stiffness_from_eq7(6200e6, 370.05e6, 0.010, 0.25);
  CHECK(k.normal == test::approx(3.93538538066e10).epsilon(1e-11));
  CHECK(k.shear == test::approx(1.57415415227e10).epsilon(1e-11));
  CHECK_THROWS_WITH_AS(contact::joint_stiffness_from_eq7(300e6, 370.05e6, 0.01, 0.25),
                       doctest::Contains("unit Young's modulus E_b must be > E_m"), InvalidArgument);
  CHECK_THROWS_WITH_AS(contact::joint_stiffness_from_eq7(6200e6, 370.05e6, 0, 0.25),
                       doctest::Contains("mortar thickness t_m must be > 0 m"), InvalidArgument);
  CHECK_THROWS_WITH_AS(contact::joint_stiffness_from_eq7(6200e6, 370.05e6, 0.01, 0.6),
                       doctest::Contains("Poisson ratio nu must be in (-1, 0.5]"), InvalidArgument);
}

TEST_CASE("softening: eq. 4-6 fracture energies, MPa -> N/mm -> N/m (hand-computed)") {
  // f_t = 0.5 MPa: (2 * 0.5)^0.7 = 1, so G_f^I = 0.025 N/mm = 25 N/m exactly.
  CHECK(contact::fracture_energy_tension_eq4(0.5e6) == test::approx(25.0).epsilon(1e-14));
  // Table 1, f_t = 0.3 MPa: 0.025 * 0.6^0.7 = 0.017 484 204 760 4 N/mm = 17.484 204 760 4 N/m.
  const double gf1 = contact::fracture_energy_tension_eq4(0.3e6);
  CHECK(gf1 == test::approx(17.4842047604).epsilon(1e-11));
  CHECK(contact::fracture_energy_shear_eq5(gf1) == test::approx(174.842047604).epsilon(1e-11));  // eq. 5
  // f_c = 10 MPa: 15 + 4.3 - 0.36 = 18.94 N/mm = 18 940 N/m; Table 1, f_c = 9.1 MPa: 15 + 3.913 - 0.298116 = 18.614884 N/mm.
  CHECK(contact::fracture_energy_compression_eq6(10e6) == test::approx(18940.0).epsilon(1e-13));
  CHECK(contact::fracture_energy_compression_eq6(9.1e6) == test::approx(18614.884).epsilon(1e-13));
  CHECK_THROWS_WITH_AS(contact::fracture_energy_tension_eq4(0), doctest::Contains("f_t must be > 0 Pa"), InvalidArgument);
  CHECK_THROWS_WITH_AS(contact::fracture_energy_compression_eq6(200e6), doctest::Contains("must be in (0, 150] MPa"),
                       InvalidArgument);

  const Parameters p = table1();
  CHECK(p.normal_stiffness == test::approx(3.93538538066e10).epsilon(1e-11));
  CHECK(p.tension_fracture_energy == test::approx(17.4842047604).epsilon(1e-11));
  CHECK(p.shear_fracture_energy == test::approx(174.842047604).epsilon(1e-11));
  CHECK(p.compression_fracture_energy == test::approx(18614.884).epsilon(1e-13));
  CHECK(p.friction_angle == test::approx(38 * degree));
}

TEST_CASE("softening: bad parameters name the field and the allowed range") {
  const contact::JointStiffness k{4e10, 1.6e10};
  ElastoSoftening::Strengths s{0.3e6, 0.3e6, 38 * degree, 9.1e6};
  const ElastoSoftening::FractureEnergies g{17.5, 175, 18615};
  CHECK_NOTHROW(Parameters(k, s, g));
  CHECK_THROWS_WITH_AS(Parameters({0, 1.6e10}, s, g), doctest::Contains("normal stiffness must be > 0 Pa/m"), InvalidArgument);
  CHECK_THROWS_WITH_AS(Parameters({4e10, -1}, s, g), doctest::Contains("shear stiffness must be > 0 Pa/m"), InvalidArgument);
  auto with = [&](auto change) {
    auto t = s;
    change(t);
    return t;
  };
  CHECK_THROWS_WITH_AS(Parameters(k, with([](auto& t) { t.tensile = 0; }), g), doctest::Contains("tensile strength must be > 0 Pa"),
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(Parameters(k, with([](auto& t) { t.cohesion = -1; }), g), doctest::Contains("cohesion must be > 0 Pa"),
                       InvalidArgument);
  CHECK_THROWS_WITH_AS(Parameters(k, with([](auto& t) { t.friction_angle = 95 * degree; }), g),
                       doctest::Contains("friction angle must be in [0, 90) degrees"), InvalidArgument);
  CHECK_THROWS_WITH_AS(Parameters(k, with([](auto& t) { t.compressive = 0.2e6; }), g),
                       doctest::Contains("compressive strength must be > the tensile strength"), InvalidArgument);
  CHECK_THROWS_WITH_AS(Parameters(k, with([](auto& t) { t.residual_tensile = 0.4e6; }), g),
                       doctest::Contains("residual tensile strength must be in [0, tensile strength"), InvalidArgument);
  CHECK_THROWS_WITH_AS(Parameters(k, with([](auto& t) { t.residual_cohesion = 0.5e6; }), g),
                       doctest::Contains("residual cohesion must be in [0, cohesion"), InvalidArgument);
  CHECK_THROWS_WITH_AS(Parameters(k, with([](auto& t) { t.residual_friction_angle = 40 * degree; }), g),
                       doctest::Contains("residual friction angle must be in [0, friction angle"), InvalidArgument);
  CHECK_THROWS_WITH_AS(Parameters(k, with([](auto& t) { t.residual_compressive = 9.1e6; }), g),
                       doctest::Contains("residual compressive strength must be in [0, compressive strength"), InvalidArgument);
  CHECK_THROWS_WITH_AS(Parameters(k, with([](auto& t) { t.residual_compressive = -1; }), g),
                       doctest::Contains("residual compressive strength must be in [0, compressive strength"), InvalidArgument);
  // f_t^2 / (2 k_n) = 0.09e12 / 8e10 = 1.125 J/m^2: a smaller G_f^I would need a snap-back.
  CHECK_THROWS_WITH_AS(Parameters(k, s, {1.0, 175, 18615}),
                       doctest::Contains("G_f^I must be > f_t^2 / (2 k_n) = 1.125"), InvalidArgument);
  CHECK_THROWS_WITH_AS(Parameters(k, s, {17.5, 0, 18615}), doctest::Contains("G_f^II must be > 0 J/m^2"), InvalidArgument);
  CHECK_THROWS_WITH_AS(Parameters(k, s, {17.5, 175, 1000}), doctest::Contains("G_c must be > f_c s_p / 2"), InvalidArgument);
  CHECK_THROWS_WITH_AS(Parameters(k, s, g, -1.0), doctest::Contains("cap shear factor C_s must be >= 0"), InvalidArgument);
  CHECK_THROWS_WITH_AS(Parameters(k, s, g, 9.0, 0.0), doctest::Contains("damping damage limit must be in (0, 1]"),
                       InvalidArgument);
}

// ---- the three modes ----

TEST_CASE("softening: pure tension to full separation dissipates G_f^I per unit area (DESIGN §6)") {
  const Parameters p = table1();
  const double u0 = p.tensile_strength / p.normal_stiffness;  // the peak, m
  Driver d(p);
  d.leg(u0, {0, 0}, 50);  // to the peak, elastic
  CHECK(d.dissipated == 0.0);
  CHECK(-d.sigma == test::approx(p.tensile_strength).epsilon(1e-12));  // peak f_t
  CHECK(d.h.damage == 0.0);
  // The envelope f_t exp(-beta_t (u - u0)) with beta_t = f_t / (G_f^I - f_t^2 / (2 k_n)).
  const double beta = p.tensile_strength / (p.tension_fracture_energy - 0.5 * p.tensile_strength * u0);
  d.leg(1e-4, {0, 0}, 2000);
  CHECK(-d.sigma == test::approx(p.tensile_strength * std::exp(-beta * 1e-4)).epsilon(1e-12));
  CHECK(d.h.damage == test::approx(1 - std::exp(-beta * 1e-4)).epsilon(1e-12));
  d.leg(3e-3, {0, 0}, 20000);  // to full separation: exp(-beta (u - u0)) < 1e-23
  CHECK(d.h.failed == 1);
  CHECK(d.stored() < 1e-9 * p.tension_fracture_energy);
  CHECK(d.dissipated == test::approx(p.tension_fracture_energy).epsilon(0.01));  // the tolerance
  CHECK(d.dissipated == test::approx(p.tension_fracture_energy).epsilon(1e-9));  // what the law achieves
  CHECK(d.min_step_dissipation >= -1e-12);
  // Independent of the step size: one step to the same opening dissipates the same.
  Driver one(p);
  one.step(u0 + 1e-4 + 3e-3);
  CHECK(one.dissipated == test::approx(d.dissipated).epsilon(1e-12));
}

TEST_CASE("softening: shear under constant compression peaks at c + sigma tan(phi), dissipates G_f^II, ends at sigma tan(phi_r)") {
  for (const double sigma_n : {0.2e6, 0.5e6, 1.5e6}) {
    CAPTURE(sigma_n);
    // Residual friction angle = peak (eq. 4-7 defaults): what the cohesion loses is G_f^II (DESIGN §6).
    const Parameters p = table1();
    Driver d(p);
    d.step(-sigma_n / p.normal_stiffness);  // elastic pre-compression (sigma_n < f_c / 3)
    CHECK(d.sigma == test::approx(sigma_n).epsilon(1e-12));
    const double peak = p.cohesion + sigma_n * p.tan_friction;
    const double u_peak = peak / p.shear_stiffness;
    d.leg(0, {u_peak, 0}, 40);
    CHECK(-d.tau[0] == test::approx(peak).epsilon(1e-12));  // Coulomb peak
    CHECK(d.dissipated < 1e-12);  // elastic (the sum of 40 steps may end an ulp beyond the peak)
    const double total = 0.03;  // beta_s * slip = 51: the cohesion is gone
    double highest = 0;
    for (int i = 0; i < 30000; ++i) highest = std::max(highest, -d.step(0, {(total - u_peak) / 30000, 0}).shear_stress[0]);
    CHECK(highest <= peak);
    CHECK(d.sigma == test::approx(sigma_n).epsilon(1e-12));  // no dilatancy: the normal stress stays
    const double slip = total + d.tau[0] / p.shear_stiffness;  // plastic slip = total - tau / k_s
    CHECK(-d.tau[0] == test::approx(sigma_n * p.tan_residual_friction).epsilon(1e-12));  // residual
    // Dissipated: friction sigma tan(phi) per metre of slip plus the cohesion's G_f^II.
    CHECK(d.dissipated - sigma_n * p.tan_friction * slip == test::approx(p.shear_fracture_energy).epsilon(1e-9));
    CHECK(d.h.failed == 1);
    CHECK(d.min_step_dissipation >= -1e-12);
    Driver one(p);  // one step from the pre-compressed state gives the same
    one.step(-sigma_n / p.normal_stiffness);
    one.step(0, {total, 0});
    CHECK(one.dissipated == test::approx(d.dissipated).epsilon(1e-12));
    CHECK(one.tau[0] == test::approx(d.tau[0]).epsilon(1e-12));
  }
  // A residual friction angle below the peak: the friction term softens too, with the same rate beta_s = c / G_f^II, so
  // integral of (c + sigma (tan phi - tan phi_r)) exp(-beta_s kappa) dkappa = G_f^II (1 + sigma (tan phi - tan phi_r) / c).
  const auto base = table1();
  ElastoSoftening::Strengths s{0.3e6, 0.3e6, 38 * degree, 9.1e6, 0, 0, 30 * degree};
  const Parameters p({base.normal_stiffness, base.shear_stiffness}, s,
                     {base.tension_fracture_energy, base.shear_fracture_energy, base.compression_fracture_energy});
  const double sigma_n = 0.8e6;
  Driver d(p);
  d.step(-sigma_n / p.normal_stiffness);
  d.leg(0, {0.03, 0}, 20000);
  const double slip = 0.03 + d.tau[0] / p.shear_stiffness;
  CHECK(-d.tau[0] == test::approx(sigma_n * std::tan(30 * degree)).epsilon(1e-12));
  const double expected = sigma_n * std::tan(30 * degree) * slip +
                          p.shear_fracture_energy * (1 + sigma_n * (p.tan_friction - std::tan(30 * degree)) / p.cohesion);
  CHECK(d.dissipated == test::approx(expected).epsilon(1e-9));
}

TEST_CASE("softening: compression peaks at f_c and dissipates G_c after the peak") {
  const Parameters p = table1();
  const double kn = p.normal_stiffness, fc = p.compressive_strength;
  const double si = fc / (3 * kn), sp = 5 * fc / (3 * kn);  // end of the elastic range, the peak (closures, m)
  Driver d(p);
  d.leg(-si, {0, 0}, 100);
  CHECK(d.sigma == test::approx(fc / 3).epsilon(1e-12));  // elastic to f_c / 3 (Lourenço and Rots 1997)
  CHECK(d.dissipated < 1e-12);
  // Hardening: the parabola f_c - (2 f_c / 3) ((s_p - s) / (s_p - s_i))^2, tangent to k_n at s_i, flat at s_p.
  d.step(-1e-9);
  CHECK((d.sigma - fc / 3) / 1e-9 == test::approx(kn).epsilon(1e-5));
  const double mid = 0.5 * (si + sp);
  d.leg(-(mid - si - 1e-9), {0, 0}, 100);
  CHECK(d.sigma == test::approx(fc - (2 * fc / 3) * 0.25).epsilon(1e-12));
  d.leg(-(sp - mid), {0, 0}, 100);
  CHECK(d.sigma == test::approx(fc).epsilon(1e-12));  // the peak, f_c
  const double at_peak = d.dissipated;
  double highest = d.sigma;
  for (int i = 0; i < 40000; ++i) highest = std::max(highest, d.step(-0.04 / 40000).normal_stress);
  CHECK(highest == test::approx(fc).epsilon(1e-12));
  // G_c: what the joint dissipates from the peak on (the post-peak envelope and the elastic energy at the peak).
  CHECK(d.stored() < 1e-6 * p.compression_fracture_energy);
  CHECK(d.dissipated - at_peak + d.stored() == test::approx(p.compression_fracture_energy).epsilon(0.02));  // the issue's
  CHECK(d.dissipated - at_peak + d.stored() == test::approx(p.compression_fracture_energy).epsilon(1e-9));
  CHECK(d.h.failed == 1);  // a crushed joint has lost its bond (d_c joins the combined damage)
  Driver one(p);
  one.step(-(sp + 0.04));
  CHECK(one.dissipated == test::approx(d.dissipated).epsilon(1e-11));
}

TEST_CASE("softening: a residual compressive strength f_c,r is what a crushed joint keeps carrying") {
  // The paper's law softens to 0, and a joint crushed through lets its blocks pass through each other. With f_c,r
  // the envelope is f_c,r + (f_c - f_c,r) exp(-beta_c (s - s_p)) with the paper's beta_c (as f_t,r keeps beta_t).
  const Parameters paper = table1();
  auto s = ElastoSoftening::Strengths{paper.tensile_strength, paper.cohesion, paper.friction_angle, paper.compressive_strength};
  const double fc = paper.compressive_strength, fr = 0.2 * fc;
  s.residual_compressive = fr;
  const Parameters p({paper.normal_stiffness, paper.shear_stiffness}, s,
                     {paper.tension_fracture_energy, paper.shear_fracture_energy, paper.compression_fracture_energy});
  CHECK(p.compression_softening_rate == paper.compression_softening_rate);
  const double sp = p.peak_closure, beta = p.compression_softening_rate;
  Driver d(p);
  d.leg(-sp, {0, 0}, 400);
  CHECK(d.sigma == test::approx(fc).epsilon(1e-12));
  const double at_peak = d.dissipated;
  const double reach = 0.005;  // 5 mm past the peak: 2.4 / beta_c
  d.leg(-reach, {0, 0}, 20000);
  const double decay = std::exp(-beta * reach);
  CHECK(d.sigma == test::approx(fr + (fc - fr) * decay).epsilon(1e-12));
  // From the peak on: the work on the envelope, in closed form, plus the elastic energy at the peak, less what the
  // secant still stores.
  const double envelope = fr * reach + (fc - fr) * (1 - decay) / beta;
  const double stored = 0.5 * d.sigma * (sp + reach);
  CHECK(d.stored() == test::approx(stored).epsilon(1e-12));
  CHECK(d.dissipated - at_peak == test::approx(envelope + 0.5 * fc * sp - stored).epsilon(1e-9));
  CHECK(d.work == test::approx(d.dissipated + d.stored()).epsilon(1e-6));
  CHECK(d.h.failed == 0);  // 91 % of f_c - f_c,r gone: not yet the 99.9 % of a failed bond
  Driver one(p);
  one.step(-(sp + reach));
  CHECK(one.dissipated == test::approx(d.dissipated).epsilon(1e-11));
  // Far on, the joint carries f_c,r however much more it closes; unloaded, it reloads along its secant to there.
  d.leg(-0.1, {0, 0}, 20000);
  CHECK(d.sigma == test::approx(fr).epsilon(1e-12));
  CHECK(d.h.failed == 1);
  const double closure = -d.h.gap;
  d.leg(0.5 * closure, {0, 0}, 100);
  CHECK(d.sigma == test::approx(0.5 * fr).epsilon(1e-9));
  d.leg(-0.5 * closure - 0.01, {0, 0}, 100);
  CHECK(d.sigma == test::approx(fr).epsilon(1e-9));
  CHECK(d.work == test::approx(d.dissipated + d.stored()).epsilon(1e-6));  // the unload-reload cycle dissipates nothing
  // The paper's law on the same path carries nothing: the blocks would pass through each other.
  Driver zero(paper);
  zero.leg(-(sp + reach + 0.1), {0, 0}, 40000);
  CHECK(zero.sigma < 1e-12 * fc);
}

// ---- cycles ----

TEST_CASE("softening: tension unloads and reloads along the secant, re-closes with k_n, and a closed loop creates no energy") {
  const Parameters p = table1();
  const double kn = p.normal_stiffness;
  const double u0 = p.tensile_strength / kn;
  Driver d(p);
  double previous_damage = 0;
  for (const double amplitude : {3 * u0, 8 * u0, 20 * u0}) {
    CAPTURE(amplitude);
    d.leg(amplitude - d.h.gap, {0, 0}, 500);
    const double t_max = -d.sigma;
    const double secant = t_max / amplitude;
    CHECK(secant < kn);
    CHECK(d.h.damage >= previous_damage);
    previous_damage = d.h.damage;
    const double work_before = d.work, dissipated_before = d.dissipated;
    // Unload to the origin and 2 u0 beyond (compression), then back: along the secant in tension, k_n in compression.
    for (int i = 1; i <= 300; ++i) {
      d.step(-(amplitude + 2 * u0) / 300);
      if (d.h.gap > 0) CHECK(-d.sigma == test::approx(secant * d.h.gap).epsilon(1e-12));
      else CHECK(d.sigma == test::approx(-kn * d.h.gap).epsilon(1e-12));
    }
    CHECK(d.sigma == test::approx(2 * u0 * kn).epsilon(1e-9));
    d.leg(amplitude + 2 * u0, {0, 0}, 300);
    CHECK(-d.sigma == test::approx(t_max).epsilon(1e-9));  // back at the envelope point
    CHECK(d.h.damage == previous_damage);                  // unloading and reloading do not damage
    CHECK(d.dissipated - dissipated_before == test::approx(0.0).scale(1e-9 * p.tension_fracture_energy));
    // The closed loop: the work done on it is what it dissipated (0 on the secant), never negative.
    CHECK(d.work - work_before >= -1e-9 * p.tension_fracture_energy);
  }
  // Beyond the last amplitude the envelope continues as under monotonic loading.
  const double beta = p.tensile_strength / (p.tension_fracture_energy - 0.5 * p.tensile_strength * u0);
  d.leg(10 * u0, {0, 0}, 200);
  CHECK(-d.sigma == test::approx(p.tensile_strength * std::exp(-beta * (29 * u0))).epsilon(1e-9));
  CHECK(d.work == test::approx(d.dissipated + d.stored()).epsilon(1e-6));
}

TEST_CASE("softening: shear unloads with the initial stiffness, cycles are symmetric, damage is monotone") {
  const Parameters p = table1();
  const double ks = p.shear_stiffness;
  const double sigma_n = 0.5e6;
  Driver d(p);
  d.step(-sigma_n / p.normal_stiffness);
  double previous_damage = 0;
  double u = 0;
  for (const double amplitude : {1e-4, 4e-4, 1.5e-3}) {
    CAPTURE(amplitude);
    const double work_before = d.work, stored_before = d.stored(), dissipated_before = d.dissipated;
    for (const double target : {amplitude, -amplitude, 0.0}) {
      const int n = 800;
      const double du = (target - u) / n;
      for (int i = 0; i < n; ++i) {
        const double tau_before = d.tau[0];
        const auto r = d.step(0, {du, 0});
        if (r.dissipated == 0) CHECK(r.shear_stress[0] - tau_before == test::approx(-ks * du).epsilon(1e-6));  // k_s
        CHECK(d.h.damage >= previous_damage);
        previous_damage = d.h.damage;
        CHECK(std::abs(r.shear_stress[0]) <= ElastoSoftening::shear_strength(p, d.h, sigma_n) * (1 + 1e-12));
      }
      u = target;
    }
    // A closed loop in displacement: the work done equals what was dissipated plus the change of stored energy, and
    // it is positive (no energy created).
    CHECK(d.work - work_before > 0);
    CHECK(d.work - work_before == test::approx(d.dissipated - dissipated_before + d.stored() - stored_before).epsilon(1e-4));
  }
  CHECK(d.h.damage > 0.5);
}

// ---- energy ----

TEST_CASE("softening: over a mixed path, work done = stored energy + sum of dissipated (1e-6)") {
  const Parameters p = table1();
  const double u0 = p.tensile_strength / p.normal_stiffness;
  Driver d(p);
  // Pre-compress, shear, lift into tension while slipping, crush, slide back: every mechanism, 40000 steps per leg
  // (the normal-then-shear split of a step differs from the straight path by a second-order term: the closure
  // error falls as 1 / steps, 1e-5 with 2000 steps per leg, 5e-7 with 40000).
  const std::vector<std::array<double, 3>> legs{{-5 * u0, 0, 0},     {0, 2e-4, 1e-4},    {12 * u0, -1e-4, 0},
                                                {-20 * u0, 3e-4, 2e-4}, {-300 * u0, 0, 0}, {100 * u0, -5e-4, 0},
                                                {200 * u0, 1e-3, -1e-3}, {-400 * u0, 2e-4, 2e-4}};
  for (const auto& leg : legs) d.leg(leg[0], {leg[1], leg[2]}, 40000);
  CHECK(d.h.damage > 0.9);
  CHECK(d.min_step_dissipation >= -1e-12);
  CHECK(d.work == test::approx(d.stored() + d.dissipated).epsilon(1e-6));
}

// ---- damping switch ----

TEST_CASE("softening: damping acts on an intact or lightly damaged closed joint, not on an open, slipping or failed one") {
  const Parameters p = table1();
  const double u0 = p.tensile_strength / p.normal_stiffness;
  {
    Driver d(p);
    d.step(0.5 * u0);  // intact, in tension: bonded, not open
    CHECK(ElastoSoftening::damping_active(p, d.h));
    d.step(0.6 * u0);  // cracking
    CHECK_FALSE(ElastoSoftening::damping_active(p, d.h));
    d.step(0.01 * u0);  // cracked and open
    CHECK_FALSE(ElastoSoftening::damping_active(p, d.h));
    d.step(-2 * u0);  // closed again, d small
    CHECK(d.h.damage > 0);
    CHECK(d.h.damage < p.damping_damage_limit);
    CHECK(ElastoSoftening::damping_active(p, d.h));
  }
  {
    Driver d(p);
    d.step(-0.3e6 / p.normal_stiffness);
    d.step(0, {0.65e6 / p.shear_stiffness, 0});  // a trial 0.65 MPa above the peak 0.3 + 0.3 tan 38 = 0.534 MPa: slips
    CHECK(d.h.inelastic == 1);
    CHECK_FALSE(ElastoSoftening::damping_active(p, d.h));
    d.step(0, {-1e-6, 0});  // elastic unloading, damage still small
    CHECK(ElastoSoftening::damping_active(p, d.h) == (d.h.damage < p.damping_damage_limit));
    d.step(0, {2e-3, 0});  // past the damping damage limit
    d.step(0, {-1e-6, 0});
    CHECK(d.h.damage >= p.damping_damage_limit);
    CHECK_FALSE(ElastoSoftening::damping_active(p, d.h));
  }
}

// ---- property test ----

TEST_CASE("softening: property test over random displacement paths (no NaN, monotone damage, stresses within the surface)") {
  // Also: damping_active, written to read two fields of an undamaged joint, agrees with its full definition.
  const auto base = table1();
  const contact::JointStiffness k{base.normal_stiffness, base.shear_stiffness};
  const ElastoSoftening::FractureEnergies g{base.tension_fracture_energy, base.shear_fracture_energy,
                                             base.compression_fracture_energy};
  const std::vector<Parameters> sets{
      base, table1(0.0),
      Parameters(k, {0.3e6, 0.3e6, 38 * degree, 9.1e6, 0.05e6, 0.1e6, 30 * degree}, g),  // residual strengths
      Parameters(k, {0.3e6, 0.1e6, 45 * degree, 9.1e6, 0, 0, 20 * degree}, g, 4.0),      // f_t tan(phi) > c
      Parameters(k, {0.1e6, 0.2e6, 0.0, 2e6, 0, 0, 0.0}, {5.0, 20.0, 500.0})};           // no friction, brittle
  SplitMix64 random(20240611);
  const int paths = 4000, steps = 250;
  long long elastic_steps = 0, inelastic_steps = 0, failed_paths = 0, checks_failed = 0;
  double most_negative = 0;
  for (int path = 0; path < paths; ++path) {
    const Parameters& p = sets[static_cast<std::size_t>(path) % sets.size()];
    History h{};
    double previous_damage = 0;
    // Increments log-uniform between 1e-8 m and 3e-4 m (elastic ranges: 8e-6 m in tension, 4e-5 m in shear, crushing
    // 4e-4 m), each component independently zero a third of the time, with a drift towards compression on some paths.
    const double drift = random.uniform() < 0.3 ? -0.4 : 0.0;
    for (int i = 0; i < steps; ++i) {
      auto increment = [&](double bias) {
        if (random.uniform() < 1.0 / 3.0) return 0.0;
        const double size = std::pow(10.0, -8.0 + 4.5 * random.uniform());
        return size * (random.uniform_symmetric() + bias);
      };
      const double dn = increment(drift);
      const contact::Shear ds{increment(0), increment(0)};
      const auto r = ElastoSoftening::update(p, h, dn, ds);
      const double stored = ElastoSoftening::stored_energy(p, h);
      const bool finite = std::isfinite(r.normal_stress) && std::isfinite(r.shear_stress[0]) &&
                          std::isfinite(r.shear_stress[1]) && std::isfinite(r.dissipated) && std::isfinite(h.damage) &&
                          std::isfinite(stored) && std::isfinite(h.gap);
      const double sigma = r.normal_stress;
      const double tau = std::hypot(r.shear_stress[0], r.shear_stress[1]);
      const double scale = p.tensile_strength * 1e-12;  // Pa of slack for rounding
      const bool ok = finite && h.damage >= previous_damage && h.damage >= 0 && h.damage <= 1 &&
                      -sigma <= ElastoSoftening::tensile_strength(p, h) * (1 + 1e-12) + scale &&
                      sigma <= ElastoSoftening::cap_strength(p, h) * (1 + 1e-12) + scale &&
                      tau <= ElastoSoftening::shear_strength(p, h, sigma) * (1 + 1e-9) + scale &&
                      std::abs(sigma - ElastoSoftening::normal_stress(p, h)) <= 1e-12 * std::abs(sigma) &&
                      r.dissipated >= -1e-9 * (1 + stored) &&
                      // damping_active's short form (d = 0 first) against its full definition
                      ElastoSoftening::damping_active(p, h) ==
                          (h.inelastic == 0 && h.damage < p.damping_damage_limit && h.failed == 0 && !(h.gap > 0 && h.damage > 0));
      if (!ok) {
        ++checks_failed;
        if (checks_failed < 5) {
          CAPTURE(path);
          CAPTURE(i);
          CAPTURE(sigma);
          CAPTURE(tau);
          CAPTURE(h.damage);
          CAPTURE(previous_damage);
          CAPTURE(r.dissipated);
          CHECK(ok);
        }
      }
      most_negative = std::min(most_negative, r.dissipated);
      (r.dissipated > 0 || h.inelastic ? inelastic_steps : elastic_steps) += 1;
      previous_damage = h.damage;
    }
    failed_paths += h.failed;
  }
  CHECK(checks_failed == 0);
  MESSAGE(paths << " paths, " << elastic_steps << " elastic and " << inelastic_steps << " inelastic steps, " << failed_paths
                << " paths ended failed; most negative step dissipation " << most_negative << " J/m^2");
  // The paths reach every regime, not only the elastic one.
  CHECK(inelastic_steps > paths * steps / 20);
  CHECK(failed_paths > paths / 20);
  CHECK(failed_paths < paths);
}

// ---- in the integrator ----

namespace {
/// A 1 x 1 x 1 m block of 2000 kg bonded to its base by Table 1 joints (4 CPs of 0.25 m^2) and pulled off by an upward
/// body acceleration of 200 m/s^2 (0.4 MPa against f_t = 0.3 MPa), vertical translation only. Returns the energy
/// report after `steps` steps and the smallest damage of the CPs.
template <class Damping>
std::pair<EnergyReport, double> pull_off(Damping damping, int steps) {
  auto s = test::block_on_base(1, 1, 1);
  s.model.gravity = Vec3(0, 0, 200);
  s.model.bodies.fixity[s.block] = model::Fixity::translation_x | model::Fixity::translation_y | model::Fixity::all_rotations;
  const Parameters joint = table1();
  Simulation<Damping, ElastoSoftening> sim(s.model, damping, [&](int, int) { return joint; });
  sim.set_timestep(1e-5);  // 35 steps to the peak, 50 through the softening
  for (int i = 0; i < steps; ++i) sim.step();
  double damage = 1;
  sim.visit_contacts([&](const auto& c) { damage = std::min(damage, c.damage); });
  return {sim.energy(), damage};
}
}  // namespace

TEST_CASE("softening: a joint pulled apart in the integrator dissipates G_f^I A and the energy balance closes") {
  // Reference: the fracture energy G_f^I (eq. 4) times the joint area, 1 m^2; the balance of DESIGN §4.
  const auto [e, damage] = pull_off(damping::None{}, 2000);
  CHECK(damage >= ElastoSoftening::failure_damage);
  CHECK(e.slip == test::approx(table1().tension_fracture_energy * 1.0).epsilon(1e-3));
  CHECK(e.balance_error < 1e-3);
  damping::MaxwellFitOptions o;
  const auto [m, maxwell_damage] = pull_off(damping::to_policy<3>(damping::fit_maxwell(o)), 2000);
  CHECK(maxwell_damage >= ElastoSoftening::failure_damage);
  CHECK(m.viscous > 0);  // the branches acted while the joint was bonded
  CHECK(m.slip == test::approx(table1().tension_fracture_energy * 1.0).epsilon(1e-3));
  CHECK(m.balance_error < 1e-3);
  MESSAGE("pull-off: slip dissipation " << e.slip << " J, balance error " << e.balance_error << " (None), "
                                        << m.balance_error << " (Maxwell<3>, viscous " << m.viscous << " J)");
}

TEST_CASE("softening: a joint that broke and separated does not heal when it closes again") {
  // Reference: the bond exists only where the joint was at the start; contact points created during the run start
  // from the failed state (damage 1: no tension, residual cohesion).
  auto s = test::block_on_base(1, 1, 1);
  s.model.gravity = Vec3(0, 0, 200);  // pulls the block off, as above
  s.model.bodies.fixity[s.block] = model::Fixity::translation_x | model::Fixity::translation_y | model::Fixity::all_rotations;
  const Parameters joint = table1();
  Simulation<damping::None, ElastoSoftening> sim(s.model, damping::None{}, [&](int, int) { return joint; });
  sim.set_timestep(1e-5);
  double intact_at_start = 1;
  sim.visit_contacts([&](const auto& c) { intact_at_start = std::min(intact_at_start, 1.0 - c.damage); });
  CHECK(intact_at_start == 1.0);
  for (int i = 0; i < 2000; ++i) sim.step();
  REQUIRE(sim.contact_points() == 0);  // separated beyond the contact tolerance: the CPs are gone
  s.model.gravity = Vec3(0, 0, -200);  // and back down
  int steps = 0;
  while (sim.contact_points() == 0 && steps < 20000) {
    sim.step();
    ++steps;
  }
  REQUIRE(sim.contact_points() == 4);
  double smallest_damage = 1;
  int never_bonded = 0, shown_as_damage = 0;
  sim.visit_contact_histories([&](std::size_t, std::size_t, const auto& h) {
    smallest_damage = std::min(smallest_damage, h.damage);
    never_bonded += h.failed == contact::never_bonded;
  });
  sim.visit_contacts([&](const auto& c) { shown_as_damage += !c.never_bonded || c.damage != 0; });
  CHECK(smallest_damage == 1.0);
  CHECK(never_bonded == 4);     // marked as new contacts through the law's updates since
  CHECK(shown_as_damage == 0);  // and not shown as broken joints
}

TEST_CASE("softening: the inline elastic step equals the full step wherever it is taken") {
  // Reference: update_inelastic, the whole step in every regime (validated by the tests above). Random paths through
  // every regime; at each step both are applied to copies of the history and must agree bit for bit.
  const Parameters p = table1();
  SplitMix64 random(7);
  long long compared = 0, fast = 0;
  for (int path = 0; path < 500; ++path) {
    ElastoSoftening::History h{};
    const double scale = 2e-5 * (1 + 10 * random.uniform());
    for (int step = 0; step < 200; ++step) {
      const double dn = scale * random.uniform_symmetric();
      const contact::Shear ds{scale * random.uniform_symmetric(), scale * random.uniform_symmetric()};
      ElastoSoftening::History a = h, b = h;
      const auto ra = ElastoSoftening::update(p, a, dn, ds);
      const auto rb = ElastoSoftening::update_inelastic(p, b, dn, ds);
      const bool same = ra.normal_stress == rb.normal_stress && ra.shear_stress == rb.shear_stress &&
                        ra.dissipated == rb.dissipated && a.gap == b.gap && a.shear == b.shear && a.damage == b.damage &&
                        a.tension_secant == b.tension_secant && a.compression_secant == b.compression_secant &&
                        a.max_closure == b.max_closure && a.failed == b.failed && a.inelastic == b.inelastic;
      CHECK(same);
      ++compared;
      fast += b.inelastic == 0;
      h = b;
    }
  }
  MESSAGE(compared << " steps compared, " << fast << " elastic");
  CHECK(fast > compared / 10);
  CHECK(fast < compared);
}

}  // namespace test_softening
