#pragma once
// Automatic detection of contact between convex blocks on their common plane (Cundall 1988, paper Sect. 3.1): a
// sweep-and-prune broad phase over bounding boxes; for each close pair, the common-plane normal is the separating
// axis of least penetration among the face normals of both blocks; the best-aligned face of each block is projected
// onto that plane, the two are clipped to their overlap polygon, and contact points (CPs) are placed at its
// vertices, subdivided by a grid so that no CP carries more than a given area. Each CP gets its tributary area, a
// normal from A to B, two shear directions and its gap.
//
// That is the face-to-face contact of a joint. General contacts (the default) add those of blocks that touch with an
// edge or a vertex (model/common_plane.hpp): where the faces are not aligned, the normal is sought among the edge-edge
// directions too, and the CPs are drawn from the faces through each block's supporting vertex, edge or face. Only
// the CPs within the tolerance of both blocks are kept, so a vertex-face contact has one CP at the vertex, an
// edge-face contact two at the ends of the edge's part over the face, an edge-edge contact one at the crossing; as a
// block turns from face-face to edge-face (rocking) its CPs stay where they were, and keep their histories. Where a
// face-to-face plane is as good as the best one (blocks that meet along a line where four joints cross), it is the
// common plane; blocks that meet edge to edge with a third block between them, face to face with both, get no CPs.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/rotation.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/polygon.hpp"
#include "blockdem/model/common_plane.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem::model {

/// Which contacts the detection finds.
enum class ContactKinds {
  faces,    ///< face to face only, between faces within max_normal_angle of each other (joints of small rotations)
  general,  ///< also vertex-face, edge-face and edge-edge: blocks that rock far, tumble and collapse
};

struct ContactSettings {
  ContactKinds kinds = ContactKinds::general;
  double tolerance = 1e-3;            ///< m: faces closer than this are in contact; also the largest overlap allowed at the start
  double max_contact_point_area = 0;  ///< m^2: subdivide overlaps so that no CP carries more (0: CPs at the polygon vertices only)
  /// m^2, per pair of joint tags: a square table of tag_count x tag_count (tags 0 .. tag_count - 1) that replaces
  /// max_contact_point_area for the joints between blocks of those tags (a model's groups, analysis/structure.hpp).
  /// Empty: max_contact_point_area everywhere. See contact_point_area().
  std::vector<double> contact_point_area_by_tag;
  int tag_count = 0;
  double max_normal_angle = 0.35;     ///< rad: faces tilted more than this from the common plane are not in face-face
                                      ///< contact (20 deg); with general contacts they may be in edge or vertex contact
  double redetection_distance = 0;    ///< m: detect again once a block moved this far (0: half the tolerance)
  int redetection_check_interval = 1;   ///< steps between checks of the distance moved

  void validate() const {
    if (!(tolerance > 0)) throw InvalidArgument("contact settings: tolerance must be > 0 m");
    if (!(max_contact_point_area >= 0)) throw InvalidArgument("contact settings: max contact point area must be >= 0 m^2");
    if (!(max_normal_angle > 0 && max_normal_angle < 1.5)) throw InvalidArgument("contact settings: max normal angle must be in (0, 1.5) rad");
    if (!(redetection_distance >= 0)) throw InvalidArgument("contact settings: redetection distance must be >= 0 m");
    if (redetection_check_interval < 1) throw InvalidArgument("contact settings: redetection check interval must be >= 1 step");
    if (contact_point_area_by_tag.size() != static_cast<std::size_t>(tag_count) * static_cast<std::size_t>(tag_count))
      throw InvalidArgument("contact settings: the table of contact-point areas must hold tag_count^2 entries");
    for (const double a : contact_point_area_by_tag)
      if (!(a >= 0) || !std::isfinite(a)) throw InvalidArgument("contact settings: contact-point areas must be >= 0 m^2");
  }
  /// The largest area a CP may carry on a joint between blocks of joint tags ta and tb, m^2 (0: CPs at the corners
  /// of the overlap only).
  double contact_point_area(int ta, int tb) const {
    if (ta < 0 || tb < 0 || ta >= tag_count || tb >= tag_count) return max_contact_point_area;
    return contact_point_area_by_tag[static_cast<std::size_t>(ta) * static_cast<std::size_t>(tag_count) + static_cast<std::size_t>(tb)];
  }
  /// The largest of them all, m^2.
  double largest_contact_point_area() const {
    double largest = max_contact_point_area;
    for (const double a : contact_point_area_by_tag) largest = std::max(largest, a);
    return largest;
  }
  double redetection() const { return redetection_distance > 0 ? redetection_distance : 0.5 * tolerance; }
};

