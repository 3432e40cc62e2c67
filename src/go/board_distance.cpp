#include "virtual_go/go/board_distance.h"

#include <cmath>
#include <limits>

namespace virtual_go {

namespace {

// Gaps closer than this (m) are a tie: round-off of sub-metre coordinates is ~1e-17 m.
constexpr double kTieM = 1e-15;

int dimension(const BoardFeature& f) {
  switch (f.kind) {
    case BoardFeatureKind::top_edge:
    case BoardFeatureKind::vertical_edge:
      return 1;
    case BoardFeatureKind::top_corner:
      return 0;
    default:
      return 2;
  }
}

int quadrant_sign_x(int q) { return (q == 0 || q == 3) ? 1 : -1; }
int quadrant_sign_y(int q) { return q < 2 ? 1 : -1; }

}  // namespace

std::string board_feature_name(const BoardFeature& f) {
  const std::string index = "[" + std::to_string(f.index) + "]";
  switch (f.kind) {
    case BoardFeatureKind::top_face:
      return "top_face";
    case BoardFeatureKind::side_face:
      return "side_face" + index;
    case BoardFeatureKind::top_edge:
      return "top_edge" + index;
    case BoardFeatureKind::vertical_edge:
      return "vertical_edge" + index;
    case BoardFeatureKind::top_corner:
      return "top_corner" + index;
    case BoardFeatureKind::table:
    default:
      return "table";
  }
}

BoardDistance::BoardDistance(const LensGeometry& lens, const BoardGeometry& board)
    : lens_(lens),
      board_(board),
      hx_(board.half_extent_m().x()),
      hy_(board.half_extent_m().y()),
      thickness_(board.thickness_m) {}

Eigen::Vector3d BoardDistance::side_normal(int index) const {
  switch (index & 3) {
    case 0:
      return Eigen::Vector3d::UnitX();
    case 1:
      return Eigen::Vector3d::UnitY();
    case 2:
      return -Eigen::Vector3d::UnitX();
    default:
      return -Eigen::Vector3d::UnitY();
  }
}

Eigen::Vector3d BoardDistance::corner(int index) const {
  return Eigen::Vector3d(quadrant_sign_x(index) * hx_, quadrant_sign_y(index) * hy_, 0.0);
}

Eigen::Vector3d BoardDistance::edge_point(const BoardFeature& edge) const {
  if (edge.kind == BoardFeatureKind::vertical_edge) {
    return Eigen::Vector3d(quadrant_sign_x(edge.index) * hx_, quadrant_sign_y(edge.index) * hy_,
                           -thickness_);
  }
  switch (edge.index & 3) {  // top edges start at their -x or -y end
    case 0:
      return Eigen::Vector3d(hx_, -hy_, 0.0);
    case 1:
      return Eigen::Vector3d(-hx_, hy_, 0.0);
    case 2:
      return Eigen::Vector3d(-hx_, -hy_, 0.0);
    default:
      return Eigen::Vector3d(-hx_, -hy_, 0.0);
  }
}

Eigen::Vector3d BoardDistance::edge_direction(const BoardFeature& edge) const {
  if (edge.kind == BoardFeatureKind::vertical_edge) return Eigen::Vector3d::UnitZ();
  return (edge.index % 2 == 0) ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
}

double BoardDistance::edge_length(const BoardFeature& edge) const {
  if (edge.kind == BoardFeatureKind::vertical_edge) return thickness_;
  return (edge.index % 2 == 0) ? 2.0 * hy_ : 2.0 * hx_;
}

double BoardDistance::box_support(const Eigen::Vector3d& n) const {
  return std::abs(n.x()) * hx_ + std::abs(n.y()) * hy_ + std::max(0.0, -n.z()) * thickness_;
}

double BoardDistance::obstacle_support(const BoardFeature& feature,
                                       const Eigen::Vector3d& n) const {
  if (feature.kind != BoardFeatureKind::table) return box_support(n);
  if (n.x() == 0.0 && n.y() == 0.0 && n.z() > 0.0) return -thickness_ * n.z();
  return std::numeric_limits<double>::infinity();
}

BoardContact BoardDistance::table(const LensPose& pose) const {
  BoardContact c;
  c.lens = lens_gap_along(lens_, pose, Eigen::Vector3d::UnitZ(), -thickness_);
  c.feature = {BoardFeatureKind::table, 0};
  return c;
}

double BoardDistance::table_gap(const LensPose& pose) const {
  return lens_gap_value_along(lens_, pose, Eigen::Vector3d::UnitZ(), -thickness_);
}

BoardContact BoardDistance::box(const LensPose& pose) const {
  const Eigen::Vector3d& x = pose.center_world;
  const Eigen::Vector3d& b = pose.axis_world;
  BoardContact best;
  best.lens = lens_gap_along(lens_, pose, Eigen::Vector3d::UnitZ(), 0.0);
  best.feature = {BoardFeatureKind::top_face, 0};
  // Features are considered from faces to edges to corners. At a tie (to round-off) the
  // lower-dimensional feature wins: the touching point then lies on all of them (a corner is on
  // its edges, an edge on its faces) and the lower-dimensional feature's axis is the less
  // constrained one, the true separating direction.
  auto consider = [&](const Eigen::Vector3d& n, const BoardFeature& feature) {
    const LensContact c = lens_gap_along(lens_, pose, n, box_support(n));
    const bool lower_dimension = dimension(feature) < dimension(best.feature);
    if (c.gap_m > best.lens.gap_m || (lower_dimension && c.gap_m >= best.lens.gap_m - kTieM)) {
      best.lens = c;
      best.feature = feature;
    }
  };
  // A side face is a face like the top one, so it replaces the best only with a larger gap: its
  // support point (the dearer part) is needed only then. On the board's interior none does, and
  // n . x - support bounds its gap from above (reach >= 0; rounding is monotone), so most faces
  // need not even their reach.
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d n = side_normal(i);
    const double support = box_support(n);
    if (n.dot(x) - support <= best.lens.gap_m) continue;
    if (lens_gap_value_along(lens_, pose, n, support) > best.lens.gap_m) {
      best.lens = lens_gap_along(lens_, pose, n, support);
      best.feature = {BoardFeatureKind::side_face, i};
    }
  }

