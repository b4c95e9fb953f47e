#pragma once
// The elasto-softening joint law of the masonry unit-mortar interfaces (paper Sect. 3.1, Fig. 5C, eq. 4-7; DESIGN.md
// §6): tension cut-off, Coulomb limit and an elliptic compression cap; exponential softening in tension and shear with
// one combined damage; hardening then softening in compression; secant unloading in tension and compression.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "blockdem/contact/closure_impulse.hpp"
#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"

namespace blockdem::contact {

/// Normal and shear stiffness of a joint.
struct JointStiffness {
  double normal = 0;  // k_n, Pa/m
  double shear = 0;   // k_s, Pa/m
};

/// eq. 7 (Lourenço 1996): a mortar joint of thickness t_m between units, as a zero-thickness interface,
/// k_n = E_b E_m / (t_m (E_b - E_m)) and k_s = k_n / (2 (1 + nu)). E_b (unit) and E_m (mortar) in Pa, t_m in m, nu the
/// mortar's Poisson ratio. Throws InvalidArgument unless E_b > E_m > 0, t_m > 0 and -1 < nu <= 0.5.
inline JointStiffness joint_stiffness_from_eq7(double unit_modulus, double mortar_modulus, double mortar_thickness,
                                               double poisson_ratio) {
  auto check = [](bool ok, const std::string& what) {
    if (!ok) throw InvalidArgument("joint stiffness (eq. 7): " + what);
  };
  check(mortar_modulus > 0 && std::isfinite(mortar_modulus),
        "mortar Young's modulus E_m must be > 0 Pa, got " + std::to_string(mortar_modulus));
  check(unit_modulus > mortar_modulus && std::isfinite(unit_modulus),
        "unit Young's modulus E_b must be > E_m = " + std::to_string(mortar_modulus) + " Pa, got " +
            std::to_string(unit_modulus));
  check(mortar_thickness > 0 && std::isfinite(mortar_thickness),
        "mortar thickness t_m must be > 0 m, got " + std::to_string(mortar_thickness));
  check(poisson_ratio > -1 && poisson_ratio <= 0.5, "Poisson ratio nu must be in (-1, 0.5], got " + std::to_string(poisson_ratio));
  const double kn = unit_modulus * mortar_modulus / (mortar_thickness * (unit_modulus - mortar_modulus));  // eq. 7
  return {kn, kn / (2.0 * (1.0 + poisson_ratio))};                                                       // eq. 7
}

namespace detail {
// Eq. 4 and 6 are empirical (CEB-FIP Model Code 1990): strengths in MPa, fracture energies in N/mm.
inline constexpr double pascal_per_megapascal = 1e6;
inline constexpr double newton_per_metre_per_newton_per_millimetre = 1e3;  // and N/m = J/m^2
}  // namespace detail

/// eq. 4: mode-I fracture energy G_f^I = 0.025 (2 f_t)^0.7 (N/mm, f_t in MPa). Takes f_t in Pa, returns J/m^2 (N/m).
inline double fracture_energy_tension_eq4(double tensile_strength) {
  if (!(tensile_strength > 0) || !std::isfinite(tensile_strength))
    throw InvalidArgument("fracture energy (eq. 4): tensile strength f_t must be > 0 Pa, got " + std::to_string(tensile_strength));
  const double ft_mpa = tensile_strength / detail::pascal_per_megapascal;
  return 0.025 * std::pow(2.0 * ft_mpa, 0.7) * detail::newton_per_metre_per_newton_per_millimetre;  // eq. 4
}

/// eq. 5: mode-II fracture energy G_f^II = 10 G_f^I (J/m^2).
inline double fracture_energy_shear_eq5(double tension_fracture_energy) {
  if (!(tension_fracture_energy > 0) || !std::isfinite(tension_fracture_energy))
    throw InvalidArgument("fracture energy (eq. 5): G_f^I must be > 0 J/m^2, got " + std::to_string(tension_fracture_energy));
  return 10.0 * tension_fracture_energy;  // eq. 5
}

/// eq. 6: compressive fracture energy G_c = 15 + 0.43 f_c - 0.0036 f_c^2 (N/mm, f_c in MPa). Takes f_c in Pa, returns
/// J/m^2. The parabola is positive for f_c below about 152 MPa.
inline double fracture_energy_compression_eq6(double compressive_strength) {
  const double fc = compressive_strength / detail::pascal_per_megapascal;
  if (!(fc > 0) || !(fc < 150) || !std::isfinite(fc))
    throw InvalidArgument("fracture energy (eq. 6): compressive strength f_c must be in (0, 150] MPa, got " +
                          std::to_string(compressive_strength) + " Pa");
  return (15.0 + 0.43 * fc - 0.0036 * fc * fc) * detail::newton_per_metre_per_newton_per_millimetre;  // eq. 6
}

/// The material inputs of a unit-mortar joint, by default the paper's Table 1 (Bianchini et al. 2024a) with a 10 mm
/// mortar layer. SI: Pa, m, rad.
struct MasonryJointProperties {
  double unit_modulus = 6200e6;                  // E_b, Pa
  double mortar_modulus = 370.05e6;              // E_m, Pa
  double mortar_thickness = 0.010;               // t_m, m
  double poisson_ratio = 0.25;                   // nu
  double tensile_strength = 0.3e6;               // f_t, Pa
  double compressive_strength = 9.1e6;           // f_c, Pa
  double cohesion = 0.3e6;                       // c, Pa
  double friction_angle = 38.0 * pi / 180.0;     // phi, rad
};

/// The elasto-softening joint (paper Fig. 5C). Formulation (DESIGN.md §6, and where it had to choose):
///
/// - Strengths. One combined damage d in [0, 1], never decreasing: 1 - d = (1 - d_t)(1 - d_s)(1 - d_c), which for
///   tension and shear is DESIGN's d = d_t + d_s - d_t d_s. Tensile strength, cohesion and tan(friction) move from peak
///   to residual in proportion to (1 - d): f_t(d) = f_t,r + (f_t - f_t,r)(1 - d), and so on.
/// - Tension (gap > 0): elastic with the secant stiffness k_t (initially k_n) up to f_t(d); beyond, exponential
///   softening: each metre of opening past the secant's limit multiplies (1 - d) by exp(-beta_t). Unloading and
///   reloading follow the secant to the origin; re-closing uses the compression stiffness (k_n unless crushed).
///   beta_t = f_t / (G_f^I - f_t^2 / (2 k_n)): DESIGN's rate f_t / G_f^I would dissipate G_f^I plus the elastic energy
///   at the peak, because with secant unloading that energy is lost too; this way a full separation dissipates G_f^I.
/// - Shear: elastic with k_s (also on unloading after the peak), Coulomb limit c(d) + sigma tan(phi(d)) (sigma
///   compression positive, so tension lowers it, never below 0); each metre of plastic slip multiplies (1 - d) by
///   exp(-beta_s), beta_s = c / G_f^II (DESIGN), so the loss of the cohesion dissipates G_f^II (with c_r = 0; with a
///   residual cohesion, (1 - c_r / c) G_f^II; a friction angle softening to phi_r adds sigma (tan phi - tan phi_r) /
///   beta_s); friction keeps dissipating sigma tan(phi_r) per metre of slip at the residual. In 2D the return is
///   radial, as in MohrCoulomb. Likewise a residual f_t,r keeps beta_t: the joint then never separates.
/// - Compression (gap < 0, closure s = -gap): elastic to f_c/3 (as Lourenço and Rots 1997), then a parabola tangent to
///   the elastic line that reaches f_c with zero slope at s_p = 5 f_c / (3 k_n), then exponential softening
///   f_c,r + (f_c - f_c,r) exp(-beta_c (s - s_p)), which also counts as damage d_c (a crushed joint has lost its
///   bond). Unloading and reloading follow the secant (the paper: stiffness degradation in tension and compression).
///   beta_c = f_c / (G_c - f_c s_p / 2): G_c is the energy dissipated from the peak on (post-peak envelope plus the
///   elastic energy at the peak, released on the way down) with f_c,r = 0, the paper's law; a residual f_c,r keeps
///   beta_c, as f_t,r keeps beta_t. The residual is the crushed masonry that still stands between two blocks: with
///   none, a joint crushed through carries nothing and the blocks pass through each other (collapse runs).
/// - Elliptic cap: beside the Coulomb limit, |tau| <= sqrt((sigma_cap^2 - sigma^2) / C_s) for sigma > 0, sigma_cap the
///   compressive strength still available (f_c until the peak, then the softened one); C_s = 9 (Lourenço and Rots)
///   by default, 0 for a cap on sigma alone. The cap itself acts on sigma only; slip on the ellipse drives d_s like any
///   other slip. For Table 1 the ellipse governs above sigma = 3.2 MPa.
/// - The step is split: the normal increment at fixed shear displacement, then the shear increment at fixed gap. If
///   the normal part shrank the Coulomb/cap limit below the old shear stress, that stress first relaxes at fixed
///   shear displacement; if shear damage lowered f_t(d) below a tensile stress, it relaxes at fixed gap. Every part
///   of `dissipated` is the work minus the change of stored energy along that split path (exact for collinear shear
///   increments; the radial return's plastic work otherwise), hence never negative and, for monotonic loading,
///   independent of the step size. The split differs from a straight path by a second-order term per step.
struct ElastoSoftening {
  struct Strengths {
    double tensile = 0;                   // f_t, Pa
    double cohesion = 0;                  // c, Pa
    double friction_angle = 0;            // phi, rad
    double compressive = 0;               // f_c, Pa
    double residual_tensile = 0;          // f_t,r, Pa
    double residual_cohesion = 0;         // c_r, Pa
    double residual_friction_angle = -1;  // phi_r, rad; negative: phi
    double residual_compressive = 0;      // f_c,r, Pa: what a crushed joint still carries
  };
  struct FractureEnergies {
    double tension = 0;      // G_f^I, J/m^2
    double shear = 0;        // G_f^II, J/m^2
    double compression = 0;  // G_c, J/m^2
  };

