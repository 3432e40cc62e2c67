// Signed distance of a Go stone's lens to a plane, a point and a line, with witness point and
// normal (docs/physics.md, "Contact geometry"). Everything is in the world frame and depends on
// the lens only through its centre G and its symmetry axis b: a spin about b moves no surface
// point.
//
// Sign convention: the gap is > 0 when apart and < 0 when overlapping. The normal n is a unit
// vector pointing from the obstacle into the stone (the direction the stone must move to
// separate). The witness point is the lens point deepest along -n, so for a plane
// n . point = plane height + gap.
//
// All three gaps are "separating-axis" gaps: the gap along a fixed unit direction n,
//   g_n = n . x_G - reach(b . n) - h_O(n),   h_O(n) = max over the obstacle of n . o,
// is a lower bound of the distance for every n and equals it for the best n (convex duality).
// For a plane n is fixed; for a point every direction is a candidate; for a line the directions
// perpendicular to it. When overlapping, the gap is minus the shortest translation that separates
// (restricted to directions perpendicular to the line for a line).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/geometry/lens_geometry.h"

namespace virtual_go {

// Where the lens is: its centre and its unit symmetry axis, world frame.
struct LensPose {
  Eigen::Vector3d center_world = Eigen::Vector3d::Zero();  // G, m
  Eigen::Vector3d axis_world = Eigen::Vector3d::UnitZ();   // b = R(q) e_z, unit
};

LensPose lens_pose(const RigidBodyState& state);

// A point of the lens at pose `from` carried rigidly to pose `to`: translated with the centre and
// turned by the shortest rotation from the one axis to the other. The lens is symmetric about its
// axis, so every rotation taking the one axis to the other maps its surface onto itself: a
// surface point stays a surface point (whatever the body's turn about its axis was).
Eigen::Vector3d lens_point_carried(const Eigen::Vector3d& point_world, const LensPose& from,
                                   const LensPose& to);

struct LensContact {
  double gap_m = 0.0;                                       // signed: > 0 apart, < 0 overlapping
  Eigen::Vector3d point_world = Eigen::Vector3d::Zero();    // on the lens surface
  Eigen::Vector3d normal_world = Eigen::Vector3d::UnitZ();  // unit, obstacle -> stone
  LensPart part = LensPart::bottom_cap;                     // where the witness point lies
};

// The lens point deepest along -n (the support point in direction -n) and its part.
Eigen::Vector3d lens_support_world(const LensGeometry& lens, const LensPose& pose,
                                   const Eigen::Vector3d& normal_world, LensPart* part = nullptr);

// Gap along a fixed unit direction n to an obstacle whose support along n is `support_m`
// (= max over the obstacle of n . o): n . x_G - reach(b . n) - support_m. For the plane
// {p : n . p = h0} with the stone on the +n side this is the exact signed distance (support h0).
LensContact lens_gap_along(const LensGeometry& lens, const LensPose& pose,
                           const Eigen::Vector3d& normal_world, double support_m);
// Its gap alone (lens_gap_along(...).gap_m bit for bit) without the support point, which costs
// more: for a caller that compares candidates first and needs the point of the winner only.
double lens_gap_value_along(const LensGeometry& lens, const LensPose& pose,
                            const Eigen::Vector3d& normal_world, double support_m);

// Exact signed distance to a point (closed form): a cap's sphere when its nearest point lies on
// the cap, else the nearest rim point; inside, the nearer of the two spheres.
LensContact lens_point_distance(const LensGeometry& lens, const LensPose& pose,
                                const Eigen::Vector3d& point_world);

// Signed distance to the infinite line through `point_world` along the unit `direction_world`.
// A cap facing the line has the closed form |S_perp| - R (S the cap's sphere centre); otherwise
// the best direction perpendicular to the line is found by a 1-D maximisation (sampling, then a
// bracketed root of the derivative: TOMS 748). Exact to round-off when apart.
LensContact lens_line_distance(const LensGeometry& lens, const LensPose& pose,
                               const Eigen::Vector3d& point_world,
                               const Eigen::Vector3d& direction_world);

}  // namespace virtual_go
