// The ContactLaw concept and the traits it requires of every law (contact/concepts.hpp): every shipped law models
// it, a law that lacks one trait or whose update may throw does not; and per law the traits do what the engine
// relies on: turn_shear turns the shear stresses with the frame, start_unbonded / never_bonded / damage agree, and
// `dissipates` says whether update() ever dissipates.

#include <doctest/doctest.h>

#include "../approx.hpp"
#include "../shipped.hpp"

#include <cmath>
#include <type_traits>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/contact/laws.hpp"
#include "blockdem/core/units.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_law_concepts {

namespace {

// ---- compile time: positive and negative ----

/// Which trait a copy of Elastic lacks (or, for noexcept_update, which promise it breaks).
enum class Without { nothing, turn_shear, damage, start_unbonded, never_bonded, dissipates, constant_dissipates, noexcept_update };

struct Dissipates {
  static constexpr bool dissipates = false;
};
struct NoDissipates {};
struct VariableDissipates {
  [[maybe_unused]] static inline bool dissipates = false;  // not a constant: the contact pass could not decide at compile time
};
template <Without without>
using DissipatesBase = std::conditional_t<without == Without::dissipates, NoDissipates,
                                          std::conditional_t<without == Without::constant_dissipates, VariableDissipates, Dissipates>>;

/// contact::Elastic, copied member by member, without one trait.
template <Without without>
struct ElasticCopy : DissipatesBase<without> {
  using Law = contact::Elastic;
  using Parameters = Law::Parameters;
  using History = Law::History;
  static constexpr contact::Response update(const Parameters& p, History& h, double du_normal, contact::Shear du_shear,
                                            const contact::Step& step = {}) noexcept(without != Without::noexcept_update) {
    return Law::update(p, h, du_normal, du_shear, step);
  }
  static constexpr double normal_stiffness(const Parameters& p) noexcept { return Law::normal_stiffness(p); }
  static constexpr double shear_stiffness(const Parameters& p) noexcept { return Law::shear_stiffness(p); }
  static constexpr bool damping_active(const Parameters& p, const History& h) noexcept { return Law::damping_active(p, h); }
  static constexpr double stored_energy(const Parameters& p, const History& h) noexcept { return Law::stored_energy(p, h); }
  static constexpr contact::Traction traction(const Parameters& p, const History& h) noexcept { return Law::traction(p, h); }
  static constexpr void turn_shear(History& h, const contact::ShearTurn& turn) noexcept
    requires(without != Without::turn_shear)
  {
    Law::turn_shear(h, turn);
  }
  static constexpr double damage(const History& h) noexcept
    requires(without != Without::damage)
  {
    return Law::damage(h);
  }
  static constexpr void start_unbonded(History& h) noexcept
    requires(without != Without::start_unbonded)
  {
    Law::start_unbonded(h);
  }
  static constexpr bool never_bonded(const History& h) noexcept
    requires(without != Without::never_bonded)
  {
    return Law::never_bonded(h);
  }
};

/// A law with every trait whose damage() may throw.
struct ThrowingDamage : ElasticCopy<Without::damage> {
  static double damage(const History&) { return 0.0; }
};

static_assert([]<class... L>(std::tuple<L...>*) { return (contact::ContactLaw<L> && ...); }(static_cast<contact::ShippedLaws*>(nullptr)));
static_assert(std::tuple_size_v<contact::ShippedLaws> == 3);
static_assert(contact::ContactLaw<ElasticCopy<Without::nothing>>);  // the copy itself is a law: what follows removes one thing
static_assert(!contact::ContactLaw<ElasticCopy<Without::turn_shear>>);
static_assert(!contact::ContactLaw<ElasticCopy<Without::damage>>);
static_assert(!contact::ContactLaw<ElasticCopy<Without::start_unbonded>>);
static_assert(!contact::ContactLaw<ElasticCopy<Without::never_bonded>>);
static_assert(!contact::ContactLaw<ElasticCopy<Without::dissipates>>);
static_assert(!contact::ContactLaw<ElasticCopy<Without::constant_dissipates>>);
static_assert(!contact::ContactLaw<ElasticCopy<Without::noexcept_update>>);
static_assert(!contact::ContactLaw<ThrowingDamage>);

// The traits are constant expressions where the law allows.
static_assert(contact::Elastic::dissipates && contact::MohrCoulomb::dissipates && contact::ElastoSoftening::dissipates);
static_assert([] {
  contact::Elastic::History h{};
  contact::Elastic::start_unbonded(h);
  return contact::Elastic::never_bonded(h) && contact::Elastic::damage(h) == 0.0;  // new, not broken: no damage
}());
static_assert([] {
  contact::MohrCoulomb::History h{};
  contact::MohrCoulomb::start_unbonded(h);
  return contact::MohrCoulomb::never_bonded(h) && contact::MohrCoulomb::damage(h) == 1.0;
}());
static_assert([] {
  contact::ElastoSoftening::History h{};
  contact::ElastoSoftening::start_unbonded(h);
  return contact::ElastoSoftening::never_bonded(h) && contact::ElastoSoftening::damage(h) == 1.0;
}());

// ---- run time, per shipped law ----

/// A bonded joint of each law: strengths that a millimetre of opening breaks.
template <class Law>
typename Law::Parameters bonded() {
  if constexpr (std::is_same_v<Law, contact::Elastic>) return {1e10, 4e9};
  else if constexpr (std::is_same_v<Law, contact::MohrCoulomb>) return {1e10, 4e9, 1e5, 2e5, 0.6};
  else if constexpr (std::is_same_v<Law, contact::ElastoSoftening>) return contact::ElastoSoftening::Parameters::from_material();
  else static_assert(test::unlisted<Law>, "a new law: give it a bonded joint here");
}

/// Whether the law has a bond to lose (and so a failed state, damage 1, that a never-bonded contact point starts
/// from). The elastic law's joints never break; its never-bonded points carry no tension but are not damage.
template <class Law>
constexpr bool has_bond() {
  if constexpr (std::is_same_v<Law, contact::Elastic>) return false;
  else if constexpr (std::is_same_v<Law, contact::MohrCoulomb> || std::is_same_v<Law, contact::ElastoSoftening>) return true;
  else static_assert(test::unlisted<Law>, "a new law: say whether it has a bond");
}

/// A closed joint (1e-6 m of closure) carrying the shear stress (tau_1, tau_2) (Pa), well inside its strength.
template <class Law>
typename Law::History loaded(const typename Law::Parameters& p, double tau_1, double tau_2) {
  typename Law::History h{};
  const double ks = Law::shear_stiffness(p);
  Law::update(p, h, -1e-6, {-tau_1 / ks, -tau_2 / ks});
  return h;
}

}  // namespace

