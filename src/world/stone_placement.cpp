#include "virtual_go/world/stone_placement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/formatting.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/world/support_plane.h"

namespace virtual_go {
namespace {

// Every disc is widened by this (m), so that a solved layout keeps a positive gap through the
// round-off of the centres (~1e-17 m at board scale).
constexpr double kMarginM = 1e-12;
// A resting stone is "flat" when its axis is this close to vertical (|b_z| >= 1 - this).
constexpr double kFlatTolerance = 1e-12;

void check_point(const World& world, GoPoint point) {
  if (!is_on_grid(point)) {
    throw InvalidArgument("point", "point (column " + std::to_string(point.column) + ", row " +
                                       std::to_string(point.row) + ") is off the 19 x 19 grid " +
                                       "(columns and rows 0 .. 18, A1 .. T19)");
  }
  if (!world.config().board_enabled) {
    throw InvalidArgument("board",
                          "stones are placed at Go points only on a board (the world "
                          "has none)");
  }
  (void)go_point_world(world.config().board, point);  // throws "board" unless 19 lines
}

struct Disc {
  Eigen::Vector2d centre;
  double radius;     // the stone's half width
  bool movable;      // flat and resting on the top face
  std::size_t from;  // its index in the planner's stones
};

struct Layout {
  Eigen::Vector2d point;  // the intersection
  double radius;          // the new stone's half width
  double z_centre;        // the new stone's centre height
  std::vector<Disc> discs;
};

void check_request(const World& world, StoneColor color, GoPoint point, double t_s) {
  if (color != StoneColor::black && color != StoneColor::white) {
    throw InvalidArgument("color", "color must be black or white, got the value " +
                                       std::to_string(static_cast<int>(color)));
  }
  check_point(world, point);
  require_finite("time", t_s);
  if (t_s < world.time()) {
    throw InvalidArgument("time", "placement time " + format_value(t_s) +
                                      " s is before the world's time " +
                                      format_value(world.time()) + " s");
  }
}

// The new stone flat at (x, y), its lowest point on the top face.
RigidBodyState flat_on_face(const World& world, std::size_t body, const Eigen::Vector2d& xy,
                            double lift_m) {
  RigidBodyState s;
  s.position_world = Eigen::Vector3d(xy.x(), xy.y(), 0.0);
  s = placed_on_plane(world.body_model(body).lens(), s, world.config().board.top_z_m());
  s.position_world.z() += lift_m;
  return s;
}

bool is_flat_on_face(const World& world, std::size_t index) {
  if (!world.is_resting(index)) return false;
  const RigidBodyState& s = world.state(index);
  const Eigen::Vector3d axis = s.orientation.normalized() * Eigen::Vector3d::UnitZ();
  if (std::abs(axis.z()) < 1.0 - kFlatTolerance) return false;
  const BoardContact c = world.body_model(world.body_of(index)).board().nearest(s);
  return c.feature.kind == BoardFeatureKind::top_face;
}

Layout layout_around(const World& world, std::size_t body, GoPoint point,
                     const std::vector<PlanStone>& stones) {
  Layout l;
  l.point = go_point_world(world.config().board, point).head<2>();
  l.radius = world.body_model(body).lens().half_width();
  l.z_centre = flat_on_face(world, body, l.point, 0.0).position_world.z();
  for (std::size_t i = 0; i < stones.size(); ++i) {
    const PlanStone& s = stones[i];
    // Only stones whose bounding ball reaches the new stone's bounding ball's height band.
    if (std::abs(s.z_m - l.z_centre) > s.half_width_m + l.radius) continue;
    l.discs.push_back(Disc{s.centre_xy, s.half_width_m, s.movable, i});
  }
  return l;
}

double reach(const Layout& l, const Disc& d) { return l.radius + d.radius + kMarginM; }

bool inside_face(const World& world, const Eigen::Vector2d& xy) {
  const BoardGeometry& b = world.config().board;
  return std::abs(xy.x()) < b.size_x_m / 2 && std::abs(xy.y()) < b.size_y_m / 2;
}

// The free position nearest the intersection within half a spacing, if any.
std::optional<Eigen::Vector2d> nearest_free(const World& world, const Layout& l) {
  const BoardGeometry& b = world.config().board;
  const double half = 0.5 * std::min(b.spacing_x_m, b.spacing_y_m);
  std::vector<const Disc*> near;
  for (const Disc& d : l.discs) {
    if ((d.centre - l.point).norm() < reach(l, d) + half) near.push_back(&d);
  }
  std::vector<Eigen::Vector2d> candidates{l.point};
  for (const Disc* d : near) {
    const Eigen::Vector2d u = l.point - d->centre;
    const double n = u.norm();
    candidates.push_back(d->centre +
                         reach(l, *d) * (n > 0.0 ? Eigen::Vector2d(u / n) : Eigen::Vector2d(1, 0)));
  }
  for (std::size_t i = 0; i < near.size(); ++i) {
    for (std::size_t j = i + 1; j < near.size(); ++j) {
      const Eigen::Vector2d c0 = near[i]->centre, c1 = near[j]->centre;
      const double r0 = reach(l, *near[i]), r1 = reach(l, *near[j]);
      const Eigen::Vector2d delta = c1 - c0;
      const double d = delta.norm();
      if (!(d > 0.0) || d > r0 + r1 || d < std::abs(r0 - r1)) continue;
      const double along = (d * d + r0 * r0 - r1 * r1) / (2 * d);
      const double across = std::sqrt(std::max(0.0, r0 * r0 - along * along));
      const Eigen::Vector2d e = delta / d, p(-e.y(), e.x());
      candidates.push_back(c0 + along * e + across * p);
      candidates.push_back(c0 + along * e - across * p);
    }
  }
  std::optional<Eigen::Vector2d> best;
  double best_distance = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& c : candidates) {
    const double distance = (c - l.point).norm();
    if (!(distance <= half) || !(distance < best_distance) || !inside_face(world, c)) continue;
    // Free of every disc, allowing the candidate's own round-off (the margin keeps the gap > 0).
    const bool free = std::all_of(l.discs.begin(), l.discs.end(), [&](const Disc& d) {
      return (c - d.centre).norm() >= reach(l, d) - 0.25 * kMarginM;
    });
    if (!free) continue;
    best = c;
    best_distance = distance;
  }
  return best;
}

// The nudge: pairwise projections over the growing cluster until no pair overlaps (by more
// than a quarter of the margin). Positions of the new stone (entry 0) and the discs, in place.
int relax(std::vector<Eigen::Vector2d>& centres, std::vector<double>& radii,
          std::vector<bool>& movable, int max_sweeps) {
  std::vector<std::size_t> cluster{0};
  std::vector<bool> in_cluster(centres.size(), false);
  in_cluster[0] = true;
  for (int sweep = 1; sweep <= max_sweeps; ++sweep) {
    double worst = 0.0;
    for (std::size_t k = 0; k < cluster.size(); ++k) {
      const std::size_t m = cluster[k];
      for (std::size_t j = 0; j < centres.size(); ++j) {
        if (j == m) continue;
        const Eigen::Vector2d delta = centres[j] - centres[m];
        const double reach_m = radii[m] + radii[j] + kMarginM;
        if (std::abs(delta.x()) >= reach_m || std::abs(delta.y()) >= reach_m) continue;
        const double d = delta.norm();
        const double overlap = reach_m - d;
        if (!(overlap > 0.25 * kMarginM)) continue;
        worst = std::max(worst, overlap);
        const Eigen::Vector2d u = d > 0.0 ? Eigen::Vector2d(delta / d) : Eigen::Vector2d(1, 0);
        if (movable[j]) {
          if (!in_cluster[j]) {
            in_cluster[j] = true;
            cluster.push_back(j);
          }
          centres[m] -= 0.5 * overlap * u;
          centres[j] += 0.5 * overlap * u;
        } else {
          centres[m] -= overlap * u;
        }
      }
    }
    if (worst == 0.0) return sweep;
  }
  return -1;
}

}  // namespace

