#pragma once
// The wall of the wall benchmarks (bench_wall, bench_wall_interleaved): 40 courses of 50 units in running bond on a
// fixed foundation, with the joint parameters and damping policies the benchmark table lists.

#include <type_traits>

#include "blockdem/contact/elastic.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/contact/softening.hpp"
#include "blockdem/damping/mass_proportional.hpp"
#include "blockdem/damping/maxwell_fit.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/damping/rayleigh.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/model/model.hpp"

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

template <class Law>
typename Law::Parameters parameters() {
  if constexpr (std::is_same_v<Law, contact::Elastic>) return elastic();
  else if constexpr (std::is_same_v<Law, contact::ElastoSoftening>) return softening();
  else return mohr_coulomb();
}

inline damping::Maxwell<3> maxwell3() {
  damping::MaxwellFitOptions o;
  return damping::to_policy<3>(damping::fit_maxwell(o));
}

template <class Damping>
Damping make_damping() {
  if constexpr (std::is_same_v<Damping, damping::None>) return {};
  else if constexpr (std::is_same_v<Damping, damping::MassProportional>) return damping::MassProportional::from_damping_ratio(0.04, 7.5);
  else if constexpr (std::is_same_v<Damping, damping::Rayleigh>) return damping::Rayleigh::from_two_frequencies(0.03, 1, 0.03, 40);
  else return maxwell3();
}

}  // namespace blockdem::benchmarks
