// Signed distance between two lenses (two Go stones, possibly of different sizes) in arbitrary
// poses, with the closest points and the features they lie on (docs/physics.md, "Stone–stone
// contact (primitives)"). World frame throughout; each lens enters only through its centre and
// symmetry axis (LensPose), as in lens_distance.h.
//
// The gap along a unit direction n (from A towards B),
//   F(n) = n . (x_B - x_A) - reach_A(b_A . n) - reach_B(b_B . n),
// is the gap between the two supporting planes with normal n, so F(n) <= signed distance for
// every n, with equality at the best n (convex duality). Its gradient on the sphere is the
// tangential part of w(n) = s_B(-n) - s_A(n), the difference of the two support points, and its
// Hessian is that of the two support functions (R (1 - n n^T) on a cap, a/|n_perp| (P_b - e e^T)
// on the rim): Newton's method on the sphere converges quadratically. When the lenses are apart,
// F has a single local maximum among its positive values (F is concave and positively
// homogeneous), so the ascent from any positive start is exact. It starts from the closed-form
// feature candidates (cap-cap: the line through the two sphere centres; cap-rim: the sphere
// centre to the nearest rim point; the centre line), and, when none of them is positive, from a
// Fibonacci sphere of directions too: overlapping lenses can have several local maxima, the
// best of which is the penetration depth (multistart: checked in the tests against a dense scan
// of directions and by translating the lenses apart).
#pragma once

#include <Eigen/Core>
#include <limits>

#include "virtual_go/geometry/lens_distance.h"
#include "virtual_go/geometry/lens_geometry.h"

namespace virtual_go {

struct LensPairContact {
  // > 0 apart: the distance. < 0 overlapping: minus the penetration depth, the length of the
  // shortest translation of B (along normal_world) that separates the lenses. 0: touching.
  double gap_m = 0.0;
  Eigen::Vector3d normal_world = Eigen::Vector3d::UnitZ();  // unit, from A towards B
  // A's support point along +normal and B's along -normal. Apart: the closest points,
  // point_b - point_a = gap * normal.
  Eigen::Vector3d point_a_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d point_b_world = Eigen::Vector3d::Zero();
  LensPart part_a = LensPart::rim;  // the feature of A at point_a (a cap or the rim)
  LensPart part_b = LensPart::rim;
  int newton_steps = 0;  // accepted steps on the sphere (all starts)
};

// F(n) above for a unit n: a lower bound of the signed distance for every n. m.
double lens_pair_gap_along(const LensGeometry& lens_a, const LensPose& pose_a,
                           const LensGeometry& lens_b, const LensPose& pose_b,
                           const Eigen::Vector3d& normal_world);

// The contact along a fixed unit n: gap F(n), normal n, A's support point along n and B's along
// -n with their features.
LensPairContact lens_pair_contact_along(const LensGeometry& lens_a, const LensPose& pose_a,
                                        const LensGeometry& lens_b, const LensPose& pose_b,
                                        const Eigen::Vector3d& normal_world);

// The signed distance, normal, witness points and features. Exact to round-off (~1e-17 m) when
// apart or touching. Touching, the normal can be any direction of a set (two flat stones rim to
// rim in one plane touch along every tilt of the rims' fans): one of them is returned.
LensPairContact lens_pair_distance(const LensGeometry& lens_a, const LensPose& pose_a,
                                   const LensGeometry& lens_b, const LensPose& pose_b);

// lens_pair_distance for a pair seen a moment before with contact normal previous_normal_world
// (an island's sub-steps and projection sweeps). Apart, the same maximum (unique). Overlapping or
// touching, the local maximum reached by the ascent from the previous normal when its gap is at
// least the closed-form candidates' (else the multistart): the contact followed continuously,
// not searched for anew. It may be a shallower local maximum than the multistart's; its gap is
// still a lower bound of the signed distance, so a correction by it along its normal separates.
LensPairContact lens_pair_distance_from(const LensGeometry& lens_a, const LensPose& pose_a,
                                        const LensGeometry& lens_b, const LensPose& pose_b,
                                        const Eigen::Vector3d& previous_normal_world);

// The contact to push along (impulses, position corrections), from lens_pair_distance's `best`.
// Touching, the normal may be any direction of a set (two flat stones rim to rim: every tilt
// within the rims' fans), and lens_pair_distance returns one of them; overlapping rims have
// their shortest separating translation at the edge of the fans, 44.6 degrees from the stones'
// plane for size 33. Either would make a stone pushed along a row ride up onto its neighbour, and
// a rounded real rim gives neither. The centre line's supporting-plane gap is a lower bound of
// the distance, so a correction along it removes the overlap too: it is taken when its gap is as
// good as best's within gap_tolerance_m, or, overlapping, when its correction is at most 1.5 times
// the shortest; else best.
LensPairContact lens_pair_push_contact(const LensGeometry& lens_a, const LensPose& pose_a,
                                       const LensGeometry& lens_b, const LensPose& pose_b,
                                       const LensPairContact& best, double gap_tolerance_m);

// lens_pair_push_contact's centre-line contact, and whether it is certain to be the push contact
// whatever `best` is, so that lens_pair_distance need not be called. Every best has gap F(n) for
// some n, at most the signed distance, which is at most any upper bound U of it: the centre
// line's gap at least U - gap_tolerance_m / 2 is then as good as best's (the other half of the
// tolerance covers the round-off of the gaps, ~1e-17 m). U is 0 when the midpoint of the two
// support points lies inside both lenses (overlapping), else those points' distance; touching
// and slightly overlapping stones side by side (a row at rest) get their contact this way.
struct CentreLineContact {
  bool valid = false;    // the centres differ: `contact` is the centre line's
  bool certain = false;  // the push contact whatever best is
  LensPairContact contact;
  // U above (m): the signed distance is at most this (infinite when not valid).
  double upper_bound_m = std::numeric_limits<double>::infinity();
};
CentreLineContact lens_pair_centre_line(const LensGeometry& lens_a, const LensPose& pose_a,
                                        const LensGeometry& lens_b, const LensPose& pose_b,
                                        double gap_tolerance_m);

// lens_pair_push_contact given the centre line's contact (from lens_pair_centre_line).
LensPairContact lens_pair_push_contact(const CentreLineContact& along, const LensPairContact& best,
                                       double gap_tolerance_m);

}  // namespace virtual_go
