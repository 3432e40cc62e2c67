#include "virtual_go/go/board.h"

#include "virtual_go/common/validation.h"

namespace virtual_go {

Eigen::Vector3d BoardGeometry::point_world(int i, int j) const {
  const double mid = 0.5 * (lines - 1);
  return Eigen::Vector3d((i - mid) * spacing_x_m, (j - mid) * spacing_y_m, top_z_m());
}

std::vector<Eigen::Vector3d> BoardGeometry::star_points_world() const {
  // Traditional hoshi: on the 4th line from each edge and in the middle (for odd sizes >= 13),
  // or on the 3rd line for small boards.
  std::vector<int> at;
  if (lines >= 13) {
    at = {3, lines / 2, lines - 4};
    if (lines % 2 == 0) at = {3, lines - 4};
  } else if (lines >= 7) {
    at = {2, lines - 3};
  }
  std::vector<Eigen::Vector3d> points;
  for (int i : at) {
    for (int j : at) points.push_back(point_world(i, j));
  }
  return points;
}

void validate_board(const std::string& field, const BoardGeometry& b) {
  auto positive = [&](const std::string& name, double v) {
    if (!(v > 0.0 && v <= kMaxBoardSizeM)) {
      throw InvalidArgument(field, field + ": the " + name + " must be between 0 (exclusive) and " +
                                       format_value(kMaxBoardSizeM) + " m, got " + format_value(v));
    }
  };
  positive("size along x", b.size_x_m);
  positive("size along y", b.size_y_m);
  positive("thickness", b.thickness_m);
  if (b.lines < 2 || b.lines > 100) {
    throw InvalidArgument(field, field + ": the number of lines must be between 2 and 100, got " +
                                     std::to_string(b.lines));
  }
  if ((b.lines - 1) * b.spacing_x_m > b.size_x_m || (b.lines - 1) * b.spacing_y_m > b.size_y_m) {
    throw InvalidArgument(field, field + ": the " + std::to_string(b.lines) + "-line grid (" +
                                     format_value((b.lines - 1) * b.spacing_x_m) + " x " +
                                     format_value((b.lines - 1) * b.spacing_y_m) +
                                     " m) does not fit on the top face (" +
                                     format_value(b.size_x_m) + " x " + format_value(b.size_y_m) +
                                     " m)");
  }
}

}  // namespace virtual_go
