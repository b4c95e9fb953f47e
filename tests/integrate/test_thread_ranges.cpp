// The threads' ranges of the deformable passes (parallel/thread_ranges.hpp): runs of whole blocks, each node
// contact point on the thread of its node. That results do not depend on them: the "deformable threads" cases.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/damping/mass_proportional.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "blockdem/parallel/thread_ranges.hpp"
#include "../threads.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_thread_ranges {

namespace {

using Sim = Simulation<damping::MassProportional, contact::MohrCoulomb>;
using State = DeformableState<damping::MassProportional, contact::MohrCoulomb>;

contact::MohrCoulomb::Parameters joint(int, int) { return contact::MohrCoulomb::Parameters(1e10, 1e10, 0, 0, 0.6); }

/// The thread (0 or 1) of item i under bounds b (three values).
int owner(const parallel::Bounds& b, std::size_t i) { return i < b[1] ? 0 : 1; }

}  // namespace

TEST_CASE("thread ranges: the bounds made for a team of that size, else an even split") {
  const parallel::Bounds b{0, 7, 10};
  CHECK(parallel::range_of(b, 10, 0, 2) == std::pair<std::size_t, std::size_t>{0, 7});
  CHECK(parallel::range_of(b, 10, 1, 2) == std::pair<std::size_t, std::size_t>{7, 10});
  CHECK(parallel::range_of(b, 10, 0, 1) == std::pair<std::size_t, std::size_t>{0, 10});  // one thread: all
  CHECK(parallel::range_of(b, 12, 1, 2) == std::pair<std::size_t, std::size_t>{6, 12});  // out of date: even
  CHECK(parallel::range_of(b, 9, 2, 3) == std::pair<std::size_t, std::size_t>{6, 9});    // another team: even
  CHECK(parallel::range_of({}, 5, 0, 2) == std::pair<std::size_t, std::size_t>{0, 2});
  CHECK(parallel::range_of({}, 5, 1, 2) == std::pair<std::size_t, std::size_t>{2, 5});
}

TEST_CASE("thread ranges: a wall of deformable blocks is cut between two blocks, each contact point with its node") {
  const test::ScopedThreads two(2);
  if (parallel::available_threads() < 2) return;  // built without OpenMP: no ranges to check
  model::Model m;
  for (const auto& b : geometry::running_bond_wall(4, 5, 0.24, 0.12, 0.055))
    m.add_block(b.shape, 1800, b.name, 0, b.support ? model::Motion::fixed : model::Motion::free);
  for (std::size_t i = 0; i < m.bodies.size(); ++i)
    if (m.bodies.motion[i] == model::Motion::free) m.make_deformable(i, 0.05, model::IsotropicElastic(5e9, 0.2));
  Sim sim(m, damping::MassProportional{}, joint);
  for (int k = 0; k < 20; ++k) sim.step();
  const auto& d = sim.deformable_state();
  const auto& nd = m.deformable.nodes;
  const auto& te = m.deformable.tetrahedra;
  REQUIRE(d.node_bounds.size() == 3);
  REQUIRE(d.tile_bounds.size() == 3);
  // The cut is the first node of a block, near the middle (the runs are of equal cost, not of equal node counts).
  bool at_block = false;
  for (const auto& blk : m.deformable.blocks) at_block = at_block || blk.first_node == d.node_bounds[1];
  CHECK(at_block);
  const double node_share = static_cast<double>(d.node_bounds[1]) / static_cast<double>(nd.size());
  MESSAGE(m.deformable.blocks.size() << " blocks, " << nd.size() << " nodes, cut at node " << d.node_bounds[1]);
  CHECK(node_share > 0.3);
  CHECK(node_share < 0.7);
  // An element reads the nodes of its block: all on its own thread, but the elements of the tile across the cut.
  std::size_t reads = 0, across = 0;
  for (std::size_t t = 0; t < te.size(); ++t)
    for (auto n : te.node[t]) {
      ++reads;
      across += owner(d.tile_bounds, t / State::element_tile) != owner(d.node_bounds, n);
    }
  MESSAGE(across << " of " << reads << " node reads of the elements across the cut");
  CHECK(across <= 4 * (State::element_tile - 1));
  // Every contact point is on the thread of its node.
  std::size_t points = 0;
  std::size_t group = 0;
  d.for_each_group([&](const auto& g) {
    const auto& b = d.contact_bounds[group++];
    REQUIRE(b.size() == 3);
    CHECK(b.back() == g.size());
    for (std::size_t k = 0; k < g.size(); ++k) CHECK(owner(b, k) == owner(d.node_bounds, g.node[k]));
    points += g.size();
  });
  CHECK(points > 100);
}

TEST_CASE("thread ranges: one deformable block is cut inside, at the same fraction of its nodes and elements") {
  const test::ScopedThreads two(2);
  if (parallel::available_threads() < 2) return;
  model::Model m;
  m.add_block(geometry::make_box(Vec3(-1, -1, -0.5), Vec3(1, 1, 0)), 2000, "base", 0, model::Motion::fixed);
  const auto a = m.add_block(geometry::make_box(Vec3(-0.5, -0.25, 0), Vec3(0.5, 0.25, 0.5)), 2000, "pier", 1);
  m.make_deformable(a, 0.08, model::IsotropicElastic(10e9, 0.2));
  Sim sim(m, damping::MassProportional{}, joint);
  const auto& d = sim.deformable_state();
  REQUIRE(d.node_bounds.size() == 3);
  const double nodes = static_cast<double>(m.deformable.nodes.size());
  const double tiles = static_cast<double>(State::element_tiles(m.deformable.tetrahedra.size()));
  const double node_share = d.node_bounds[1] / nodes, tile_share = d.tile_bounds[1] / tiles;
  MESSAGE("one block: the first thread takes " << node_share << " of the nodes and " << tile_share << " of the element tiles");
  CHECK(node_share > 0.25);
  CHECK(node_share < 0.75);
  CHECK(tile_share == doctest::Approx(node_share).epsilon(0.05));
}

}  // namespace test_thread_ranges