/// One contact point found by the detection, in world coordinates.
struct ContactCandidate {
  std::size_t a = 0;  // block A (the lower index)
  std::size_t b = 0;  // block B
  Vec3 position;      // m, on the common plane, midway between the two faces
  Vec3 normal;        // from A to B
  Vec3 tangent;       // first shear direction t1; t2 = normal x t1
  double area = 0;    // m^2, tributary area
  double gap = 0;     // m, positive open, negative overlap
};

namespace detail {

using geometry::Point2;
using geometry::Polygon2;
using geometry::cross2;
using geometry::clip_convex;
using geometry::polygon_centroid;

inline double polygon_area(const Polygon2& p) { return geometry::polygon_area(p); }

/// Contact points of an overlap polygon with their tributary areas: each cell (the polygon itself, or its
/// intersection with the squares of a grid of side h) is fanned from its centroid, and each fan triangle gives
/// half its area to each of its two polygon vertices. Coincident vertices of neighbouring cells are merged.
inline std::vector<std::pair<Point2, double>> tributary_points(const Polygon2& polygon, double max_area) {
  std::vector<Polygon2> cells;
  const double area = polygon_area(polygon);
  if (max_area > 0 && area / static_cast<double>(polygon.size()) > max_area) {
    const double h = std::sqrt(max_area);
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (const auto& v : polygon)
      for (int k = 0; k < 2; ++k) {
        lo[k] = std::min(lo[k], v[k]);
        hi[k] = std::max(hi[k], v[k]);
      }
    const int nx = std::max(1, static_cast<int>(std::ceil((hi[0] - lo[0]) / h - 1e-9)));
    const int ny = std::max(1, static_cast<int>(std::ceil((hi[1] - lo[1]) / h - 1e-9)));
    const double hx = (hi[0] - lo[0]) / nx;
    const double hy = (hi[1] - lo[1]) / ny;
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j) {
        const double x0 = lo[0] + i * hx, x1 = lo[0] + (i + 1) * hx;
        const double y0 = lo[1] + j * hy, y1 = lo[1] + (j + 1) * hy;
        auto cell = clip_convex(polygon, {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
        if (cell.size() >= 3 && polygon_area(cell) > 1e-12 * area) cells.push_back(std::move(cell));
      }
  } else {
    cells.push_back(polygon);
  }
  const double merge = 1e-9 * std::sqrt(std::max(area, 1e-300));
  std::vector<std::pair<Point2, double>> points;
  for (const auto& cell : cells) {
    const Point2 c = polygon_centroid(cell);
    for (std::size_t i = 0; i < cell.size(); ++i) {
      const Point2& p = cell[i];
      const Point2& q = cell[(i + 1) % cell.size()];
      const double half = 0.25 * std::abs(cross2(c, p, q));  // half of the fan triangle (c, p, q)
      for (const Point2* v : {&p, &q}) {
        auto found = std::find_if(points.begin(), points.end(), [&](const auto& e) {
          return std::abs(e.first[0] - (*v)[0]) <= merge && std::abs(e.first[1] - (*v)[1]) <= merge;
        });
        if (found == points.end())
          points.push_back({*v, half});
        else
          found->second += half;
      }
    }
  }
  return points;
}

struct FacePlanes {
  std::vector<Vec3> normal;
  std::vector<Vec3> point;
};

inline FacePlanes face_planes(const geometry::ConvexPolyhedron& p) {
  FacePlanes f;
  for (std::size_t i = 0; i < p.faces.size(); ++i) {
    f.normal.push_back(p.face_normal(i));
    f.point.push_back(p.face_centroid(i));
  }
  return f;
}

/// Largest separation of `other` from the face planes of `p`: max over faces of min over vertices of other.
inline std::pair<double, std::size_t> max_face_separation(const FacePlanes& p, const geometry::ConvexPolyhedron& other) {
  double best = -1e300;
  std::size_t best_face = 0;
  for (std::size_t f = 0; f < p.normal.size(); ++f) {
    double sep = 1e300;
    for (const auto& v : other.vertices) sep = std::min(sep, p.normal[f].dot(v - p.point[f]));
    if (sep > best) {
      best = sep;
      best_face = f;
    }
  }
  return {best, best_face};
}

/// A face plane of A or of B with a separation of at least `floor` whose faces are face to face (the other block's
/// best-aligned face within acos(cos_max) of it), the one with the largest separation: its normal (from A to B) in
/// `normal` and its separation in `separation`. False if there is none.
inline bool aligned_face_plane(const FacePlanes& pa, const geometry::ConvexPolyhedron& a, const FacePlanes& pb,
                               const geometry::ConvexPolyhedron& b, double floor, double cos_max, Vec3& normal,
                               double& separation) {
  bool found = false;
  const auto consider = [&](const FacePlanes& p, const geometry::ConvexPolyhedron& other, const FacePlanes& q, double sign) {
    for (std::size_t f = 0; f < p.normal.size(); ++f) {
      double sep = std::numeric_limits<double>::infinity();
      for (const auto& v : other.vertices) sep = std::min(sep, p.normal[f].dot(v - p.point[f]));
      if (sep < floor || (found && sep <= separation)) continue;
      double alignment = -2;  // of the other block's best-aligned face with -normal[f]
      for (const auto& n : q.normal) alignment = std::max(alignment, -n.dot(p.normal[f]));
      if (alignment < cos_max) continue;
      found = true;
      separation = sep;
      normal = sign * p.normal[f];
    }
  };
  consider(pa, b, pb, 1.0);
  consider(pb, a, pa, -1.0);
  return found;
}

inline std::size_t best_aligned_face(const FacePlanes& p, const Vec3& direction) {
  std::size_t best = 0;
  double alignment = -2;
  for (std::size_t f = 0; f < p.normal.size(); ++f) {
    const double a = p.normal[f].dot(direction);
    if (a > alignment) {
      alignment = a;
      best = f;
    }
  }
  return best;
}

/// Drops the edge CPs (out[first, last) for each range) of two blocks that touch edge to edge along a line where a
/// third block meets both face to face: eight blocks meeting at the crown line of a vault, where a block of each web
/// lies between blocks of the neighbouring webs. The third block fills the wedge between them and carries what
/// passes there; edge CPs would tie them across it like a joint. Every CP must lie on an edge of both blocks and on
/// the third block, within `tolerance`: an edge standing on a face (a sliver of infill on its anchor, a rocking block)
/// keeps its CPs. `joints`: the block pairs in face-to-face contact (a < b).
inline void drop_edge_contacts_across_a_block(std::vector<ContactCandidate>& out,
                                              const std::vector<std::pair<std::size_t, std::size_t>>& edge_ranges,
                                              const std::vector<std::pair<std::size_t, std::size_t>>& joints,
                                              const std::vector<FacePlanes>& planes, double tolerance) {
  // The face-to-face neighbours of every block, in compressed rows.
  std::vector<std::size_t> start(planes.size() + 1, 0), neighbour(2 * joints.size());
  for (const auto& [a, b] : joints) ++start[a + 1], ++start[b + 1];
  for (std::size_t i = 0; i < planes.size(); ++i) start[i + 1] += start[i];
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (const auto& [a, b] : joints) neighbour[fill[a]++] = b, neighbour[fill[b]++] = a;
  const auto touches = [&](std::size_t i, std::size_t j) {
    return std::find(neighbour.begin() + static_cast<std::ptrdiff_t>(start[i]), neighbour.begin() + static_cast<std::ptrdiff_t>(start[i + 1]), j) !=
           neighbour.begin() + static_cast<std::ptrdiff_t>(start[i + 1]);
  };
  const auto within = [&](std::size_t block, const Vec3& p, std::size_t f) {
    return std::abs(planes[block].normal[f].dot(p - planes[block].point[f])) <= tolerance;
  };
  const auto on_edge = [&](std::size_t block, const Vec3& p) {
    int faces = 0;
    for (std::size_t f = 0; f < planes[block].normal.size() && faces < 2; ++f) faces += within(block, p, f);
    return faces >= 2;
  };
  std::vector<char> drop(out.size(), 0);
  for (const auto& [first, last] : edge_ranges) {
    const std::size_t a = out[first].a, b = out[first].b;
    bool edge_to_edge = true;
    for (std::size_t i = first; i < last && edge_to_edge; ++i)
      edge_to_edge = on_edge(a, out[i].position) && on_edge(b, out[i].position);
    if (!edge_to_edge) continue;
    for (std::size_t k = start[a]; k < start[a + 1]; ++k) {
      const std::size_t c = neighbour[k];
      if (!touches(b, c)) continue;
      bool on_c = true;
      for (std::size_t i = first; i < last && on_c; ++i)
        for (std::size_t f = 0; f < planes[c].normal.size() && on_c; ++f)
          on_c = planes[c].normal[f].dot(out[i].position - planes[c].point[f]) <= tolerance;
      if (on_c) {
        std::fill(drop.begin() + static_cast<std::ptrdiff_t>(first), drop.begin() + static_cast<std::ptrdiff_t>(last), 1);
        break;
      }
    }
  }
  std::size_t kept = 0;
  for (std::size_t i = 0; i < out.size(); ++i)
    if (!drop[i]) out[kept++] = out[i];
  out.resize(kept);
}

}  // namespace detail

/// All contact points between the blocks in `bodies`. Pairs of blocks that are both fixed or base are skipped.
/// `deepest` receives the pair with the largest overlap (most negative separation), for the start-up check.
inline std::vector<ContactCandidate> detect_contacts(const RigidBodies& bodies, const ContactSettings& settings,
                                                     std::pair<std::pair<std::size_t, std::size_t>, double>* deepest = nullptr) {
  const std::size_t n = bodies.size();
  std::vector<geometry::ConvexPolyhedron> world(n);
  std::vector<detail::FacePlanes> planes(n);
  std::vector<std::vector<Vec3>> edges(n);  // edge directions, for the blocks of a general contact only
  std::vector<Vec3> lo(n), hi(n);
  for (std::size_t i = 0; i < n; ++i) {
    world[i] = bodies.world_shape(i);
    planes[i] = detail::face_planes(world[i]);
    lo[i] = Vec3::Constant(1e300);
    hi[i] = Vec3::Constant(-1e300);
    for (const auto& v : world[i].vertices) {
      lo[i] = lo[i].cwiseMin(v);
      hi[i] = hi[i].cwiseMax(v);
    }
    lo[i].array() -= settings.tolerance;
    hi[i].array() += settings.tolerance;
  }
  const auto edges_of = [&](std::size_t i) -> const std::vector<Vec3>& {
    if (edges[i].empty()) edges[i] = geometry::edge_directions(world[i]);
    return edges[i];
  };
  // Sweep and prune along x.
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lo[a].x() < lo[b].x(); });
  const double cos_max = std::cos(settings.max_normal_angle);
  const bool general = settings.kinds == ContactKinds::general;
  std::vector<ContactCandidate> out;
  std::vector<std::pair<std::size_t, std::size_t>> joints;       // general: block pairs in face-to-face contact
  std::vector<std::pair<std::size_t, std::size_t>> edge_ranges;  // general: [first, last) of out, a pair's edge CPs
  if (deepest) *deepest = {{0, 0}, 0.0};
  for (std::size_t u = 0; u < n; ++u) {
    for (std::size_t w = u + 1; w < n && lo[order[w]].x() <= hi[order[u]].x(); ++w) {
      std::size_t a = order[u], b = order[w];
      if (a > b) std::swap(a, b);
      if (bodies.motion[a] != Motion::free && bodies.motion[b] != Motion::free) continue;
      if ((lo[a].array() > hi[b].array()).any() || (lo[b].array() > hi[a].array()).any()) continue;
      const auto [sep_a, face_a] = detail::max_face_separation(planes[a], world[b]);
      const auto [sep_b, face_b] = detail::max_face_separation(planes[b], world[a]);
      double separation = std::max(sep_a, sep_b);
      if (separation > settings.tolerance) continue;
      Vec3 n_common = sep_a >= sep_b ? planes[a].normal[face_a] : Vec3(-planes[b].normal[face_b]);
      std::size_t fa = detail::best_aligned_face(planes[a], n_common);
      std::size_t fb = detail::best_aligned_face(planes[b], -n_common);
      bool face_to_face =
          planes[a].normal[fa].dot(n_common) >= cos_max && -planes[b].normal[fb].dot(n_common) >= cos_max;
      if (!face_to_face && general) {
        // Blocks that touch along a line only (four blocks meeting at a corner line, as the courses of two webs at
        // a groin) have nearly the same gap on every plane through that line: the face-to-face one among them is
        // their common plane, and its overlap, a line, makes no CP. Their neighbours across the joints carry what
        // passes there. Otherwise rounding, and the joints' own closure as the vault settles, would pick a plane
        // that a face meets at an angle, and the pair would get edge CPs as stiff as a joint's. Planes within a
        // hundredth of the tolerance count as equal: a pair pressed together along the line gets its edge CPs once
        // they overlap by about that much. Why a hundredth: the allowance must exceed what separates the planes
        // through a line contact, rounding (1e-15 m) and the joints' elastic closure as the structure settles
        // (sigma / k_n: 2.5 um for a stress of 0.1 MPa on the vault's joints, k_n = 3.9e10 Pa/m by eq. 7), and
        // stay small against the tolerance, which sets where contacts are resolved at all. At the default 1 mm it
        // is 10 um: an edge CP missed up to there would carry k_n 10 um = 0.4 MPa on the vault's joints, the
        // tensile strength's order and 4 % of the compressive one, until the overlap passes it.
        if (detail::aligned_face_plane(planes[a], world[a], planes[b], world[b], separation - 0.01 * settings.tolerance,
                                       cos_max, n_common, separation)) {
          face_to_face = true;
          fa = detail::best_aligned_face(planes[a], n_common);
          fb = detail::best_aligned_face(planes[b], -n_common);
        } else if (const CommonPlane e = best_edge_edge_plane(world[a], edges_of(a), world[b], edges_of(b));
                   e.separation > separation) {
          // Not face to face: the plane may be that of an edge of each (edge-edge), whose separation is the truer one.
          separation = e.separation;
          n_common = e.normal;
          if (separation > settings.tolerance) continue;
        }
      }
      if (deepest && separation < deepest->second) *deepest = {{a, b}, separation};
      if (!face_to_face) {
        if (!general) continue;
        // The CPs come from the faces through the features that touch the plane.
        double cos_a = 0, cos_b = 0;
        fa = supporting_face(world[a], planes[a].normal, n_common, cos_a);
        fb = supporting_face(world[b], planes[b].normal, -n_common, cos_b);
        // A face nearly perpendicular to the plane projects onto a sliver; a gap measured across it means nothing.
        // cos < 0.05 is a face within 3 degrees of perpendicular: its projection is under 5 % of its width wide,
        // and its CPs' tributary areas would change by their whole size with a rotation of 3 degrees, which
        // blocks in contact turn through between detections in a rocking or a collapse. The supporting face is
        // the best aligned of the faces through the block's vertex furthest along the normal, so this is a vertex
        // with no face that faces the plane (a needle's tip, an edge of two faces both near perpendicular): no
        // area to draw CPs from.
        if (cos_a < 0.05 || cos_b < 0.05) continue;
      }

      // 2D frame on the common plane: t1 along the longest edge of A's face.
      const auto& face = world[a].faces[fa];
      Vec3 t1 = Vec3::Zero();
      for (std::size_t i = 0; i < face.size(); ++i) {
        Vec3 e = world[a].vertices[static_cast<std::size_t>(face[(i + 1) % face.size()])] -
                 world[a].vertices[static_cast<std::size_t>(face[i])];
        e -= e.dot(n_common) * n_common;
        if (e.squaredNorm() > t1.squaredNorm()) t1 = e;
      }
      t1.normalize();
      const Vec3 t2 = n_common.cross(t1);
      const Vec3 origin = planes[a].point[fa];
      auto project = [&](const geometry::ConvexPolyhedron& p, std::size_t f, bool reverse) {
        detail::Polygon2 poly;
        for (int v : p.faces[f]) {
          const Vec3 d = p.vertices[static_cast<std::size_t>(v)] - origin;
          poly.push_back({d.dot(t1), d.dot(t2)});
        }
        if (reverse) std::reverse(poly.begin(), poly.end());
        return poly;
      };
      // Corners only where edges of the two faces nearly coincide (geometry::drop_shallow_vertices): features
      // finer than a quarter of the tolerance are not resolved, and the CPs stay where they are between detections.
      // Why a quarter: the blocks move up to the re-detection distance (half the tolerance by default) between
      // detections, so a finer feature of the overlap is below what a detection resolves; dropping a vertex
      // within tolerance / 4 of its chord changes the overlap's area by at most tolerance / 8 times that chord
      // (a triangle's area), a sliver of the joint, and moves no CP by more than tolerance / 4.
      const auto overlap = geometry::drop_shallow_vertices(
          detail::clip_convex(project(world[a], fa, false), project(world[b], fb, true)), 0.25 * settings.tolerance,
          settings.max_normal_angle);
      if (overlap.size() < 3 || detail::polygon_area(overlap) <= 1e-12 * world[a].face_area(fa)) continue;

      const Vec3 na = planes[a].normal[fa], nb = planes[b].normal[fb];
      const Vec3 ca = planes[a].point[fa], cb = planes[b].point[fb];
      const std::size_t first = out.size();
      for (const auto& [uv, area] : detail::tributary_points(overlap, settings.contact_point_area(bodies.joint_tag[a], bodies.joint_tag[b]))) {
        const Vec3 p = origin + uv[0] * t1 + uv[1] * t2;
        const double s_a = na.dot(ca - p) / na.dot(n_common);  // p + s n lies on A's face plane
        const double s_b = nb.dot(cb - p) / nb.dot(n_common);
        // Only where the faces are within the tolerance: a face touching along an edge (a rocking block, a vault
        // block on a tilted neighbour) has part of its overlap wide open, and a CP there would be a spring
        // stretched across the gap.
        if (s_b - s_a > settings.tolerance) continue;
        out.push_back({a, b, p + 0.5 * (s_a + s_b) * n_common, n_common, t1, area, s_b - s_a});
      }
      if (general && out.size() > first) {
        if (face_to_face)
          joints.push_back({a, b});
        else
          edge_ranges.push_back({first, out.size()});
      }
    }
  }
  if (!edge_ranges.empty()) detail::drop_edge_contacts_across_a_block(out, edge_ranges, joints, planes, settings.tolerance);
  return out;
}

