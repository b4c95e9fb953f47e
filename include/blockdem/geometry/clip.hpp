#pragma once
// Clipping a convex polyhedron by a plane: the part on one side is again a convex polyhedron (an intersection of
// half-spaces), closed by a cap face in the cutting plane. Used to trim vault blocks at the groins.

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"

namespace blockdem::geometry {

/// The part of `p` where normal . x <= offset (normal need not be unit length; offset in the same units times m).
/// Vertices within `relative_tolerance` times the diameter of the plane count as on it: they are kept and no
/// cut is made next to them, so a plane through a vertex, an edge or a face does not create slivers of zero size.
/// Returns `p` unchanged if no vertex lies beyond the plane, and an empty polyhedron (no vertices) if nothing
/// of positive volume remains.
inline ConvexPolyhedron clip(const ConvexPolyhedron& p, const Vec3& normal, double offset,
                             double relative_tolerance = 1e-10) {
  const double length = normal.norm();
  if (!(length > 0) || !std::isfinite(length)) throw InvalidArgument("clip: the plane normal must be a nonzero finite vector");
  const Vec3 n = normal / length;
  const double d0 = offset / length;
  const double eps = relative_tolerance * std::max(p.diameter(), 1e-300);
  std::vector<double> d(p.vertices.size());
  bool any_inside = false, any_outside = false;
  for (std::size_t i = 0; i < p.vertices.size(); ++i) {
    d[i] = n.dot(p.vertices[i]) - d0;
    any_outside = any_outside || d[i] > eps;
    any_inside = any_inside || d[i] < -eps;
  }
  if (!any_outside) return p;
  if (!any_inside) return {};

  ConvexPolyhedron out;
  std::vector<int> kept(p.vertices.size(), -1);
  std::vector<bool> on_plane;  // per vertex of `out`
  for (std::size_t i = 0; i < p.vertices.size(); ++i)
    if (d[i] <= eps) {
      kept[i] = static_cast<int>(out.vertices.size());
      out.vertices.push_back(p.vertices[i]);
      on_plane.push_back(d[i] >= -eps);
    }
  std::map<std::pair<int, int>, int> cut;  // edge (lower, higher vertex index) -> new vertex on the plane
  auto cut_point = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    if (const auto found = cut.find(key); found != cut.end()) return found->second;
    const double t = d[static_cast<std::size_t>(a)] / (d[static_cast<std::size_t>(a)] - d[static_cast<std::size_t>(b)]);
    const Vec3& pa = p.vertices[static_cast<std::size_t>(a)];
    const Vec3& pb = p.vertices[static_cast<std::size_t>(b)];
    const int index = static_cast<int>(out.vertices.size());
    out.vertices.push_back(pa + t * (pb - pa));
    on_plane.push_back(true);
    cut.emplace(key, index);
    return index;
  };
  for (const auto& face : p.faces) {
    std::vector<int> polygon;
    for (std::size_t i = 0; i < face.size(); ++i) {
      const int a = face[i];
      const int b = face[(i + 1) % face.size()];
      const double da = d[static_cast<std::size_t>(a)], db = d[static_cast<std::size_t>(b)];
      if (da <= eps) polygon.push_back(kept[static_cast<std::size_t>(a)]);
      if ((da < -eps && db > eps) || (da > eps && db < -eps)) polygon.push_back(cut_point(a, b));
    }
    if (polygon.size() >= 3) out.faces.push_back(std::move(polygon));
  }

  // The cap: every vertex on the plane that a kept face uses, counter-clockwise seen from the outside (+n).
  std::vector<bool> used(out.vertices.size(), false);
  for (const auto& face : out.faces)
    for (int v : face) used[static_cast<std::size_t>(v)] = true;
  std::vector<int> cap;
  Vec3 centre = Vec3::Zero();
  for (std::size_t v = 0; v < out.vertices.size(); ++v)
    if (used[v] && on_plane[v]) {
      cap.push_back(static_cast<int>(v));
      centre += out.vertices[v];
    }
  if (cap.size() < 3) return {};
  centre /= static_cast<double>(cap.size());
  const Vec3 t1 = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
  const Vec3 t2 = n.cross(t1);
  std::vector<std::pair<double, int>> by_angle;
  for (int v : cap) {
    const Vec3 r = out.vertices[static_cast<std::size_t>(v)] - centre;
    by_angle.emplace_back(std::atan2(r.dot(t2), r.dot(t1)), v);
  }
  std::sort(by_angle.begin(), by_angle.end());
  std::vector<int> cap_face;
  for (const auto& [angle, v] : by_angle) cap_face.push_back(v);
  out.faces.push_back(std::move(cap_face));

  // Drop the vertices beyond the plane's reach that no face uses any more, and renumber.
  std::vector<int> renumber(out.vertices.size(), -1);
  std::vector<Vec3> vertices;
  for (auto& face : out.faces)
    for (int& v : face) {
      auto& r = renumber[static_cast<std::size_t>(v)];
      if (r < 0) {
        r = static_cast<int>(vertices.size());
        vertices.push_back(out.vertices[static_cast<std::size_t>(v)]);
      }
      v = r;
    }
  out.vertices = std::move(vertices);
  if (out.faces.size() < 4 || out.vertices.size() < 4) return {};
  return out;
}

/// `p` clipped by several half-spaces normal_i . x <= offset_i in turn.
inline ConvexPolyhedron clip(ConvexPolyhedron p, const std::vector<std::pair<Vec3, double>>& half_spaces,
                             double relative_tolerance = 1e-10) {
  for (const auto& [normal, offset] : half_spaces) {
    if (p.vertices.empty()) break;
    p = clip(p, normal, offset, relative_tolerance);
  }
  return p;
}

}  // namespace blockdem::geometry
