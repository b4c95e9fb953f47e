#pragma once
// The common plane of two convex blocks in any relative orientation (Cundall 1988, as in 3DEC): the plane that
// separates them with the largest gap, or, where they overlap, with the least penetration. For convex polyhedra its
// normal is one of the separating axes: a face normal of either block (vertex-face, edge-face and face-face
// contacts) or the cross product of an edge of each (edge-edge contacts). Each block then touches the plane with its
// supporting feature: the vertex, edge or face furthest along the normal. The contact points are drawn on the plane
// from the face of each block through that feature that is best aligned with the plane (model/contact_detection).
//
// The search is the brute-force one of the separating-axis theorem over the edge pairs, run only for the pairs whose
// faces are not aligned (the face normals settle the others); for the few such pairs of a block model (a rocking or
// tumbling block, a collapsing arch) its cost is small against the rest of a detection (Nezami et al. 2004 give a
// faster search for many-sided particles).

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "blockdem/core/types.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/queries.hpp"

namespace blockdem::model {

/// A candidate common plane: its normal (unit, from A to B) and the gap between the blocks along it (m; negative:
/// they overlap by that much).
struct CommonPlane {
  Vec3 normal = Vec3::UnitZ();
  double separation = -std::numeric_limits<double>::infinity();
};

/// The best common plane normal to an edge of A and an edge of B: among the cross products of their edge
/// directions (geometry::edge_directions), the one with the largest gap between the blocks' projections, oriented
/// from A to B.
inline CommonPlane best_edge_edge_plane(const geometry::ConvexPolyhedron& a, const std::vector<Vec3>& edges_a,
                                        const geometry::ConvexPolyhedron& b, const std::vector<Vec3>& edges_b) {
  CommonPlane best;
  for (const Vec3& u : edges_a)
    for (const Vec3& v : edges_b) {
      Vec3 axis = u.cross(v);
      const double length = axis.norm();
      if (length < 1e-6) continue;  // parallel edges: a face normal of either block gives their plane
      axis /= length;
      const auto [a_lo, a_hi] = geometry::projection(a, axis);
      const auto [b_lo, b_hi] = geometry::projection(b, axis);
      if (b_lo - a_hi > best.separation) best = {axis, b_lo - a_hi};
      if (a_lo - b_hi > best.separation) best = {-axis, a_lo - b_hi};
    }
  return best;
}

/// The face of p through its vertex furthest along `direction` that is best aligned with it: the face of the
/// supporting feature (a vertex, an edge or a face) from which the contact points on the common plane are drawn.
/// Returns the face's index, and the cosine of its normal with `direction` in `alignment`.
inline std::size_t supporting_face(const geometry::ConvexPolyhedron& p, const std::vector<Vec3>& face_normal,
                                   const Vec3& direction, double& alignment) {
  int support = 0;
  double furthest = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.vertices.size(); ++i)
    if (const double s = direction.dot(p.vertices[i]); s > furthest) {
      furthest = s;
      support = static_cast<int>(i);
    }
  std::size_t best = 0;
  alignment = -2;
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    bool through = false;
    for (const int v : p.faces[f]) through = through || v == support;
    if (!through) continue;
    if (const double c = face_normal[f].dot(direction); c > alignment) {
      alignment = c;
      best = f;
    }
  }
  return best;
}

}  // namespace blockdem::model