/// Per block, how far it may move (relative to the base, rotation counting with its radius) before the contacts
/// are detected again: the settings' redetection distance r (half the tolerance), or half the clearance c between
/// its bounding box and every other block's if that is more, the blocks at the given poses (those of the last
/// detection). Two blocks that each moved less than their distance have closed a gap d between them by less than d
/// (c/2 + c'/2 <= d with c, c' <= d; r + c'/2 <= d if d >= 2 r), so no contact is missed; a block in contact
/// (c <= 2 r) keeps r. A block in flight, far from the others, is no longer detected again every half millimetre of
/// its fall. widened(i): a block whose box is widened by the tolerance (a deformable block, whose nodes may have
/// moved off its rigid entry's shape). Non-free blocks get r (they are not checked).
template <class Widened>
std::vector<double> redetection_distances(const RigidBodies& bodies, const std::vector<Vec3>& position,
                                          const std::vector<Quaternion>& orientation, const ContactSettings& settings,
                                          Widened&& widened) {
  const std::size_t n = bodies.size();
  const double r = settings.redetection();
  std::vector<double> distance(n, r);
  std::vector<Vec3> lo(n), hi(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Mat3 rotation = rotation_matrix(orientation[i]);
    lo[i] = Vec3::Constant(std::numeric_limits<double>::infinity());
    hi[i] = -lo[i];
    for (const auto& v : bodies.shape[i].vertices) {
      const Vec3 x = position[i] + rotation * v;
      lo[i] = lo[i].cwiseMin(x);
      hi[i] = hi[i].cwiseMax(x);
    }
    if (widened(i)) {
      lo[i].array() -= settings.tolerance;
      hi[i].array() += settings.tolerance;
    }
  }
  // The nearest box to each free block by a sweep along x (sorted by lo.x): forward the x gap only grows; backward
  // it is at least lo_i.x - lo_j.x - the widest box.
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return lo[x].x() < lo[y].x(); });
  double widest = 0;
  for (std::size_t i = 0; i < n; ++i) widest = std::max(widest, hi[i].x() - lo[i].x());
  const auto box_distance = [&](std::size_t i, std::size_t j) { return (lo[j] - hi[i]).cwiseMax(lo[i] - hi[j]).cwiseMax(0.0).norm(); };
  for (std::size_t u = 0; u < n; ++u) {
    const std::size_t i = order[u];
    if (bodies.motion[i] != Motion::free) continue;
    double clearance = std::numeric_limits<double>::infinity();
    for (std::size_t w = u + 1; w < n && lo[order[w]].x() - hi[i].x() < clearance; ++w)
      clearance = std::min(clearance, box_distance(i, order[w]));
    for (std::size_t w = u; w-- > 0 && lo[i].x() - lo[order[w]].x() - widest < clearance;)
      clearance = std::min(clearance, box_distance(i, order[w]));
    distance[i] = std::max(r, 0.5 * clearance);
  }
  return distance;
}

}  // namespace blockdem::model