  /// The bond counts as broken (History::failed) once 99.9 % of the strengths above residual are gone.
  static constexpr double failure_damage = 0.999;

  struct Parameters {
    double normal_stiffness = 0;        // k_n, Pa/m
    double shear_stiffness = 0;         // k_s, Pa/m
    double tensile_strength = 0;        // Pa
    double cohesion = 0;                // Pa
    double friction_angle = 0;          // rad
    double compressive_strength = 0;    // Pa
    double residual_tensile_strength = 0;  // Pa
    double residual_cohesion = 0;          // Pa
    double residual_friction_angle = 0;    // rad
    double residual_compressive_strength = 0;  // Pa
    double tension_fracture_energy = 0;     // G_f^I, J/m^2
    double shear_fracture_energy = 0;       // G_f^II, J/m^2
    double compression_fracture_energy = 0; // G_c, J/m^2
    double cap_shear_factor = 9;        // C_s of the elliptic cap, 0: no shear term
    /// Viscous damping (Maxwell branches, dashpots) acts only while d is below this: a joint that has lost at least
    /// this fraction of its bond counts as failed, as a broken Mohr-Coulomb joint does (DESIGN §4). Below it, a closed
    /// joint still has its initial stiffnesses (the secant acts on the tension side only; shear unloads with k_s), so
    /// branches sized on k_n, k_s still describe it. Default 0.5: half the strength above residual is gone.
    double damping_damage_limit = 0.5;
    // Derived once here, not in the loop.
    double tan_friction = 0;
    double tan_residual_friction = 0;
    double tensile_drop = 0;           // f_t - f_t,r, Pa
    double cohesion_drop = 0;          // c - c_r, Pa
    double friction_drop = 0;          // tan(phi) - tan(phi_r)
    double tension_softening_rate = 0;      // beta_t, 1/m
    double shear_softening_rate = 0;        // beta_s, 1/m
    double compression_softening_rate = 0;  // beta_c, 1/m
    double elastic_limit_closure = 0;  // m, f_c / (3 k_n): the hardening starts
    double peak_closure = 0;           // m, 5 f_c / (3 k_n): the compressive peak
    double hardening_span = 0;         // m, peak_closure - elastic_limit_closure
    double inverse_cap_shear_factor = 0;  // 1 / C_s, 0 without the shear term