TEST_CASE_TEMPLATE_DEFINE("contact law traits: turn_shear re-expresses the shear stresses along the turned tangents", Law, turn_shear_case) {
  // Reference: a turn by 90 degrees about n (t1 = t2o, t2 = n x t1 = -t1o) takes a stress along t1o to minus the new
  // t2; a turn by theta keeps the stress vector: new_1 = cos s1 + sin s2, new_2 = -sin s1 + cos s2.
  const auto p = bonded<Law>();
  auto h = loaded<Law>(p, 1.0, 0.0);
  const contact::Traction before = Law::traction(p, h);
  CHECK(before[1] == test::approx(1.0).epsilon(1e-12));
  CHECK(before[2] == 0.0);
  Law::turn_shear(h, contact::ShearTurn{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitY(), -Vec3::UnitX()});
  const contact::Traction quarter = Law::traction(p, h);
  CHECK(quarter[0] == before[0]);  // the normal stress does not turn
  CHECK(quarter[1] == 0.0);
  CHECK(quarter[2] == -before[1]);

  const double theta = 30.0 * pi / 180.0, c = std::cos(theta), s = std::sin(theta);
  auto g = loaded<Law>(p, 300.0, -400.0);
  const contact::Traction old = Law::traction(p, g);
  Law::turn_shear(g, contact::ShearTurn{Vec3::UnitX(), Vec3::UnitY(), Vec3(c, s, 0), Vec3(-s, c, 0)});
  const contact::Traction turned = Law::traction(p, g);
  CHECK(turned[1] == test::approx(c * old[1] + s * old[2]).epsilon(1e-14));
  CHECK(turned[2] == test::approx(-s * old[1] + c * old[2]).epsilon(1e-14));
  CHECK(std::hypot(turned[1], turned[2]) == test::approx(500.0).epsilon(1e-12));
  auto unturned = g;
  Law::turn_shear(unturned, contact::ShearTurn{});  // the default is no turn
  CHECK(Law::traction(p, unturned) == turned);
}
TEST_CASE_TEMPLATE_APPLY(turn_shear_case, contact::ShippedLaws);

