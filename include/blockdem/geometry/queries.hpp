#pragma once
// Distance queries on convex polyhedra: from a point (to attach monitor points to blocks) and between two blocks
// by the full separating-axis test, face normals and edge-edge directions (to check an assembly for overlaps).

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "blockdem/core/types.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"

namespace blockdem::geometry {

namespace detail {

inline double point_segment_distance(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0 ? std::clamp((x - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + t * ab - x).norm();
}

}  // namespace detail

/// Unit directions of the edges of p, one per edge (each edge is listed by its two faces).
inline std::vector<Vec3> edge_directions(const ConvexPolyhedron& p) {
  std::vector<Vec3> out;
  for (const auto& face : p.faces)
    for (std::size_t i = 0; i < face.size(); ++i) {
      const int a = face[i], b = face[(i + 1) % face.size()];
      if (a > b) continue;
      const Vec3 e = p.vertices[static_cast<std::size_t>(b)] - p.vertices[static_cast<std::size_t>(a)];
      if (e.norm() > 0) out.push_back(e.normalized());
    }
  return out;
}

/// The interval (lowest, highest) of p's projection on `axis`.
inline std::pair<double, double> projection(const ConvexPolyhedron& p, const Vec3& axis) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& v : p.vertices) {
    const double s = axis.dot(v);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  return {lo, hi};
}

/// Euclidean distance (m) from x to the convex polyhedron p: 0 inside or on its boundary.
inline double distance(const ConvexPolyhedron& p, const Vec3& x) {
  bool inside = true;
  for (std::size_t f = 0; f < p.faces.size() && inside; ++f) inside = p.face_distance(f, x) <= 0;
  if (inside) return 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    const double h = p.face_distance(f, x);
    if (h <= 0) continue;  // the nearest point lies on a face that x is in front of
    const Vec3 normal = p.face_normal(f);
    const Vec3 foot = x - h * normal;
    const auto& face = p.faces[f];
    bool within = true;
    for (std::size_t i = 0; i < face.size() && within; ++i) {
      const Vec3& a = p.vertices[static_cast<std::size_t>(face[i])];
      const Vec3& b = p.vertices[static_cast<std::size_t>(face[(i + 1) % face.size()])];
      within = (b - a).cross(foot - a).dot(normal) >= 0;
    }
    if (within) {
      best = std::min(best, h);
      continue;
    }
    for (std::size_t i = 0; i < face.size(); ++i)
      best = std::min(best, detail::point_segment_distance(x, p.vertices[static_cast<std::size_t>(face[i])],
                                                           p.vertices[static_cast<std::size_t>(face[(i + 1) % face.size()])]));
  }
  return best;
}

/// Separation (m) of two convex polyhedra by the separating-axis theorem over the face normals of both and the
/// cross products of their edge directions: the largest gap between their projections on any of these axes.
/// Positive: the blocks are apart by at least that much; zero: they touch; negative: they overlap, and its size
/// is the depth of penetration (the shortest translation that separates them).
inline double separation(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  double best = -std::numeric_limits<double>::infinity();
  auto test = [&](const Vec3& axis) {
    const auto [alo, ahi] = projection(a, axis);
    const auto [blo, bhi] = projection(b, axis);
    best = std::max(best, std::max(blo - ahi, alo - bhi));
  };
  for (std::size_t f = 0; f < a.faces.size(); ++f) test(a.face_normal(f));
  for (std::size_t f = 0; f < b.faces.size(); ++f) test(b.face_normal(f));
  if (best > 0) return best;  // a face separates them; edge axes can only show a larger gap, not change the sign
  const auto ea = edge_directions(a), eb = edge_directions(b);
  for (const auto& u : ea)
    for (const auto& v : eb) {
      const Vec3 axis = u.cross(v);
      if (axis.norm() > 1e-9) test(axis.normalized());
    }
  return best;
}

}  // namespace blockdem::geometry
