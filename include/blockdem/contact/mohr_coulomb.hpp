#pragma once
// The Mohr-Coulomb joint law (paper Fig. 5B): tension cut-off f_t, shear strength c + sigma tan(phi); at the first
// failure in tension or shear, tension and cohesion drop to residual values (default 0) and friction to its
// residual angle. Without tensile strength the joint carries no tension once open.

#include <cmath>
#include <cstdint>
#include <string>

#include "blockdem/contact/closure_impulse.hpp"
#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/error.hpp"

namespace blockdem::contact {

struct MohrCoulomb {
  struct Parameters {
    double normal_stiffness = 0;   // Pa/m
    double shear_stiffness = 0;    // Pa/m
    double tensile_strength = 0;   // Pa
    double cohesion = 0;           // Pa
    double friction_angle = 0;     // rad
    double residual_tensile_strength = 0;  // Pa
    double residual_cohesion = 0;          // Pa
    double residual_friction_angle = 0;    // rad
    // Derived once here, not in the loop.
    double tan_friction = 0;
    double tan_residual_friction = 0;

    Parameters() = default;
    bool operator==(const Parameters&) const = default;
    /// Angles in radians. Residual friction defaults to the peak friction angle.
    Parameters(double kn, double ks, double ft, double c, double phi, double ft_res = 0, double c_res = 0,
               double phi_res = -1)
        : normal_stiffness(kn), shear_stiffness(ks), tensile_strength(ft), cohesion(c), friction_angle(phi),
          residual_tensile_strength(ft_res), residual_cohesion(c_res), residual_friction_angle(phi_res < 0 ? phi : phi_res) {
      auto check = [](bool ok, const std::string& what) {
        if (!ok) throw InvalidArgument("mohr-coulomb joint: " + what);
      };
      check(kn > 0 && std::isfinite(kn), "normal stiffness must be > 0 Pa/m, got " + std::to_string(kn));
      check(ks > 0 && std::isfinite(ks), "shear stiffness must be > 0 Pa/m, got " + std::to_string(ks));
      check(ft >= 0, "tensile strength must be >= 0 Pa, got " + std::to_string(ft));
      check(c >= 0, "cohesion must be >= 0 Pa, got " + std::to_string(c));
      check(phi >= 0 && phi < 1.5707963267948966, "friction angle must be in [0, 90) degrees");
      check(ft_res >= 0 && ft_res <= ft, "residual tensile strength must be in [0, tensile strength]");
      check(c_res >= 0 && c_res <= c, "residual cohesion must be in [0, cohesion]");
      check(residual_friction_angle >= 0 && residual_friction_angle < 1.5707963267948966,
            "residual friction angle must be in [0, 90) degrees");
      tan_friction = std::tan(friction_angle);
      tan_residual_friction = std::tan(residual_friction_angle);
    }
  };
  struct History {
    double gap = 0;        // m, positive open
    Shear shear{0, 0};     // Pa
    double normal = 0;     // Pa, compression positive
    std::uint8_t failed = 0;    // the bond broke: residual strengths from now on
    std::uint8_t slipping = 0;  // at the Coulomb limit in the last step
    ClosureImpulse impulse;     // the correction of the last sample, if its normal spring closed or opened
  };