    Parameters() = default;
    bool operator==(const Parameters&) const = default;

    Parameters(JointStiffness k, Strengths s, FractureEnergies g, double cap_shear = 9.0, double damping_limit = 0.5)
        : normal_stiffness(k.normal), shear_stiffness(k.shear), tensile_strength(s.tensile), cohesion(s.cohesion),
          friction_angle(s.friction_angle), compressive_strength(s.compressive),
          residual_tensile_strength(s.residual_tensile), residual_cohesion(s.residual_cohesion),
          residual_friction_angle(s.residual_friction_angle < 0 ? s.friction_angle : s.residual_friction_angle),
          residual_compressive_strength(s.residual_compressive), tension_fracture_energy(g.tension), shear_fracture_energy(g.shear), compression_fracture_energy(g.compression),
          cap_shear_factor(cap_shear), damping_damage_limit(damping_limit) {
      auto check = [](bool ok, const std::string& what) {
        if (!ok) throw InvalidArgument("elasto-softening joint: " + what);
      };
      auto finite_positive = [](double v) { return v > 0 && std::isfinite(v); };
      constexpr double right_angle = 0.5 * pi;
      check(finite_positive(k.normal), "normal stiffness must be > 0 Pa/m, got " + std::to_string(k.normal));
      check(finite_positive(k.shear), "shear stiffness must be > 0 Pa/m, got " + std::to_string(k.shear));
      check(finite_positive(s.tensile), "tensile strength must be > 0 Pa, got " + std::to_string(s.tensile));
      check(finite_positive(s.cohesion), "cohesion must be > 0 Pa, got " + std::to_string(s.cohesion));
      check(s.friction_angle >= 0 && s.friction_angle < right_angle, "friction angle must be in [0, 90) degrees, got " +
                                                                         std::to_string(s.friction_angle * 180 / pi));
      check(finite_positive(s.compressive) && s.compressive > s.tensile,
            "compressive strength must be > the tensile strength " + std::to_string(s.tensile) + " Pa, got " +
                std::to_string(s.compressive));
      check(s.residual_tensile >= 0 && s.residual_tensile <= s.tensile,
            "residual tensile strength must be in [0, tensile strength " + std::to_string(s.tensile) + "] Pa, got " +
                std::to_string(s.residual_tensile));
      check(s.residual_cohesion >= 0 && s.residual_cohesion <= s.cohesion,
            "residual cohesion must be in [0, cohesion " + std::to_string(s.cohesion) + "] Pa, got " +
                std::to_string(s.residual_cohesion));
      check(residual_friction_angle <= friction_angle,
            "residual friction angle must be in [0, friction angle " + std::to_string(friction_angle * 180 / pi) +
                "] degrees, got " + std::to_string(residual_friction_angle * 180 / pi));
      check(s.residual_compressive >= 0 && s.residual_compressive < s.compressive,
            "residual compressive strength must be in [0, compressive strength " + std::to_string(s.compressive) +
                ") Pa, got " + std::to_string(s.residual_compressive));
      const double tension_elastic = s.tensile * s.tensile / (2.0 * k.normal);
      check(finite_positive(g.tension) && g.tension > tension_elastic,
            "tensile fracture energy G_f^I must be > f_t^2 / (2 k_n) = " + std::to_string(tension_elastic) +
                " J/m^2 (the elastic energy at the peak), got " + std::to_string(g.tension));
      check(finite_positive(g.shear), "shear fracture energy G_f^II must be > 0 J/m^2, got " + std::to_string(g.shear));
      elastic_limit_closure = s.compressive / (3.0 * k.normal);
      peak_closure = 5.0 * s.compressive / (3.0 * k.normal);
      hardening_span = peak_closure - elastic_limit_closure;
      const double compression_elastic = 0.5 * s.compressive * peak_closure;
      check(finite_positive(g.compression) && g.compression > compression_elastic,
            "compressive fracture energy G_c must be > f_c s_p / 2 = 5 f_c^2 / (6 k_n) = " +
                std::to_string(compression_elastic) + " J/m^2 (the elastic energy at the peak), got " +
                std::to_string(g.compression));
      check(cap_shear >= 0 && std::isfinite(cap_shear),
            "cap shear factor C_s must be >= 0 (0: no shear term), got " + std::to_string(cap_shear));
      check(damping_limit > 0 && damping_limit <= 1,
            "damping damage limit must be in (0, 1], got " + std::to_string(damping_limit));
      tan_friction = std::tan(friction_angle);
      tan_residual_friction = std::tan(residual_friction_angle);
      tensile_drop = tensile_strength - residual_tensile_strength;
      cohesion_drop = cohesion - residual_cohesion;
      friction_drop = tan_friction - tan_residual_friction;
      tension_softening_rate = tensile_strength / (g.tension - tension_elastic);
      shear_softening_rate = cohesion / g.shear;
      compression_softening_rate = compressive_strength / (g.compression - compression_elastic);
      inverse_cap_shear_factor = cap_shear > 0 ? 1.0 / cap_shear : 0.0;
    }

