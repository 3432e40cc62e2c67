// Signed distance of a stone's lens to the Go board (a box, top face at z = 0) and the table
// (the plane z = -thickness the board stands on; docs/physics.md, "Contact geometry"), with the
// feature touched, the witness point on the lens and the normal. The board's features that a stone
// can reach from above or beside it: the top face, the 4 side faces, the 4 top edges, the 4
// vertical edges and the 4 top corners; the table is a plane everywhere (under the board it is
// never the nearest).
//
// The box distance is a separating-axis maximum over the axes of the features the lens can be
// near: the 5 face normals always, and each edge or corner whose Voronoi region the lens's
// bounding box reaches, with its best direction from the lens-line or lens-point distance.
// Every axis gives a lower bound of the distance (so the gap is never overestimated, which is
// what conservative advancement needs) and the nearest feature's axis gives the exact distance
// when apart. When overlapping the gap is minus the smallest overlap over those axes.
#pragma once

#include <Eigen/Core>
#include <string>

#include "virtual_go/geometry/lens_distance.h"
#include "virtual_go/geometry/lens_geometry.h"
#include "virtual_go/go/board.h"

namespace virtual_go {

enum class BoardFeatureKind { top_face, side_face, top_edge, vertical_edge, top_corner, table };

// Index conventions (0..3, counter-clockwise seen from above):
//   side_face, top_edge: the side at +x, +y, -x, -y;
//   vertical_edge, top_corner: the quadrant (+x,+y), (-x,+y), (-x,-y), (+x,-y).
//   top_face and table: 0.
struct BoardFeature {
  BoardFeatureKind kind = BoardFeatureKind::top_face;
  int index = 0;
  bool operator==(const BoardFeature& o) const { return kind == o.kind && index == o.index; }
  bool operator!=(const BoardFeature& o) const { return !(*this == o); }
};

std::string board_feature_name(const BoardFeature& feature);  // e.g. "top_edge[1]"

struct BoardContact {
  LensContact lens;  // gap, witness point on the lens, normal (board -> stone), lens part
  BoardFeature feature;
  bool on_table() const { return feature.kind == BoardFeatureKind::table; }
};

class BoardDistance {
 public:
  BoardDistance(const LensGeometry& lens, const BoardGeometry& board);

  const LensGeometry& lens() const { return lens_; }
  const BoardGeometry& board() const { return board_; }

  // The nearer of box() and table().
  BoardContact nearest(const LensPose& pose) const;
  BoardContact nearest(const RigidBodyState& state) const { return nearest(lens_pose(state)); }
  BoardContact box(const LensPose& pose) const;
  BoardContact table(const LensPose& pose) const;
  // table(pose).lens.gap_m bit for bit, without the witness point (the normal is +z).
  double table_gap(const LensPose& pose) const;
  // The distance to one feature's carrier (its whole plane, line or point), closed form; equal
  // to the board's distance when that feature holds the nearest board point.
  BoardContact feature(const LensPose& pose, const BoardFeature& feature) const;

  // Support of the box along a unit direction: max over the box of n . x, m.
  double box_support(const Eigen::Vector3d& n) const;
  // Support along n of the obstacle `feature` belongs to (box or table); +infinity for the
  // table unless n is +z (a half-space has a finite support only along its normal).
  double obstacle_support(const BoardFeature& feature, const Eigen::Vector3d& n) const;

  // Geometry of the features: the outward normal of a side face, the line of an edge (a point
  // and the unit direction; the segment runs from the point over `edge_length`), a corner.
  Eigen::Vector3d side_normal(int index) const;
  Eigen::Vector3d edge_point(const BoardFeature& edge) const;
  Eigen::Vector3d edge_direction(const BoardFeature& edge) const;
  double edge_length(const BoardFeature& edge) const;
  Eigen::Vector3d corner(int index) const;

 private:
  LensGeometry lens_;
  BoardGeometry board_;
  double hx_, hy_, thickness_;
};

}  // namespace virtual_go
