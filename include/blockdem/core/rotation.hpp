#pragma once
// Orientation updates of the block loop, written out so that they inline: no libm call for the small rotations
// of one explicit step.

#include <cmath>

#include "blockdem/core/types.hpp"

namespace blockdem {

/// cos x and sin x / x of a half angle x from their series, given x^2 (below 1e-4: the first omitted term is below
/// 1e-26). Horner in x^2 with the Taylor coefficients as constants: a division by 12.0 is not turned into a product
/// (1/12 is not exact), and the seven divisions of the nested form were most of the orientation update.
[[gnu::always_inline]] constexpr void half_angle_series(double x2, double& c, double& s) noexcept {
  c = 1.0 + x2 * (-1.0 / 2 + x2 * (1.0 / 24 + x2 * (-1.0 / 720 + x2 * (1.0 / 40320))));
  s = 1.0 + x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040 + x2 * (1.0 / 362880))));
}

/// The orientation q turned by the world angular velocity w for dt: exp(w dt / 2) q, exactly (to rounding) for
/// any angle; for half angles below 0.01 rad, cos x and sin x / x come from their series (the first omitted term
/// is below 1e-26), otherwise from libm.
[[gnu::always_inline]] inline Quaternion turned(const Quaternion& q, const Vec3& w, double dt) noexcept {
  const double x2 = 0.25 * dt * dt * w.squaredNorm();  // half angle squared
  double c, s;                                          // cos x, sin x / x
  if (x2 < 1e-4) [[likely]] {
    half_angle_series(x2, c, s);
  } else {
    const double x = std::sqrt(x2);
    c = std::cos(x);
    s = std::sin(x) / x;
  }
  const Vec3 v = (0.5 * dt * s) * w;  // vector part of the increment (c, v)
  const Vec3 qv = q.vec();
  const Vec3 r = c * qv + q.w() * v + v.cross(qv);
  const double rw = c * q.w() - v.dot(qv);
  // Renormalised exactly: a Newton step for 1/sqrt (no square root, no division) biases the norm by its rounding
  // and made the time reversibility of a spinning block two times worse.
  const double scale = 1.0 / std::sqrt(rw * rw + r.squaredNorm());
  return Quaternion(scale * rw, scale * r[0], scale * r[1], scale * r[2]);
}

/// The nine coefficients of the rotation matrix of the unit quaternion (x, y, z, w) at q[0..3], column-major into
/// r[0..8] (r(j, k) at r[3 k + j]). On plain arrays, so that the block pass's vector loops use it too.
[[gnu::always_inline]] inline void rotation_coefficients(const double* q, double* r) noexcept {
  const double x = q[0], y = q[1], z = q[2], w = q[3];
  const double xx = 2 * x * x, yy = 2 * y * y, zz = 2 * z * z;
  const double xy = 2 * x * y, xz = 2 * x * z, yz = 2 * y * z, wx = 2 * w * x, wy = 2 * w * y, wz = 2 * w * z;
  r[0] = 1 - yy - zz;
  r[1] = xy + wz;
  r[2] = xz - wy;
  r[3] = xy - wz;
  r[4] = 1 - xx - zz;
  r[5] = yz + wx;
  r[6] = xz + wy;
  r[7] = yz - wx;
  r[8] = 1 - xx - yy;
}

/// The rotation matrix of a unit quaternion.
[[gnu::always_inline]] inline Mat3 rotation_matrix(const Quaternion& q) noexcept {
  Mat3 r;
  rotation_coefficients(q.coeffs().data(), r.data());  // Eigen keeps (x, y, z, w) and column-major matrices
  return r;
}

/// The angle between two orientations, 2 |vector part of q q0^-1|: exact to third order in the angle, without acos.
[[gnu::always_inline]] inline double small_angle_between(const Quaternion& q, const Quaternion& q0) noexcept {
  const Vec3 v = q0.w() * q.vec() - q.w() * q0.vec() - q.vec().cross(q0.vec());
  return 2.0 * v.norm();
}

}  // namespace blockdem