    /// Stiffnesses from eq. 7, fracture energies from eq. 4-6, no residual tension or cohesion, residual friction
    /// angle = peak.
    static Parameters from_material(const MasonryJointProperties& m = {}, double cap_shear = 9.0,
                                    double damping_limit = 0.5) {
      const JointStiffness k = joint_stiffness_from_eq7(m.unit_modulus, m.mortar_modulus, m.mortar_thickness, m.poisson_ratio);
      const double gf1 = fracture_energy_tension_eq4(m.tensile_strength);
      Strengths s;
      s.tensile = m.tensile_strength;
      s.cohesion = m.cohesion;
      s.friction_angle = m.friction_angle;
      s.compressive = m.compressive_strength;
      return {k, s, {gf1, fracture_energy_shear_eq5(gf1), fracture_energy_compression_eq6(m.compressive_strength)},
              cap_shear, damping_limit};
    }
  };

  /// Per contact point: 64 bytes, doubles, flags and the closure correction (in what was padding).
  struct History {
    double gap = 0;                  // m, positive open
    Shear shear{0, 0};               // Pa
    double damage = 0;               // combined d in [0, 1], never decreases
    double tension_secant = 1;       // tension stiffness / k_n (the secant to the origin once cracked)
    double compression_secant = 1;   // compression stiffness / k_n (the secant once hardened or crushed)
    double max_closure = 0;          // m, largest closure reached beyond f_c / 3 (0 until then)
    std::uint8_t failed = 0;         // d >= failure_damage: residual strengths
    std::uint8_t inelastic = 0;      // the last step cracked, crushed or slipped
    ClosureImpulse impulse;          // the correction of the last sample, if the gap changed sign in its step
  };

