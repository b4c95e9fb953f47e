// Every joint law and damping policy models its concept; things that are not do not (compile-time checks).

#include <doctest/doctest.h>

#include "blockdem/contact/concepts.hpp"
#include "blockdem/contact/elastic.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/contact/softening.hpp"
#include "blockdem/damping/concepts.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/damping/mass_proportional.hpp"
#include "blockdem/damping/maxwell.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/damping/rayleigh.hpp"
#include "blockdem/damping/stiffness_proportional.hpp"

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

using namespace blockdem;
static_assert(contact::ContactLaw<contact::Elastic>);
static_assert(contact::ContactLaw<contact::MohrCoulomb>);
static_assert(contact::ContactLaw<contact::ElastoSoftening>);
static_assert(!contact::ContactLaw<NotALaw>);
static_assert(!contact::ContactLaw<int>);
static_assert(damping::DampingPolicy<damping::None>);
static_assert(damping::DampingPolicy<damping::Local>);
static_assert(damping::DampingPolicy<damping::MassProportional>);
static_assert(damping::DampingPolicy<damping::StiffnessProportional>);
static_assert(damping::DampingPolicy<damping::Rayleigh>);
static_assert(damping::DampingPolicy<damping::Maxwell<1>>);
static_assert(damping::DampingPolicy<damping::Maxwell<3>>);
static_assert(damping::DampingPolicy<damping::Maxwell<8>>);
static_assert(!damping::DampingPolicy<NoVelocityUpdate>);
static_assert(!damping::DampingPolicy<double>);
// None keeps no per-spring state: it must cost nothing in the contact arrays.
static_assert(sizeof(damping::None::ContactState) == 1 && std::is_empty_v<damping::None::ContactState>);

TEST_CASE("static: every joint law and damping policy models its concept (checked at compile time)") { CHECK(true); }
