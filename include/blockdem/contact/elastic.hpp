#pragma once
// The elastic joint law (paper Fig. 5A): normal and shear springs without strength limits.

#include <cmath>
#include <string>

#include "blockdem/contact/closure_impulse.hpp"
#include "blockdem/contact/concepts.hpp"
#include "blockdem/core/error.hpp"

namespace blockdem::contact {

struct Elastic {
  struct Parameters {
    double normal_stiffness = 0;  // Pa/m
    double shear_stiffness = 0;   // Pa/m

    Parameters() = default;
    bool operator==(const Parameters&) const = default;
    Parameters(double kn, double ks) : normal_stiffness(kn), shear_stiffness(ks) {
      if (!(kn > 0) || !std::isfinite(kn)) throw InvalidArgument("elastic joint: normal stiffness must be > 0 Pa/m, got " + std::to_string(kn));
      if (!(ks > 0) || !std::isfinite(ks)) throw InvalidArgument("elastic joint: shear stiffness must be > 0 Pa/m, got " + std::to_string(ks));
    }
  };
  struct History {
    double gap = 0;         // m, positive open
    Shear shear{0, 0};      // Pa
  };

  /// No kink (the spring is linear through tension), so no closure correction: the step is ignored.
  static constexpr Response update(const Parameters& p, History& h, double du_normal, Shear du_shear, const Step& = {}) noexcept {
    // The new values from locals, not read back from the history: read back, GCC loaded the two shear stresses as
    // one 16-byte word right after storing them apart (a failed store forward per CP-step).
    const double gap = h.gap + du_normal;
    const Shear tau{h.shear[0] - p.shear_stiffness * du_shear[0], h.shear[1] - p.shear_stiffness * du_shear[1]};
    h.gap = gap;
    h.shear = tau;
    return {-p.normal_stiffness * gap, tau, 0.0, true};  // never fails nor opens: damping always active
  }
  static constexpr double normal_stiffness(const Parameters& p) noexcept { return p.normal_stiffness; }
  static constexpr double shear_stiffness(const Parameters& p) noexcept { return p.shear_stiffness; }
  static constexpr bool damping_active(const Parameters&, const History&) noexcept { return true; }
  static constexpr double stored_energy(const Parameters& p, const History& h) noexcept {
    return 0.5 * p.normal_stiffness * h.gap * h.gap +
           0.5 * (h.shear[0] * h.shear[0] + h.shear[1] * h.shear[1]) / p.shear_stiffness;
  }
  static constexpr Traction traction(const Parameters& p, const History& h) noexcept {
    return {-p.normal_stiffness * h.gap, h.shear[0], h.shear[1]};
  }

  // Traits (ContactLaw): no bond, hence no damage and nothing to start unbonded; no dissipation.
  static void turn_shear(History& h, const ShearTurn& turn) noexcept { turn.apply(h.shear[0], h.shear[1]); }
  static constexpr double damage(const History&) noexcept { return 0.0; }
  static constexpr void start_unbonded(History&) noexcept {}
  static constexpr bool never_bonded(const History&) noexcept { return false; }
  static constexpr bool dissipates = false;
};

static_assert(ContactLaw<Elastic>);

}  // namespace blockdem::contact
