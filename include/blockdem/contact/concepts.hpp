#pragma once
// The ContactLaw concept: the pointwise joint law of one contact point, in incremental form as 3DEC uses it.

#include <array>
#include <concepts>
#include <cstddef>
#include <type_traits>

#include "blockdem/contact/closure_impulse.hpp"
#include "blockdem/core/types.hpp"

namespace blockdem::contact {

/// Shear components along the contact point's tangent directions t1, t2.
using Shear = std::array<double, 2>;

/// The traction on B at a contact point in its frame, Pa: normal (compression positive), t1, t2.
using Traction = std::array<double, 3>;

/// What a joint's shear springs dissipate over a step in which their stresses went from `before` to `after` (Pa)
/// under the shear increment `du` (m; the stresses are the traction on B, so the work done on the springs is
/// -(before + after)/2 . du, the trapezoid, the scheme's own measure of work) less what they store more (J/m^2). Exact
/// for any path that ends where the return put it, slip or release.
constexpr double shear_dissipation(const Shear& before, const Shear& after, const Shear& du, double shear_stiffness) noexcept {
  const double work = -0.5 * ((before[0] + after[0]) * du[0] + (before[1] + after[1]) * du[1]);
  const double stored_change =
      0.5 * (after[0] * after[0] + after[1] * after[1] - before[0] * before[0] - before[1] * before[1]) / shear_stiffness;
  return work - stored_change;
}

/// What a law returns for one step of one contact point. Sign conventions: the normal n points from block A to
/// block B; the gap is positive when the joint is open; `normal_stress` is positive in compression; `shear_stress`
/// is the traction A exerts on B along t1, t2. The traction on B is normal_stress n + shear_stress_1 t1 + ..., on A
/// its opposite.
struct Response {
  double normal_stress = 0;       // Pa, compression positive
  Shear shear_stress{0, 0};       // Pa
  double dissipated = 0;          // J/m^2 dissipated by slip (and softening) during this step
  // damping_active(params, history) after the step, from the step's own values. No default: a law that leaves it
  // out of its return is named by -Wextra (missing-field-initializers) instead of keeping dashpots on silently.
  bool damping_active;
};

/// The value of a law's `History::failed` for a contact point that appeared during the run (an impact after
/// separation, a new overlap after sliding): it never was part of a bonded joint, so it starts failed (no tension,
/// residual cohesion), and laws keep the value, so that output and damage counts can tell such a contact from a
/// joint that broke (contact points found at the first detection are bonded, failed = 0; a broken one has 1).
inline constexpr unsigned char never_bonded = 2;

/// The turn of a contact point's tangent directions from an old contact frame (old_t1, old_t2) to a new one (t1, t2)
/// in the same plane (world frame), when a redetection gives the contact another frame: the in-plane vector
/// s1 old_t1 + s2 old_t2 gets the components along the new tangents, its dot products with t1 and t2 (through the
/// vector, so that a turn is computed as the frames give it, to the last bit). A pure turn (both frames orthonormal)
/// keeps the vector's length. The default is no turn.
struct ShearTurn {
  Vec3 old_t1 = Vec3::UnitX(), old_t2 = Vec3::UnitY();
  Vec3 t1 = Vec3::UnitX(), t2 = Vec3::UnitY();