  /// The step: inline while it stays elastic (the common case, a few comparisons); the cracking, crushing and
  /// slipping paths out of line (`update_inelastic`), so that the fused contact loop keeps the law inline.
  [[gnu::always_inline]] static Response update(const Parameters& p, History& h, double du_normal, Shear du_shear,
                                                const Step& step = {}) noexcept {
    const double gap = h.gap + du_normal;
    const double intact = 1.0 - h.damage;
    const double kn = p.normal_stiffness;
    double sigma;  // compression positive
    if (gap > 0) {
      sigma = -kn * h.tension_secant * gap;
      if (-sigma > p.residual_tensile_strength + p.tensile_drop * intact) return update_inelastic(p, h, du_normal, du_shear, step);
    } else {
      if (-gap > std::max(h.max_closure, p.elastic_limit_closure)) return update_inelastic(p, h, du_normal, du_shear, step);
      sigma = -kn * h.compression_secant * gap;
    }
    const double limit2 = shear_limit_squared(p, sigma, intact, cap_strength(p, h));
    const Shear tau{h.shear[0] - p.shear_stiffness * du_shear[0], h.shear[1] - p.shear_stiffness * du_shear[1]};
    const double old2 = h.shear[0] * h.shear[0] + h.shear[1] * h.shear[1];
    if (old2 > limit2 * (1.0 + 1e-12) || tau[0] * tau[0] + tau[1] * tau[1] > limit2)
      return update_inelastic(p, h, du_normal, du_shear, step);
    double dissipated = 0.0;
    double kink_crossing = 0.0;
    if ((h.gap > 0) != (gap > 0)) [[unlikely]] {
      // The gap changed sign: the normal spring crossed its kink between the secants (contact/closure_impulse.hpp).
      const double k0 = kn * (h.gap > 0 ? h.tension_secant : h.compression_secant);
      const double k1 = kn * (gap > 0 ? h.tension_secant : h.compression_secant);
      kink_crossing = kink_error(h.gap, gap, k0, k1);
    }
    const double correction = h.impulse.step(kink_crossing, du_normal, sigma, kn, step, dissipated);
    h.gap = gap;
    h.shear = tau;
    h.inelastic = 0;
    // damping_active with inelastic = 0 and the new gap; the normal stress with the closure correction of this
    // sample (normal_stress(), the spring's, without it).
    return {sigma + correction, tau, dissipated,
            h.damage == 0 || (h.damage < p.damping_damage_limit && h.failed == 0 && !(gap > 0))};
  }

