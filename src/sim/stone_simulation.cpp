#include "virtual_go/sim/stone_simulation.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "virtual_go/common/sim_time.h"
#include "virtual_go/flight/integrator_registry.h"

namespace virtual_go {
namespace {

// 1 s behind ROS time: skip rather than catch up.
constexpr std::int64_t kMaxLagNs = kNanosecondsPerSecond;

}  // namespace

StoneSimulation::StoneSimulation(const StoneConfig& config)
    : StoneSimulation(check_config(config)) {}

StoneSimulation::StoneSimulation(CheckedConfig checked)
    : checked_(std::move(checked)),
      integrator_(checked_.integrator->make(*checked_.integrator, checked_.setup)),
      clock_(checked_.dt_ns, std::max(kMaxLagNs, 2 * checked_.dt_ns)),
      state_(checked_.initial_state) {}

void StoneSimulation::reset() {
  pending_.push_back({EventReason::reset, checked_.initial_state, {}, {}});
}

void StoneSimulation::set_angular_velocity(const Eigen::Vector3d& omega, const std::string& frame) {
  const StoneConfig& c = checked_.config;
  const RequestFrame f = request_frame("frame", frame, c.world_frame, c.stone_frame);
  check_angular_velocity("angular_velocity", omega, checked_.angular_velocity_limit);
  pending_.push_back({EventReason::set_angular_velocity, {}, omega, f});
}

void StoneSimulation::set_state(const Eigen::Vector3d& position_world,
                                const Eigen::Vector4d& orientation_xyzw,
                                const Eigen::Vector3d& velocity_world,
                                const Eigen::Vector3d& angular_velocity_world) {
  const RigidBodyState s =
      state_from_request({"pose.position", "pose.orientation", "twist.linear", "twist.angular"},
                         checked_.setup.model, position_world, orientation_xyzw, velocity_world,
                         angular_velocity_world, checked_.angular_velocity_limit);
  pending_.push_back({EventReason::set_state, s, {}, {}});
}

void StoneSimulation::replace_state(const RigidBodyState& state) {
  state_ = state;
  flight_cache_.invalidate();  // the integrator must not continue the old motion
}

void StoneSimulation::begin_segment(EventReason reason, std::int64_t stamp_ns,
                                    UpdateResult& result) {
  if (reason != EventReason::start) ++segment_;
  segment_start_ns_ = stamp_ns;
  result.events.push_back({stamp_ns, segment_, reason, state_});
}

UpdateResult StoneSimulation::update(std::int64_t now_ns) {
  UpdateResult result;
  const SimClock::Plan plan = clock_.plan(now_ns);
  switch (plan.action) {
    case SimClock::Action::wait:
      return result;
    case SimClock::Action::start:
      clock_.restart(now_ns);
      start_ns_ = now_ns;
      replace_state(checked_.initial_state);
      begin_segment(EventReason::start, now_ns, result);
      break;
    case SimClock::Action::jump_back:
    case SimClock::Action::jump_forward:
      // The state keeps going from where it was, but on the new time line: a new segment,
      // and nothing stamped on the old one is published again.
      clock_.restart(now_ns);
      // A held state is only re-timed (so a reset takes effect near ROS time): announcing or
      // publishing it would present the stale state as new.
      if (held_) return result;
      begin_segment(EventReason::time_jump, now_ns, result);
      break;
    case SimClock::Action::advance:
      for (std::int64_t i = 0; i < plan.steps; ++i) {
        try {
          step(result);
        } catch (const IntegrationError& e) {
          result.error = e.what();
          held_ = true;
          break;
        }
        held_ = false;
        result.advanced = true;
      }
      result.stamp_ns = clock_.time_ns();
      return result;
  }
  result.advanced = true;
  result.stamp_ns = clock_.time_ns();
  return result;
}

void StoneSimulation::step(UpdateResult& result) {
  const std::int64_t next_ns = clock_.next_time_ns();
  const std::int64_t auto_reset_ns = checked_.auto_reset_ns;
  const bool auto_reset = auto_reset_ns > 0 && next_ns - segment_start_ns_ >= auto_reset_ns;
  RigidBodyState next = state_;
  // A change that replaces the whole state (any pending one: all apply at this step) makes
  // integrating this step pointless, and lets a reset recover from a state the integrator
  // cannot handle.
  const bool replaced =
      auto_reset || std::any_of(pending_.begin(), pending_.end(),
                                [](const Change& change) { return change.replaces_state(); });
  // Throws with nothing changed (the cache then starts afresh at the next step).
  if (!replaced) integrator_->advance(next, checked_.dt_s, flight_cache_);

  clock_.step();
  state_ = next;
  // Everything due at this step applies in order and starts one segment, named after the last
  // change: an event each would make segments of zero length at the same stamp.
  std::optional<EventReason> reason;
  if (auto_reset) {
    replace_state(checked_.initial_state);
    reason = EventReason::auto_reset;
  }
  for (const Change& change : pending_) {
    if (change.replaces_state()) {
      replace_state(change.state);
    } else {
      const Eigen::Vector3d omega_world = change.frame == RequestFrame::body
                                              ? Eigen::Vector3d(state_.orientation * change.omega)
                                              : change.omega;
      replace_state(with_angular_velocity_world(checked_.setup.model, state_, omega_world));
    }
    reason = change.reason;
  }
  pending_.clear();
  if (reason) begin_segment(*reason, next_ns, result);
}

}  // namespace virtual_go
