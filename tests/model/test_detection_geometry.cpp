// Contact detection (model/contact_detection.hpp) checked against geometry that owes nothing to it: random pairs of
// convex prisms placed face to face, tilted onto an edge or a vertex, in touch, near touch and overlap, and the
// vault's own pairs. Every reference quantity is computed here from the vertices and faces alone:
//  - the separating-axis separation S of the two blocks (over both blocks' face normals and every cross product of
//    an edge of each): the distance between them when apart, minus the penetration depth when they overlap;
//  - the separation along the detection's normal n, min over B of n.x - max over A of n.x;
//  - the two surface points of a contact point (position -/+ gap/2 along n), which must lie on A's and B's surface;
//  - the exact overlap of two parallel faces (polygon clipping written here), against the contact points' area.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include "blockdem/core/rotation.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "blockdem/model/model.hpp"
#include "blockdem/models/cross_vault.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_detection_geometry {

namespace {

using Polyhedron = geometry::ConvexPolyhedron;

/// Outward unit normal of face f by Newell's method (written here, not the library's).
Vec3 normal_of(const Polyhedron& p, std::size_t f) {
  Vec3 n = Vec3::Zero();
  const auto& face = p.faces[f];
  for (std::size_t i = 0; i < face.size(); ++i) {
    const Vec3& a = p.vertices[static_cast<std::size_t>(face[i])];
    const Vec3& b = p.vertices[static_cast<std::size_t>(face[(i + 1) % face.size()])];
    n += Vec3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()), (a.x() - b.x()) * (a.y() + b.y()));
  }
  return n.normalized();
}

double highest(const Polyhedron& p, const Vec3& n) {
  double h = -1e300;
  for (const auto& v : p.vertices) h = std::max(h, n.dot(v));
  return h;
}

/// min over B of n.x - max over A of n.x: how far apart the blocks are along n (negative: they overlap along it).
double separation_along(const Polyhedron& a, const Polyhedron& b, const Vec3& n) { return -highest(b, -n) - highest(a, n); }

/// The separating-axis separation: the largest separation along the candidate axes (both blocks' face normals and
/// the cross products of their edges), which for convex polyhedra is the largest over all directions.
double sat_separation(const Polyhedron& a, const Polyhedron& b) {
  double s = -1e300;
  for (std::size_t f = 0; f < a.faces.size(); ++f) s = std::max(s, separation_along(a, b, normal_of(a, f)));
  for (std::size_t f = 0; f < b.faces.size(); ++f) s = std::max(s, separation_along(a, b, -normal_of(b, f)));
  const auto edges = [](const Polyhedron& p) {
    std::vector<Vec3> e;
    for (const auto& face : p.faces)
      for (std::size_t i = 0; i < face.size(); ++i)
        e.push_back(p.vertices[static_cast<std::size_t>(face[(i + 1) % face.size()])] - p.vertices[static_cast<std::size_t>(face[i])]);
    return e;
  };
  for (const Vec3& ea : edges(a))
    for (const Vec3& eb : edges(b)) {
      const Vec3 c = ea.cross(eb);
      if (c.norm() < 1e-9 * ea.norm() * eb.norm()) continue;  // parallel edges: a face normal covers it
      s = std::max({s, separation_along(a, b, c.normalized()), separation_along(a, b, -c.normalized())});
    }
  return s;
}

/// How far x lies outside p: the largest signed distance to its face planes (0 on the surface, < 0 inside).
double outside(const Polyhedron& p, const Vec3& x) {
  double d = -1e300;
  for (std::size_t f = 0; f < p.faces.size(); ++f)
    d = std::max(d, normal_of(p, f).dot(x - p.vertices[static_cast<std::size_t>(p.faces[f][0])]));
  return d;
}

using Point = std::array<double, 2>;

