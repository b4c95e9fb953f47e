#pragma once
// Vector types of blockdem (Eigen, double precision).

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace blockdem {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quaternion = Eigen::Quaterniond;

}  // namespace blockdem
