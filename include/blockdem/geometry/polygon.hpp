#pragma once
// Convex polygons in a plane (the overlap of two faces on a contact's common plane): area, area centroid, convex
// hull, clipping, barycentric coordinates.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace blockdem::geometry {

using Point2 = std::array<double, 2>;
using Polygon2 = std::vector<Point2>;

inline double cross2(const Point2& o, const Point2& a, const Point2& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/// Signed area (m^2) of a simple polygon, counter-clockwise positive (the shoelace formula); any point type with
/// p[0], p[1] (Point2, Eigen::Vector2d).
template <class Polygon>
double polygon_area(const Polygon& p) {
  double s = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& u = p[i];
    const auto& v = p[(i + 1) % p.size()];
    s += u[0] * v[1] - v[0] * u[1];
  }
  return 0.5 * s;
}

/// The mean of the vertices (not the area centroid: area_centroid).
inline Point2 polygon_centroid(const Polygon2& p) {
  Point2 c{0, 0};
  for (const auto& v : p) {
    c[0] += v[0];
    c[1] += v[1];
  }
  return {c[0] / static_cast<double>(p.size()), c[1] / static_cast<double>(p.size())};
}

/// Sutherland-Hodgman: the part of `subject` inside the convex counter-clockwise polygon `clip`.
inline Polygon2 clip_convex(Polygon2 subject, const Polygon2& clip) {
  for (std::size_t e = 0; e < clip.size() && !subject.empty(); ++e) {
    const Point2& c0 = clip[e];
    const Point2& c1 = clip[(e + 1) % clip.size()];
    Polygon2 input = std::move(subject);
    subject.clear();
    for (std::size_t i = 0; i < input.size(); ++i) {
      const Point2& p = input[i];
      const Point2& q = input[(i + 1) % input.size()];
      const double dp = cross2(c0, c1, p);
      const double dq = cross2(c0, c1, q);
      if (dp >= 0) subject.push_back(p);
      if ((dp >= 0) != (dq >= 0)) {
        const double t = dp / (dp - dq);
        subject.push_back({p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])});
      }
    }
  }
  // Drop the repeated and collinear points that clipping along (nearly) common edges leaves behind.
  double scale = 0;
  for (const auto& v : clip) scale = std::max({scale, std::abs(v[0] - clip[0][0]), std::abs(v[1] - clip[0][1])});
  const double eps = 1e-9 * scale;
  bool changed = true;
  while (changed && subject.size() >= 3) {
    changed = false;
    for (std::size_t i = 0; i < subject.size() && subject.size() >= 3; ++i) {
      const Point2& prev = subject[(i + subject.size() - 1) % subject.size()];
      const Point2& v = subject[i];
      const Point2& next = subject[(i + 1) % subject.size()];
      const bool repeated = std::hypot(v[0] - prev[0], v[1] - prev[1]) <= eps;
      const bool collinear = std::abs(cross2(prev, v, next)) <= eps * scale;
      if (repeated || collinear) {
        subject.erase(subject.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
        break;
      }
    }
  }
  return subject;
}

/// Drops the vertices of a convex polygon that lie within `distance` of the chord between their two neighbours
/// where its boundary turns by less than `max_turn` (rad), the shallowest first, keeping three at least. Such a
/// vertex is where two nearly parallel edges cross: two faces of the same size that nearly coincide (a block on
/// another of its own size) have their edges an offset d and an angle a apart, and cross at d / a along them, a
/// place that jumps from one detection to the next while the polygon itself hardly changes. Below `distance` the
/// polygon keeps its corners only, which stay where they are.
inline Polygon2 drop_shallow_vertices(Polygon2 p, double distance, double max_turn) {
  // Squared forms, without roots: the deviation |(next - prev) x (v - prev)| / |next - prev| < distance, and the
  // turn at v below max_turn, (v - prev) . (next - v) >= cos(max_turn) |v - prev| |next - v|.
  const double cos_turn = std::cos(max_turn);
  const double cos2 = cos_turn * cos_turn;
  while (p.size() > 3) {
    std::size_t shallowest = p.size();
    double smallest = 1.0;  // deviation^2 / distance^2
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Point2& prev = p[(i + p.size() - 1) % p.size()];
      const Point2& v = p[i];
      const Point2& next = p[(i + 1) % p.size()];
      const double in0 = v[0] - prev[0], in1 = v[1] - prev[1], out0 = next[0] - v[0], out1 = next[1] - v[1];
      const double c0 = in0 + out0, c1 = in1 + out1;  // the chord next - prev
      const double chord2 = c0 * c0 + c1 * c1;
      const double cross = c0 * in1 - c1 * in0;
      const double ratio = cross * cross / (distance * distance * chord2);
      if (!(ratio < smallest)) continue;  // also a chord of zero length
      const double dot = in0 * out0 + in1 * out1;
      if (dot < 0 || dot * dot < cos2 * (in0 * in0 + in1 * in1) * (out0 * out0 + out1 * out1)) continue;
      smallest = ratio;
      shallowest = i;
    }
    if (shallowest == p.size()) break;
    p.erase(p.begin() + static_cast<std::ptrdiff_t>(shallowest));
  }
  return p;
}

/// Barycentric coordinates of p in the triangle t.
inline std::array<double, 3> barycentric2(const Polygon2& t, const Point2& p) {
  const double den = cross2(t[0], t[1], t[2]);
  return {cross2(p, t[1], t[2]) / den, cross2(t[0], p, t[2]) / den,
          cross2(t[0], t[1], p) / den};
}
/// The area (m^2, unsigned) and the area centroid of a simple polygon.
inline std::pair<double, Point2> area_centroid(const Polygon2& p) {
  double a = 0, cx = 0, cy = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& u = p[i];
    const auto& v = p[(i + 1) % p.size()];
    const double c = u[0] * v[1] - v[0] * u[1];
    a += c;
    cx += (u[0] + v[0]) * c;
    cy += (u[1] + v[1]) * c;
  }
  a *= 0.5;
  return {std::abs(a), {cx / (6 * a), cy / (6 * a)}};
}
/// Whether `q` lies in the convex counter-clockwise polygon `p` or within `tolerance` (m) outside any of its edges.
inline bool inside_convex(const Polygon2& p, const Point2& q, double tolerance) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Point2& a = p[i];
    const Point2& b = p[(i + 1) % p.size()];
    const double length = std::hypot(b[0] - a[0], b[1] - a[1]);
    if (cross2(a, b, q) < -tolerance * length) return false;
  }
  return true;
}

/// Andrew's monotone chain, counter-clockwise, collinear points dropped.
inline Polygon2 convex_hull(Polygon2 p) {
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  double scale = 0;
  for (const auto& v : p) scale = std::max({scale, std::abs(v[0] - p[0][0]), std::abs(v[1] - p[0][1])});
  const double eps = 1e-12 * scale * scale;
  Polygon2 h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross2(h[k - 2], h[k - 1], p[i]) <= eps) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross2(h[k - 2], h[k - 1], p[i - 1]) <= eps) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}


}  // namespace blockdem::geometry