/// Area of the intersection of two convex polygons (counter-clockwise), by Sutherland-Hodgman clipping.
double intersection_area(std::vector<Point> subject, const std::vector<Point>& clip) {
  const auto cross = [](const Point& o, const Point& a, const Point& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  for (std::size_t i = 0; i < clip.size() && !subject.empty(); ++i) {
    const Point& p = clip[i];
    const Point& q = clip[(i + 1) % clip.size()];
    std::vector<Point> kept;
    for (std::size_t j = 0; j < subject.size(); ++j) {
      const Point& s = subject[j];
      const Point& e = subject[(j + 1) % subject.size()];
      const double cs = cross(p, q, s), ce = cross(p, q, e);
      if (cs >= 0) kept.push_back(s);
      if ((cs >= 0) != (ce >= 0)) {
        const double t = cs / (cs - ce);
        kept.push_back({s[0] + t * (e[0] - s[0]), s[1] + t * (e[1] - s[1])});
      }
    }
    subject = kept;
  }
  double area = 0;
  for (std::size_t j = 0; j < subject.size(); ++j)
    area += subject[j][0] * subject[(j + 1) % subject.size()][1] - subject[(j + 1) % subject.size()][0] * subject[j][1];
  return 0.5 * std::abs(area);
}

/// Face f of p projected on the plane (origin, u, v), counter-clockwise seen along u x v.
std::vector<Point> projected_face(const Polyhedron& p, std::size_t f, const Vec3& origin, const Vec3& u, const Vec3& v) {
  std::vector<Point> out;
  for (int i : p.faces[f]) {
    const Vec3 d = p.vertices[static_cast<std::size_t>(i)] - origin;
    out.push_back({d.dot(u), d.dot(v)});
  }
  double area = 0;
  for (std::size_t j = 0; j < out.size(); ++j) area += out[j][0] * out[(j + 1) % out.size()][1] - out[(j + 1) % out.size()][0] * out[j][1];
  if (area < 0) std::reverse(out.begin(), out.end());
  return out;
}

/// A random convex prism: 3 to 7 corners on an ellipse, extruded; centred near the origin.
Polyhedron random_prism(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int n = 3 + static_cast<int>(unit(rng) * 5);
  const double rx = 0.1 + 0.4 * unit(rng), ry = 0.1 + 0.4 * unit(rng), h = 0.05 + 0.45 * unit(rng);
  std::vector<double> angles;
  for (int i = 0; i < n; ++i) angles.push_back(2 * std::numbers::pi * (i + 0.8 * unit(rng)) / n);
  std::vector<Vec3> base;
  for (double t : angles) base.push_back(Vec3(rx * std::cos(t), ry * std::sin(t), -h / 2));
  return geometry::make_prism(base, Vec3(0, 0, h));
}

/// The rotation that turns unit vector a onto unit vector b.
Mat3 turning(const Vec3& a, const Vec3& b) {
  return Quaternion::FromTwoVectors(a, b).toRotationMatrix();
}

struct Trial {
  Polyhedron a, b;
  bool parallel = false;   // B's face lies parallel to A's face: the overlap of the two faces is the contact
  std::size_t face_a = 0, face_b = 0;
};

/// B set on a random face of A: face to face at a random turn and offset, or tilted about an axis in that face by
/// up to 40 degrees (standing on an edge or a vertex); its lowest point at `gap` from A's face plane.
Trial random_trial(std::mt19937_64& rng, double gap, bool tilt) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Trial t;
  const Mat3 ra = turning(Vec3::UnitZ(), Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5).normalized());
  t.a = random_prism(rng).transformed(ra, Vec3::Zero());
  Polyhedron b = random_prism(rng);
  t.face_a = static_cast<std::size_t>(unit(rng) * static_cast<double>(t.a.faces.size())) % t.a.faces.size();
  t.face_b = static_cast<std::size_t>(unit(rng) * static_cast<double>(b.faces.size())) % b.faces.size();
  const Vec3 na = normal_of(t.a, t.face_a);
  // B's face against A's face, turned about the normal by a random angle.
  Mat3 r = Eigen::AngleAxisd(2 * std::numbers::pi * unit(rng), na).toRotationMatrix() * turning(normal_of(b, t.face_b), -na);
  if (tilt) {
    const Vec3 axis = na.unitOrthogonal();
    const Vec3 across = Eigen::AngleAxisd(2 * std::numbers::pi * unit(rng), na) * axis;
    r = Eigen::AngleAxisd((1.0 + 39.0 * unit(rng)) * std::numbers::pi / 180, across).toRotationMatrix() * r;
  }
  b = b.transformed(r, Vec3::Zero());
  // Centre B's face over a random point of A's face, then bring B's lowest point (along -na) to the gap.
  Vec3 ca = Vec3::Zero(), cb = Vec3::Zero();
  for (int i : t.a.faces[t.face_a]) ca += t.a.vertices[static_cast<std::size_t>(i)];
  ca /= static_cast<double>(t.a.faces[t.face_a].size());
  const Vec3 corner = t.a.vertices[static_cast<std::size_t>(t.a.faces[t.face_a][0])];
  const Vec3 target = ca + 0.8 * unit(rng) * (corner - ca);
  for (int i : b.faces[t.face_b]) cb += b.vertices[static_cast<std::size_t>(i)];
  cb /= static_cast<double>(b.faces[t.face_b].size());
  Vec3 shift = target - cb;
  shift -= shift.dot(na) * na;
  const double lowest = -highest(b, -na);          // of B along na, before the shift
  const double plane = na.dot(corner);             // A's face plane
  shift += (plane + gap - lowest) * na;
  t.b = b.transformed(Mat3::Identity(), shift);
  t.parallel = !tilt;
  return t;
}