std::vector<PlanStone> plan_stones(const World& world) {
  std::vector<PlanStone> out;
  out.reserve(world.stone_count());
  for (std::size_t i = 0; i < world.stone_count(); ++i) {
    const RigidBodyState& s = world.state(i);
    out.push_back(PlanStone{world.id(i), s.position_world.head<2>(), s.position_world.z(),
                            world.body_model(world.body_of(i)).lens().half_width(),
                            is_flat_on_face(world, i)});
  }
  return out;
}

SetDownPlan plan_set_down(const World& world, std::size_t body, GoPoint point,
                          const std::vector<PlanStone>& stones, const SetDownOptions& options) {
  check_point(world, point);
  if (options.max_sweeps < 1) {
    throw InvalidArgument(
        "max_sweeps", "max_sweeps must be at least 1, got " + std::to_string(options.max_sweeps));
  }
  const Layout l = layout_around(world, body, point, stones);
  SetDownPlan plan;
  Eigen::Vector2d xy = l.point;
  if (const std::optional<Eigen::Vector2d> free = nearest_free(world, l)) {
    xy = *free;
  } else {
    // Entry 0 is the new stone, at its intersection; then every disc.
    std::vector<Eigen::Vector2d> centres{l.point};
    std::vector<double> radii{l.radius};
    std::vector<bool> movable{true};
    for (const Disc& d : l.discs) {
      centres.push_back(d.centre);
      radii.push_back(d.radius);
      movable.push_back(d.movable);
    }
    const int sweeps = relax(centres, radii, movable, options.max_sweeps);
    const std::string name = gtp_name(point);
    if (sweeps < 0) {
      throw InvalidArgument("point", "no room at " + name +
                                         ": the neighbours' nudge did not "
                                         "converge in " +
                                         std::to_string(options.max_sweeps) + " sweeps");
    }
    for (const Eigen::Vector2d& c : centres) {
      if (!inside_face(world, c)) {
        throw InvalidArgument("point", "no room at " + name +
                                           ": the nudge would push a stone "
                                           "off the board's top face");
      }
    }
    plan.nudged = true;
    plan.sweeps = sweeps;
    xy = centres[0];
    for (std::size_t k = 0; k < l.discs.size(); ++k) {
      if (centres[k + 1] == l.discs[k].centre) continue;
      plan.moves.emplace_back(l.discs[k].from, centres[k + 1]);
    }
  }
  plan.xy = xy;
  plan.offset_m = (xy - l.point).norm();
  plan.stone = PlanStone{StoneId{}, xy, l.z_centre, l.radius, true};
  return plan;
}

