#pragma once
// Convex polyhedra: vertices and faces (vertex indices counter-clockwise seen from outside), their validation and
// the planes, normals and areas the contact detection needs.

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"

namespace blockdem::geometry {

struct ConvexPolyhedron {
  std::vector<Vec3> vertices;             // m
  std::vector<std::vector<int>> faces;    // vertex indices, counter-clockwise seen from outside

  /// Area-weighted outward normal of face f (Newell's method), of length 2 * area.
  Vec3 face_area_vector(std::size_t f) const {
    Vec3 n = Vec3::Zero();
    const auto& face = faces[f];
    for (std::size_t i = 0; i < face.size(); ++i) {
      const Vec3& p = vertices[static_cast<std::size_t>(face[i])];
      const Vec3& q = vertices[static_cast<std::size_t>(face[(i + 1) % face.size()])];
      n += p.cross(q);
    }
    return n;
  }
  Vec3 face_normal(std::size_t f) const { return face_area_vector(f).normalized(); }
  double face_area(std::size_t f) const { return 0.5 * face_area_vector(f).norm(); }
  Vec3 face_centroid(std::size_t f) const {  // vertex average: enough for planes of convex faces
    Vec3 c = Vec3::Zero();
    for (int v : faces[f]) c += vertices[static_cast<std::size_t>(v)];
    return c / static_cast<double>(faces[f].size());
  }
  /// Signed distance of x from the plane of face f, positive outside.
  double face_distance(std::size_t f, const Vec3& x) const { return face_normal(f).dot(x - face_centroid(f)); }

  Vec3 centroid_of_vertices() const {
    Vec3 c = Vec3::Zero();
    for (const auto& v : vertices) c += v;
    return c / static_cast<double>(vertices.size());
  }
  /// Largest distance between two vertices.
  double diameter() const {
    double d = 0;
    for (const auto& a : vertices)
      for (const auto& b : vertices) d = std::max(d, (a - b).norm());
    return d;
  }

  /// The same polyhedron moved: x -> rotation x + translation.
  ConvexPolyhedron transformed(const Mat3& rotation, const Vec3& translation) const {
    ConvexPolyhedron p = *this;
    for (auto& v : p.vertices) v = rotation * v + translation;
    return p;
  }

  /// Throws InvalidArgument naming `name` unless the polyhedron is closed (every edge shared by exactly two faces
  /// in opposite directions), has planar faces, outward normals and is convex, all within `tolerance` (m).
  void validate(std::string_view name, double tolerance = 1e-9) const {
    auto fail = [&](const std::string& what) {
      throw InvalidArgument("block '" + std::string(name) + "': " + what);
    };
    if (vertices.size() < 4) fail("a polyhedron needs at least 4 vertices, it has " + std::to_string(vertices.size()));
    if (faces.size() < 4) fail("a polyhedron needs at least 4 faces, it has " + std::to_string(faces.size()));
    const double scale = std::max(diameter(), 1e-300);
    const double tol = tolerance * std::max(1.0, scale);
    std::map<std::pair<int, int>, int> edges;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const auto& face = faces[f];
      if (face.size() < 3) fail("face " + std::to_string(f) + " has fewer than 3 vertices");
      for (int v : face)
        if (v < 0 || static_cast<std::size_t>(v) >= vertices.size())
          fail("face " + std::to_string(f) + " refers to vertex " + std::to_string(v) + ", outside 0.." +
               std::to_string(vertices.size() - 1));
      if (face_area(f) <= tol * tol) fail("face " + std::to_string(f) + " has zero area");
      for (std::size_t i = 0; i < face.size(); ++i) {
        const int a = face[i];
        const int b = face[(i + 1) % face.size()];
        if (++edges[{a, b}] > 1) fail("edge " + std::to_string(a) + "-" + std::to_string(b) + " is used twice in the same direction (faces not consistently oriented)");
      }
      for (int v : face)
        if (std::abs(face_distance(f, vertices[static_cast<std::size_t>(v)])) > tol)
          fail("face " + std::to_string(f) + " is not planar");
    }
    for (const auto& [edge, count] : edges)
      if (!edges.count({edge.second, edge.first}))
        fail("edge " + std::to_string(edge.first) + "-" + std::to_string(edge.second) + " belongs to one face only (the polyhedron is open)");
    for (std::size_t f = 0; f < faces.size(); ++f)
      for (std::size_t v = 0; v < vertices.size(); ++v)
        if (face_distance(f, vertices[v]) > tol)
          fail("not convex (or normals point inward): vertex " + std::to_string(v) + " lies " +
               std::to_string(face_distance(f, vertices[v])) + " m outside face " + std::to_string(f));
  }
};

/// A hexahedron from its 8 corners: c[0..3] the bottom face counter-clockwise seen from above, c[4..7] the top
/// corners above c[0..3]. Boxes, voussoirs and bricks are hexahedra.
inline ConvexPolyhedron make_hexahedron(const std::array<Vec3, 8>& c) {
  ConvexPolyhedron p;
  p.vertices.assign(c.begin(), c.end());
  p.faces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  // Corners given clockwise instead: turn every face around so that the normals point outward.
  const Vec3 o = p.centroid_of_vertices();
  double volume = 0;
  for (const auto& face : p.faces)
    for (std::size_t i = 1; i + 1 < face.size(); ++i)
      volume += (p.vertices[static_cast<std::size_t>(face[0])] - o)
                    .dot((p.vertices[static_cast<std::size_t>(face[i])] - o)
                             .cross(p.vertices[static_cast<std::size_t>(face[i + 1])] - o));
  if (volume < 0)
    for (auto& face : p.faces) std::reverse(face.begin(), face.end());
  return p;
}

/// A prism: the planar convex polygon `base` (in either winding) swept along `extrusion`, which must not lie in
/// its plane. Vault blocks, infill slices and beams are prisms.
inline ConvexPolyhedron make_prism(const std::vector<Vec3>& base, const Vec3& extrusion) {
  const int n = static_cast<int>(base.size());
  ConvexPolyhedron p;
  p.vertices = base;
  for (const auto& v : base) p.vertices.push_back(v + extrusion);
  std::vector<int> bottom, top;
  for (int i = 0; i < n; ++i) {
    bottom.push_back(n - 1 - i);
    top.push_back(n + i);
    p.faces.push_back({i, (i + 1) % n, n + (i + 1) % n, n + i});
  }
  p.faces.push_back(bottom);
  p.faces.push_back(top);
  // Winding such that the bottom's normal points against the extrusion: otherwise turn every face around.
  Vec3 area = Vec3::Zero();
  for (int i = 0; i < n; ++i) area += base[static_cast<std::size_t>(i)].cross(base[static_cast<std::size_t>((i + 1) % n)]);
  if (area.dot(extrusion) < 0)
    for (auto& face : p.faces) std::reverse(face.begin(), face.end());
  return p;
}

/// The axis-aligned box [lo, hi].
inline ConvexPolyhedron make_box(const Vec3& lo, const Vec3& hi) {
  return make_hexahedron({Vec3(lo.x(), lo.y(), lo.z()), Vec3(hi.x(), lo.y(), lo.z()), Vec3(hi.x(), hi.y(), lo.z()),
                          Vec3(lo.x(), hi.y(), lo.z()), Vec3(lo.x(), lo.y(), hi.z()), Vec3(hi.x(), lo.y(), hi.z()),
                          Vec3(hi.x(), hi.y(), hi.z()), Vec3(lo.x(), hi.y(), hi.z())});
}

}  // namespace blockdem::geometry
