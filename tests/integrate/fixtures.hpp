#pragma once
// A block on a fixed (or base) block: the single-degree-of-freedom systems with known answers.

#include <cmath>
#include <vector>

#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem::test {

struct BlockOnBase {
  model::Model model;
  std::size_t base = 0;
  std::size_t block = 0;
};

/// A block `width` x `depth` x `height` (x, y, z) of density rho standing on a larger base whose top is z = 0.
inline BlockOnBase block_on_base(double width, double depth, double height, double rho = 2000.0,
                                 model::Motion base_motion = model::Motion::fixed) {
  BlockOnBase s;
  s.base = s.model.add_block(geometry::make_box(Vec3(-2 * width, -2 * depth, -0.5), Vec3(2 * width, 2 * depth, 0)), 2000.0,
                             "base", 0, base_motion);
  s.block = s.model.add_block(geometry::make_box(Vec3(-0.5 * width, -0.5 * depth, 0), Vec3(0.5 * width, 0.5 * depth, height)),
                              rho, "block", 1);
  return s;
}

/// Free vibration record: damping ratio from the decay of successive peak-to-trough amplitudes, and frequency
/// from the times between successive peaks.
struct Decay {
  double damping_ratio = 0;
  double frequency_hz = 0;
};

inline Decay measure_decay(const std::vector<double>& t, const std::vector<double>& x, int cycles_to_skip = 1) {
  std::vector<double> peaks, troughs, peak_times;
  for (std::size_t i = 1; i + 1 < x.size(); ++i) {
    if (x[i] > x[i - 1] && x[i] >= x[i + 1]) {
      // Parabolic interpolation of the peak.
      const double d = 0.5 * (x[i - 1] - x[i + 1]) / (x[i - 1] - 2 * x[i] + x[i + 1]);
      peaks.push_back(x[i] - 0.25 * (x[i - 1] - x[i + 1]) * d);
      peak_times.push_back(t[i] + d * (t[i + 1] - t[i]));
    }
    if (x[i] < x[i - 1] && x[i] <= x[i + 1]) {
      const double d = 0.5 * (x[i - 1] - x[i + 1]) / (x[i - 1] - 2 * x[i] + x[i + 1]);
      troughs.push_back(x[i] - 0.25 * (x[i - 1] - x[i + 1]) * d);
    }
  }
  Decay r;
  const std::size_t n = std::min(peaks.size(), troughs.size());
  if (n < static_cast<std::size_t>(cycles_to_skip) + 3) return r;
  const std::size_t first = static_cast<std::size_t>(cycles_to_skip);
  const std::size_t last = n - 1;
  const double a0 = peaks[first] - troughs[first];
  const double a1 = peaks[last] - troughs[last];
  const double delta = std::log(a0 / a1) / static_cast<double>(last - first);  // logarithmic decrement
  r.damping_ratio = delta / std::sqrt(4 * M_PI * M_PI + delta * delta);
  r.frequency_hz = static_cast<double>(last - first) / (peak_times[last] - peak_times[first]);
  return r;
}

/// A deformable block (0.4 x 0.4 x 0.3 m, tetrahedra of 0.2 m, E 1 GPa) on a fixed base, a small rigid block off its
/// centre on it (which tilts it: rotations take part) and a rigid pillar beside it, all 2000 kg/m^3. Under gravity
/// on joints of 1e9 Pa/m the small block sinks 1.177e-5 m (its weight on its joint plus the deformable block's).
inline model::Model deformable_block_with_rigid_ones() {
  model::Model m;
  m.add_block(geometry::make_box(Vec3(-1, -1, -0.5), Vec3(1, 1, 0)), 2000, "base", 0, model::Motion::fixed);
  const auto d = m.add_block(geometry::make_box(Vec3(-0.2, -0.2, 0), Vec3(0.2, 0.2, 0.3)), 2000, "deformable", 1);
  m.add_block(geometry::make_box(Vec3(0.05, -0.025, 0.3), Vec3(0.1, 0.025, 0.35)), 2000, "small", 1);
  m.add_block(geometry::make_box(Vec3(-0.5, -0.3, 0), Vec3(-0.25, 0.3, 0.6)), 2000, "pillar", 1);
  m.make_deformable(d, 0.2, model::IsotropicElastic(1e9, 0.2));
  return m;
}

}  // namespace blockdem::test