void apply_plan(std::vector<PlanStone>& stones, const SetDownPlan& plan) {
  for (const auto& [index, centre] : plan.moves) stones.at(index).centre_xy = centre;
  stones.push_back(plan.stone);
}

namespace {

// Advances to t_s and moves the stones a plan nudges; the result without the new stone.
PlacementResult apply_moves(World& world, const std::vector<PlanStone>& stones,
                            const SetDownPlan& plan, double t_s, std::vector<WorldEvent>& events) {
  if (t_s > world.time()) world.advance_to(t_s, events);
  PlacementResult result;
  result.nudged = plan.nudged;
  result.sweeps = plan.sweeps;
  result.offset_m = plan.offset_m;
  for (const auto& [index, centre] : plan.moves) {
    const StoneId id = stones[index].id;
    world.move_resting_stone(id, centre, t_s, events);
    result.moved.push_back(
        MovedStone{id, world.state(id), (centre - stones[index].centre_xy).norm()});
  }
  return result;
}

// A stone lies over the point already: its centre is nearer the intersection than half the
// new stone's width (a player drops onto it, not beside it).
bool point_taken(const Layout& l) {
  return std::any_of(l.discs.begin(), l.discs.end(),
                     [&](const Disc& d) { return (d.centre - l.point).norm() < l.radius; });
}

}  // namespace

