#pragma once
// Meshing of a convex block into constant-strain tetrahedra with a maximum edge length (paper Sect. 3.1-3.2): a
// structured grid of the hexahedron's trilinear map, each cell split into the 6 tetrahedra of Kuhn's split (conforming
// across cells, nodes shared), for any block with the topology of a hexahedron; a triangular prism with short ends in
// layers along its length (3 tetrahedra each: the infill's wedges); other convex polyhedra are fanned
// from the centroid over their triangulated faces and refined uniformly (each tetrahedron into 8, Bey's red
// refinement, conforming) until every edge is short enough. A quality check rejects degenerate tetrahedra.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"

namespace blockdem::geometry {

using Tetrahedron = std::array<std::uint32_t, 4>;  // node indices, positive volume ((x1-x0) x (x2-x0) . (x3-x0) > 0)

/// A tetrahedral mesh of one block: shared nodes, tetrahedra, and the boundary triangles (outward winding) with the
/// face of the polyhedron each lies on.
struct TetMesh {
  std::vector<Vec3> nodes;  // m
  std::vector<Tetrahedron> tetrahedra;
  std::vector<std::array<std::uint32_t, 3>> boundary;  // counter-clockwise seen from outside
  std::vector<int> boundary_face;                      // face of the polyhedron (-1 if none was found)

  double volume(std::size_t t) const {
    const auto& e = tetrahedra[t];
    return (nodes[e[1]] - nodes[e[0]]).cross(nodes[e[2]] - nodes[e[0]]).dot(nodes[e[3]] - nodes[e[0]]) / 6.0;
  }
  double longest_edge() const {
    double l = 0;
    for (const auto& e : tetrahedra)
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) l = std::max(l, (nodes[e[static_cast<std::size_t>(i)]] - nodes[e[static_cast<std::size_t>(j)]]).norm());
    return l;
  }
};

/// Quality 6 sqrt(2) V / l_max^3 of a tetrahedron: 1 for the regular one, 0.27 for Kuhn's, 0 when flat.
inline double tetrahedron_quality(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  const double v = (x1 - x0).cross(x2 - x0).dot(x3 - x0) / 6.0;
  const std::array<Vec3, 4> x{x0, x1, x2, x3};
  double l = 0;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i + 1; j < 4; ++j) l = std::max(l, (x[i] - x[j]).norm());
  return l > 0 ? 6.0 * std::sqrt(2.0) * v / (l * l * l) : 0.0;
}

/// Tetrahedra below this quality are rejected as degenerate.
inline constexpr double min_tetrahedron_quality = 1e-3;

/// Throws InvalidArgument naming the block and the tetrahedron if one is inverted or degenerate (quality below
/// min_tetrahedron_quality) or refers to a node that does not exist.
inline void check_mesh_quality(const TetMesh& mesh, const std::string& name) {
  for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t) {
    const auto& e = mesh.tetrahedra[t];
    for (auto n : e)
      if (n >= mesh.nodes.size())
        throw InvalidArgument("block '" + name + "': tetrahedron " + std::to_string(t) + " refers to node " +
                              std::to_string(n) + ", outside 0.." + std::to_string(mesh.nodes.size() - 1));
    const double q = tetrahedron_quality(mesh.nodes[e[0]], mesh.nodes[e[1]], mesh.nodes[e[2]], mesh.nodes[e[3]]);
    if (!(q >= min_tetrahedron_quality))
      throw InvalidArgument("block '" + name + "': tetrahedron " + std::to_string(t) + " is degenerate or inverted (volume " +
                            std::to_string(mesh.volume(t)) + " m^3, quality 6 sqrt(2) V / l_max^3 = " + std::to_string(q) +
                            ", must be >= " + std::to_string(min_tetrahedron_quality) + ")");
  }
}

