#pragma once
// The elastic joint law (paper Fig. 5A): normal and shear springs without strength limits. The joints of the model
// as built are glued (tension as well as compression); a contact point that appears during the run, where the blocks
// were not joined, carries no tension (docs/energy.md).

#include <cmath>
#include <cstdint>
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
    double gap = 0;             // m, positive open
    Shear shear{0, 0};          // Pa
    std::uint8_t failed = 0;    // contact::never_bonded: a point found during the run, not part of the glued joint
    ClosureImpulse impulse;     // the correction of the last sample, if an unbonded point's spring closed or opened
  };

  /// A bonded point (the joints of the model as built): linear springs through tension, no kink, nothing to correct.
  /// An unbonded point (start_unbonded: it appeared during the run, an impact or a new pair after sliding) is the
  /// same spring in compression and carries nothing while open: no tension, and its shear springs, which hold no
  /// friction limit while it is closed, let go when it opens (their stored energy is booked as dissipated). Its
  /// normal spring has the kink of a joint without tensile strength at gap 0, corrected like Mohr-Coulomb's
  /// (contact/closure_impulse.hpp).
  static Response update(const Parameters& p, History& h, double du_normal, Shear du_shear, const Step& step = {}) noexcept {
    // The new values from locals, not read back from the history: read back, GCC loaded the two shear stresses as
    // one 16-byte word right after storing them apart (a failed store forward per CP-step).
    const double gap_before = h.gap;
    const double gap = gap_before + du_normal;
    const Shear tau{h.shear[0] - p.shear_stiffness * du_shear[0], h.shear[1] - p.shear_stiffness * du_shear[1]};
    h.gap = gap;
    if (h.failed == 0) [[likely]] {
      h.shear = tau;
      return {-p.normal_stiffness * gap, tau, 0.0, true};  // never fails nor opens: damping always active
    }
    return update_unbonded(p, h, gap_before, du_normal, du_shear, tau, step);
  }
  static constexpr double normal_stiffness(const Parameters& p) noexcept { return p.normal_stiffness; }
  static constexpr double shear_stiffness(const Parameters& p) noexcept { return p.shear_stiffness; }
  /// Always on at a bonded point; at an unbonded one while it is closed.
  static constexpr bool damping_active(const Parameters&, const History& h) noexcept { return h.failed == 0 || h.gap <= 0; }
  static constexpr double stored_energy(const Parameters& p, const History& h) noexcept {
    const double gap = h.failed == 0 || h.gap < 0 ? h.gap : 0.0;
    return 0.5 * p.normal_stiffness * gap * gap +
           0.5 * (h.shear[0] * h.shear[0] + h.shear[1] * h.shear[1]) / p.shear_stiffness;
  }
  /// What the last update returned: the spring's stresses and this sample's closure correction.
  static Traction traction(const Parameters& p, const History& h) noexcept {
    const double gap = h.failed == 0 || h.gap < 0 ? h.gap : 0.0;
    return {-p.normal_stiffness * gap + h.impulse.stress(), h.shear[0], h.shear[1]};
  }

  // Traits (ContactLaw): the joints as built are glued and never break (damage 0); a point found during the run
  // starts unbonded and stays so (ContactView marks it never bonded).
  static void turn_shear(History& h, const ShearTurn& turn) noexcept { turn.apply(h.shear[0], h.shear[1]); }
  static constexpr double damage(const History&) noexcept { return 0.0; }
  static constexpr void start_unbonded(History& h) noexcept { h.failed = contact::never_bonded; }
  static constexpr bool never_bonded(const History& h) noexcept { return h.failed == contact::never_bonded; }
  static constexpr bool dissipates = true;  // an unbonded point's closure correction, and its shear let go as it opens

 private:
  /// update() at an unbonded point.
  [[gnu::noinline]] static Response update_unbonded(const Parameters& p, History& h, double gap_before, double du_normal,
                                                    Shear du_shear, Shear tau, const Step& step) noexcept {
    const double gap = h.gap;
    const double sigma = gap > 0.0 ? 0.0 : -p.normal_stiffness * gap;
    double dissipated = 0.0;
    if (gap > 0.0) {  // open: the shear springs let go, booked as Mohr-Coulomb books slip
      tau = {0.0, 0.0};
      dissipated = shear_dissipation(h.shear, tau, du_shear, p.shear_stiffness);
    }
    double kink_crossing = 0.0;  // J/m^2, the trapezoid error of a step across the kink at gap 0
    if ((gap_before > 0.0) != (gap > 0.0)) [[unlikely]]
      kink_crossing = kink_error(gap_before, gap, gap_before > 0.0 ? 0.0 : p.normal_stiffness, gap > 0.0 ? 0.0 : p.normal_stiffness);
    const double correction = h.impulse.step(kink_crossing, du_normal, sigma, p.normal_stiffness, step, dissipated);
    h.shear = tau;
    return {sigma + correction, tau, dissipated, !(gap > 0.0)};
  }
};

static_assert(ContactLaw<Elastic>);
static_assert(sizeof(Elastic::History) == 32);  // the flag and the closure impulse in 8 bytes

}  // namespace blockdem::contact
