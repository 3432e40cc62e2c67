#include "virtual_go/sim/click_placement.h"

#include <exception>
#include <optional>

#include "virtual_go/common/formatting.h"
#include "virtual_go/go/go_point.h"

namespace virtual_go {

namespace {

std::string millimetres(const Eigen::Vector3d& position_world) {
  return "(" + format_value(1e3 * position_world.x()) + ", " +
         format_value(1e3 * position_world.y()) + ") mm";
}

}  // namespace

ClickOutcome ClickPlacement::click(StoneSimulation& sim, const Eigen::Vector3d& position_world) {
  ClickOutcome out;
  const std::optional<WorldConfig>& world = sim.world_config();
  if (!world || !world->board_enabled) {
    out.message = "click at " + millimetres(position_world) +
                  " places nothing: there is no board (~board/enabled is false)";
    return out;
  }
  if (!has_go_points(world->board)) {
    out.message = "click at " + millimetres(position_world) +
                  " places nothing: " + no_go_points_reason(world->board);
    return out;
  }
  const BoardGeometry& board = world->board;
  const std::optional<GoPoint> point = nearest_go_point(board, position_world);
  if (!point) {
    out.message = "click at " + millimetres(position_world) +
                  " places nothing: it is off the board (more than half a spacing, " +
                  format_value(1e3 * 0.5 * board.spacing_x_m) + " mm across or " +
                  format_value(1e3 * 0.5 * board.spacing_y_m) +
                  " mm along, beyond the outer lines)";
    return out;
  }
  out.point = gtp_name(*point);
  const std::string occupant = sim.stone_at(*point);
  if (!occupant.empty()) {
    out.message = "click at " + out.point + " places nothing: " + occupant + " already lies there";
    return out;
  }
  PlaceRequest request;  // set down flat at rest (drop_height 0, no twist)
  request.point = out.point;
  request.color = stone_color_name(next_);
  try {
    std::string answer;
    out.name = sim.place(request, answer);
    out.placed = true;
    out.message =
        "click at " + out.point + ": " + request.color + " stone " + out.name + ", " + answer;
    next_ = opponent(next_);
  } catch (const std::exception& e) {
    out.name.clear();
    out.message = "click at " + out.point + " places nothing: " + e.what();
  }
  return out;
}

}  // namespace virtual_go
