// Every joint law and damping policy models its concept; things that are not do not (compile-time checks).

#include <doctest/doctest.h>

#include <tuple>
#include <type_traits>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/contact/laws.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/damping/policies.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_static_policy_concepts {

namespace {
struct NotALaw {
  struct Parameters {};
  struct History {};
};
struct NoVelocityUpdate {
  using ContactState = blockdem::damping::NoState;
  double spring_stress(ContactState&, double, double, double, bool, double&) const noexcept { return 0; }
  static double held_stress(const ContactState&) noexcept { return 0; }
  double timestep_factor(double) const noexcept { return 1; }
};
}  // namespace

static_assert([]<class... L>(std::tuple<L...>*) { return (contact::ContactLaw<L> && ...); }(static_cast<contact::ShippedLaws*>(nullptr)));
static_assert(!contact::ContactLaw<NotALaw>);
static_assert(!contact::ContactLaw<int>);
static_assert([]<class... D>(std::tuple<D...>*) { return (damping::DampingPolicy<D> && ...); }(static_cast<damping::ShippedPolicies*>(nullptr)));
static_assert(damping::DampingPolicy<damping::Maxwell<1>>);  // the list has Maxwell<3>: the extremes of N
static_assert(damping::DampingPolicy<damping::Maxwell<8>>);
static_assert(!damping::DampingPolicy<NoVelocityUpdate>);
static_assert(!damping::DampingPolicy<double>);
// None keeps no per-spring state: it must cost nothing in the contact arrays.
static_assert(sizeof(damping::None::ContactState) == 1 && std::is_empty_v<damping::None::ContactState>);

TEST_CASE("static: every joint law and damping policy models its concept (checked at compile time)") { CHECK(true); }

}  // namespace test_static_policy_concepts