  /// Re-expresses the pair (s1, s2), components along old_t1, old_t2, along t1, t2.
  void apply(double& s1, double& s2) const noexcept {
    const Vec3 shear = s1 * old_t1 + s2 * old_t2;
    s1 = shear.dot(t1);
    s2 = shear.dot(t2);
  }
  /// The same for N pairs (s1[i], s2[i]) at once, e.g. one per Maxwell branch.
  template <std::size_t N>
  void apply(std::array<double, N>& s1, std::array<double, N>& s2) const noexcept {
    for (std::size_t i = 0; i < N; ++i) apply(s1[i], s2[i]);
  }
};

/// A joint law: `Parameters` (validated on construction: throws InvalidArgument naming the field and range),
/// `History` (per contact point; `gap` in m, positive open), and static functions
/// - `update(params, history, du_normal, du_shear, step = {}) -> Response`: du_normal is the increment of the gap
///   (m), du_shear the increment of B's displacement relative to A along t1, t2 (m); updates the history. Its
///   `damping_active` is damping_active(params, history) after the step: the contact pass reads it there, where the
///   step has the flags and the gap in registers, instead of loading them back from the history per CP. A law whose
///   normal spring has a kink (a joint that opens) corrects the sample where the kink was crossed with the closure
///   impulse of `step` (contact/closure_impulse.hpp) and books its work in `dissipated`; `traction()` includes that
///   one-sample correction (what update returned), `stored_energy()` is the spring's;
/// - `normal_stiffness(params)`, `shear_stiffness(params)`: the elastic stiffnesses, Pa/m, for the timestep;
/// - `damping_active(params, history)`: false once the joint has failed or while it is open, so that a dashpot
///   never acts across an open joint (the damping policy releases its stresses);
/// - `stored_energy(params, history)`: elastic energy per area in the joint springs, J/m^2;
/// - `traction(params, history) -> Traction`: the stresses the history holds, those the last update returned (to
///   rounding). The contact pass stores no traction per CP: output asks the history (ContactGroup::traction_at);
/// and its traits, which the engine uses instead of reading the history's members:
/// - `turn_shear(history, turn)`: re-expresses the history's shear stresses (Pa), and any other vector state it keeps
///   in the contact plane, along the tangents of a new contact frame (ShearTurn), when a redetection carries the
///   history over to a contact whose frame turned;
/// - `damage(history) -> double`: the damage for output, in [0, 1] (0 intact, 1 failed); for a contact point that was
///   never bonded (below) output marks that instead;
/// - `start_unbonded(history)`: the state of a contact point that appears during the run where there was no contact
///   (an impact after separation, a new pair after sliding): it never was part of a bonded joint, so it starts from
///   the law's failed state (no tension, residual cohesion), and a joint that broke and separated does not heal when
///   it closes again; a law whose joints never break (the elastic law) carries no tension there;
/// - `never_bonded(history) -> bool`: the point started so (start_unbonded) and the law kept it: output and damage
///   counts tell it from a joint that broke;
/// - `dissipates`, a constant: whether update() can return a non-zero `dissipated`; the contact pass books no slip
///   dissipation for a law that never dissipates (no memory traffic).
/// Every function is static and noexcept (update runs in the hot loop, the others in redetection and output).
template <class L>
concept ContactLaw = requires(const typename L::Parameters& p, typename L::History& h, const typename L::History& held,
                              double du, Shear ds, const ShearTurn& turn, const Step& step) {
  { L::update(p, h, du, ds, step) } noexcept -> std::same_as<Response>;
  { L::update(p, h, du, ds) } noexcept -> std::same_as<Response>;
  { L::normal_stiffness(p) } noexcept -> std::convertible_to<double>;
  { L::shear_stiffness(p) } noexcept -> std::convertible_to<double>;
  { L::damping_active(p, h) } noexcept -> std::convertible_to<bool>;
  { L::stored_energy(p, h) } noexcept -> std::convertible_to<double>;
  { L::traction(p, h) } noexcept -> std::same_as<Traction>;
  { h.gap } -> std::convertible_to<double>;
  { L::turn_shear(h, turn) } noexcept -> std::same_as<void>;
  { L::damage(held) } noexcept -> std::same_as<double>;
  { L::start_unbonded(h) } noexcept -> std::same_as<void>;
  { L::never_bonded(held) } noexcept -> std::same_as<bool>;
  requires std::same_as<decltype(L::dissipates), const bool>;
  typename std::bool_constant<L::dissipates>;  // a constant expression
};

}  // namespace blockdem::contact