  /// The whole step, any regime (the elastic one included).
  [[gnu::noinline]] static Response update_inelastic(const Parameters& p, History& h, double du_normal, Shear du_shear,
                                                     const Step& step = {}) noexcept {
    const double kn = p.normal_stiffness;
    const double gap_before = h.gap;
    const double sigma_before = normal_stress(p, h);
    const double normal_energy_before = normal_energy(p, h);
    const Shear shear_before = h.shear;
    double dissipated = 0.0;  // by the normal spring, as its envelopes give it
    const double gap = h.gap + du_normal;
    h.gap = gap;
    const double intact0 = 1.0 - h.damage;  // 1 - d
    double intact = intact0;
    bool inelastic = false;

    // Normal part, at fixed shear displacement. The side the gap left is unloaded along its secant (no dissipation),
    // so only the side it ends on can leave the elastic range.
    double sigma;  // compression positive
    if (gap > 0) {
      const double strength = p.residual_tensile_strength + p.tensile_drop * intact;
      const double t = kn * h.tension_secant * gap;
      if (t > strength) {
        sigma = -soften_in_tension(p, h, strength, intact, dissipated);
        inelastic = true;
      } else {
        sigma = -t;
      }
    } else {
      const double closure = -gap;
      const double limit = std::max(h.max_closure, p.elastic_limit_closure);
      if (closure > limit) {
        sigma = crush(p, h, closure, limit, intact, dissipated);
        inelastic = true;
      } else {
        sigma = kn * h.compression_secant * closure;
      }
    }
    const double intact_after_normal = intact;
    // The normal spring's path bent within the step: it softened or crushed, crossed the kink between its secants
    // (the gap changed sign), or relaxes below. Elastic and on one side, the trapezoid is exact.
    bool normal_bent = inelastic || (gap_before > 0) != (gap > 0);

    // Shear part, at fixed gap: the limit with the damage so far, the elastic predictor with k_s, the return.
    const double ks = p.shear_stiffness;
    const double cap = cap_strength(p, h);
    double limit2 = shear_limit_squared(p, sigma, intact, cap);
    Shear tau = h.shear;
    const double old2 = tau[0] * tau[0] + tau[1] * tau[1];
    double shear_dissipated = 0.0;  // as the return integrates it
    if (old2 > limit2 * (1.0 + 1e-12)) {
      // The normal part lowered the limit: relax at fixed shear displacement (no work; the released elastic energy
      // is dissipated).
      const double m = std::sqrt(old2);
      const Slip r = return_to_surface(p, sigma, intact, cap, m);
      shear_dissipated += 0.5 * (old2 - r.strength * r.strength) / ks;
      intact *= std::exp(-p.shear_softening_rate * r.slip);
      tau = {tau[0] * (r.strength / m), tau[1] * (r.strength / m)};
      limit2 = shear_limit_squared(p, sigma, intact, cap);
      inelastic = true;
    }
    tau = {tau[0] - ks * du_shear[0], tau[1] - ks * du_shear[1]};
    const double trial2 = tau[0] * tau[0] + tau[1] * tau[1];
    if (trial2 > limit2) {
      const double m = std::sqrt(trial2);
      const Slip r = return_to_surface(p, sigma, intact, cap, m);
      shear_dissipated += r.work;
      intact *= std::exp(-p.shear_softening_rate * r.slip);
      tau = {tau[0] * (r.strength / m), tau[1] * (r.strength / m)};
      inelastic = true;
    }
    h.shear = tau;

    // Shear damage lowered f_t(d): a tensile stress above it relaxes at fixed gap along a new secant.
    if (gap > 0 && intact < intact_after_normal) {
      const double strength = p.residual_tensile_strength + p.tensile_drop * intact;
      const double t = -sigma;
      if (t > strength) {
        dissipated += 0.5 * gap * (t - strength);
        h.tension_secant = strength / (kn * gap);
        sigma = -strength;
        normal_bent = true;
      }
    }

    // In a step of a dynamic run, what the step dissipated is booked as the scheme's work on the springs, the
    // trapezoid of the stresses at both samples, less the change of their stored energy: the energy report's own
    // measure, so that the balance closes on any path. The envelopes and the return integrate the stress along the
    // path within the step, which differs from the trapezoid where the path bends (the peak of tension or
    // compression, the onset of slip, slip at a normal stress that changed within the step): for the shear springs the
    // booking is that measure; for the normal spring the difference is the step's trapezoid error, which goes to the
    // closure impulse like a kink crossed (contact/closure_impulse.hpp) and is removed where it is energy made. Under
    // displacement control (no time passes: the joint test) the envelopes' integrals are booked, independent of the
    // step size.
    const double dissipated_normal = dissipated;
    dissipated += step.dt > 0.0 ? shear_dissipation(shear_before, tau, du_shear, ks) : shear_dissipated;
    const double trapezoid_error =
        normal_bent ? path_error(sigma_before, sigma, du_normal, normal_energy_before, normal_energy(p, h), dissipated_normal) : 0.0;
    const double correction = h.impulse.step(trapezoid_error, du_normal, sigma, kn, step, dissipated);

    if (intact < intact0) h.damage = std::max(h.damage, std::min(1.0, 1.0 - intact));
    if (h.failed != contact::never_bonded) h.failed = h.damage >= failure_damage;
    h.inelastic = inelastic;
    return {sigma + correction, tau, dissipated, damping_active(p, h)};
  }

  static constexpr double normal_stiffness(const Parameters& p) noexcept { return p.normal_stiffness; }
  static constexpr double shear_stiffness(const Parameters& p) noexcept { return p.shear_stiffness; }

  /// Off while the last step cracked, crushed or slipped, once the bond has failed or d reached the damping damage
  /// limit, and while a cracked joint is open (gap > 0 with d > 0). An intact joint in tension is bonded, not open.
  static constexpr bool damping_active(const Parameters& p, const History& h) noexcept {
    // An undamaged joint (d = 0, the common case) has not failed (failed implies d >= failure_damage) and is below
    // the damping damage limit (> 0): two fields to read instead of four. The two flags are not tested side by
    // side: GCC then reads them as one word, right after the step stored `inelastic` alone, a store-forwarding
    // stall that cost a quarter of the contact loop with Maxwell damping.
    return h.inelastic == 0 && (h.damage == 0 || (h.damage < p.damping_damage_limit && h.failed == 0 && !(h.gap > 0)));
  }

  /// Recoverable elastic energy per area, with the current secant stiffness on the side the gap is on.
  static constexpr double stored_energy(const Parameters& p, const History& h) noexcept {
    return normal_energy(p, h) + 0.5 * (h.shear[0] * h.shear[0] + h.shear[1] * h.shear[1]) / p.shear_stiffness;
  }
  /// The normal spring's part of stored_energy (J/m^2).
  static constexpr double normal_energy(const Parameters& p, const History& h) noexcept {
    const double secant = h.gap > 0 ? h.tension_secant : h.compression_secant;
    return 0.5 * p.normal_stiffness * secant * h.gap * h.gap;
  }

