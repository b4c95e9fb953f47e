#pragma once
// Vector types of blockdem (Eigen, double precision).

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace blockdem {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quaternion = Eigen::Quaterniond;

/// r v, written out: in the hot loops GCC does not always inline Eigen's fixed-size product (it showed as an
/// out-of-line call taking 10 % of a step).
[[gnu::always_inline]] inline Vec3 rotate(const Mat3& r, const Vec3& v) {
  return Vec3(r(0, 0) * v[0] + r(0, 1) * v[1] + r(0, 2) * v[2], r(1, 0) * v[0] + r(1, 1) * v[1] + r(1, 2) * v[2],
              r(2, 0) * v[0] + r(2, 1) * v[1] + r(2, 2) * v[2]);
}

/// r^T v, written out.
[[gnu::always_inline]] inline Vec3 rotate_back(const Mat3& r, const Vec3& v) {
  return Vec3(r(0, 0) * v[0] + r(1, 0) * v[1] + r(2, 0) * v[2], r(0, 1) * v[0] + r(1, 1) * v[1] + r(2, 1) * v[2],
              r(0, 2) * v[0] + r(1, 2) * v[1] + r(2, 2) * v[2]);
}

}  // namespace blockdem
