#pragma once
// What in an imported block (geometry/imported_block.hpp) cannot be used as a rigid or deformable block, and the
// convex polyhedron of what can: coincident corners welded, triangulated faces merged into one face per plane, faces
// turned outward (said so), corners moved onto their faces' planes; refused when open, not planar within the
// tolerance, not convex (naming the worst face) or without volume. docs/geometry-import.md says what each check means.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "blockdem/core/number_text.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/imported_block.hpp"

namespace blockdem::geometry {

/// One finding of a check, about one block (or a pair, for the assembly's checks).
struct BlockIssue {
  enum class Severity { note, warning, error };  // error: the block cannot be used
  Severity severity = Severity::error;
  std::string block;   // its name
  std::string origin;  // where it is defined ("blocks.obj:12"), "" if unknown
  std::string what;    // "not convex: ...", "inward normals: turned outward"

  /// "block 'c3 u5' (walls.obj:120)", or the origin alone for a finding about no one block.
  std::string subject() const {
    if (block.empty()) return origin;
    return "block '" + block + "'" + (origin.empty() ? "" : " (" + origin + ")");
  }
  static const char* severity_name(Severity s) { return s == Severity::note ? "note" : s == Severity::warning ? "warning" : "error"; }
};

struct PolyhedronCheckOptions {
  double weld = 1e-9;        // corners closer than this fraction of the block's size are one corner
  double planarity = 1e-4;   // fraction of the block's size a corner may lie off its face's plane (or outside another
                             // face's plane, for convexity); such corners are moved onto the planes
};

namespace detail {

struct FacePlane {
  Vec3 normal;    // unit
  double offset;  // normal . x on the plane
};

/// The best-fit plane of a face through the average of its corners, its normal by Newell's method (in the face's
/// winding).
inline FacePlane fit_plane(const std::vector<Vec3>& v, const std::vector<int>& face) {
  Vec3 n = Vec3::Zero(), c = Vec3::Zero();
  for (std::size_t i = 0; i < face.size(); ++i) {
    const Vec3& p = v[static_cast<std::size_t>(face[i])];
    n += p.cross(v[static_cast<std::size_t>(face[(i + 1) % face.size()])]);
    c += p;
  }
  c /= static_cast<double>(face.size());
  const double length = n.norm();
  if (!(length > 0)) return {Vec3::Zero(), 0};
  n /= length;
  return {n, n.dot(c)};
}

inline std::string point_text(const Vec3& x) {
  std::string s(1, '(');  // appended piece by piece: "(" + std::string makes GCC 12 warn, wrongly, of an overlap
  ((((s += num(x.x())) += ", ") += num(x.y())) += ", ") += num(x.z());
  return s += ')';
}

/// The corners with those within `weld` (m) of another made one (a CAD mesh repeats a corner for each face at a
/// sharp edge), numbered in the file's order (the first of each welded set); `id` maps the file's to them.
inline std::vector<Vec3> weld_corners(const std::vector<Vec3>& x, double weld, std::vector<int>& id) {
  std::vector<std::size_t> order(x.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a].x() < x[b].x(); });
  id.assign(x.size(), -1);
  int sets = 0;
  for (std::size_t k = 0; k < order.size(); ++k) {  // sweep along x: only corners within `weld` in x can weld
    int found = -1;
    for (std::size_t j = k; j-- > 0 && x[order[j]].x() >= x[order[k]].x() - weld && found < 0;)
      if ((x[order[j]] - x[order[k]]).norm() <= weld) found = id[order[j]];
    id[order[k]] = found >= 0 ? found : sets++;
  }
  std::vector<int> renumber(static_cast<std::size_t>(sets), -1);
  std::vector<Vec3> out;
  for (std::size_t k = 0; k < x.size(); ++k) {
    auto& r = renumber[static_cast<std::size_t>(id[k])];
    if (r < 0) {
      r = static_cast<int>(out.size());
      out.push_back(x[k]);
    }
    id[k] = r;
  }
  return out;
}