TEST_CASE_TEMPLATE_DEFINE("contact law traits: start_unbonded, never_bonded and damage agree, and the law keeps the mark", Law, unbonded_case) {
  const auto p = bonded<Law>();
  const typename Law::History fresh{};
  CHECK_FALSE(Law::never_bonded(fresh));
  CHECK(Law::damage(fresh) == 0.0);

  // A contact point that appeared during the run: marked, and failed from the start (damage 1) where the law has a
  // bond.
  typename Law::History h{};
  Law::start_unbonded(h);
  CHECK(Law::never_bonded(h));
  CHECK(Law::damage(h) == (has_bond<Law>() ? 1.0 : 0.0));
  for (int i = 0; i < 100; ++i) Law::update(p, h, i < 50 ? -1e-8 : 2e-8, {1e-7, -1e-7});  // closes, slides, opens
  CHECK(Law::never_bonded(h));
  CHECK(Law::damage(h) == (has_bond<Law>() ? 1.0 : 0.0));
  CHECK(h.gap > 0);
  CHECK(Law::traction(p, h) == contact::Traction{0.0, 0.0, 0.0});  // open and never bonded: no stress of any kind

  // A bonded joint torn open by a millimetre: broken (damage 1 to within the law's failure damage), not never-bonded.
  typename Law::History torn{};
  for (int i = 0; i < 1000; ++i) Law::update(p, torn, 1e-6, {0.0, 0.0});
  CHECK_FALSE(Law::never_bonded(torn));
  if (has_bond<Law>()) CHECK(Law::damage(torn) > 0.999);
  else CHECK(Law::damage(torn) == 0.0);
  CHECK(Law::damage(torn) <= 1.0);
}
TEST_CASE_TEMPLATE_APPLY(unbonded_case, contact::ShippedLaws);

TEST_CASE_TEMPLATE_DEFINE("contact law traits: a law dissipates along a millimetre of slip exactly when it has a strength", Law, dissipates_case) {
  const auto p = bonded<Law>();
  typename Law::History h{};
  double dissipated = 0.0;
  Law::update(p, h, -1e-6, {0.0, 0.0});  // closed: 1e4 Pa and more of compression
  for (int i = 0; i < 1000; ++i) dissipated += Law::update(p, h, 0.0, {1e-6, 0.0}).dissipated;
  CHECK((dissipated > 0.0) == has_bond<Law>());
  CHECK((dissipated > 0.0) <= Law::dissipates);  // what it returns, it says it can
}
TEST_CASE_TEMPLATE_APPLY(dissipates_case, contact::ShippedLaws);

TEST_CASE("elastic law: a never-bonded point carries no tension, and lets its shear go as it opens") {
  // Reference: a linear spring in compression only. Closed by 1e-6 m and sheared by 1e-6 m it stores
  // 1/2 k_n d^2 + 1/2 k_s s^2; opened, it carries nothing, and the shear energy it held is dissipated (the work on
  // the shear springs over the opening step, -(tau + 0)/2 ds with ds = 0, less the change of stored energy).
  const contact::Elastic::Parameters p(1e10, 4e9);
  contact::Elastic::History h{};
  h.gap = 2e-4;  // found open by 0.2 mm, within the tolerance: a bonded point would pull with 2 MPa
  contact::Elastic::start_unbonded(h);
  auto r = contact::Elastic::update(p, h, 0.0, {0.0, 0.0});
  CHECK(r.normal_stress == 0.0);
  CHECK_FALSE(r.damping_active);
  CHECK(contact::Elastic::stored_energy(p, h) == 0.0);
  r = contact::Elastic::update(p, h, -2e-4 - 1e-6, {0.0, 0.0});  // closes: no time passes, so no closure correction
  CHECK(r.normal_stress == test::approx(1e4).epsilon(1e-9));
  CHECK(r.damping_active);
  r = contact::Elastic::update(p, h, 0.0, {1e-6, 0.0});
  CHECK(r.shear_stress[0] == test::approx(-4e3).epsilon(1e-12));
  CHECK(r.dissipated == 0.0);
  const double held = 0.5 * 4e3 * 4e3 / 4e9;
  CHECK(contact::Elastic::stored_energy(p, h) == test::approx(0.5 * 1e10 * 1e-12 + held).epsilon(1e-9));
  r = contact::Elastic::update(p, h, 3e-6, {0.0, 0.0});  // opens by 2 micrometres
  CHECK(r.normal_stress == 0.0);
  CHECK(r.shear_stress == contact::Shear{0.0, 0.0});
  CHECK(r.dissipated == test::approx(held).epsilon(1e-12));
  CHECK(contact::Elastic::stored_energy(p, h) == 0.0);

  // A bonded point at the same gaps: tension through 0, and nothing dissipated.
  contact::Elastic::History g{};
  g.gap = 2e-4;
  r = contact::Elastic::update(p, g, 0.0, {0.0, 0.0});
  CHECK(r.normal_stress == test::approx(-2e6).epsilon(1e-12));
  CHECK(r.damping_active);
}

}  // namespace test_law_concepts
