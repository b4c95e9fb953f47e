#pragma once
// A 3-vector of four contacts at once, one per lane (each component a Lanes), for the per-contact kinematics of
// the fused contact loop (contact_pass_of, integrate/contact_pass.hpp).
//
// Plain components rather than Eigen: Eigen evaluates Vector3d expressions with a 2-wide packet for the first two
// components and a scalar for the third; in a loop body with more live values than registers, such temporaries
// are spilled, and a packet read back from two scalar stores (or two scalars from one packet store) cannot be
// forwarded from the store buffer. Here every spill is read back as it was written.

#include "blockdem/core/lanes.hpp"
#include "blockdem/core/types.hpp"

namespace blockdem {

struct Triple {
  Lanes x, y, z;

  /// Lane j of each component.
  [[gnu::always_inline]] Vec3 vec(std::size_t j) const { return Vec3(x[j], y[j], z[j]); }
  [[gnu::always_inline]] Triple cross(const Triple& o) const {
    return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x};
  }
};

/// a . b, lane by lane.
[[gnu::always_inline]] inline Lanes dot(const Triple& a, const Triple& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

[[gnu::always_inline]] inline Triple operator+(const Triple& a, const Triple& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
[[gnu::always_inline]] inline Triple operator-(const Triple& a, const Triple& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
[[gnu::always_inline]] inline Triple operator-(const Triple& a) { return {-a.x, -a.y, -a.z}; }
[[gnu::always_inline]] inline Triple operator*(double s, const Triple& a) { return {s * a.x, s * a.y, s * a.z}; }

/// r v for four rotation matrices and four vectors, one per lane (r[i][k]: the lanes of entry (i, k)).
[[gnu::always_inline]] inline Triple turn(const Lanes (&r)[3][3], const Triple& v) {
  return {r[0][0] * v.x + r[0][1] * v.y + r[0][2] * v.z, r[1][0] * v.x + r[1][1] * v.y + r[1][2] * v.z,
          r[2][0] * v.x + r[2][1] * v.y + r[2][2] * v.z};
}

/// a e1 + b e2 + c e3, lane by lane.
[[gnu::always_inline]] inline Triple combine(const Triple& e1, const Triple& e2, const Triple& e3, const Lanes& a, const Lanes& b,
                                             const Lanes& c) {
  return {a * e1.x + b * e2.x + c * e3.x, a * e1.y + b * e2.y + c * e3.y, a * e1.z + b * e2.z + c * e3.z};
}

}  // namespace blockdem