struct Tally {
  int pairs = 0, detected = 0, missed = 0, parallel_checked = 0;
  double worst_plane = 0, worst_surface = 0, worst_area = 0, worst_depth = 0;
};

}  // namespace

TEST_CASE("detection against geometry: 3000 random pairs of prisms in touch, near touch and overlap") {
  // For each pair, with the default settings (general contacts, tolerance 1 mm):
  //  - the common plane: a face normal as good as the best face normal (its separation along n within a hundredth of
  //    the tolerance, the allowance contact_detection.hpp gives a face-to-face plane over a slightly better one), or
  //    an edge-edge plane as good as the best axis of all;
  //  - every contact point's two surface points lie on the surfaces of A and B, to 1e-9 m;
  //  - every gap is at least the separation along n and at most the tolerance; for blocks that are apart (S > 0), at
  //    least their distance S: no contact point claims an overlap of blocks that do not touch;
  //  - for blocks that overlap, no contact point reports an overlap deeper than their penetration depth -S (to
  //    1e-6 m). A block tilted by less than max_normal_angle onto the rim of A's face keeps A's face normal, a joint's
  //    plane, where an edge-edge axis separates better (the whole blocks overlap by up to 1.1 mm more along it in
  //    these trials), but the contact points, on the overlap of the two faces, do not;
  //  - a pair closer than 0.9 of the tolerance has contact points;
  //  - parallel faces: the contact points' area is the exact overlap of the two faces, to a quarter of the tolerance
  //    times the perimeter of A's face (at least the overlap's: measured 2.1e-5 m^2 per m).
  const double tolerance = model::ContactSettings{}.tolerance;
  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Tally tally;
  for (int k = 0; k < 3000; ++k) {
    CAPTURE(k);
    const double gap = (-0.5 + 1.8 * unit(rng)) * tolerance;  // overlap 0.5 mm to a gap of 1.3 mm
    const Trial t = random_trial(rng, gap, k % 2 == 1);
    model::Model m;
    m.add_block(t.a, 2000, "A", 0, model::Motion::fixed);
    m.add_block(t.b, 2000, "B", 0, model::Motion::free);
    const auto points = model::detect_contacts(m.bodies, model::ContactSettings{});
    const auto& a = m.bodies.world_shape(0);
    const auto& b = m.bodies.world_shape(1);
    const double s = sat_separation(a, b);
    ++tally.pairs;
    if (points.empty()) {
      if (s < 0.9 * tolerance) {
        ++tally.missed;
        FAIL_CHECK("no contact points for a pair " << s << " m apart (gap set " << gap << " m, tilted " << !t.parallel << ")");
      }
      continue;
    }
    ++tally.detected;
    const Vec3 n = points.front().normal;
    const double along = separation_along(a, b, n);
    double best_face = -1e300;
    bool face_plane = false;
    for (std::size_t f = 0; f < a.faces.size(); ++f) {
      best_face = std::max(best_face, separation_along(a, b, normal_of(a, f)));
      face_plane = face_plane || normal_of(a, f).isApprox(n, 1e-9);
    }
    for (std::size_t f = 0; f < b.faces.size(); ++f) {
      best_face = std::max(best_face, separation_along(a, b, -normal_of(b, f)));
      face_plane = face_plane || (-normal_of(b, f)).isApprox(n, 1e-9);
    }
    tally.worst_plane = std::max(tally.worst_plane, (face_plane ? best_face : s) - along);
    CHECK(along >= (face_plane ? best_face : s) - 0.01 * tolerance - 1e-12);
    double area = 0, deepest = 1e300;
    for (const auto& c : points) {
      CHECK(c.normal.isApprox(n, 1e-12));
      const Vec3 on_a = c.position - 0.5 * c.gap * n, on_b = c.position + 0.5 * c.gap * n;
      const double off = std::max({std::abs(outside(a, on_a)), std::abs(outside(b, on_b))});
      tally.worst_surface = std::max(tally.worst_surface, off);
      CHECK(off <= 1e-9);
      CHECK(c.gap >= along - 1e-9);
      CHECK(c.gap <= tolerance + 1e-12);
      if (s > 0) CHECK(c.gap >= s - 1e-9);
      deepest = std::min(deepest, c.gap);
      area += c.area;
    }
    if (s < 0) {
      tally.worst_depth = std::max(tally.worst_depth, s - deepest);
      CHECK(deepest >= s - 1e-6);
    }
    if (t.parallel && n.isApprox(normal_of(a, t.face_a), 1e-9) && gap <= tolerance) {
      const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
      const Vec3 o = a.vertices[static_cast<std::size_t>(a.faces[t.face_a][0])];
      const auto fa = projected_face(a, t.face_a, o, u, v);
      const double exact = intersection_area(fa, projected_face(b, t.face_b, o, u, v));
      double perimeter = 0;
      for (std::size_t j = 0; j < fa.size(); ++j)
        perimeter += std::hypot(fa[(j + 1) % fa.size()][0] - fa[j][0], fa[(j + 1) % fa.size()][1] - fa[j][1]);
      ++tally.parallel_checked;
      tally.worst_area = std::max(tally.worst_area, std::abs(area - exact) / perimeter);
      CHECK(std::abs(area - exact) <= 0.25 * tolerance * perimeter + 1e-12);
    }
  }
  MESSAGE(tally.pairs << " pairs, " << tally.detected << " in contact, " << tally.missed << " missed; worst: plane "
                      << tally.worst_plane << " m below the best axis, surface point " << tally.worst_surface
                      << " m off, overlap " << tally.worst_depth << " m deeper than the penetration depth, area "
                      << tally.worst_area << " m^2 per m of perimeter over " << tally.parallel_checked
                      << " parallel pairs");
}

