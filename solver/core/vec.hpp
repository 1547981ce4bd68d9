#pragma once
// Small vector types used throughout the solver: Eigen's fixed-size types, so the linear algebra
// (rotations, inertia tensors, eigen-decompositions) comes from a well-kept library.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace seedcal {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

inline Vec3 zero3() { return Vec3::Zero(); }

}  // namespace seedcal
