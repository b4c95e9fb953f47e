#pragma once
// A 3-vector of three plain components, for the per-contact kinematics of the fused contact loop: doubles
// (Triple), or four contacts at once, one per lane (TripleOf<Lanes>).
//
// Eigen evaluates Vector3d expressions with a 2-wide packet for the first two components and a scalar for the
// third. In a loop body with more live values than registers, such temporaries are spilled: a packet read back
// from two scalar stores (or two scalars from one packet store) cannot be forwarded from the store buffer, and
// each such read waits for the stores to complete. With plain components every spill is read back as it was
// written.

#include <type_traits>

#include "blockdem/core/lanes.hpp"
#include "blockdem/core/types.hpp"

namespace blockdem {

template <class T>
struct TripleOf {
  T x{}, y{}, z{};

  [[gnu::always_inline]] static TripleOf of(const Vec3& v)
    requires std::is_same_v<T, double>
  {
    return {v[0], v[1], v[2]};
  }
  [[gnu::always_inline]] Vec3 vec() const
    requires std::is_same_v<T, double>
  {
    return Vec3(x, y, z);
  }
  /// Lane j of each component.
  [[gnu::always_inline]] Vec3 vec(std::size_t j) const
    requires std::is_same_v<T, Lanes>
  {
    return Vec3(x[j], y[j], z[j]);
  }
  [[gnu::always_inline]] TripleOf cross(const TripleOf& o) const {
    return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x};
  }
};

using Triple = TripleOf<double>;

/// a . b.
template <class T>
[[gnu::always_inline]] inline T dot(const TripleOf<T>& a, const TripleOf<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <class T>
[[gnu::always_inline]] inline TripleOf<T> operator+(const TripleOf<T>& a, const TripleOf<T>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
[[gnu::always_inline]] inline TripleOf<T> operator-(const TripleOf<T>& a, const TripleOf<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
[[gnu::always_inline]] inline TripleOf<T> operator-(const TripleOf<T>& a) {
  return {-a.x, -a.y, -a.z};
}
/// s a, for s a double (broadcast to every lane) or of a's component type.
template <class S, class T>
  requires std::is_same_v<S, double> || std::is_same_v<S, T>
[[gnu::always_inline]] inline TripleOf<T> operator*(S s, const TripleOf<T>& a) {
  return {s * a.x, s * a.y, s * a.z};
}

/// r v for a rotation matrix r, as a Triple.
[[gnu::always_inline]] inline Triple turn(const Mat3& r, const Vec3& v) {
  return {r(0, 0) * v[0] + r(0, 1) * v[1] + r(0, 2) * v[2], r(1, 0) * v[0] + r(1, 1) * v[1] + r(1, 2) * v[2],
          r(2, 0) * v[0] + r(2, 1) * v[1] + r(2, 2) * v[2]};
}

/// r v for four rotation matrices and four vectors, one per lane (r[i][k]: the lanes of entry (i, k)).
[[gnu::always_inline]] inline TripleOf<Lanes> turn(const Lanes (&r)[3][3], const TripleOf<Lanes>& v) {
  return {r[0][0] * v.x + r[0][1] * v.y + r[0][2] * v.z, r[1][0] * v.x + r[1][1] * v.y + r[1][2] * v.z,
          r[2][0] * v.x + r[2][1] * v.y + r[2][2] * v.z};
}

/// a e1 + b e2 + c e3.
template <class T>
[[gnu::always_inline]] inline TripleOf<T> combine(const TripleOf<T>& e1, const TripleOf<T>& e2, const TripleOf<T>& e3,
                                                  const T& a, const T& b, const T& c) {
  return {a * e1.x + b * e2.x + c * e3.x, a * e1.y + b * e2.y + c * e3.y, a * e1.z + b * e2.z + c * e3.z};
}

}  // namespace blockdem
