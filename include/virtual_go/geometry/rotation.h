// Quaternion helpers: exponential map, geodesic distance.
#pragma once

#include <Eigen/Geometry>

namespace virtual_go {

// Rotation by angle |v| about v / |v| (identity for v = 0). Accurate for tiny |v|.
// Throws InvalidArgument for a non-finite v.
Eigen::Quaterniond rotation_exp(const Eigen::Vector3d& v);

// q * v for a unit q, without the intermediate overflow of the plain product: Eigen's
// v + 2w (u x v) + 2 u x (u x v) overflows once |v| exceeds about half the largest double
// (|2 u x v| reaches 2 |v|), although the result, of length |v|, is representable. A vector that
// large is scaled by its largest component first. Non-finite v gives a non-finite result.
Eigen::Vector3d rotate_without_overflow(const Eigen::Quaterniond& q, const Eigen::Vector3d& v);

// Geodesic angle between two orientations, sign-insensitive and accurate near zero:
// 2 atan2(|vec(p* q)|, |w(p* q)|).
double orientation_error(const Eigen::Quaterniond& reference, const Eigen::Quaterniond& q);

}  // namespace virtual_go
