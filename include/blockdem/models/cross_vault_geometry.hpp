#pragma once
// The geometry the cross vault generator builds its blocks from: the barrels' profile (segmental or elliptical), the
// faceted ring of courses, prisms of a section clipped to the north web's side of the groins, and the rotations that
// take the north web onto the others.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "blockdem/core/types.hpp"
#include "blockdem/geometry/clip.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/mass_properties.hpp"
#include "blockdem/geometry/polygon.hpp"
#include "blockdem/models/cross_vault_description.hpp"

namespace blockdem::models {

namespace detail {

/// The intrados of a barrel in its cross-section (u across, w above the springing), parameter s in [-1, 1] from
/// the springing at u = -span/2 through the crown (s = 0) to u = +span/2; the normal points to the extrados.
struct ArchProfile {
  VaultProfile kind = VaultProfile::segmental;
  double a = 0, f = 0;           // m, half span and rise
  double radius = 0, centre_w = 0, springing_angle = 0;  // segmental: circle of radius R centred at (0, w_c)

  explicit ArchProfile(const CrossVaultOptions& o) : kind(o.profile), a(0.5 * o.span), f(o.rise) {
    if (kind == VaultProfile::segmental) {
      radius = (a * a + f * f) / (2 * f);
      centre_w = f - radius;
      springing_angle = std::asin(std::min(1.0, a / radius));
    }
  }
  Vec2 point(double s) const {
    if (kind == VaultProfile::segmental) {
      const double t = s * springing_angle;
      return {radius * std::sin(t), centre_w + radius * std::cos(t)};
    }
    const double t = s * 0.5 * pi;
    return {a * std::sin(t), f * std::cos(t)};
  }
  Vec2 normal(double s) const {
    if (kind == VaultProfile::segmental) {
      const double t = s * springing_angle;
      return {std::sin(t), std::cos(t)};
    }
    const double t = s * 0.5 * pi;
    return Vec2(std::sin(t) / a, std::cos(t) / f).normalized();
  }
};

/// The faceted ring: courses of equal length along the mid-thickness curve; the first and last course end on the
/// springing plane w = 0 (their outer corner where the extrados chord meets it).
inline void faceted_ring(const CrossVaultOptions& o, const ArchProfile& profile, std::vector<Vec2>& intrados,
                         std::vector<Vec2>& extrados) {
  const int samples = 8192;
  std::vector<double> s(samples + 1), length(samples + 1, 0.0);
  Vec2 previous = Vec2::Zero();
  for (int j = 0; j <= samples; ++j) {
    s[static_cast<std::size_t>(j)] = -1.0 + 2.0 * j / samples;
    const Vec2 m = profile.point(s[static_cast<std::size_t>(j)]) + 0.5 * o.thickness * profile.normal(s[static_cast<std::size_t>(j)]);
    if (j > 0) length[static_cast<std::size_t>(j)] = length[static_cast<std::size_t>(j - 1)] + (m - previous).norm();
    previous = m;
  }
  const double total = length.back();
  const int courses = std::max(3, static_cast<int>(std::lround(total / o.course_height())));
  intrados.assign(static_cast<std::size_t>(courses + 1), Vec2::Zero());
  extrados.assign(static_cast<std::size_t>(courses + 1), Vec2::Zero());
  std::size_t j = 0;
  for (int k = 0; k <= courses; ++k) {
    double sk = -1.0;
    if (k == courses) {
      sk = 1.0;
    } else if (k > 0) {
      const double target = total * k / courses;
      while (j + 1 < length.size() && length[j + 1] < target) ++j;
      const double t = (target - length[j]) / (length[j + 1] - length[j]);
      sk = s[j] + t * (s[j + 1] - s[j]);
    }
    intrados[static_cast<std::size_t>(k)] = profile.point(sk);
    extrados[static_cast<std::size_t>(k)] = profile.point(sk) + o.thickness * profile.normal(sk);
  }
  // Springings exactly on w = 0; the outer corner of the end courses where their extrados chord meets w = 0.
  for (const auto& [end, next] : {std::pair<std::size_t, std::size_t>{0, 1},
                                  std::pair<std::size_t, std::size_t>{static_cast<std::size_t>(courses), static_cast<std::size_t>(courses - 1)}}) {
    intrados[end] = Vec2(end == 0 ? -profile.a : profile.a, 0.0);
    const Vec2 e0 = extrados[end], e1 = extrados[next];
    if (e0.y() > 0) extrados[end] = e0 + (e0 - e1) * (e0.y() / (e1.y() - e0.y()));
    extrados[end].y() = 0.0;
  }
}

/// The area of a section polygon (m^2, unsigned).
inline double polygon_area(const std::vector<Vec2>& p) { return std::abs(geometry::polygon_area(p)); }

inline double volume(const geometry::ConvexPolyhedron& p) {
  if (p.vertices.empty()) return 0;
  double v = 0;
  const Vec3 o = p.centroid_of_vertices();
  for (const auto& face : p.faces) {
    const Vec3 a = p.vertices[static_cast<std::size_t>(face[0])] - o;
    for (std::size_t i = 1; i + 1 < face.size(); ++i)
      v += a.dot((p.vertices[static_cast<std::size_t>(face[i])] - o).cross(p.vertices[static_cast<std::size_t>(face[i + 1])] - o));
  }
  return v / 6.0;
}

/// A prism over the section polygon (u, w) of a barrel along v in [v_lo, v_hi], in the frame of the north web
/// (x = u, y = v, z = springing + w), clipped to the north web's side of the groins, y >= |x|.
inline geometry::ConvexPolyhedron north_web_piece(const std::vector<Vec2>& section, double v_lo, double v_hi, double z0) {
  std::vector<Vec3> base;
  for (const auto& q : section) base.emplace_back(q.x(), v_lo, z0 + q.y());
  const auto prism = geometry::make_prism(base, Vec3(0, v_hi - v_lo, 0));
  return geometry::clip(prism, {{Vec3(1, -1, 0), 0.0}, {Vec3(-1, -1, 0), 0.0}});
}

/// Rotations about z taking the north web onto the north, east, south and west webs.
inline Mat3 web_rotation(int web) {
  Mat3 r;
  switch (web) {
    case 1: r << 0, 1, 0, -1, 0, 0, 0, 0, 1; break;   // (x, y) -> (y, -x): east
    case 2: r << -1, 0, 0, 0, -1, 0, 0, 0, 1; break;  // south
    case 3: r << 0, -1, 0, 1, 0, 0, 0, 0, 1; break;   // (x, y) -> (-y, x): west
    default: r = Mat3::Identity();
  }
  return r;
}
inline constexpr std::array<std::string_view, 4> web_names{"N", "E", "S", "W"};

inline std::string corner_name(double x, double y) { return std::string(y > 0 ? "N" : "S") + (x > 0 ? "E" : "W"); }

}  // namespace detail

}  // namespace blockdem::models