/// The farthest a corner lies off its face's plane (m), and that face.
inline std::pair<double, std::size_t> worst_off_plane(const std::vector<Vec3>& v, const std::vector<std::vector<int>>& faces,
                                                      const std::vector<FacePlane>& planes) {
  std::pair<double, std::size_t> worst{0.0, 0};
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k : faces[f]) worst = std::max(worst, {std::abs(planes[f].normal.dot(v[static_cast<std::size_t>(k)]) - planes[f].offset), f});
  return worst;
}

/// The farthest a corner lies outside a face's plane (m), with the face and the corner.
inline std::tuple<double, std::size_t, std::size_t> worst_outside(const std::vector<Vec3>& v, const std::vector<FacePlane>& planes) {
  std::tuple<double, std::size_t, std::size_t> worst{0.0, 0, 0};
  for (std::size_t f = 0; f < planes.size(); ++f)
    for (std::size_t k = 0; k < v.size(); ++k) {
      const double d = planes[f].normal.dot(v[k]) - planes[f].offset;
      if (d > std::get<0>(worst)) worst = {d, f, k};
    }
  return worst;
}

/// The polyhedron of outward faces as given, its corners in their order (those no face uses left out).
inline ConvexPolyhedron as_given(const std::vector<Vec3>& v, std::vector<std::vector<int>> faces) {
  ConvexPolyhedron out;
  std::vector<int> used(v.size(), -1);
  for (const auto& face : faces)
    for (int k : face) used[static_cast<std::size_t>(k)] = 0;
  for (std::size_t k = 0; k < v.size(); ++k)
    if (used[k] >= 0) {
      used[k] = static_cast<int>(out.vertices.size());
      out.vertices.push_back(v[k]);
    }
  for (auto& face : faces) {
    for (int& k : face) k = used[static_cast<std::size_t>(k)];
    out.faces.push_back(std::move(face));
  }
  return out;
}

/// The polyhedron with one face per plane: faces on a plane (a triangulated face) merged into the polygon of their
/// corners, counter-clockwise seen from outside (sorted by angle about their average). Each plane is refitted over
/// its corners and each corner on three planes or more moved where they meet (least squares); corners on fewer (a
/// triangulation's points inside a face or along an edge) are left out. `moved`: the farthest a corner moved, m.
inline ConvexPolyhedron one_face_per_plane(std::vector<Vec3> v, const std::vector<std::vector<int>>& faces, const std::vector<int>& plane_of,
                                           std::vector<FacePlane> planes, double& moved) {
  std::vector<std::vector<int>> on_plane(planes.size());
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k : faces[f]) on_plane[static_cast<std::size_t>(plane_of[f])].push_back(k);
  std::vector<std::vector<std::size_t>> planes_of_corner(v.size());
  for (std::size_t p = 0; p < planes.size(); ++p) {
    auto& ks = on_plane[p];
    std::sort(ks.begin(), ks.end());
    ks.erase(std::unique(ks.begin(), ks.end()), ks.end());
    Vec3 c = Vec3::Zero();
    for (int k : ks) c += v[static_cast<std::size_t>(k)];
    planes[p].offset = planes[p].normal.dot(c / static_cast<double>(ks.size()));
    for (int k : ks) planes_of_corner[static_cast<std::size_t>(k)].push_back(p);
  }
  moved = 0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const auto& ps = planes_of_corner[k];
    if (ps.size() < 3) continue;
    Mat3 a = Mat3::Zero();
    Vec3 b = Vec3::Zero();
    for (auto p : ps) {
      a += planes[p].normal * planes[p].normal.transpose();
      b += planes[p].normal * planes[p].offset;
    }
    const double scale = a.trace();  // the sum of a's eigenvalues
    if (!(std::abs(a.determinant()) > 1e-6 * scale * scale * scale)) continue;  // planes meeting along a line: keep it
    const Vec3 x = a.inverse() * b;
    moved = std::max(moved, (x - v[k]).norm());
    v[k] = x;
  }
  ConvexPolyhedron out;
  std::vector<int> used(v.size(), -1);
  for (std::size_t p = 0; p < planes.size(); ++p) {
    std::vector<int> ks;
    for (int k : on_plane[p])
      if (planes_of_corner[static_cast<std::size_t>(k)].size() >= 3) ks.push_back(k);
    if (ks.size() < 3) continue;
    Vec3 c = Vec3::Zero();
    for (int k : ks) c += v[static_cast<std::size_t>(k)];
    c /= static_cast<double>(ks.size());
    const Vec3 e1 = (v[static_cast<std::size_t>(ks[0])] - c).normalized(), e2 = planes[p].normal.cross(e1);
    const auto angle = [&](int k) {
      const Vec3 d = v[static_cast<std::size_t>(k)] - c;
      return std::atan2(d.dot(e2), d.dot(e1));
    };
    std::sort(ks.begin(), ks.end(), [&](int a, int b) { return angle(a) < angle(b); });
    std::vector<int> face;
    for (int k : ks) {
      auto& u = used[static_cast<std::size_t>(k)];
      if (u < 0) {
        u = static_cast<int>(out.vertices.size());
        out.vertices.push_back(v[static_cast<std::size_t>(k)]);
      }
      face.push_back(u);
    }
    out.faces.push_back(std::move(face));
  }
  return out;
}