  // Traits (ContactLaw). A never-bonded point starts fully damaged: residual strengths, no tension.
  static void turn_shear(History& h, const ShearTurn& turn) noexcept { turn.apply(h.shear[0], h.shear[1]); }
  static constexpr double damage(const History& h) noexcept { return h.damage; }
  static constexpr void start_unbonded(History& h) noexcept {
    h.failed = contact::never_bonded;
    h.damage = 1.0;
  }
  static constexpr bool never_bonded(const History& h) noexcept { return h.failed == contact::never_bonded; }
  static constexpr bool dissipates = true;  // cracking, crushing, slip

  // ---- the current state, for output and tests ----

  /// Pa, compression positive.
  static constexpr double normal_stress(const Parameters& p, const History& h) noexcept {
    return -p.normal_stiffness * (h.gap > 0 ? h.tension_secant : h.compression_secant) * h.gap;
  }
  /// The secants are kept so that this is the normal stress the step returned (to rounding: after softening or
  /// crushing, secant = stress / (k_n gap)).
  static Traction traction(const Parameters& p, const History& h) noexcept {
    return {normal_stress(p, h) + h.impulse.stress(), h.shear[0], h.shear[1]};  // with this sample's closure correction
  }
  /// f_t(d), Pa.
  static constexpr double tensile_strength(const Parameters& p, const History& h) noexcept {
    return p.residual_tensile_strength + p.tensile_drop * (1.0 - h.damage);
  }
  /// The compressive strength still available, Pa: f_c until the peak, then the softened value.
  static constexpr double cap_strength(const Parameters& p, const History& h) noexcept {
    return h.max_closure > p.peak_closure ? p.normal_stiffness * h.compression_secant * h.max_closure
                                          : p.compressive_strength;
  }
  /// The largest |tau| at normal stress sigma (Pa, compression positive) with the current damage: min(Coulomb, cap).
  static double shear_strength(const Parameters& p, const History& h, double sigma) noexcept {
    return std::sqrt(shear_limit_squared(p, sigma, 1.0 - h.damage, cap_strength(p, h)));
  }

 private:
  static double shear_limit_squared(const Parameters& p, double sigma, double intact, double cap) noexcept {
    const double coulomb = std::max(
        0.0, p.residual_cohesion + p.cohesion_drop * intact + sigma * (p.tan_residual_friction + p.friction_drop * intact));
    double limit2 = coulomb * coulomb;
    if (sigma > 0 && p.cap_shear_factor > 0)
      limit2 = std::min(limit2, std::max(0.0, cap * cap - sigma * sigma) * p.inverse_cap_shear_factor);
    return limit2;
  }

  /// Exponential softening in tension from where the secant meets f_t(d) to `h.gap`. Returns the tensile stress.
  static double soften_in_tension(const Parameters& p, History& h, double strength, double& intact,
                                  double& dissipated) noexcept {
    const double kn = p.normal_stiffness;
    const double gap = h.gap;
    const double start = strength / (kn * h.tension_secant);
    const double reach = gap - start;
    const double beta = p.tension_softening_rate;
    const double decay = std::expm1(-beta * reach);  // exp(-beta reach) - 1
    const double drop = p.tensile_drop * intact;
    intact *= 1.0 + decay;
    const double t = p.residual_tensile_strength + p.tensile_drop * intact;
    const double work = p.residual_tensile_strength * reach - drop * decay / beta;  // area under the envelope
    dissipated += work - 0.5 * (t * gap - strength * start);
    h.tension_secant = t / (kn * gap);
    return t;
  }

  /// The compression envelope from closure `from` (on it already) to `to`: the hardening parabola up to the peak,
  /// exponential softening to the residual beyond. Returns the compressive stress.
  static double crush(const Parameters& p, History& h, double to, double from, double& intact, double& dissipated) noexcept {
    const double kn = p.normal_stiffness;
    const double fc = p.compressive_strength;
    const double start_stress = kn * h.compression_secant * from;
    double a = from, sigma_a = start_stress, work = 0.0;
    if (a < p.peak_closure) {
      // sigma = f_c - (2 f_c / 3) ((s_p - s) / (s_p - s_i))^2: tangent to k_n at s_i = f_c / (3 k_n), flat at s_p.
      const double b = std::min(to, p.peak_closure);
      const double ra = p.peak_closure - a, rb = p.peak_closure - b;
      const double span2 = p.hardening_span * p.hardening_span;
      work += fc * (b - a) - (2.0 * fc / (9.0 * span2)) * (b - a) * (ra * ra + ra * rb + rb * rb);
      sigma_a = fc - (2.0 * fc / 3.0) * rb * rb / span2;
      a = b;
    }
    double sigma = sigma_a;
    if (to > a) {
      // sigma_a is on the envelope, at or above the residual: the part above it decays.
      const double fr = p.residual_compressive_strength;
      const double decay = std::expm1(-p.compression_softening_rate * (to - a));
      sigma = fr + (sigma_a - fr) * (1.0 + decay);
      work += fr * (to - a) - (sigma_a - fr) * decay / p.compression_softening_rate;
      intact *= 1.0 + decay;  // crushing damage d_c joins the combined damage
    }
    dissipated += work - 0.5 * (sigma * to - start_stress * from);
    h.max_closure = to;
    h.compression_secant = sigma / (kn * to);
    return sigma;
  }