namespace detail {

inline void orient(TetMesh& m) {
  for (std::size_t t = 0; t < m.tetrahedra.size(); ++t)
    if (m.volume(t) < 0) std::swap(m.tetrahedra[t][2], m.tetrahedra[t][3]);
}

/// Boundary triangles: tetrahedron faces used once, wound outward, tagged with the polyhedron face they lie on.
inline void find_boundary(TetMesh& m, const ConvexPolyhedron& p) {
  std::map<std::array<std::uint32_t, 3>, std::pair<int, std::array<std::uint32_t, 4>>> faces;
  static constexpr int local[4][4] = {{1, 2, 3, 0}, {0, 3, 2, 1}, {0, 1, 3, 2}, {0, 2, 1, 3}};  // outward, then opposite
  for (const auto& e : m.tetrahedra)
    for (const auto& l : local) {
      std::array<std::uint32_t, 3> key{e[static_cast<std::size_t>(l[0])], e[static_cast<std::size_t>(l[1])], e[static_cast<std::size_t>(l[2])]};
      std::sort(key.begin(), key.end());
      auto [it, fresh] = faces.try_emplace(key, 0, std::array<std::uint32_t, 4>{});
      ++it->second.first;
      if (fresh)
        it->second.second = {e[static_cast<std::size_t>(l[0])], e[static_cast<std::size_t>(l[1])], e[static_cast<std::size_t>(l[2])],
                             e[static_cast<std::size_t>(l[3])]};
    }
  const double tol = 1e-9 * std::max(1.0, p.diameter());
  for (const auto& [key, value] : faces) {
    if (value.first != 1) continue;
    const auto& f = value.second;
    std::array<std::uint32_t, 3> tri{f[0], f[1], f[2]};
    // Outward: away from the fourth node of the tetrahedron.
    const Vec3 n = (m.nodes[tri[1]] - m.nodes[tri[0]]).cross(m.nodes[tri[2]] - m.nodes[tri[0]]);
    if (n.dot(m.nodes[f[3]] - m.nodes[tri[0]]) > 0) std::swap(tri[1], tri[2]);
    int face = -1;
    for (std::size_t k = 0; k < p.faces.size() && face < 0; ++k)
      if (std::abs(p.face_distance(k, m.nodes[tri[0]])) < tol && std::abs(p.face_distance(k, m.nodes[tri[1]])) < tol &&
          std::abs(p.face_distance(k, m.nodes[tri[2]])) < tol)
        face = static_cast<int>(k);
    m.boundary.push_back(tri);
    m.boundary_face.push_back(face);
  }
}

/// The 8 corners of p in the order of make_hexahedron (bottom counter-clockwise, then the top above them), if p has
/// the topology of a hexahedron (8 vertices, 6 quadrilateral faces).
inline bool hexahedron_corners(const ConvexPolyhedron& p, std::array<Vec3, 8>& c) {
  if (p.vertices.size() != 8 || p.faces.size() != 6) return false;
  for (const auto& f : p.faces)
    if (f.size() != 4) return false;
  std::map<int, std::vector<int>> neighbours;
  for (const auto& f : p.faces)
    for (std::size_t i = 0; i < 4; ++i) neighbours[f[i]].push_back(f[(i + 1) % 4]);
  const auto& bottom = p.faces[0];
  for (std::size_t i = 0; i < 4; ++i) {
    c[i] = p.vertices[static_cast<std::size_t>(bottom[i])];
    int top = -1;
    for (int v : neighbours[bottom[i]])
      if (std::find(bottom.begin(), bottom.end(), v) == bottom.end()) top = v;
    for (const auto& [v, ns] : neighbours)
      if (std::find(bottom.begin(), bottom.end(), v) == bottom.end() &&
          std::find(ns.begin(), ns.end(), bottom[i]) != ns.end())
        top = v;
    if (top < 0) return false;
    c[i + 4] = p.vertices[static_cast<std::size_t>(top)];
  }
  return true;
}

/// If p is a triangular prism (two triangles joined by three quadrilaterals), its corners: c[0..2] one triangle,
/// c[3..5] the other, c[i + 3] joined to c[i] by an edge.
inline bool triangular_prism_corners(const ConvexPolyhedron& p, std::array<Vec3, 6>& c) {
  if (p.vertices.size() != 6 || p.faces.size() != 5) return false;
  const std::vector<int>* bottom = nullptr;
  int triangles = 0;
  for (const auto& f : p.faces) {
    if (f.size() == 3 && ++triangles == 1) bottom = &f;
    else if (f.size() != 3 && f.size() != 4) return false;
  }
  if (triangles != 2) return false;
  std::map<int, std::vector<int>> neighbours;
  for (const auto& f : p.faces)
    for (std::size_t i = 0; i < f.size(); ++i) neighbours[f[i]].push_back(f[(i + 1) % f.size()]);
  for (std::size_t i = 0; i < 3; ++i) {
    const int b = (*bottom)[i];
    c[i] = p.vertices[static_cast<std::size_t>(b)];
    int top = -1;
    for (const auto& [v, ns] : neighbours)
      if (std::find(bottom->begin(), bottom->end(), v) == bottom->end() &&
          (std::find(ns.begin(), ns.end(), b) != ns.end() ||
           std::find(neighbours[b].begin(), neighbours[b].end(), v) != neighbours[b].end()))
        top = v;
    if (top < 0) return false;
    c[i + 3] = p.vertices[static_cast<std::size_t>(top)];
  }
  return true;
}

/// A triangular prism in n layers along its lateral edges, each layer split into 3 tetrahedra (the lateral faces
/// are the block's boundary, so the layers share only their whole triangles and the mesh conforms). For a long
/// thin prism (an infill wedge) this keeps every tetrahedron as thick as the prism, where a fan from the centroid
/// gives flat ones.
inline TetMesh layered_prism(const std::array<Vec3, 6>& c, int n) {
  TetMesh m;
  for (int k = 0; k <= n; ++k)
    for (std::size_t i = 0; i < 3; ++i) m.nodes.push_back(c[i] + (c[i + 3] - c[i]) * (double(k) / n));
  for (int k = 0; k < n; ++k) {
    const auto a = static_cast<std::uint32_t>(3 * k), b = a + 3;
    m.tetrahedra.push_back({a, a + 1, a + 2, b});
    m.tetrahedra.push_back({a + 1, a + 2, b, b + 1});
    m.tetrahedra.push_back({a + 2, b, b + 1, b + 2});
  }
  return m;
}

inline TetMesh structured_hexahedron(const std::array<Vec3, 8>& c, std::array<int, 3> n) {
  TetMesh m;
  auto map = [&](double u, double v, double w) {  // trilinear, corners 0-1-2-3 bottom (u, v), 4-7 top
    const Vec3 bottom = (1 - u) * (1 - v) * c[0] + u * (1 - v) * c[1] + u * v * c[2] + (1 - u) * v * c[3];
    const Vec3 top = (1 - u) * (1 - v) * c[4] + u * (1 - v) * c[5] + u * v * c[6] + (1 - u) * v * c[7];
    return Vec3((1 - w) * bottom + w * top);
  };
  auto id = [&](int i, int j, int k) { return static_cast<std::uint32_t>((k * (n[1] + 1) + j) * (n[0] + 1) + i); };
  for (int k = 0; k <= n[2]; ++k)
    for (int j = 0; j <= n[1]; ++j)
      for (int i = 0; i <= n[0]; ++i) m.nodes.push_back(map(double(i) / n[0], double(j) / n[1], double(k) / n[2]));
  // Kuhn's split: the 6 monotone paths from corner (0,0,0) to (1,1,1), one per permutation of the axes.
  static constexpr int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        for (const auto& a : axes) {
          std::array<int, 3> at{i, j, k};
          Tetrahedron t{};
          t[0] = id(at[0], at[1], at[2]);
          for (int s = 0; s < 3; ++s) {
            ++at[static_cast<std::size_t>(a[s])];
            t[static_cast<std::size_t>(s + 1)] = id(at[0], at[1], at[2]);
          }
          m.tetrahedra.push_back(t);
        }
  return m;
}

inline TetMesh red_refined(const TetMesh& in) {
  TetMesh m;
  m.nodes = in.nodes;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoint;
  auto mid = [&](std::uint32_t a, std::uint32_t b) {
    const auto key = std::minmax(a, b);
    auto [it, fresh] = midpoint.try_emplace({key.first, key.second}, static_cast<std::uint32_t>(m.nodes.size()));
    if (fresh) m.nodes.push_back(0.5 * (in.nodes[a] + in.nodes[b]));
    return it->second;
  };
  for (const auto& t : in.tetrahedra) {
    const std::uint32_t x0 = t[0], x1 = t[1], x2 = t[2], x3 = t[3];
    const std::uint32_t m01 = mid(x0, x1), m02 = mid(x0, x2), m03 = mid(x0, x3), m12 = mid(x1, x2), m13 = mid(x1, x3),
                        m23 = mid(x2, x3);
    for (const Tetrahedron& c : {Tetrahedron{x0, m01, m02, m03}, Tetrahedron{m01, x1, m12, m13}, Tetrahedron{m02, m12, x2, m23},
                                 Tetrahedron{m03, m13, m23, x3}, Tetrahedron{m01, m02, m03, m13}, Tetrahedron{m01, m02, m12, m13},
                                 Tetrahedron{m02, m03, m13, m23}, Tetrahedron{m02, m12, m13, m23}})
      m.tetrahedra.push_back(c);
  }
  orient(m);
  return m;
}

}  // namespace detail