inline double volume(const ConvexPolyhedron& p) {  // by the divergence theorem over the outward faces, m^3
  double six_v = 0;
  for (const auto& face : p.faces)
    for (std::size_t i = 1; i + 1 < face.size(); ++i)
      six_v += p.vertices[static_cast<std::size_t>(face[0])].dot(
          p.vertices[static_cast<std::size_t>(face[i])].cross(p.vertices[static_cast<std::size_t>(face[i + 1])]));
  return six_v / 6;
}

}  // namespace detail

/// The block's convex polyhedron, or none if it cannot be used; every finding goes to `issues`.
inline std::optional<ConvexPolyhedron> check_polyhedron(const ImportedBlock& in, std::vector<BlockIssue>& issues,
                                                        const PolyhedronCheckOptions& o = {}) {
  using Severity = BlockIssue::Severity;
  auto say = [&](Severity s, const std::string& what) { issues.push_back({s, in.name, in.origin, what}); };
  auto refuse = [&](const std::string& what) -> std::optional<ConvexPolyhedron> {
    say(Severity::error, what);
    return std::nullopt;
  };
  if (in.vertices.empty() || in.faces.empty()) return refuse("no faces: not a solid");
  for (const auto& x : in.vertices)
    if (!x.allFinite()) return refuse("a corner is not a finite point");
  Vec3 lo = in.vertices.front(), hi = lo;
  for (const auto& x : in.vertices) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const double size = (hi - lo).norm();
  if (!(size > 0)) return refuse("every corner is at the same point: no volume");
  const double tol = o.planarity * size;

  // Corners welded; faces on them, without repeated corners and slivers without area.
  std::vector<int> id;
  const std::vector<Vec3> v = detail::weld_corners(in.vertices, o.weld * size, id);
  std::vector<std::vector<int>> faces;
  for (std::size_t f = 0; f < in.faces.size(); ++f) {
    std::vector<int> face;
    for (int k : in.faces[f]) {
      if (k < 0 || static_cast<std::size_t>(k) >= id.size())
        return refuse("face " + std::to_string(f + 1) + " refers to corner " + std::to_string(k + 1) + ", not in the block");
      if (face.empty() || face.back() != id[static_cast<std::size_t>(k)]) face.push_back(id[static_cast<std::size_t>(k)]);
    }
    while (face.size() > 1 && face.front() == face.back()) face.pop_back();
    if (face.size() >= 3 && detail::fit_plane(v, face).normal.squaredNorm() > 0) faces.push_back(std::move(face));
  }
  if (faces.size() < 4)
    return refuse("no volume: only " + std::to_string(faces.size()) + " faces with an area (a solid has at least 4): a flat or degenerate solid");

  // Closed: every edge shared by exactly two faces.
  {
    std::map<std::pair<int, int>, int> edges;
    for (const auto& face : faces)
      for (std::size_t i = 0; i < face.size(); ++i) ++edges[std::minmax(face[i], face[(i + 1) % face.size()])];
    std::size_t open = 0, shared = 0;
    std::pair<int, int> first_open{-1, -1};
    for (const auto& [e, count] : edges) {
      if (count == 1 && open++ == 0) first_open = e;
      if (count > 2) ++shared;
    }
    if (open > 0)
      return refuse("not closed: " + std::to_string(open) + " edge" + (open > 1 ? "s belong" : " belongs") + " to one face only (the first from " +
                    detail::point_text(v[static_cast<std::size_t>(first_open.first)]) + " to " +
                    detail::point_text(v[static_cast<std::size_t>(first_open.second)]) + ")");
    if (shared > 0) return refuse("not a single solid: " + std::to_string(shared) + " edges are shared by more than two faces");
  }

  // Planar faces.
  std::vector<detail::FacePlane> planes;
  for (const auto& face : faces) planes.push_back(detail::fit_plane(v, face));
  const auto [off_plane, bent_face] = detail::worst_off_plane(v, faces, planes);
  if (off_plane > tol)
    return refuse("face " + std::to_string(bent_face + 1) + " is not planar: a corner lies " + num(off_plane) + " m off its plane (tolerance " +
                  num(tol) + " m): split it into triangles or flatten it");

  // Outward: for a convex block each face's normal points away from its inside (the corners' average).
  Vec3 centre = Vec3::Zero();
  for (const auto& x : v) centre += x;
  centre /= static_cast<double>(v.size());
  std::size_t inward = 0;
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (planes[f].normal.dot(centre) > planes[f].offset) {
      std::reverse(faces[f].begin(), faces[f].end());
      planes[f] = {-planes[f].normal, -planes[f].offset};
      ++inward;
    }

  // Convex: no corner outside any face's plane.
  if (const auto [outside, face, corner] = detail::worst_outside(v, planes); outside > tol)
    return refuse("not convex: corner " + detail::point_text(v[corner]) + " lies " + num(outside) + " m outside the plane of face " +
                  std::to_string(face + 1) + " (the worst face); split the block into convex parts in the CAD model");
  if (inward == faces.size())
    say(Severity::warning, "inward normals: every face pointed inward; turned outward");
  else if (inward > 0)
    say(Severity::warning, "inward normals: " + std::to_string(inward) + " of " + std::to_string(faces.size()) + " faces pointed inward; turned outward");

  // Faces on one plane (a triangulated face) become one face; corners off their planes by less than the tolerance are
  // moved onto them. A block needing neither keeps its corners' and faces' order: written and read back, it is the
  // block bit for bit.
  std::vector<int> plane_of(faces.size(), -1);
  std::vector<detail::FacePlane> distinct;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (std::size_t p = 0; p < distinct.size() && plane_of[f] < 0; ++p)
      if (distinct[p].normal.dot(planes[f].normal) > 1 - 1e-9 && std::abs(distinct[p].offset - planes[f].offset) <= tol)
        plane_of[f] = static_cast<int>(p);
    if (plane_of[f] < 0) {
      plane_of[f] = static_cast<int>(distinct.size());
      distinct.push_back(planes[f]);
    }
  }
  ConvexPolyhedron out;
  if (distinct.size() == faces.size() && off_plane <= 1e-12 * size) {
    out = detail::as_given(v, std::move(faces));
  } else {
    if (distinct.size() < faces.size())
      say(Severity::note, std::to_string(faces.size()) + " faces on " + std::to_string(distinct.size()) + " planes: merged into one face per plane");
    double moved = 0;
    out = detail::one_face_per_plane(v, faces, plane_of, distinct, moved);
    if (moved > 1e-12 * size) say(Severity::note, "corners moved onto their faces' planes by up to " + num(moved) + " m");
  }
  if (const double vol = detail::volume(out); !(vol > 1e-9 * size * size * size))
    return refuse("no volume (" + num(vol) + " m^3): a flat or degenerate solid");
  try {
    out.validate(in.name);
  } catch (const InvalidArgument& e) {
    return refuse(std::string("cannot be made a convex polyhedron: ") + e.what());
  }
  return out;
}

}  // namespace blockdem::geometry
