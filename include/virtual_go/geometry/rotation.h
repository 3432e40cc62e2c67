// Quaternion helpers: exponential map, geodesic distance.
#pragma once

#include <Eigen/Geometry>

namespace virtual_go {

// Rotation by angle |v| about v / |v| (identity for v = 0). Accurate for tiny |v|.
// Throws InvalidArgument for a non-finite v.
Eigen::Quaterniond rotation_exp(const Eigen::Vector3d& v);

// Geodesic angle between two orientations, sign-insensitive and accurate near zero:
// 2 atan2(|vec(p* q)|, |w(p* q)|).
double orientation_error(const Eigen::Quaterniond& reference, const Eigen::Quaterniond& q);

}  // namespace virtual_go