PlacementResult set_down_stone(World& world, StoneColor color, GoPoint point, double t_s,
                               std::vector<WorldEvent>& events, const SetDownOptions& options) {
  check_request(world, color, point, t_s);
  if (t_s > world.time() && !world.all_resting()) {
    // The stones that move would be elsewhere at t_s: the plan below would be of the wrong
    // layout, and planning at t_s means advancing first (a change before the checks end).
    throw InvalidArgument("time", "placement time " + format_value(t_s) +
                                      " s is after the world's time " + format_value(world.time()) +
                                      " s while stones move: advance the world to it first");
  }
  const std::size_t body = world.color_body(color);
  const std::vector<PlanStone> stones = plan_stones(world);
  const SetDownPlan plan = plan_set_down(world, body, point, stones, options);
  // Checked: from here on nothing refuses. All at rest (or t_s is now), so the advance moves
  // nothing and the plan holds at t_s.
  PlacementResult result = apply_moves(world, stones, plan, t_s, events);
  result.state = flat_on_face(world, body, plan.xy, 0.0);
  result.id = world.add_stone(body, result.state, t_s, events);
  return result;
}

SetDownPlan plan_drop(const World& world, std::size_t body, GoPoint point,
                      const std::vector<PlanStone>& stones) {
  check_point(world, point);
  // Aimed as a player aims: where set_down_stone would put it (a stone is 22.2 mm wide on a
  // 22 mm grid, so over the intersection itself it would land on its neighbour's rim): the free
  // spot nearest the intersection, else with the resting neighbours nudged apart. Over a point
  // a stone already covers, or with no room, it falls over the intersection onto whatever lies
  // there: physics, not rules.
  const Layout l = layout_around(world, body, point, stones);
  SetDownPlan plan;
  plan.xy = l.point;
  if (const std::optional<Eigen::Vector2d> free = nearest_free(world, l)) {
    plan.xy = *free;
    plan.offset_m = (*free - l.point).norm();
  } else if (!point_taken(l)) {
    try {
      plan = plan_set_down(world, body, point, stones);
    } catch (const InvalidArgument&) {
      plan = SetDownPlan{};  // no room even with a nudge: over the intersection
      plan.xy = l.point;
    }
  }
  plan.stone = PlanStone{StoneId{}, plan.xy, l.z_centre, l.radius, false};  // in the air
  return plan;
}

PlacementResult drop_stone(World& world, StoneColor color, GoPoint point, double drop_height_m,
                           double t_s, std::vector<WorldEvent>& events,
                           const Eigen::Vector3d& velocity_world,
                           const Eigen::Vector3d& angular_velocity_world) {
  check_request(world, color, point, t_s);
  if (!(std::isfinite(drop_height_m) && drop_height_m >= 0.0)) {
    throw InvalidArgument(
        "drop_height", "drop_height must be finite and >= 0 m, got " + format_value(drop_height_m));
  }
  require_finite("velocity", velocity_world);
  require_finite("angular_velocity", angular_velocity_world);
  const std::size_t body = world.color_body(color);
  const std::vector<PlanStone> stones = plan_stones(world);
  SetDownPlan plan = plan_drop(world, body, point, stones);
  if (plan.nudged && t_s > world.time() && !world.all_resting()) {
    // The nudge is planned on the layout now, and stones move before t_s: over the point instead.
    plan = SetDownPlan{};
    plan.xy = go_point_world(world.config().board, point).head<2>();
  }
  // Checked: from here on nothing refuses.
  PlacementResult result = apply_moves(world, stones, plan, t_s, events);
  RigidBodyState s = flat_on_face(world, body, plan.xy, drop_height_m);
  s.velocity_world = velocity_world;
  s = with_angular_velocity_world(world.body_model(body).setup().model, s, angular_velocity_world);
  result.state = s;
  result.id = world.add_stone(body, s, t_s, events);
  return result;
}

}  // namespace virtual_go