  static Response update(const Parameters& p, History& h, double du_normal, Shear du_shear, const Step& step = {}) noexcept {
    const double normal_before = h.normal;
    const double gap_before = h.gap;
    h.gap += du_normal;
    const bool failed_before = h.failed != 0;
    bool failed = failed_before;
    const double tension = failed ? p.residual_tensile_strength : p.tensile_strength;
    const double elastic = -p.normal_stiffness * h.gap;
    double sigma = elastic;
    if (sigma < -tension) {  // tension cut-off
      if (!failed && p.tensile_strength > 0) failed = true;
      sigma = -(failed ? p.residual_tensile_strength : tension);
    }
    h.normal = sigma;
    // Where the tensile strength drops to the residual one (the bond breaks in tension now, or broke in shear at the
    // last step while the joint carried more tension than the residual strength): the energy the normal spring loses
    // at its present gap (normal_energy), released by no force. Once per failure, never negative.
    double dissipated = 0.0;
    bool bent = false;  // the spring's path bent within the step: the bond broke, or the kink was crossed
    if (failed && (!failed_before || normal_before < -p.residual_tensile_strength)) [[unlikely]] {
      dissipated = normal_energy(p, elastic > -p.tensile_strength ? elastic : -p.tensile_strength, h.gap) -
                    normal_energy(p, sigma, h.gap);
      bent = true;
    } else if ((gap_before * p.normal_stiffness > tension) != (h.gap * p.normal_stiffness > tension)) [[unlikely]] {
      // The normal spring crossed its kink at the cut-off (gap T / k_n; 0 without tension): closed or opened
      // between the samples (contact/closure_impulse.hpp).
      bent = true;
    }
    // Where it bent, the trapezoid of the stresses at both samples (the scheme's work) differs from the change of
    // stored energy and what was booked: the step's error (J/m^2, + made), which the closure impulse removes where
    // it is energy made, and books. Across the kink it is 1/2 y0 y1 (k1 - k0), y the gap from the kink; where the
    // bond breaks, the drop at the failure gap against the trapezoid across the step.
    const double kink_crossing =
        bent ? path_error(normal_before, sigma, du_normal, normal_energy(p, normal_before, gap_before), normal_energy(p, sigma, h.gap), dissipated)
             : 0.0;
    const double correction = h.impulse.step(kink_crossing, du_normal, sigma, p.normal_stiffness, step, dissipated);
    Shear tau{h.shear[0] - p.shear_stiffness * du_shear[0], h.shear[1] - p.shear_stiffness * du_shear[1]};
    // Comparisons, not std::fmax: GCC calls libm for fmax (its NaN rules), one call per CP-step in the hot loop.
    const double compression = sigma > 0.0 ? sigma : 0.0;
    const double strength = (failed ? p.residual_cohesion : p.cohesion) + compression * (failed ? p.tan_residual_friction : p.tan_friction);
    const double limit = strength > 0.0 ? strength : 0.0;
    const double magnitude2 = tau[0] * tau[0] + tau[1] * tau[1];
    const bool slipping = magnitude2 > limit * limit;  // no square root unless it slips
    if (slipping) {  // slip: return to the Coulomb limit along the trial direction
      const double magnitude = std::sqrt(magnitude2);
      const double scale = limit / magnitude;
      tau = {tau[0] * scale, tau[1] * scale};
      // The scheme's work on the shear springs less what they store more (shear_dissipation). Limit times the
      // plastic slip is that only at a constant limit: as the normal stress changed, a block that bounced while
      // sliding was credited with slip it never dissipated.
      dissipated += shear_dissipation(h.shear, tau, du_shear, p.shear_stiffness);
      if (p.cohesion > 0 || p.tensile_strength > 0) failed = true;
    }
    h.shear = tau;
    // Both flags stored together, at the end: damping_active, right after the step, reads them as one word, which
    // a lone byte store just before would stall (store forwarding).
    h.failed = failed ? (h.failed == contact::never_bonded ? contact::never_bonded : 1) : 0;
    h.slipping = slipping ? 1 : 0;
    // damping_active as the last field; the normal stress with the closure correction of this sample (h.normal, the
    // spring's, without it).
    return {sigma + correction, tau, dissipated, !failed && !slipping && (h.gap <= 0 || p.tensile_strength > 0)};
  }
  static constexpr double normal_stiffness(const Parameters& p) noexcept { return p.normal_stiffness; }
  static constexpr double shear_stiffness(const Parameters& p) noexcept { return p.shear_stiffness; }
  /// Off once the bond has failed, while the joint slips, and while it is open (a gap without tensile strength).
  static constexpr bool damping_active(const Parameters& p, const History& h) noexcept {
    return h.failed == 0 && h.slipping == 0 && (h.gap <= 0 || p.tensile_strength > 0);
  }
  static constexpr double stored_energy(const Parameters& p, const History& h) noexcept {
    return normal_energy(p, h.normal, h.gap) + 0.5 * (h.shear[0] * h.shear[0] + h.shear[1] * h.shear[1]) / p.shear_stiffness;
  }
  /// The normal spring's energy (J/m^2) at stress sigma and gap: 1/2 sigma^2 / k_n while elastic (sigma = -k_n gap);
  /// at the cut-off, opened past it at sigma = -T, that plus T times the opening beyond T / k_n, which closing gives
  /// back (the stress follows the total gap): -sigma gap - 1/2 sigma^2 / k_n in both cases.
  static constexpr double normal_energy(const Parameters& p, double sigma, double gap) noexcept {
    return -sigma * gap - 0.5 * sigma * sigma / p.normal_stiffness;
  }
  /// What the last update returned: the spring's stresses and this sample's closure correction.
  static Traction traction(const Parameters&, const History& h) noexcept {
    return {h.normal + h.impulse.stress(), h.shear[0], h.shear[1]};
  }

  // Traits (ContactLaw). Damage is all or nothing: 1 once the bond broke (or never was, contact::never_bonded).
  static void turn_shear(History& h, const ShearTurn& turn) noexcept { turn.apply(h.shear[0], h.shear[1]); }
  static constexpr double damage(const History& h) noexcept { return h.failed ? 1.0 : 0.0; }
  static constexpr void start_unbonded(History& h) noexcept { h.failed = contact::never_bonded; }
  static constexpr bool never_bonded(const History& h) noexcept { return h.failed == contact::never_bonded; }
  static constexpr bool dissipates = true;  // slip
};

static_assert(ContactLaw<MohrCoulomb>);
static_assert(sizeof(MohrCoulomb::History) == 40);  // the closure impulse in what was padding

}  // namespace blockdem::contact
