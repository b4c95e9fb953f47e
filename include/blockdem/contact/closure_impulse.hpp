#pragma once
// The closure impulse: what a joint law does when its normal spring closes or opens between two samples, so that
// an impact makes no energy at any timestep (docs/energy.md).
//
// The central-difference scheme conserves 1/2 m v(n-1/2).v(n+1/2) + U(x_n) exactly for a linear spring. A normal
// spring whose stiffness changes within a step (a joint that closes: 0 -> k_n; that opens: k_n -> 0; a cracked
// joint: secant -> k_n) breaks that: the work the scheme does over the step, the trapezoid (sigma_0 + sigma_1)/2 du,
// differs from the change of stored energy by
//     e = 1/2 k_n y0 y1 (k_1 - k_0) / k_n = 1/2 y0 y1 (k_1 - k_0)       (J/m^2; + made, - lost)
// with y the gap measured from the kink, before (y0) and after (y1) the step and k_0, k_1 the stiffness on either
// side. A closing joint loses 1/2 k_n y0 |y1|, an opening one makes 1/2 k_n |y0| y1: at omega dt = 1.6 (the default
// timestep) one impact gives back between 0.64 and 1.56 times its speed, as the instant of touch falls within the
// step. Both errors are of order (omega dt)^2 and vanish with the timestep.
//
// The correction: at the sample where the kink was crossed, a one-sample stress delta on the contact point that
// removes what the crossing made (opening) or gives back what it lost (closing), then the work of both (the
// crossing's error and delta's work, the trapezoid over the two steps delta acts in) is booked as the law's
// dissipation, so that the balance closes to rounding and says what happened. The impulse delta dt changes the
// point's relative normal speed by delta dt / m*, m* the effective mass of the two bodies at the point (per unit
// area), which the point does not know; but a stable run bounds it below: k_n / m* <= omega^2 for every spring of
// the model, with omega an upper bound on omega_max (Simulation keeps FrequencyBound's for the present contacts and
// masses, Simulation::closure_inverse_omega_squared). With mu = k_n / omega^2 <= m*:
// - opening (e > 0, energy made): the impulse j against the motion that removes e if m* = mu removes at least e for
//   any m* >= mu, so an impact never gives back more than it came with (restitution <= 1), exactly 1 where the
//   point alone sets omega (one contact point, or a face landing flat on its own points);
// - closing (e < 0, energy lost): the impulse j along the motion with j |v| = |e| gives back at most |e| for any
//   m* (the spring's own impulse at that sample opposes the motion and is at least twice j: j is capped at half of
//   it), exactly |e| as m* -> infinity.
// What is left is a loss, booked as dissipation, of order (omega dt)^2: an undamped block dropped on a joint at the
// default timestep bounces back with a restitution between 0.77 and 1 (one contact point), converging to 1 with dt.
// A step in which no time passes (dt = 0: forces of the present state after a re-detection) applies the stored
// delta again and books nothing.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace blockdem::contact {

/// What a law needs to know of the step to correct a kink crossing: the step's increment dt (s; 0 when no time
/// passes, as in a displacement-controlled joint test, where no correction is made) and 1 / omega^2 (s^2), omega an
/// upper bound on the model's highest eigenfrequency (rad/s).
struct Step {
  double dt = 0;
  double inverse_omega_squared = 0;
};

/// The correction stress (Pa, compression positive, applied for this sample only) for a crossing whose trapezoid
/// error is `error` (J/m^2, + made), at a point whose normal spring has stiffness `kn` (Pa/m) and stress `sigma`
/// after the step (Pa, compression positive), whose gap changed by `du` (m) over the step `step`.
inline double closure_correction(double error, double du, double sigma, double kn, const Step& step) noexcept {
  const double mu = kn * step.inverse_omega_squared;  // kg/m^2, a lower bound on the effective mass per area
  if (error == 0.0 || du == 0.0 || !(step.dt > 0.0) || !(mu > 0.0)) return 0.0;
  const double speed = std::abs(du) / step.dt;
  const double along = du > 0.0 ? 1.0 : -1.0;               // the direction of the motion (+: opening)
  const double spring_impulse = sigma * step.dt * along;     // Pa s, the spring's own impulse along the motion
  if (error > 0.0) {
    // j (a - j / (2 mu)) = error with a the speed the spring's impulse leaves at m* = mu (less where it opposes the
    // motion): removes at least `error` for any m* >= mu. No root (the step far above omega's bound): stop the
    // relative motion at m* = mu, the most that can be removed.
    const double a = speed + std::min(spring_impulse, 0.0) / mu;
    if (!(a > 0.0)) return 0.0;
    const double j = mu * (a - std::sqrt(std::max(a * a - 2.0 * error / mu, 0.0)));
    return -along * j / step.dt;
  }
  // Closing: gives back at most -error for any m* when the spring's own impulse opposes the motion and is at least
  // twice j (capped at half of it, so that the correction stays a correction); otherwise (a rarer kink, the stiffer
// side opening) solve with mu as above.
  const double lost = -error;
  double j;
  if (spring_impulse <= 0.0) {
    j = std::min(lost / speed, -0.5 * spring_impulse);  // at least half the spring's push is kept
  } else {
    const double a = speed + spring_impulse / mu;
    j = mu * (std::sqrt(a * a + 2.0 * lost / mu) - a);
  }
  return along * j / step.dt;
}

