#pragma once
// The wall of the wall benchmarks (bench_wall, bench_wall_interleaved): 40 courses of 50 units in running bond on a
// fixed foundation, with the joint parameters and damping policies the benchmark table lists.

#include <type_traits>

#include "blockdem/contact/laws.hpp"
#include "blockdem/damping/maxwell_fit.hpp"
#include "blockdem/damping/policies.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/model/model.hpp"
#include "shipped.hpp"

namespace blockdem::benchmarks {

inline model::Model make_wall() {
  model::Model m;
  // 40 courses of 50 units (0.24 x 0.12 x 0.055 m): 2020 blocks.
  for (const auto& b : geometry::running_bond_wall(40, 50, 0.24, 0.12, 0.055))
    m.add_block(b.shape, 1800, b.name, 0, b.support ? model::Motion::fixed : model::Motion::free);
  return m;
}

inline contact::Elastic::Parameters elastic() { return {1e10, 4e9}; }
inline contact::MohrCoulomb::Parameters mohr_coulomb() { return {1e10, 4e9, 1e5, 2e5, 0.6}; }
/// The paper's Table 1 through eq. 4-7 (k_n = 3.9e10 Pa/m: a smaller timestep than the other laws, same step cost).
inline contact::ElastoSoftening::Parameters softening() { return contact::ElastoSoftening::Parameters::from_material(); }

/// The joints of the wall for each shipped law.
template <class Law>
typename Law::Parameters parameters() {
  if constexpr (std::is_same_v<Law, contact::Elastic>) return elastic();
  else if constexpr (std::is_same_v<Law, contact::MohrCoulomb>) return mohr_coulomb();
  else if constexpr (std::is_same_v<Law, contact::ElastoSoftening>) return softening();
  else static_assert(unlisted<Law>, "a new law: give the wall its joints here");
}

/// The law's name on the command line (bench_wall_interleaved --law).
template <class Law>
constexpr const char* law_option() {
  if constexpr (std::is_same_v<Law, contact::Elastic>) return "elastic";
  else if constexpr (std::is_same_v<Law, contact::MohrCoulomb>) return "mohr-coulomb";
  else if constexpr (std::is_same_v<Law, contact::ElastoSoftening>) return "softening";
  else static_assert(unlisted<Law>, "a new law: name it for the command line here");
}

inline damping::Maxwell<3> maxwell3() {
  damping::MaxwellFitOptions o;
  return damping::to_policy<3>(damping::fit_maxwell(o));
}

/// The policies of a dynamic run of the wall, with the paper's coefficients.
template <class Damping>
Damping make_damping() {
  if constexpr (std::is_same_v<Damping, damping::None>) return {};
  else if constexpr (std::is_same_v<Damping, damping::MassProportional>) return damping::MassProportional::from_damping_ratio(0.04, 7.5);
  else if constexpr (std::is_same_v<Damping, damping::Rayleigh>) return damping::Rayleigh::from_two_frequencies(0.03, 1, 0.03, 40);
  else if constexpr (std::is_same_v<Damping, damping::Maxwell<3>>) return maxwell3();
  else static_assert(unlisted<Damping>, "a new policy: give the wall its coefficients here");
}

/// Whether bench_wall has a row for the law and policy (docs/performance.md's table): the policies of a dynamic run
/// (not Local, which settles a model; not StiffnessProportional, Rayleigh without its mass part), ElastoSoftening
/// without Rayleigh.
template <class Law, class Damping>
constexpr bool in_wall_table() {
  if constexpr (std::is_same_v<Damping, damping::None> || std::is_same_v<Damping, damping::MassProportional> ||
                std::is_same_v<Damping, damping::Maxwell<3>>)
    return true;
  else if constexpr (std::is_same_v<Damping, damping::Rayleigh>) return !std::is_same_v<Law, contact::ElastoSoftening>;
  else if constexpr (std::is_same_v<Damping, damping::Local> || std::is_same_v<Damping, damping::StiffnessProportional>) return false;
  else static_assert(unlisted<Damping>, "a new policy: say whether the wall table has it (and give it a make_damping)");
}

}  // namespace blockdem::benchmarks