  struct Slip {
    double strength = 0;  // Pa, the limit |tau| returns to
    double slip = 0;      // m, plastic slip of the return
    double work = 0;      // J/m^2, the limit integrated over the slip
  };

  /// Radial return of a trial shear stress of magnitude m at normal stress sigma: the plastic slip x solves
  /// m - k_s x = S(x), with S(x) = min(E, max(0, B + A exp(-beta_s x))) the limit after the slip (Coulomb with the
  /// cohesion and friction softened by the slip, E the elliptic cap). Cold path: one exp per Newton step.
  static Slip return_to_surface(const Parameters& p, double sigma, double intact, double cap, double m) noexcept {
    const double k = p.shear_stiffness;
    const double beta = p.shear_softening_rate;
    const double B = p.residual_cohesion + sigma * p.tan_residual_friction;
    const double A = intact * (p.cohesion_drop + sigma * p.friction_drop);
    const double E = (sigma > 0 && p.cap_shear_factor > 0) ? std::sqrt(std::max(0.0, cap * cap - sigma * sigma) * p.inverse_cap_shear_factor)
                                                          : std::numeric_limits<double>::infinity();
    auto coulomb = [&](double x) { return B + A * std::exp(-beta * x); };
    Slip r;
    double lo = 0.0;
    if (E < m) {
      const double x = (m - E) / k;
      if (coulomb(x) >= E) {  // the cap governs at the end of the slip, and so all along it (Coulomb only falls)
        r.strength = E;
        r.slip = x;
        r.work = E * x;
        return r;
      }
      lo = x;
    }
    double hi = m / k;
    double x;
    if (coulomb(hi) <= 0) {  // the limit reaches zero: all of the trial stress slips away
      x = hi;
      r.strength = 0;
    } else {
      // g(x) = m - k x - coulomb(x): g(lo) > 0 > g(hi). Newton, bisecting whenever a step leaves the bracket.
      x = lo;
      for (int i = 0; i < 100; ++i) {
        const double e = std::exp(-beta * x);
        const double g = m - k * x - B - A * e;
        if (g > 0) lo = x;
        else hi = x;
        double next = x + g / (k - beta * A * e);
        if (!(next >= lo && next <= hi)) next = 0.5 * (lo + hi);
        if (g == 0 || std::abs(next - x) <= 1e-15 * x) break;
        x = next;
      }
      r.strength = std::clamp(coulomb(x), 0.0, E);
    }
    r.slip = x;
    r.work = limit_integral(A, B, beta, E, x);
    return r;
  }

  /// Integral over [0, x] of min(E, max(0, B + A exp(-beta xi))): B + A exp(-beta xi) is monotone, so it is at or
  /// above a level v on one interval that touches 0 (A > 0) or x (A < 0).
  static double limit_integral(double A, double B, double beta, double E, double x) noexcept {
    if (A == 0) return std::min(E, std::max(0.0, B)) * x;
    // Where the curve reaches v, clamped to [0, x].
    auto crossing = [&](double v) {
      const double q = (v - B) / A;
      if (!(q > 0)) return x;  // A > 0: above v on all of [0, x]; A < 0: nowhere, the empty [x, x]
      return std::clamp(-std::log(q) / beta, 0.0, x);
    };
    auto curve = [&](double a, double b) { return B * (b - a) + (A / beta) * (std::exp(-beta * a) - std::exp(-beta * b)); };
    const double zero = crossing(0.0);
    if (A > 0) {  // falling: E on [0, at_cap], the curve on [at_cap, zero], 0 beyond
      const double at_cap = std::isfinite(E) ? std::min(crossing(E), zero) : 0.0;
      return (at_cap > 0 ? E * at_cap : 0.0) + curve(at_cap, zero);
    }
    // rising (only without a cap, sigma <= 0): 0 on [0, zero], the curve on [zero, x]
    return curve(zero, x);
  }
};

static_assert(ContactLaw<ElastoSoftening>);
static_assert(sizeof(ElastoSoftening::History) == 64);

}  // namespace blockdem::contact