/// Meshes the convex polyhedron p (world coordinates) into constant-strain tetrahedra whose edges are at most
/// max_edge (m). Throws InvalidArgument naming the block if max_edge is not positive, if more than `max_tetrahedra`
/// would be needed, or if a tetrahedron fails the quality check.
inline TetMesh mesh_convex_polyhedron(const ConvexPolyhedron& p, double max_edge, const std::string& name = "block",
                                      std::size_t max_tetrahedra = 2'000'000) {
  if (!(max_edge > 0) || !std::isfinite(max_edge))
    throw InvalidArgument("block '" + name + "': maximum edge length must be > 0 m, got " + std::to_string(max_edge));
  TetMesh m;
  std::array<Vec3, 8> c;
  std::array<Vec3, 6> prism;
  auto short_ends = [&] {  // both triangles' edges within max_edge: layers alone are enough
    for (std::size_t i = 0; i < 3; ++i)
      if ((prism[i] - prism[(i + 1) % 3]).norm() > max_edge * (1 + 1e-9) ||
          (prism[i + 3] - prism[(i + 1) % 3 + 3]).norm() > max_edge * (1 + 1e-9))
        return false;
    return true;
  };
  if (detail::triangular_prism_corners(p, prism) && short_ends()) {
    double length = 0;
    for (std::size_t i = 0; i < 3; ++i) length = std::max(length, (prism[i + 3] - prism[i]).norm());
    int n = std::max(1, static_cast<int>(std::ceil(length / max_edge - 1e-9)));
    for (m = detail::layered_prism(prism, n); m.longest_edge() > max_edge * (1 + 1e-9); m = detail::layered_prism(prism, ++n))
      if (3.0 * n > double(max_tetrahedra))
        throw InvalidArgument("block '" + name + "': a maximum edge of " + std::to_string(max_edge) + " m needs more than " +
                              std::to_string(max_tetrahedra) + " tetrahedra");
  } else if (detail::hexahedron_corners(p, c)) {
    // Divisions along u, v, w from the longest of the four parallel edges; refined until the cells' diagonals (edges
    // of Kuhn's tetrahedra) also fit.
    auto longest = [&](int a, int b, int d, int e, int f, int g, int h, int k) {
      return std::max({(c[static_cast<std::size_t>(a)] - c[static_cast<std::size_t>(b)]).norm(), (c[static_cast<std::size_t>(d)] - c[static_cast<std::size_t>(e)]).norm(),
                       (c[static_cast<std::size_t>(f)] - c[static_cast<std::size_t>(g)]).norm(), (c[static_cast<std::size_t>(h)] - c[static_cast<std::size_t>(k)]).norm()});
    };
    const std::array<double, 3> length{longest(0, 1, 3, 2, 4, 5, 7, 6), longest(0, 3, 1, 2, 4, 7, 5, 6), longest(0, 4, 1, 5, 2, 6, 3, 7)};
    std::array<int, 3> n{};
    for (std::size_t a = 0; a < 3; ++a) n[a] = std::max(1, static_cast<int>(std::ceil(length[a] / max_edge - 1e-9)));
    for (;;) {
      const double cells = double(n[0]) * n[1] * n[2];
      if (6 * cells > double(max_tetrahedra))
        throw InvalidArgument("block '" + name + "': a maximum edge of " + std::to_string(max_edge) + " m needs more than " +
                              std::to_string(max_tetrahedra) + " tetrahedra");
      m = detail::structured_hexahedron(c, n);
      const double l = m.longest_edge();
      if (l <= max_edge * (1 + 1e-9)) break;
      // Refine the direction whose cell size is largest relative to the limit.
      std::size_t worst = 0;
      for (std::size_t a = 1; a < 3; ++a)
        if (length[a] / n[a] > length[worst] / n[worst]) worst = a;
      ++n[worst];
    }
  } else {
    const Vec3 centre = p.centroid_of_vertices();
    m.nodes = p.vertices;
    m.nodes.push_back(centre);
    const auto apex = static_cast<std::uint32_t>(p.vertices.size());
    for (const auto& f : p.faces)
      for (std::size_t i = 1; i + 1 < f.size(); ++i)
        m.tetrahedra.push_back({static_cast<std::uint32_t>(f[0]), static_cast<std::uint32_t>(f[i]),
                                static_cast<std::uint32_t>(f[i + 1]), apex});
    detail::orient(m);
    while (m.longest_edge() > max_edge * (1 + 1e-9)) {
      if (8 * m.tetrahedra.size() > max_tetrahedra)
        throw InvalidArgument("block '" + name + "': a maximum edge of " + std::to_string(max_edge) + " m needs more than " +
                              std::to_string(max_tetrahedra) + " tetrahedra");
      m = detail::red_refined(m);
    }
  }
  detail::orient(m);
  check_mesh_quality(m, name);
  detail::find_boundary(m, p);
  return m;
}

}  // namespace blockdem::geometry