/// The correction a law keeps in its history (6 bytes, in what was padding: no memory traffic) and the booking of
/// its work. The correction is closed-loop: the stress applied at a sample does its work over the two steps around
/// it, and what it removed or gave back is known only after the second. Other forces on the two bodies within those
/// steps (gravity, other contacts) change that work by a fraction of order g dt / v at a relative speed v: in the
/// samples after the crossing, an excess left (energy still made, measured) gets a further correction aimed at
/// twice it, so that other forces up to half the speed's change per step cannot leave one; the follow-ups stop at
/// the first shortfall, which is a loss and stays booked. Laws call `step` once per update(), with the error of any
/// step in which their normal spring's path bent (a kink crossed, a bond broken, a joint cracked or crushed): the
/// trapezoid of the stresses at both samples, less the change of stored energy and what the law booked.
struct ClosureImpulse {
  std::uint16_t stress_bits = 0;        // Pa, bfloat16: the correction applied at the last sample (0: none)
  std::uint16_t remaining_bits[2] = {};  // J/m^2, float: what the corrections have yet to remove (+) or give back (-)

  /// This sample's correction stress (Pa, to add to the spring's): the last one again when no time passes
  /// (dt = 0); else the second half of the last correction's work booked, the crossing's `error` (J/m^2, + made;
  /// 0 if no kink was crossed in this step) booked, and a new correction for what is left, at a crossing and after
  /// it while an excess is left. `dissipated` (J/m^2) gets the bookings; `du`, `sigma`, `kn`: as closure_correction.
  /// Inline where nothing is to be done (the common case, one test); the rest out of line, so that the fused
  /// contact loop keeps its law inline.
  [[gnu::always_inline]] double step(double error, double du, double sigma, double kn, const Step& s,
                                     double& dissipated) noexcept {
    if (stress_bits == 0 && error == 0.0) [[likely]]
      return 0.0;
    return correct(error, du, sigma, kn, s, dissipated);
  }

  /// step() past its test.
  [[gnu::noinline]] double correct(double error, double du, double sigma, double kn, const Step& s,
                                   double& dissipated) noexcept {
    const double last = stress();
    if (!(s.dt > 0.0)) return last;
    // The last correction's work over this step, the second half of its trapezoid (it removed -delta du / 2).
    dissipated -= 0.5 * last * du;
    double remaining = remaining_energy() + 0.5 * last * du;
    double target = 0.0;  // the energy the new correction is aimed at (J/m^2, + to remove)
    if (error != 0.0) {   // a crossing: its error, and what is left of the last one's
      dissipated -= error;
      remaining += error;
      target = remaining;
    } else if (remaining > 0.0) {
      target = 2.0 * remaining;
    }
    // The correction in bfloat16 (3 digits: what it misses, the next sample measures), booked as applied.
    const double delta = target != 0.0 ? round_to_bfloat16(closure_correction(target, du, sigma, kn, s)) : 0.0;
    dissipated -= 0.5 * delta * du;  // the first half of its work, in this step
    remaining += 0.5 * delta * du;
    stress_bits = to_bfloat16(delta);
    // Kept while a correction is doing its work (the next sample adds its second half and removes an excess left),
    // and an excess that no correction could remove here (the motion reversing under the spring's push) until the
    // next crossing, whose correction takes it with its own error.
    set_remaining(delta != 0.0 || remaining > 0.0 ? remaining : 0.0);
    return delta;
  }

  double stress() const noexcept { return from_bfloat16(stress_bits); }
  double remaining_energy() const noexcept {
    float f;
    std::memcpy(&f, remaining_bits, sizeof f);
    return static_cast<double>(f);
  }

 private:
  void set_remaining(double r) noexcept {
    const auto f = static_cast<float>(r);
    std::memcpy(remaining_bits, &f, sizeof f);
  }
  static std::uint16_t to_bfloat16(double x) noexcept {
    const auto f = static_cast<float>(x);
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    bits += 0x7fffu + ((bits >> 16) & 1u);  // round to nearest even (x finite)
    return static_cast<std::uint16_t>(bits >> 16);
  }
  static double from_bfloat16(std::uint16_t b) noexcept {
    const std::uint32_t bits = static_cast<std::uint32_t>(b) << 16;
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return static_cast<double>(f);
  }
  static double round_to_bfloat16(double x) noexcept { return from_bfloat16(to_bfloat16(x)); }
};
static_assert(sizeof(ClosureImpulse) == 6 && alignof(ClosureImpulse) == 2);

/// The trapezoid error of a step across a kink of a piecewise-linear spring (J/m^2, + made): y0, y1 the gap before
/// and after, measured from the kink; k0, k1 the stiffness (Pa/m) on their sides.
constexpr double kink_error(double y0, double y1, double k0, double k1) noexcept { return 0.5 * y0 * y1 * (k1 - k0); }

/// The same for any step whose path bent (a kink crossed, a bond broken, a joint cracked or crushed): the scheme's
/// work on the normal spring, the trapezoid of its stresses sigma0, sigma1 (Pa, compression positive) over the gap's
/// change du (m), against the change of its stored energy u1 - u0 and what the law booked as dissipated (J/m^2).
/// Across a kink of a piecewise-linear spring it is kink_error.
constexpr double path_error(double sigma0, double sigma1, double du, double u0, double u1, double booked) noexcept {
  return 0.5 * (sigma0 + sigma1) * du + u1 - u0 + booked;
}

}  // namespace blockdem::contact
