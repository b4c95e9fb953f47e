// The damping capability concepts (damping/concepts.hpp): which shipped policy has which capability, positive and
// negative, and copies of Maxwell's interface without one member of a capability, which then lack it (compile-time
// checks; the engine chooses its code paths with these concepts).

#include <doctest/doctest.h>

#include <array>
#include <cstddef>
#include <tuple>
#include <type_traits>

#include "blockdem/core/lanes.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/damping/policies.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_policy_concepts {
using namespace blockdem::damping;

namespace {

/// Every shipped policy is a DampingPolicy with a per-degree-of-freedom update.
static_assert([]<class... D>(std::tuple<D...>*) { return ((DampingPolicy<D> && PerDofDamping<D>) && ...); }(static_cast<ShippedPolicies*>(nullptr)));
static_assert(std::tuple_size_v<ShippedPolicies> == 6);

// Which policy has what. Columns: per spring, three springs at once, stored energy, prepared, contact field,
// element tiles, per-element spring states.
static_assert(!PerSpringDamping<None> && !SpringTripleDamping<None> && !SpringEnergyDamping<None> && !PreparedDamping<None> &&
              !ContactFieldDamping<None> && !ElementTileDamping<None> && !ElementStateDamping<None>);
static_assert(!PerSpringDamping<Local> && !SpringTripleDamping<Local> && !SpringEnergyDamping<Local> && !PreparedDamping<Local> &&
              !ContactFieldDamping<Local> && !ElementTileDamping<Local> && !ElementStateDamping<Local>);
static_assert(!PerSpringDamping<MassProportional> && !SpringTripleDamping<MassProportional> &&
              !SpringEnergyDamping<MassProportional> && !PreparedDamping<MassProportional> &&
              !ContactFieldDamping<MassProportional> && !ElementTileDamping<MassProportional> &&
              !ElementStateDamping<MassProportional>);
static_assert(PerSpringDamping<StiffnessProportional> && !SpringTripleDamping<StiffnessProportional> &&
              !SpringEnergyDamping<StiffnessProportional> && !PreparedDamping<StiffnessProportional> &&
              !ContactFieldDamping<StiffnessProportional> && !ElementTileDamping<StiffnessProportional> &&
              ElementStateDamping<StiffnessProportional>);
static_assert(PerSpringDamping<Rayleigh> && !SpringTripleDamping<Rayleigh> && !SpringEnergyDamping<Rayleigh> &&
              !PreparedDamping<Rayleigh> && !ContactFieldDamping<Rayleigh> && !ElementTileDamping<Rayleigh> &&
              ElementStateDamping<Rayleigh>);
template <int N>
constexpr bool maxwell_has_all() {
  using M = Maxwell<N>;
  return PerSpringDamping<M> && SpringTripleDamping<M> && SpringEnergyDamping<M> && PreparedDamping<M> &&
         ContactFieldDamping<M> && ElementTileDamping<M> && !ElementStateDamping<M>;
}
static_assert(maxwell_has_all<1>() && maxwell_has_all<2>() && maxwell_has_all<3>() && maxwell_has_all<4>() &&
              maxwell_has_all<8>());
// Tiles of other widths than the engine's.
static_assert(ElementTileDamping<Maxwell<3>, 4> && ElementTileDamping<Maxwell<3>, 8>);

// Not a policy at all.
struct NoVelocityUpdate {
  using ContactState = NoState;
  double spring_stress(ContactState&, double, double, double, bool, double&) const noexcept { return 0; }
  static double held_stress(const ContactState&) noexcept { return 0; }
  double timestep_factor(double) const noexcept { return 1; }
};
static_assert(!PerDofDamping<NoVelocityUpdate> && !DampingPolicy<NoVelocityUpdate>);
static_assert(!DampingPolicy<double> && !PerDofDamping<double>);

// ---- a copy of Maxwell<3>'s interface (declarations only: concepts do not call) without one member ----

using M3 = Maxwell<3>;

/// The member a copy lacks (spring_stresses is not a field member, but the field's release needs it).
enum class Drop {
  nothing, ContactField, FieldLanes, contact_field, advance_field, advance_field_masked, field_force, field_sum,
  branch_forces, field_of, field_stress, field_branch_stresses, contact_stiffness, stiffness_slot, spring_stresses
};

template <int>
struct Nothing {};
struct WithContactField {
  using ContactField = M3::ContactField;
};
struct WithFieldLanes {
  using FieldLanes = M3::FieldLanes;
};
struct WithFlag {
  bool contact_field = true;
};

template <Drop drop>
struct MaxwellCopy : std::conditional_t<drop == Drop::ContactField, Nothing<0>, WithContactField>,
                     std::conditional_t<drop == Drop::FieldLanes, Nothing<1>, WithFieldLanes>,
                     std::conditional_t<drop == Drop::contact_field, Nothing<2>, WithFlag> {
  using ContactState = M3::ContactState;
  using Generalised = M3::Generalised;
  using FieldStiffness = M3::FieldStiffness;
  using Forces = std::array<Generalised, 3>;
  double spring_stress(ContactState&, double, double, double, bool, double&) const noexcept;
  static double held_stress(const ContactState&) noexcept;
  double velocity_update(double, double, Inertia, double, double&) const noexcept;
  double timestep_factor(double) const noexcept;
  std::array<double, 3> spring_stresses(std::array<ContactState, 3>&, double, double, const std::array<double, 3>&, double,
                                        bool, double&) const noexcept
    requires(drop != Drop::spring_stresses);
  void advance_field(M3::FieldLanes&, const Lanes (&)[6]) const noexcept
    requires(drop != Drop::advance_field);
  void advance_field(M3::FieldLanes&, const Lanes (&)[6], const LaneMask&, Lanes (&)[6]) const noexcept
    requires(drop != Drop::advance_field_masked);
  static void field_force(const M3::FieldLanes&, const LaneMask&, Lanes (&)[6]) noexcept
    requires(drop != Drop::field_force);
  static Lanes field_sum(const M3::FieldLanes&, std::size_t) noexcept
    requires(drop != Drop::field_sum);
  static Forces branch_forces(const M3::ContactField&) noexcept
    requires(drop != Drop::branch_forces);
  static M3::ContactField field_of(const Forces&) noexcept
    requires(drop != Drop::field_of);
  static std::array<double, 3> field_stress(const Generalised&, double, double, double, double) noexcept
    requires(drop != Drop::field_stress);
  static std::array<ContactState, 3> field_branch_stresses(const Forces&, double, double, double, double) noexcept
    requires(drop != Drop::field_branch_stresses);
  static FieldStiffness contact_stiffness(double, double, double, double, double) noexcept
    requires(drop != Drop::contact_stiffness);
  static std::size_t stiffness_slot(std::size_t) noexcept
    requires(drop != Drop::stiffness_slot);
};

static_assert(ContactFieldDamping<MaxwellCopy<Drop::nothing>>);  // the copy is complete: each below lacks one member
static_assert(!ContactFieldDamping<MaxwellCopy<Drop::ContactField>>);
static_assert(!ContactFieldDamping<MaxwellCopy<Drop::FieldLanes>>);
static_assert(!ContactFieldDamping<MaxwellCopy<Drop::contact_field>>);
static_assert(!ContactFieldDamping<MaxwellCopy<Drop::advance_field>>);
static_assert(!ContactFieldDamping<MaxwellCopy<Drop::advance_field_masked>>);
static_assert(!ContactFieldDamping<MaxwellCopy<Drop::field_force>>);
static_assert(!ContactFieldDamping<MaxwellCopy<Drop::field_sum>>);
static_assert(!ContactFieldDamping<MaxwellCopy<Drop::branch_forces>>);
static_assert(!ContactFieldDamping<MaxwellCopy<Drop::field_of>>);
static_assert(!ContactFieldDamping<MaxwellCopy<Drop::field_stress>>);
static_assert(!ContactFieldDamping<MaxwellCopy<Drop::field_branch_stresses>>);
static_assert(!ContactFieldDamping<MaxwellCopy<Drop::contact_stiffness>>);
static_assert(!ContactFieldDamping<MaxwellCopy<Drop::stiffness_slot>>);
static_assert(!ContactFieldDamping<MaxwellCopy<Drop::spring_stresses>> && !SpringTripleDamping<MaxwellCopy<Drop::spring_stresses>>);
// What the field members do not take away.
static_assert(SpringTripleDamping<MaxwellCopy<Drop::field_of>> && PerSpringDamping<MaxwellCopy<Drop::ContactField>>);

// ---- the other capabilities: Maxwell<3> with one member hidden, or a member that breaks the promise ----

struct HiddenTileEnergy : M3 {
 private:
  using M3::element_stored_energy;
};
struct HiddenTile : M3 {
 private:
  template <std::size_t Width>
  using ElementTile = M3::ElementTile<Width>;
};
struct HiddenStoredEnergy : M3 {
 private:
  using M3::stored_energy;
};
struct ThrowingPrepare : StiffnessProportional {
  void prepare(double) {}  // may throw: the engine calls it where nothing may
};
struct NoexceptPrepare : StiffnessProportional {
  void prepare(double) noexcept {}
};
struct TripleOfFloats : StiffnessProportional {
  std::array<float, 3> spring_stresses(std::array<ContactState, 3>&, double, double, const std::array<double, 3>&, double,
                                       bool, double&) const noexcept;
};
static_assert(!ElementTileDamping<HiddenTileEnergy> && ContactFieldDamping<HiddenTileEnergy>);
static_assert(!ElementTileDamping<HiddenTile> && ElementStateDamping<HiddenTile>);  // then its elements take seven springs
static_assert(!SpringEnergyDamping<HiddenStoredEnergy> && SpringTripleDamping<HiddenStoredEnergy>);
static_assert(!PreparedDamping<ThrowingPrepare> && PreparedDamping<NoexceptPrepare>);
static_assert(!SpringTripleDamping<TripleOfFloats> && PerSpringDamping<TripleOfFloats>);

}  // namespace

TEST_CASE("static: the damping capability concepts accept and reject what they should (checked at compile time)") { CHECK(true); }

}  // namespace test_policy_concepts
