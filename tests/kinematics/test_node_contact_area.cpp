// Node contact points of a deformable block: their tributary areas stay on the joint's overlap.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <variant>
#include <vector>

#include "blockdem/contact/elastic.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/integrate/node_contact_assignment.hpp"

using namespace blockdem;

TEST_CASE("node contact area: only nodes on the overlap carry it, and it sums to the overlap's area") {
  // A 0.2 m square block (rigid) on a deformable slab 0.8 m long whose mesh does not line up with the block's edges.
  // The slab's triangles that straddle an edge of the block's footprint used to give their nodes beyond the edge a
  // share of the area: those nodes pushed on the block's face plane extended past its edge, a lever that held a
  // block rocking about that edge back (0.8 mm instead of 11 mm in 0.3 s). Every node contact point must now lie on
  // the footprint, within the contact tolerance, and their areas sum to the footprint's 0.04 m^2.
  model::Model m;
  const auto slab = m.add_block(geometry::make_box(Vec3(-0.4, -0.1, 0), Vec3(0.4, 0.1, 0.2)), 2000, "slab");
  const auto block = m.add_block(geometry::make_box(Vec3(-0.1, -0.1, 0.2), Vec3(0.1, 0.1, 0.6)), 2000, "block");
  m.make_deformable(slab, 0.1, model::IsotropicElastic(20e9, 0.2));
  DeformableState<damping::None, contact::Elastic> state;
  state.setup(m);
  std::vector<model::ContactCandidate> joint;
  for (const double x : {-0.1, 0.1})
    for (const double y : {-0.1, 0.1}) joint.push_back({slab, block, Vec3(x, y, 0.2), Vec3(0, 0, 1), Vec3(1, 0, 0), 0.01, 0.0});
  const model::ContactSettings settings;
  const contact::Elastic::Parameters parameters{1e9, 1e9};
  NodeContactAssignment<damping::None, contact::Elastic> assignment;
  assignment.assign(state, m, joint, [&](int, int) { return std::variant<contact::Elastic::Parameters>(parameters); }, settings, false);
  std::size_t points = 0, off = 0;
  double area = 0, farthest = 0;
  state.for_each_group([&](const auto& g) {
    for (std::size_t k = 0; k < g.size(); ++k) {
      const Vec3& x = m.deformable.nodes.position[g.node[k]];
      ++points;
      area += g.area[k];
      const double outside = std::max(std::abs(x.x()), std::abs(x.y())) - 0.1;
      farthest = std::max(farthest, outside);
      if (outside > settings.tolerance) ++off;
    }
  });
  MESSAGE(points << " node contact points, " << off << " off the footprint (farthest " << farthest << " m), area " << area << " m^2");
  CHECK(points >= 4);
  CHECK(off == 0);
  CHECK(area == doctest::Approx(0.04).epsilon(1e-9));
}
