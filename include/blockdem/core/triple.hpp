#pragma once
// A 3-vector of three plain doubles, for the per-contact kinematics of the fused contact loop.
//
// Eigen evaluates Vector3d expressions with a 2-wide packet for the first two components and a scalar for the
// third. In a loop body with more live values than registers, such temporaries are spilled: a packet read back
// from two scalar stores (or two scalars from one packet store) cannot be forwarded from the store buffer, and
// each such read waits for the stores to complete. With plain doubles every spill is read back as it was written,
// and the compiler still pairs components where that pays.

#include "blockdem/core/types.hpp"

namespace blockdem {

struct Triple {
  double x = 0, y = 0, z = 0;

  [[gnu::always_inline]] static Triple of(const Vec3& v) { return {v[0], v[1], v[2]}; }
  [[gnu::always_inline]] Vec3 vec() const { return Vec3(x, y, z); }
  [[gnu::always_inline]] double dot(const Triple& o) const { return x * o.x + y * o.y + z * o.z; }
  [[gnu::always_inline]] Triple cross(const Triple& o) const { return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x}; }
};

[[gnu::always_inline]] inline Triple operator+(const Triple& a, const Triple& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
[[gnu::always_inline]] inline Triple operator-(const Triple& a, const Triple& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
[[gnu::always_inline]] inline Triple operator-(const Triple& a) { return {-a.x, -a.y, -a.z}; }
[[gnu::always_inline]] inline Triple operator*(double s, const Triple& a) { return {s * a.x, s * a.y, s * a.z}; }

/// r v for a rotation matrix r, as a Triple.
[[gnu::always_inline]] inline Triple turn(const Mat3& r, const Vec3& v) {
  return {r(0, 0) * v[0] + r(0, 1) * v[1] + r(0, 2) * v[2], r(1, 0) * v[0] + r(1, 1) * v[1] + r(1, 2) * v[2],
          r(2, 0) * v[0] + r(2, 1) * v[1] + r(2, 2) * v[2]};
}

/// a e1 + b e2 + c e3.
[[gnu::always_inline]] inline Triple combine(const Triple& e1, const Triple& e2, const Triple& e3, double a, double b, double c) {
  return {a * e1.x + b * e2.x + c * e3.x, a * e1.y + b * e2.y + c * e3.y, a * e1.z + b * e2.z + c * e3.z};
}

}  // namespace blockdem
