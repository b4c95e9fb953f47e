#pragma once
// The one list of the joint laws blockdem ships, which tests and benchmarks iterate.

#include <tuple>
#include <variant>

#include "blockdem/contact/elastic.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/contact/softening.hpp"

namespace blockdem::contact {

/// Every shipped joint law. Tests of the ContactLaw contract (tests/contact/test_law_concepts.cpp,
/// test_traction.cpp) and the wall benchmarks run each law of this list, so that none is forgotten. A new law: one
/// header, one test file and one line here (then each test or benchmark that needs per-law parameters names what
/// it wants for it, or fails to compile).
using ShippedLaws = std::tuple<Elastic, MohrCoulomb, ElastoSoftening>;

static_assert([]<class... L>(std::tuple<L...>*) { return (ContactLaw<L> && ...); }(static_cast<ShippedLaws*>(nullptr)));

/// The parameters of one joint under any of the laws a study is compiled with (analysis/study.hpp), in the order of
/// its simulation's contact groups: the elasto-softening mortar joint (Fig. 5C), Mohr-Coulomb friction (Fig. 5B),
/// elastic (Fig. 5A). A model's law table (analysis/structure.hpp) holds one per pair of groups.
using JointLaw = std::variant<ElastoSoftening::Parameters, MohrCoulomb::Parameters, Elastic::Parameters>;

}  // namespace blockdem::contact
