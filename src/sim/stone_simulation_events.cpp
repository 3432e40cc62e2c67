// StoneSimulation's segment events: the World's events converted (exact instant as a whole-ns
// stamp and an offset, names, checked outputs), numbered into segments, and its own announced.
#include <cmath>
#include <stdexcept>

#include "virtual_go/common/sim_time.h"
#include "virtual_go/sim/stone_simulation.h"

namespace virtual_go {
namespace {

EventReason event_reason(WorldEventKind kind) {
  switch (kind) {
    case WorldEventKind::impact:
      return EventReason::impact;
    case WorldEventKind::slide:
      return EventReason::slide;
    case WorldEventKind::roll:
      return EventReason::roll;
    case WorldEventKind::rim:
      return EventReason::rim;
    case WorldEventKind::lift_off:
      return EventReason::lift_off;
    case WorldEventKind::rest:
      return EventReason::rest;
    case WorldEventKind::wake:
      return EventReason::wake;
  }
  throw std::logic_error("unknown world event kind");
}

}  // namespace

void StoneSimulation::split_world_time(double t_s, std::int64_t& stamp_ns, double& offset_s) const {
  // Relative to the epoch t_s resolves far below a nanosecond; the offset is what remains of it
  // after the whole nanoseconds, in [0, 1e-9).
  std::int64_t k = static_cast<std::int64_t>(std::floor(to_nanoseconds(t_s)));
  double offset = t_s - to_seconds(k);
  while (offset < 0.0) offset = t_s - to_seconds(--k);
  while (offset >= 1e-9) offset = t_s - to_seconds(++k);
  stamp_ns = epoch_ns_ + k;
  offset_s = offset;
}

SegmentEvent StoneSimulation::segment_event(const WorldEvent& event) const {
  SegmentEvent out;
  split_world_time(event.time_s, out.stamp_ns, out.time_offset_s);
  out.reason = event_reason(event.kind);
  out.detail = world_event_detail_name(event.detail);
  out.stone = name_of(event.id);
  if (event.other) out.other_stone = name_of(*event.other);
  out.state = event.state;
  out.output = state_output(model_of(event.id), event.state);  // throws if not finite
  return out;
}

SegmentEvent StoneSimulation::command_event(std::int64_t stamp_ns, EventReason reason,
                                            const std::string& stone, const RigidBodyState& state,
                                            const MotionModel& model) {
  SegmentEvent e;
  e.stamp_ns = stamp_ns;
  e.reason = reason;
  e.stone = stone;
  e.state = state;
  e.output = state_output(model, state);
  return e;
}

void StoneSimulation::append_after_wake(const std::vector<WorldEvent>& world_events,
                                        std::vector<SegmentEvent> commands,
                                        std::vector<SegmentEvent>& events) const {
  std::size_t i = 0;
  for (; i < world_events.size() && world_events[i].kind == WorldEventKind::wake; ++i) {
    events.push_back(segment_event(world_events[i]));
  }
  for (SegmentEvent& command : commands) events.push_back(std::move(command));
  for (; i < world_events.size(); ++i) events.push_back(segment_event(world_events[i]));
}

void StoneSimulation::commit_events(std::vector<SegmentEvent>& events, UpdateResult& result) {
  for (SegmentEvent& event : events) {
    if (event.reason != EventReason::start) ++segment_;
    event.segment = segment_;
    // Rest and the age of the motion (~auto_reset_*) are those of the initial stone.
    if (event.stone != stone_name(0)) {
      result.events.push_back(std::move(event));
      continue;
    }
    if (event.reason == EventReason::rest) {
      rest_since_ns_ = event.stamp_ns + (event.time_offset_s > 0.0 ? 1 : 0);
    } else {
      rest_since_ns_ = -1;
    }
    // The age ~auto_reset_period counts is that of the motion given from outside.
    if (event.reason < EventReason::impact) segment_start_ns_ = event.stamp_ns;
    result.events.push_back(std::move(event));
  }
}

void StoneSimulation::begin_segment(EventReason reason, std::int64_t stamp_ns,
                                    UpdateResult& result) {
  announce(reason, stamp_ns, state_, output_, result);
}

void StoneSimulation::announce(EventReason reason, std::int64_t stamp_ns,
                               const RigidBodyState& state, const StateOutput& output,
                               UpdateResult& result) {
  if (reason != EventReason::start) ++segment_;
  if (reason != EventReason::held) segment_start_ns_ = stamp_ns;
  SegmentEvent event;
  event.stamp_ns = stamp_ns;
  event.segment = segment_;
  event.reason = reason;
  event.stone = stone_name(0);
  event.state = state;
  event.output = output;
  if (reason == EventReason::held) event.detail = failure_;
  result.events.push_back(std::move(event));
}

}  // namespace virtual_go
