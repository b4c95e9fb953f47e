#pragma once
// The forces of the deformable part that depend only on the nodes' state (DESIGN.md §4, steps 1 and 2): the node
// contacts of every group and the elements, in one parallel region. Each thread takes its contact points, group after
// group, then its element tiles (parallel/thread_ranges.hpp), with no barrier between them: they write different
// arrays and read only the nodes' positions and velocities, so that a thread that ends its contacts early starts on
// its elements, and what the cut leaves unequal in one pass the other may even out. Apart, each pass ended in a
// barrier where the thread with the smaller share waited (14 % of the two threads' time in the libgomp wait, in a
// profile of the vault's study).

#include <cstddef>

#include "blockdem/integrate/element_pass.hpp"
#include "blockdem/integrate/node_pass.hpp"
#include "blockdem/model/model.hpp"
#include "blockdem/parallel/thread_ranges.hpp"

namespace blockdem {

/// Node contacts of every group (node_contact_range) and the elements (element_range), each thread on its ranges.
template <class State, class Damping>
void deformable_forces(State& state, model::Model& m, const Damping& damping, double increment_dt, double inverse_omega_squared) {
  const auto* moduli = detail::material_moduli_of(state, m);
  const std::size_t elements = m.deformable.tetrahedra.size();
#pragma omp parallel if (elements + state.contact_points() > 1024)
  {
    std::size_t group = 0;
    state.for_each_group([&](auto& g) {
      const auto [first_point, end_point] = parallel::my_range(state.contact_bounds[group++], g.size());
      node_contact_range(g, m, damping, increment_dt, inverse_omega_squared, first_point, end_point);
    });
    const auto [first_tile, end_tile] = parallel::my_range(state.tile_bounds, State::element_tiles(elements));
    element_range(state, m, damping, increment_dt, moduli, first_tile, end_tile);
  }
}

}  // namespace blockdem
