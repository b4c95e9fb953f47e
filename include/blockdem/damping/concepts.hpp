#pragma once
// The damping concepts: DampingPolicy, what the fused explicit loop asks of every viscous damping scheme, and the
// capabilities beyond it that the engine uses where a policy has them (per-spring states, Maxwell's contact field and
// element tiles, ...), each with every member the engine uses for it.

#include <array>
#include <concepts>
#include <cstddef>
#include <tuple>
#include <type_traits>

#include "blockdem/core/lanes.hpp"

namespace blockdem::damping {

/// A mass or a principal moment of inertia with its inverse, both computed once per block: the velocity update
/// multiplies by the inverse (no division in the block loop), the dissipated energy uses the value.
struct Inertia {
  double value = 1;    // kg or kg m^2
  double inverse = 1;  // 1 / value
  static constexpr Inertia of(double value) noexcept { return {value, 1.0 / value}; }
};

/// Per-spring state of the policies that keep none.
struct NoState {};

/// Damping of each degree of freedom in the block and node passes: `velocity_update(v, force, inertia, dt,
/// dissipated) -> double`, the central-difference update of one degree of freedom, velocity v (m/s or rad/s) at the
/// half step, force (N or N m), inertia the mass (kg) or principal moment of inertia (kg m^2) with its inverse; adds
/// the energy its damping force dissipated (J) to `dissipated`. Every policy has it; those that damp only the
/// springs return the undamped update (undamped_velocity_update). Physically: a force on the body's motion, mass
/// proportional (MassProportional, Rayleigh's alpha) or Cundall's local damping (Local).
template <class D>
concept PerDofDamping = requires(const D& d, double x, double& e, Inertia m) {
  { d.velocity_update(x, x, m, x, e) } noexcept -> std::same_as<double>;
};

/// A damping policy: a small copyable value (the engine keeps one and copies it into its loops; a checkpoint saves
/// it as its bytes, so it holds no pointers) with PerDofDamping's velocity_update, and
/// - `ContactState`: per contact point and spring direction (normal, shear 1, shear 2) state, e.g. the stresses of
///   the Maxwell branches; NoState if the policy does not act on springs;
/// - `spring_stress(state, stiffness, du, dt, active, dissipated) -> double`: the viscous stress (Pa) the policy adds
///   to a spring of stiffness (Pa/m) whose elongation grew by du (m) during the step dt (s); with active == false
///   (joint failed or open) it releases its state and returns 0; adds the work its elements received (J/m^2) to
///   `dissipated` (policies with springs of their own also provide `stored_energy(state, stiffness)`, which the
///   energy report subtracts from that work: SpringEnergyDamping); a policy without springs returns 0;
/// - `held_stress(state) -> double`: the viscous stress (Pa) the state holds, the one spring_stress returned last
///   while the joint is active (the contact pass stores no traction per CP; output asks the state);
/// - `timestep_factor(omega_max) -> double`: the reduction of the critical timestep 2 / omega_max (eq. 11, eq. 20).
/// What a policy has beyond this the capability concepts below name; the engine asks for each with `if constexpr`.
template <class D>
concept DampingPolicy =
    PerDofDamping<D> && std::copyable<D> && std::semiregular<typename D::ContactState> &&
    requires(const D& d, typename D::ContactState& s, double x, bool active, double& e) {
      { d.spring_stress(s, x, x, x, active, e) } noexcept -> std::same_as<double>;
      { D::held_stress(s) } noexcept -> std::same_as<double>;
      { d.timestep_factor(x) } noexcept -> std::convertible_to<double>;
    };

/// Dashpots (or spring-dashpot branches) in parallel with every joint spring, with a state per contact point and
/// spring: the ContactState is not NoState, and spring_stress / held_stress act on it. The contact passes (rigid and
/// node contacts) update the three springs of a CP (normal k_n, shear k_s twice); the element pass of deformable
/// blocks applies the same spring_stress to seven strain components of each tetrahedron (ElementStateDamping) unless
/// the policy has an element tile form. StiffnessProportional, Rayleigh, Maxwell<N>; not None, Local,
/// MassProportional.
template <class D>
concept PerSpringDamping =
    DampingPolicy<D> && !std::same_as<typename D::ContactState, NoState> &&
    requires(const D& d, typename D::ContactState& s, const typename D::ContactState& held, double x, bool active, double& e) {
      { d.spring_stress(s, x, x, x, active, e) } noexcept -> std::same_as<double>;
      { D::held_stress(held) } noexcept -> std::same_as<double>;
    };

/// The three springs of a CP at once: `spring_stresses(states, kn, ks, du, dt, active, dissipated) -> {normal,
/// shear 1, shear 2}` (Pa) for the CP's three states, stiffnesses k_n, k_s, k_s (Pa/m) and elongation increments du
/// (m), equal to three spring_stress calls but one loop the compiler vectorises. The rigid contact pass uses it when
/// a policy has it, and always for a contact whose Maxwell field was released (ContactFieldDamping). Maxwell<N>.
template <class D>
concept SpringTripleDamping =
    PerSpringDamping<D> &&
    requires(const D& d, std::array<typename D::ContactState, 3>& s, double x, const std::array<double, 3>& du, bool active,
             double& e) {
      { d.spring_stresses(s, x, x, du, x, active, e) } noexcept -> std::same_as<std::array<double, 3>>;
    };

/// Springs of its own that store energy: `stored_energy(state, stiffness) -> double`, the elastic energy (J/m^2 for
/// a joint spring of stiffness Pa/m, J/m^3 for a strain component of stiffness Pa) in the branch springs of a state.
/// spring_stress counted the work on them as dissipated; the energy report moves what they still store from viscous
/// to elastic. Maxwell<N> (sum s_i^2 / (2 alpha_i k)); a dashpot alone (StiffnessProportional) stores nothing.
template <class D>
concept SpringEnergyDamping = PerSpringDamping<D> && requires(const D& d, const typename D::ContactState& s, double k) {
  { d.stored_energy(s, k) } noexcept -> std::convertible_to<double>;
};

/// Constants that depend on the timestep: `prepare(dt)`, called whenever the timestep is set, before any
/// spring_stress / element_stress_tile / advance_field with that timestep. Maxwell<N> (the decays e^(-dt/tau_i) and
/// gains of its branches).
template <class D>
concept PreparedDamping = DampingPolicy<D> && requires(D& d, double dt) {
  { d.prepare(dt) } noexcept;
};

namespace detail {
/// The branch forces F_1 .. F_N of a contact field (ContactFieldDamping), one generalised force per branch.
template <class D>
using BranchForces = std::array<typename D::Generalised, std::tuple_size_v<typename D::ContactField>>;
}  // namespace detail

/// The branches of a whole contact between rigid blocks in one state per contact (a contact field) instead of one
/// per CP: while every CP of a contact is active, the branch stresses at its CPs follow from N generalised forces on
/// the contact (force along n, t1, t2 and moment about the origin, in the contact frame; damping::Maxwell explains
/// the algebra). Maxwell<N>, with `contact_field` true (false keeps per-CP states from the start). Members, as the
/// contact group and the contact pass use them:
/// - types: `Generalised` and `FieldStiffness`, std::array<double, 6> (the six components); `ContactField`, a
///   std::array of N Generalised, the field of one contact (branch forces, N and N m; the last slot their sum);
///   `FieldLanes`, the record of four contacts' fields, one per lane: `forces[branch][component]`,
///   `stiffness[stiffness_slot(component)]` (diag G) and `work` (twice the viscous work, J), each Lanes;
/// - `contact_field` (bool member): whether contacts start in the field form;
/// - `advance_field(record, du)` and `advance_field(record, du, keep, sum)`: one step of four fields under the
///   contacts' generalised displacement increments du[6] (m, rad), all lanes or the lanes of `keep` (their force at
///   the end of the step in `sum`, N and N m, zero elsewhere); `field_force(record, keep, sum)`: that force without a
///   step; `field_sum(record, j)`: component j of the four fields' force;
/// - `branch_forces(field)`: the N branch forces; `field_of(forces)`: the field of N branch forces;
/// - `field_stress(h, kn, ks, x1, x2)`: the stresses (Pa) at a CP at plane coordinates (x1, x2) (m) of a generalised
///   elongation h; `field_branch_stresses(elongations, kn, ks, x1, x2)`: the CP's spring states of N branch
///   elongations (where a field releases into per-CP states, which then take spring_stresses: SpringTripleDamping);
/// - `contact_stiffness(area, i1, i2, kn, ks)`: diag G of a contact from its CPs' area and second moments of area
///   about the principal axes (m^2, m^4); `stiffness_slot(j)`: the slot of FieldLanes::stiffness of component j.
template <class D>
concept ContactFieldDamping =
    SpringTripleDamping<D> &&
    requires {
      typename D::ContactField;
      typename D::FieldLanes;
      requires std::same_as<typename D::Generalised, std::array<double, 6>>;
      requires std::same_as<typename D::FieldStiffness, std::array<double, 6>>;
      requires std::same_as<typename D::ContactField, detail::BranchForces<D>>;
      requires std::semiregular<typename D::FieldLanes>;
    } &&
    requires(const D& d, typename D::FieldLanes& record, const typename D::FieldLanes& held, const Lanes (&du)[6],
             const LaneMask& keep, Lanes (&sum)[6], std::size_t j, const typename D::ContactField& field,
             const typename D::Generalised& h, const detail::BranchForces<D>& forces, double x) {
      { d.contact_field } -> std::convertible_to<bool>;
      { d.advance_field(record, du) } noexcept -> std::same_as<void>;
      { d.advance_field(record, du, keep, sum) } noexcept -> std::same_as<void>;
      { D::field_force(held, keep, sum) } noexcept -> std::same_as<void>;
      { D::field_sum(held, j) } noexcept -> std::same_as<Lanes>;
      { D::branch_forces(field) } noexcept -> std::same_as<detail::BranchForces<D>>;
      { D::field_of(forces) } noexcept -> std::same_as<typename D::ContactField>;
      { D::field_stress(h, x, x, x, x) } noexcept -> std::same_as<std::array<double, 3>>;
      { D::field_branch_stresses(forces, x, x, x, x) } noexcept -> std::same_as<std::array<typename D::ContactState, 3>>;
      { D::contact_stiffness(x, x, x, x, x) } noexcept -> std::same_as<typename D::FieldStiffness>;
      { D::stiffness_slot(j) } noexcept -> std::convertible_to<std::size_t>;
      { record.forces[j][j] } -> std::same_as<Lanes&>;
      { record.stiffness[j] } -> std::same_as<Lanes&>;
      { record.work } -> std::same_as<Lanes&>;
    };

/// The width of the element tiles of deformable blocks (DeformableState::element_tile, integrate/deformable_state.hpp).
inline constexpr std::size_t element_tile_width = 32;

/// Branches in parallel with the elastic stiffness D of a whole constant-strain tetrahedron, as a stress tensor per
/// branch (Pa, xx yy zz xy yz zx), kept and updated for a tile of Width tetrahedra at once (one per SIMD lane):
/// - types: `ElementTile<Width>`, the branch stresses of a tile, `stress[component][branch][lane]`;
///   `ElementLanes<Width>`, one value per component and lane, `[component][lane]`; `ElementState`, the branch
///   stresses of one element, `[branch][component]` (the engine gathers it from the tile for the energy report);
/// - `element_stress_tile(tile, elastic_increment, strain_increment, dt, branch_stress, work)`: one step of the tile
///   under the elements' elastic stress increments D de (Pa) and strain increments de (engineering shear strains):
///   the summed branch stresses (Pa) and their work (J/m^3) per lane;
/// - `element_stored_energy(state, bulk, shear) -> double`: the energy in one element's branch springs, J/m^3
///   (bulk and shear modulus in Pa).
/// Maxwell<N>. The other per-spring policies act on seven strain components instead (ElementStateDamping).
template <class D, std::size_t Width = element_tile_width>
concept ElementTileDamping =
    DampingPolicy<D> &&
    requires {
      typename D::template ElementTile<Width>;
      typename D::template ElementLanes<Width>;
      typename D::ElementState;
      requires std::semiregular<typename D::template ElementTile<Width>>;
      requires std::semiregular<typename D::ElementState>;
    } &&
    requires(const D& d, typename D::template ElementTile<Width>& tile, const typename D::template ElementLanes<Width>& in,
             typename D::template ElementLanes<Width>& out, std::array<double, Width>& work,
             typename D::ElementState& state, double x, std::size_t i) {
      { d.element_stress_tile(tile, in, in, x, out, work) } noexcept -> std::same_as<void>;
      { d.element_stored_energy(state, x, x) } noexcept -> std::convertible_to<double>;
      { tile.stress[i][i][i] } -> std::same_as<double&>;
      { out[i][i] } -> std::same_as<double&>;
      { state[i][i] } -> std::same_as<double&>;
    };

/// The per-element path of deformable blocks: a policy with spring states and no element tile form keeps seven of
/// its ContactStates per tetrahedron (volumetric with the bulk modulus, three deviatoric normal components with
/// twice the shear modulus, three shear components with the shear modulus) and updates them with spring_stress
/// (always active); with SpringEnergyDamping, their stored_energy enters the energy report. StiffnessProportional,
/// Rayleigh; not Maxwell<N> (ElementTileDamping), nor the policies without spring states.
template <class D, std::size_t Width = element_tile_width>
concept ElementStateDamping = PerSpringDamping<D> && !ElementTileDamping<D, Width>;

/// The plain central-difference velocity update, v+ = v- + dt F / m.
constexpr double undamped_velocity_update(double v, double force, Inertia mass, double dt) noexcept {
  return v + dt * force * mass.inverse;
}

/// v+ = ((1 - a dt/2) v- + dt F/m) / (1 + a dt/2): the damping force -a m v at the mid-step velocity (v- + v+)/2.
constexpr double mass_damped_velocity_update(double a, double v, double force, Inertia mass, double dt,
                                             double& dissipated) noexcept {
  const double h = 0.5 * a * dt;
  // 1 / (1 + h) is the same for every degree of freedom: the compiler hoists it out of the block loop.
  const double v_new = ((1.0 - h) * v + dt * force * mass.inverse) * (1.0 / (1.0 + h));
  const double v_mid = 0.5 * (v + v_new);
  dissipated += a * mass.value * v_mid * v_mid * dt;
  return v_new;
}

}  // namespace blockdem::damping