  // Which Voronoi regions of the box (outside it: per coordinate below / within / above the
  // box's range) the lens's axis-aligned bounding box reaches; the lens extends reach(b_k)
  // from G along +/- e_k.
  const Eigen::Vector3d ext(lens_.reach(b.x()), lens_.reach(b.y()), lens_.reach(b.z()));
  const bool lo_x = x.x() - ext.x()<-hx_, hi_x = x.x() + ext.x()> hx_;
  const bool mid_x = x.x() - ext.x() <= hx_ && x.x() + ext.x() >= -hx_;
  const bool lo_y = x.y() - ext.y()<-hy_, hi_y = x.y() + ext.y()> hy_;
  const bool mid_y = x.y() - ext.y() <= hy_ && x.y() + ext.y() >= -hy_;
  const bool top_z = x.z() + ext.z() > 0.0;
  const bool band_z = x.z() - ext.z() < 0.0 && x.z() + ext.z() > -thickness_;
  const bool side_x[4] = {hi_x, mid_x, lo_x, mid_x};
  const bool side_y[4] = {mid_y, hi_y, mid_y, lo_y};
  for (int i = 0; i < 4; ++i) {
    if (!(top_z && side_x[i] && side_y[i])) continue;
    const BoardFeature edge{BoardFeatureKind::top_edge, i};
    const LensContact line =
        lens_line_distance(lens_, pose, edge_point(edge), edge_direction(edge));
    consider(line.normal_world, edge);
  }
  for (int q = 0; q < 4; ++q) {
    const bool in_x = quadrant_sign_x(q) > 0 ? hi_x : lo_x;
    const bool in_y = quadrant_sign_y(q) > 0 ? hi_y : lo_y;
    if (!(in_x && in_y)) continue;
    if (top_z) {
      const LensContact point = lens_point_distance(lens_, pose, corner(q));
      consider(point.normal_world, {BoardFeatureKind::top_corner, q});
    }
    if (band_z) {
      const BoardFeature edge{BoardFeatureKind::vertical_edge, q};
      const LensContact line =
          lens_line_distance(lens_, pose, edge_point(edge), edge_direction(edge));
      consider(line.normal_world, edge);
    }
  }
  return best;
}

BoardContact BoardDistance::nearest(const LensPose& pose) const {
  const BoardContact on_box = box(pose);
  // The table's support point only when the table is nearer (above the board it never is).
  return table_gap(pose) < on_box.lens.gap_m ? table(pose) : on_box;
}

BoardContact BoardDistance::feature(const LensPose& pose, const BoardFeature& f) const {
  BoardContact c;
  c.feature = f;
  switch (f.kind) {
    case BoardFeatureKind::top_face:
      c.lens = lens_gap_along(lens_, pose, Eigen::Vector3d::UnitZ(), 0.0);
      break;
    case BoardFeatureKind::side_face: {
      const Eigen::Vector3d n = side_normal(f.index);
      c.lens = lens_gap_along(lens_, pose, n, box_support(n));
      break;
    }
    case BoardFeatureKind::top_edge:
    case BoardFeatureKind::vertical_edge:
      c.lens = lens_line_distance(lens_, pose, edge_point(f), edge_direction(f));
      break;
    case BoardFeatureKind::top_corner:
      c.lens = lens_point_distance(lens_, pose, corner(f.index));
      break;
    case BoardFeatureKind::table:
    default:
      c.lens = lens_gap_along(lens_, pose, Eigen::Vector3d::UnitZ(), -thickness_);
      break;
  }
  return c;
}

}  // namespace virtual_go
