#pragma once
// The ContactLaw concept: the pointwise joint law of one contact point, in incremental form as 3DEC uses it.

#include <array>
#include <concepts>

namespace blockdem::contact {

/// Shear components along the contact point's tangent directions t1, t2.
using Shear = std::array<double, 2>;

/// The traction on B at a contact point in its frame, Pa: normal (compression positive), t1, t2.
using Traction = std::array<double, 3>;

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

/// A joint law: `Parameters` (validated on construction: throws InvalidArgument naming the field and range),
/// `History` (per contact point; `gap` in m, positive open), and static functions
/// - `update(params, history, du_normal, du_shear) -> Response`: du_normal is the increment of the gap (m),
///   du_shear the increment of B's displacement relative to A along t1, t2 (m); updates the history. Its
///   `damping_active` is damping_active(params, history) after the step: the contact pass reads it there, where the
///   step has the flags and the gap in registers, instead of loading them back from the history per CP;
/// - `normal_stiffness(params)`, `shear_stiffness(params)`: the elastic stiffnesses, Pa/m, for the timestep;
/// - `damping_active(params, history)`: false once the joint has failed or while it is open, so that a dashpot
///   never acts across an open joint (the damping policy releases its stresses);
/// - `stored_energy(params, history)`: elastic energy per area in the joint springs, J/m^2;
/// - `traction(params, history) -> Traction`: the stresses the history holds, those the last update returned (to
///   rounding). The contact pass stores no traction per CP: output asks the history (ContactGroup::traction_at).
template <class L>
concept ContactLaw = requires(const typename L::Parameters& p, typename L::History& h, double du, Shear ds) {
  { L::update(p, h, du, ds) } noexcept -> std::same_as<Response>;
  { L::normal_stiffness(p) } noexcept -> std::convertible_to<double>;
  { L::shear_stiffness(p) } noexcept -> std::convertible_to<double>;
  { L::damping_active(p, h) } noexcept -> std::convertible_to<bool>;
  { L::stored_energy(p, h) } noexcept -> std::convertible_to<double>;
  { L::traction(p, h) } noexcept -> std::same_as<Traction>;
  { h.gap } -> std::convertible_to<double>;
};

}  // namespace blockdem::contact