TEST_CASE("detection against geometry: every contact point of the cross vault as built lies on both blocks' surfaces") {
  // The vault's own pairs (groins, infill wedges, slivers on their anchors), general contacts: each CP's two surface
  // points on A's and B's surfaces (measured: to 1.5e-14 m), its gap at least the separation along its normal.
  const auto vault = models::make_cross_vault();
  const auto m = models::build_rigid_model(vault);
  const auto points = model::detect_contacts(m.bodies, model::ContactSettings{});
  std::vector<Polyhedron> world(m.bodies.size());
  for (std::size_t i = 0; i < world.size(); ++i) world[i] = m.bodies.world_shape(i);
  double worst = 0;
  for (const auto& c : points) {
    const Vec3 on_a = c.position - 0.5 * c.gap * c.normal, on_b = c.position + 0.5 * c.gap * c.normal;
    const double off = std::max({std::abs(outside(world[c.a], on_a)), std::abs(outside(world[c.b], on_b))});
    worst = std::max(worst, off);
    CHECK(off <= 1e-9);
    CHECK(c.gap >= separation_along(world[c.a], world[c.b], c.normal) - 1e-9);
  }
  MESSAGE(points.size() << " contact points; the farthest surface point lies " << worst << " m off its block's surface");
}

}  // namespace test_detection_geometry
