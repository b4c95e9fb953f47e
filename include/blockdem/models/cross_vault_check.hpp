#pragma once
// Checks of a generated cross vault: the analytical volume of each component (closed form, quadrature), and
// check_assembly(): contacts as detected, the deepest overlap of any two blocks, the vault's contact graph and the
// mass of each component against its analytical volume.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include "blockdem/core/types.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/geometry/queries.hpp"
#include "blockdem/model/contact_detection.hpp"
#include "blockdem/model/model.hpp"
#include "blockdem/models/cross_vault_description.hpp"
#include "blockdem/models/cross_vault_geometry.hpp"

namespace blockdem::models {

/// Volumes per component (m^3) of the exact (not faceted) geometry, for checking the generated blocks: the vault
/// ring in closed form for the segmental profile, by Gauss quadrature over the ring for the elliptical one; the
/// infill by Simpson's rule over the exact extrados; boxes exactly.
inline std::array<double, component_count> analytical_volumes(const CrossVaultOptions& o) {
  o.validate();
  std::array<double, component_count> volume{};
  const detail::ArchProfile profile(o);
  const double Y = o.half_plan(), t = o.thickness, h = o.infill_height();
  // Exact extrados height w at horizontal position u >= 0 (0 beyond the springing); and its u where w = 0.
  auto extrados_point = [&](double s) -> Vec2 { return profile.point(s) + t * profile.normal(s); };
  const double R = profile.radius, c = -profile.centre_w, Re = R + t;
  // u of the extrados on the springing plane (w = 0).
  const double u_springing = o.profile == VaultProfile::segmental ? std::sqrt(Re * Re - c * c) : extrados_point(1.0).x();
  auto extrados = [&](double u) {
    if (u >= u_springing) return 0.0;
    if (o.profile == VaultProfile::segmental) return std::sqrt(Re * Re - u * u) - c;
    double lo = 0, hi = 1;  // the extrados' u grows with s on [0, 1]
    for (int i = 0; i < 100; ++i) {
      const double mid = 0.5 * (lo + hi);
      (extrados_point(mid).x() < u ? lo : hi) = mid;
    }
    return extrados_point(0.5 * (lo + hi)).y();
  };
  if (o.profile == VaultProfile::segmental) {
    // Ring section {R <= r <= R + t, w >= 0} in polar coordinates about the centre (0, -c): the angle from the
    // vertical reaches theta(r) = acos(c / r). A web is the section swept from the groin |u| to the outer face Y:
    // V = int (Y - |u|) dA = Y A - int |u| dA, with A = 2 int r theta(r) dr and int |u| dA = 2 int (r^2 - c r) dr.
    auto area_primitive = [c](double r) { return 0.5 * r * r * std::acos(c / r) - 0.5 * c * std::sqrt(r * r - c * c); };
    auto moment_primitive = [c](double r) { return r * r * r / 3.0 - 0.5 * c * r * r; };
    const double area = 2 * (area_primitive(Re) - area_primitive(R));
    const double moment = 2 * (moment_primitive(Re) - moment_primitive(R));
    volume[index(Component::vault)] = 4 * (Y * area - moment);
  } else {
    // int over s in [0, 1] (u >= 0, doubled by symmetry), r in [0, t] of (Y - u) |d(x)/d(s, r)|, x = p(s) + r n(s);
    // 2-point Gauss in r (the integrand is a polynomial of degree 2 in r), 5-point Gauss on 4000 panels in s.
    const double gs[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
    const double gw[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665, 0.2369268850561891};
    const int panels = 4000;
    const double ds = 1.0 / panels, step = 1e-7;
    double web = 0;
    for (int i = 0; i < panels; ++i)
      for (int g = 0; g < 5; ++g) {
        const double s = (i + 0.5 + 0.5 * gs[g]) * ds;
        const Vec2 dp = (profile.point(std::min(1.0, s + step)) - profile.point(std::max(0.0, s - step))) /
                        (std::min(1.0, s + step) - std::max(0.0, s - step));
        const Vec2 dn = (profile.normal(std::min(1.0, s + step)) - profile.normal(std::max(0.0, s - step))) /
                        (std::min(1.0, s + step) - std::max(0.0, s - step));
        const Vec2 n = profile.normal(s);
        for (double r : {0.5 * t * (1 - 1 / std::sqrt(3.0)), 0.5 * t * (1 + 1 / std::sqrt(3.0))}) {
          const Vec2 ds_vec = dp + r * dn;
          const double jacobian = std::abs(ds_vec.x() * n.y() - ds_vec.y() * n.x());
          const double u = profile.point(s).x() + r * n.x();
          web += gw[g] * 0.5 * ds * 0.5 * t * (Y - u) * jacobian;
        }
      }
    volume[index(Component::vault)] = 4 * 2 * web;
  }
  if (h > 0) {
    // Where the exact extrados reaches the infill top: bisection on u in [0, u_springing].
    double lo = 0, hi = u_springing;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (extrados(mid) > h ? lo : hi) = mid;
    }
    const double u_top = 0.5 * (lo + hi);
    // Half a corner: int_{u_top}^{Y} (h - extrados(u)) (Y - u) du, split at the springing (kink of the extrados).
    auto simpson = [&](double a, double b) {
      const int n = 20000;
      const double dx = (b - a) / n;
      double sum = 0;
      for (int i = 0; i <= n; ++i) {
        const double u = a + i * dx;
        const double f = (h - extrados(u)) * (Y - u);
        sum += f * (i == 0 || i == n ? 1 : (i % 2 == 1 ? 4 : 2));
      }
      return sum * dx / 3;
    };
    volume[index(Component::infill)] = 8 * (simpson(u_top, u_springing) + simpson(u_springing, Y));
  }
  const double w = o.pier_width();
  volume[index(Component::fixed_pier)] = 2 * w * w * o.pier_height;
  volume[index(Component::movable_pier)] = 2 * w * w * o.pier_height;
  volume[index(Component::anchor)] = 4 * w * w * o.anchor_height;
  volume[index(Component::slab)] = o.slab_length_x * o.slab_length_y * o.slab_thickness;
  const double d = o.steel_profile_depth, s = o.steel_profile_width;
  volume[index(Component::steel_frame)] = 4 * d * s * (o.springing_level() + std::max(h, 0.0)) + s * d * 2 * (Y - w);
  return volume;
}

/// What check_assembly() found.
struct AssemblyCheck {
  std::vector<model::ContactCandidate> contacts;           // as detected, block pair ids a < b
  std::size_t contact_points = 0;
  std::size_t open_contact_points = 0;                     // gap beyond the contact tolerance
  std::array<std::size_t, 3> contact_points_by_joint{};   // by JointKind
  double max_penetration = 0;                              // m, deepest overlap of two blocks (separating axes)
  std::pair<std::size_t, std::size_t> deepest_pair{0, 0};
  bool vault_connected = false;                            // through vault-vault contacts
  std::size_t min_vault_neighbours = 0;                    // fewest vault blocks any vault block touches
  std::size_t vault_blocks_below_two_neighbours = 0;
  std::array<double, component_count> mass{};              // kg, of the blocks
  std::array<double, component_count> analytical_mass{};   // kg, analytical volume x density
  double tie_mass = 0;                                     // kg
  double detection_seconds = 0;
  double max_mass_error() const {  // largest |mass / analytical - 1| over the components present
    double e = 0;
    for (std::size_t c = 0; c < component_count; ++c)
      if (analytical_mass[c] > 0) e = std::max(e, std::abs(mass[c] / analytical_mass[c] - 1));
    return e;
  }
};

/// Checks the assembly: contact detection on the rigid model (every block taken as free, so that no pair is
/// skipped), the deepest overlap of any two blocks by the separating-axis test over all pairs whose boxes meet,
/// the contact graph of the vault, and the mass of each component against its analytical volume.
inline AssemblyCheck check_assembly(const CrossVault& v, const model::Model& m, const model::ContactSettings& settings) {
  AssemblyCheck r;
  auto bodies = m.bodies;
  std::fill(bodies.motion.begin(), bodies.motion.end(), model::Motion::free);
  const auto start = std::chrono::steady_clock::now();
  r.contacts = model::detect_contacts(bodies, settings);
  const auto& contacts = r.contacts;
  r.detection_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.contact_points = contacts.size();
  const std::size_t n = v.blocks.size();
  std::vector<std::vector<std::size_t>> neighbours(n);
  for (const auto& c : contacts) {
    if (c.gap > settings.tolerance) ++r.open_contact_points;
    ++r.contact_points_by_joint[static_cast<std::size_t>(v.joint(c).kind)];
    if (v.blocks[c.a].component == Component::vault && v.blocks[c.b].component == Component::vault) {
      neighbours[c.a].push_back(c.b);
      neighbours[c.b].push_back(c.a);
    }
  }
  std::vector<std::size_t> vault;
  for (std::size_t i = 0; i < n; ++i) {
    auto& nb = neighbours[i];
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
    if (v.blocks[i].component == Component::vault) vault.push_back(i);
  }
  if (!vault.empty()) {
    r.min_vault_neighbours = std::numeric_limits<std::size_t>::max();
    for (std::size_t i : vault) {
      r.min_vault_neighbours = std::min(r.min_vault_neighbours, neighbours[i].size());
      if (neighbours[i].size() < 2) ++r.vault_blocks_below_two_neighbours;
    }
    std::vector<bool> seen(n, false);
    std::vector<std::size_t> stack{vault.front()};
    seen[vault.front()] = true;
    std::size_t reached = 0;
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      ++reached;
      for (std::size_t j : neighbours[i])
        if (!seen[j]) {
          seen[j] = true;
          stack.push_back(j);
        }
    }
    r.vault_connected = reached == vault.size();
  }
  // Overlaps: sweep and prune along x over the world boxes, exact separation of every pair whose boxes meet.
  std::vector<Vec3> lo(n), hi(n);
  for (std::size_t i = 0; i < n; ++i) {
    lo[i] = Vec3::Constant(1e300);
    hi[i] = Vec3::Constant(-1e300);
    for (const auto& p : v.blocks[i].shape.vertices) {
      lo[i] = lo[i].cwiseMin(p);
      hi[i] = hi[i].cwiseMax(p);
    }
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lo[a].x() < lo[b].x(); });
  for (std::size_t u = 0; u < n; ++u)
    for (std::size_t w = u + 1; w < n && lo[order[w]].x() < hi[order[u]].x(); ++w) {
      const std::size_t a = order[u], b = order[w];
      if ((lo[a].array() >= hi[b].array()).any() || (lo[b].array() >= hi[a].array()).any()) continue;
      const double s = geometry::separation(v.blocks[a].shape, v.blocks[b].shape);
      if (-s > r.max_penetration) {
        r.max_penetration = -s;
        r.deepest_pair = std::minmax(a, b);
      }
    }
  const auto reference = analytical_volumes(v.options);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& b = v.blocks[i];
    r.mass[index(b.component)] += v.materials[b.material].density * detail::volume(b.shape);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = index(v.blocks[i].component);
    if (r.analytical_mass[c] == 0) r.analytical_mass[c] = reference[c] * v.materials[v.blocks[i].material].density;
  }
  for (const auto& t : v.ties) r.tie_mass += t.mass();
  return r;
}

/// Axis-aligned bounding box of the blocks of one component: {min corner, max corner}, m. Empty component: zeros.
inline std::array<Vec3, 2> bounding_box(const CrossVault& v, Component c) {
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  bool any = false;
  for (const auto& b : v.blocks)
    if (b.component == c)
      for (const auto& p : b.shape.vertices) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
        any = true;
      }
  if (!any) return {Vec3::Zero(), Vec3::Zero()};
  return {lo, hi};
}

}  // namespace blockdem::models
