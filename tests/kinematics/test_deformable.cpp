// Deformable blocks: meshing, constant-strain tetrahedra, damping inside the elements, density scaling, mixed
// rigid/deformable models and trusses.

#include <doctest/doctest.h>

#include "../approx.hpp"
#include "../integrate/fixtures.hpp"

#include <cmath>

#include "blockdem/contact/elastic.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/damping/mass_proportional.hpp"
#include "blockdem/damping/maxwell.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/geometry/tetrahedral_mesh.hpp"
#include "blockdem/integrate/simulation.hpp"

using namespace blockdem;

TEST_CASE("deformable mesh: a box meshed with a maximum edge, conforming, volume exact") {
  const auto box = geometry::make_box(Vec3(0, 0, 0), Vec3(1.0, 0.5, 0.3));
  const auto mesh = geometry::mesh_convex_polyhedron(box, 0.25, "box");
  CHECK(mesh.longest_edge() <= 0.25 * (1 + 1e-9));
  double volume = 0;
  for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t) {
    CHECK(mesh.volume(t) > 0);
    volume += mesh.volume(t);
  }
  CHECK(volume == test::approx(0.15));
  // Boundary area = surface area, every boundary triangle on a face of the box.
  double area = 0;
  for (std::size_t k = 0; k < mesh.boundary.size(); ++k) {
    const auto& t = mesh.boundary[k];
    area += 0.5 * (mesh.nodes[t[1]] - mesh.nodes[t[0]]).cross(mesh.nodes[t[2]] - mesh.nodes[t[0]]).norm();
    CHECK(mesh.boundary_face[k] >= 0);
  }
  CHECK(area == test::approx(2 * (0.5 + 0.3 + 0.15)));
}
