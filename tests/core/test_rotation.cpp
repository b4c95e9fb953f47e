// The inlined orientation update against Eigen's angle-axis rotation (the reference), for angles on both sides of
// the series threshold.
#include <doctest/doctest.h>

#include <cmath>

#include "blockdem/core/rotation.hpp"
#include "../approx.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_rotation {

TEST_CASE("rotation: turned() equals exp(w dt / 2) q from Eigen's angle-axis, for small and large angles") {
  const Quaternion q = Quaternion(Eigen::AngleAxisd(0.7, Vec3(1, -2, 0.5).normalized()));
  const Vec3 axis = Vec3(-0.3, 0.8, 0.2).normalized();
  for (const double angle : {1e-9, 1e-5, 1e-3, 0.0199, 0.0201, 0.5, 3.0}) {  // the series holds below 0.02 rad
    const double dt = 1e-3;
    const Vec3 w = axis * (angle / dt);
    const Quaternion expected = Quaternion(Eigen::AngleAxisd(angle, axis)) * q;
    const Quaternion got = turned(q, w, dt);
    CAPTURE(angle);
    CHECK((got.coeffs() - expected.coeffs()).norm() < 4e-16);
    CHECK(std::abs(got.norm() - 1.0) < 3e-16);
    CHECK((rotation_matrix(got) - got.toRotationMatrix()).norm() < 1e-15);
  }
}

TEST_CASE("rotation: small_angle_between() is the angle to third order (plus rounding of the unit quaternions)") {
  const Quaternion q0 = Quaternion(Eigen::AngleAxisd(1.1, Vec3(0, 0.6, 0.8)));
  for (const double angle : {1e-8, 1e-4, 1e-2}) {
    const Quaternion q = Quaternion(Eigen::AngleAxisd(angle, Vec3(1, 0, 0))) * q0;
    CAPTURE(angle);
    CHECK(std::abs(small_angle_between(q, q0) - angle) < angle * angle * angle + 1e-15);
  }
}

}  // namespace test_rotation
