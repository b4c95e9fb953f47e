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

}  // namespace detail

/// The block's convex polyhedron, or none if it cannot be used; every finding goes to `issues`.
inline std::optional<ConvexPolyhedron> check_polyhedron(const ImportedBlock& in, std::vector<BlockIssue>& issues,
                                                        const PolyhedronCheckOptions& o = {}) {
  using Severity = BlockIssue::Severity;
  bool usable = true;
  auto say = [&](Severity s, const std::string& what) {
    issues.push_back({s, in.name, in.origin, what});
    if (s == Severity::error) usable = false;
  };
  if (in.vertices.empty() || in.faces.empty()) {
    say(Severity::error, "no faces: not a solid");
    return std::nullopt;
  }
  for (const auto& x : in.vertices)
    if (!x.allFinite()) {
      say(Severity::error, "a corner is not a finite point");
      return std::nullopt;
    }
  Vec3 lo = in.vertices.front(), hi = lo;
  for (const auto& x : in.vertices) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const double size = (hi - lo).norm();
  if (!(size > 0)) {
    say(Severity::error, "every corner is at the same point: no volume");
    return std::nullopt;
  }
  const double weld = o.weld * size, tol = o.planarity * size;

  // Weld coincident corners (a CAD mesh repeats a corner for each face at a sharp edge), in sorted order along x.
  std::vector<int> id(in.vertices.size());
  std::vector<Vec3> v;
  {
    std::vector<std::size_t> order(in.vertices.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return in.vertices[a].x() < in.vertices[b].x(); });
    std::vector<std::size_t> first_of;  // the kept corner's index in `order` terms
    for (std::size_t k = 0; k < order.size(); ++k) {
      const Vec3& x = in.vertices[order[k]];
      int found = -1;
      for (std::size_t j = k; j-- > 0 && in.vertices[order[j]].x() >= x.x() - weld;)
        if ((in.vertices[order[j]] - x).norm() <= weld) {
          found = id[order[j]];
          break;
        }
      if (found < 0) {
        found = static_cast<int>(v.size());
        v.push_back(x);
      }
      id[order[k]] = found;
    }
    // Numbered in the file's order again (the first of each welded set), so that a clean block keeps its order.
    std::vector<int> renumber(v.size(), -1);
    std::vector<Vec3> in_order;
    for (auto& k : id) {
      auto& r = renumber[static_cast<std::size_t>(k)];
      if (r < 0) {
        r = static_cast<int>(in_order.size());
        in_order.push_back(v[static_cast<std::size_t>(k)]);
      }
      k = r;
    }
    v = std::move(in_order);
  }
  std::vector<std::vector<int>> faces;
  for (std::size_t f = 0; f < in.faces.size(); ++f) {
    std::vector<int> face;
    for (int k : in.faces[f]) {
      if (k < 0 || static_cast<std::size_t>(k) >= id.size()) {
        say(Severity::error, "face " + std::to_string(f + 1) + " refers to corner " + std::to_string(k + 1) + ", not in the block");
        return std::nullopt;
      }
      if (face.empty() || face.back() != id[static_cast<std::size_t>(k)]) face.push_back(id[static_cast<std::size_t>(k)]);
    }
    while (face.size() > 1 && face.front() == face.back()) face.pop_back();
    if (face.size() < 3 || !(detail::fit_plane(v, face).normal.squaredNorm() > 0)) continue;  // a sliver: no area
    faces.push_back(std::move(face));
  }
  if (faces.size() < 4) {
    say(Severity::error, "no volume: only " + std::to_string(faces.size()) + " faces with an area (a solid has at least 4): a flat or degenerate solid");
    return std::nullopt;
  }

  // Closed: every edge shared by exactly two faces.
  {
    std::map<std::pair<int, int>, int> edges;
    for (const auto& face : faces)
      for (std::size_t i = 0; i < face.size(); ++i) {
        const int a = face[i], b = face[(i + 1) % face.size()];
        ++edges[{std::min(a, b), std::max(a, b)}];
      }
    std::size_t open = 0, shared = 0;
    std::pair<int, int> first_open{-1, -1};
    for (const auto& [e, count] : edges) {
      if (count == 1 && open++ == 0) first_open = e;
      if (count > 2) ++shared;
    }
    if (open > 0)
      say(Severity::error, "not closed: " + std::to_string(open) + " edge" + (open > 1 ? "s belong" : " belongs") +
                               " to one face only (the first from " + detail::point_text(v[static_cast<std::size_t>(first_open.first)]) +
                               " to " + detail::point_text(v[static_cast<std::size_t>(first_open.second)]) + ")");
    if (shared > 0) say(Severity::error, "not a single solid: " + std::to_string(shared) + " edges are shared by more than two faces");
    if (!usable) return std::nullopt;
  }

  // Planar faces.
  std::vector<detail::FacePlane> planes;
  double off_plane = 0;  // m, the farthest a corner lies off its face's plane
  {
    double& worst = off_plane;
    std::size_t worst_face = 0;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      planes.push_back(detail::fit_plane(v, faces[f]));
      for (int k : faces[f]) {
        const double d = std::abs(planes[f].normal.dot(v[static_cast<std::size_t>(k)]) - planes[f].offset);
        if (d > worst) {
          worst = d;
          worst_face = f;
        }
      }
    }
    if (worst > tol) {
      say(Severity::error, "face " + std::to_string(worst_face + 1) + " is not planar: a corner lies " + num(worst) +
                               " m off its plane (tolerance " + num(tol) + " m): split it into triangles or flatten it");
      return std::nullopt;
    }
  }

  // Outward: for a convex block each face's normal points away from the block's inside (the corners' average).
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
  {
    double worst = 0;
    std::size_t worst_face = 0, worst_vertex = 0;
    for (std::size_t f = 0; f < faces.size(); ++f)
      for (std::size_t k = 0; k < v.size(); ++k) {
        const double d = planes[f].normal.dot(v[k]) - planes[f].offset;
        if (d > worst) {
          worst = d;
          worst_face = f;
          worst_vertex = k;
        }
      }
    if (worst > tol) {
      say(Severity::error, "not convex: corner " + detail::point_text(v[worst_vertex]) + " lies " + num(worst) +
                               " m outside the plane of face " + std::to_string(worst_face + 1) +
                               " (the worst face); split the block into convex parts in the CAD model");
      return std::nullopt;
    }
  }
  if (inward == faces.size())
    say(Severity::warning, "inward normals: every face pointed inward; turned outward");
  else if (inward > 0)
    say(Severity::warning, "inward normals: " + std::to_string(inward) + " of " + std::to_string(faces.size()) +
                               " faces pointed inward; turned outward");

  // One face per plane: faces whose planes coincide (a triangulated face) merge into the polygon of their corners.
  std::vector<int> plane_of(faces.size(), -1);
  std::vector<detail::FacePlane> merged;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (std::size_t p = 0; p < merged.size() && plane_of[f] < 0; ++p)
      if (merged[p].normal.dot(planes[f].normal) > 1 - 1e-9 && std::abs(merged[p].offset - planes[f].offset) <= tol)
        plane_of[f] = static_cast<int>(p);
    if (plane_of[f] < 0) {
      plane_of[f] = static_cast<int>(merged.size());
      merged.push_back(planes[f]);
    }
  }
  // Volume (by the divergence theorem over the outward faces) and validity of the polyhedron made.
  const auto finish = [&](ConvexPolyhedron out) -> std::optional<ConvexPolyhedron> {
    double volume = 0;
    for (const auto& face : out.faces)
      for (std::size_t i = 1; i + 1 < face.size(); ++i)
        volume += out.vertices[static_cast<std::size_t>(face[0])].dot(
            out.vertices[static_cast<std::size_t>(face[i])].cross(out.vertices[static_cast<std::size_t>(face[i + 1])]));
    volume /= 6;
    if (!(volume > 1e-9 * size * size * size)) {
      say(Severity::error, "no volume (" + num(volume) + " m^3): a flat or degenerate solid");
      return std::nullopt;
    }
    try {
      out.validate(in.name);
    } catch (const InvalidArgument& e) {
      say(Severity::error, std::string("cannot be made a convex polyhedron: ") + e.what());
      return std::nullopt;
    }
    return out;
  };
  ConvexPolyhedron out;
  if (merged.size() == faces.size() && off_plane <= 1e-12 * size) {
    // Nothing to merge or move: the block as given (welded, faces outward), corners and faces in the file's order, so
    // that a block written and read back is the block bit for bit.
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
    return finish(std::move(out));
  }
  if (merged.size() < faces.size())
    say(Severity::note, std::to_string(faces.size()) + " faces on " + std::to_string(merged.size()) + " planes: merged into one face per plane");
  // Refit each plane over all its faces' corners, then move each corner onto the planes it lies on (least squares).
  std::vector<std::vector<int>> on_plane(merged.size());
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k : faces[f]) on_plane[static_cast<std::size_t>(plane_of[f])].push_back(k);
  for (std::size_t p = 0; p < merged.size(); ++p) {
    auto& ks = on_plane[p];
    std::sort(ks.begin(), ks.end());
    ks.erase(std::unique(ks.begin(), ks.end()), ks.end());
    Vec3 c = Vec3::Zero();
    for (int k : ks) c += v[static_cast<std::size_t>(k)];
    merged[p].offset = merged[p].normal.dot(c / static_cast<double>(ks.size()));
  }
  std::vector<std::vector<std::size_t>> planes_of_vertex(v.size());
  for (std::size_t p = 0; p < merged.size(); ++p)
    for (int k : on_plane[p]) planes_of_vertex[static_cast<std::size_t>(k)].push_back(p);
  double moved = 0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const auto& ps = planes_of_vertex[k];
    if (ps.size() < 3) continue;  // on no corner of the solid (a corner of a triangulation inside a face)
    Mat3 a = Mat3::Zero();
    Vec3 b = Vec3::Zero();
    for (auto p : ps) {
      a += merged[p].normal * merged[p].normal.transpose();
      b += merged[p].normal * merged[p].offset;
    }
    const double scale = a.trace();  // the sum of the eigenvalues of a (>= 3 unit normals)
    if (!(std::abs(a.determinant()) > 1e-6 * scale * scale * scale)) continue;  // planes meeting along a line: keep it
    const Vec3 x = a.inverse() * b;
    moved = std::max(moved, (x - v[k]).norm());
    v[k] = x;
  }
  if (moved > 1e-12 * size) say(Severity::note, "corners moved onto their faces' planes by up to " + num(moved) + " m");

  // Each plane's face: its corners in counter-clockwise order seen from outside (the corners of a convex face, sorted by
  // angle about their average); corners inside a merged face's outline (a triangulation's inner points) are left out.
  std::vector<int> used(v.size(), -1);
  for (std::size_t p = 0; p < merged.size(); ++p) {
    const Vec3& n = merged[p].normal;
    std::vector<int> ks;
    for (int k : on_plane[p])
      if (planes_of_vertex[static_cast<std::size_t>(k)].size() >= 3) ks.push_back(k);
    if (ks.size() < 3) continue;
    Vec3 c = Vec3::Zero();
    for (int k : ks) c += v[static_cast<std::size_t>(k)];
    c /= static_cast<double>(ks.size());
    const Vec3 e1 = (v[static_cast<std::size_t>(ks[0])] - c).normalized(), e2 = n.cross(e1);
    std::sort(ks.begin(), ks.end(), [&](int a, int b) {
      const Vec3 da = v[static_cast<std::size_t>(a)] - c, db = v[static_cast<std::size_t>(b)] - c;
      return std::atan2(da.dot(e2), da.dot(e1)) < std::atan2(db.dot(e2), db.dot(e1));
    });
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

  return finish(std::move(out));
}

}  // namespace blockdem::geometry
