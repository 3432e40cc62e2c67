// The World's stone commands and lookups (docs/physics.md, "World", "Stones, bodies and ids"):
// bodies, adding, removing and clearing stones, moving a resting stone, and reading stones by id
// or index. The physics of advancing is in world.cpp.
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/formatting.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/go/stone_set.h"
#include "virtual_go/world/support_plane.h"
#include "virtual_go/world/world.h"

namespace virtual_go {

std::size_t World::add_body(const WorldBody& body) {
  bodies_.emplace_back(body, config_.motion.gravity_world, config_.board);
  return bodies_.size() - 1;
}

std::size_t World::color_body(StoneColor color) {
  if (color != StoneColor::black && color != StoneColor::white) {
    throw InvalidArgument("color", "color must be black or white, got the value " +
                                       std::to_string(static_cast<int>(color)));
  }
  std::optional<std::size_t>& slot = color_bodies_[color == StoneColor::black ? 0 : 1];
  if (!slot) {
    slot = add_body(world_body(make_stone_body(StoneSet{}, color), config_.motion.model.kind()));
  }
  return *slot;
}

const WorldBodyModel& World::body_model(std::size_t body) const { return bodies_.at(body); }

std::size_t World::start_stone(std::size_t body, const RigidBodyState& state, double t_s) {
  const std::size_t i = stones_.add(body);
  StoneHot& h = stones_.hot(i);
  h.state = state;
  h.state_time_s = t_s;
  begin_flight(i, state, t_s, false);
  (void)advance_stone(i, t_s, std::numeric_limits<long>::max());
  return i;
}

StoneId World::add_stone(std::size_t body, const RigidBodyState& state, double t_s,
                         std::vector<WorldEvent>& events) {
  if (body >= bodies_.size()) {
    throw InvalidArgument("body", "body " + std::to_string(body) + " does not exist (" +
                                      std::to_string(bodies_.size()) + " bodies)");
  }
  check_time("stone", t_s);
  check_state("state", bodies_[body], state);
  if (t_s > time_) advance_to(t_s, events);
  const std::size_t i = start_stone(body, state.validated(), t_s);
  flush(events);
  return stones_.id(i);
}

StoneId World::add_stone(StoneColor color, const RigidBodyState& state, double t_s,
                         std::vector<WorldEvent>& events) {
  if (color != StoneColor::black && color != StoneColor::white) (void)color_body(color);  // throws
  std::optional<std::size_t>& slot = color_bodies_[color == StoneColor::black ? 0 : 1];
  if (!slot) {
    // The colour's first stone: its body is checked with the stone before it is kept, so that
    // a refused stone changes nothing.
    const WorldBodyModel model(
        world_body(make_stone_body(StoneSet{}, color), config_.motion.model.kind()),
        config_.motion.gravity_world, config_.board);
    check_time("stone", t_s);
    check_state("state", model, state);
    bodies_.push_back(model);
    slot = bodies_.size() - 1;
  }
  return add_stone(*slot, state, t_s, events);
}

std::size_t World::index_of(StoneId id) const {
  const std::optional<std::size_t> i = stones_.index_of(id);
  if (!i) {
    throw InvalidArgument("stone", stone_id_name(id) + " is not in the world (" +
                                       std::to_string(stones_.size()) + " stones)");
  }
  return *i;
}

StoneId World::id(std::size_t stone) const {
  check_stone_index(stone);
  return stones_.id(stone);
}

void World::remove_stone(StoneId id, double t_s, std::vector<WorldEvent>& events) {
  (void)index_of(id);
  check_time("removal", t_s);
  if (t_s > time_) advance_to(t_s, events);
  const std::size_t i = index_of(id);
  if (stones_.record(i).island) dissolve_island(*stones_.record(i).island, i);
  flush(events);  // before the indices after it shift
  stones_.erase(i);
  rebuild_broad_phase();  // its entries are by index (a command: O(stones) as the erase)
}

void World::clear(double t_s) {
  check_time("clear", t_s);
  stones_.clear();
  islands_.clear();
  pending_.clear();
  rebuild_broad_phase();
  time_ = t_s;
}

void World::set_state(StoneId id, const RigidBodyState& state, double t_s,
                      std::vector<WorldEvent>& events) {
  set_state(index_of(id), state, t_s, events);
}

void World::move_resting_stone(StoneId id, const Eigen::Vector2d& position_xy_world, double t_s,
                               std::vector<WorldEvent>& events) {
  const std::size_t i = index_of(id);
  if (stones_.hot(i).mode != StoneMode::resting) {
    throw InvalidArgument("stone", stone_id_name(id) + " is not resting (" +
                                       stone_mode_name(stones_.hot(i).mode) +
                                       "): only a resting stone is moved without waking it");
  }
  if (!position_xy_world.allFinite()) {
    throw InvalidArgument("position", "position must be finite, got (" +
                                          format_value(position_xy_world.x()) + ", " +
                                          format_value(position_xy_world.y()) + ") m");
  }
  check_time("move", t_s);
  const WorldBodyModel& body = body_at(i);
  RigidBodyState moved = stones_.hot(i).state;
  moved.position_world.x() = position_xy_world.x();
  moved.position_world.y() = position_xy_world.y();
  if (config_.board_enabled) {
    // It must lie on the top face as before: its lowest point inside the face, at the same
    // height (a flat stone's contact does not depend on where on the face it is).
    const BoardContact before = body.board().nearest(stones_.hot(i).state);
    const BoardContact after = body.board().nearest(moved);
    const std::optional<SupportPlane> plane =
        support_plane(body.board(), after, lens_pose(moved), 0.0);
    if (before.feature.kind != BoardFeatureKind::top_face || !plane ||
        plane->feature.kind != BoardFeatureKind::top_face) {
      throw InvalidArgument("position", "position (" + format_value(position_xy_world.x()) + ", " +
                                            format_value(position_xy_world.y()) +
                                            ") m: a resting stone is moved only on the board's "
                                            "top face, with its lowest point inside it");
    }
  }
  if (t_s > time_) advance_to(t_s, events);
  stones_.hot(i).state = moved;
  stones_.hot(i).state_time_s = t_s;
  if (broad_phase_.contains(i))
    broad_phase_.update(i, sphere_bounds(moved.position_world, body.lens().half_width()), false);
  // Said, not silent: a recording must see the resting stone's new pose begin here.
  WorldEvent e;
  e.time_s = t_s;
  e.stone = i;
  e.id = id;
  e.kind = WorldEventKind::rest;
  e.detail = WorldEventDetail::nudge;
  e.state = moved;
  events.push_back(e);
}

std::optional<StoneColor> World::color(StoneId id) const {
  return bodies_[stones_.body(index_of(id))].body().color;
}

const RigidBodyState& World::state(std::size_t stone) const {
  check_stone_index(stone);
  return stones_.hot(stone).state;
}
StoneMode World::mode(std::size_t stone) const {
  check_stone_index(stone);
  return stones_.hot(stone).mode;
}
ContactPhase World::contact_phase(std::size_t stone) const {
  check_stone_index(stone);
  return virtual_go::contact_phase(stones_.hot(stone).mode);
}
std::size_t World::body_of(std::size_t stone) const {
  check_stone_index(stone);
  return stones_.body(stone);
}

double World::next_contact_time(std::size_t stone) const {
  check_stone_index(stone);
  const StoneHot& h = stones_.hot(stone);
  return h.mode == StoneMode::flight ? h.next_contact_s : std::numeric_limits<double>::infinity();
}

double World::energy(std::size_t stone) const {
  const MotionSetup& setup = bodies_[body_of(stone)].setup();
  return body_energy(setup.model, state(stone), setup.gravity_world);
}

}  // namespace virtual_go
