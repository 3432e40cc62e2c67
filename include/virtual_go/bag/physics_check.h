// Physics health of a recorded run: splits ~odom into segments at each ~events message, then
// holds each segment to what must hold in its regime (docs/physics.md, "World"):
// - flight (start, reset, auto_reset, set_state, set_angular_velocity, time_jump, lift_off, wake,
//   an impact after which the stone flies): every sample against the exact closed form started
//   from the event's exact instant and state; |q|, energy, world angular momentum, Jellett's
//   integral;
// - contact (slide, roll, rim; an impact that ends in sustained contact): the energy never
//   rises, Jellett's integral on a cap without rolling resistance and spinning friction;
// - rest: every sample bitwise identical, velocities exactly zero;
// and, with the board in ~info, the stone never below the board's top or the table.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "virtual_go/bag/recording.h"
#include "virtual_go/body/motion_model.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/body/rigid_body_state.h"

namespace virtual_go {
namespace bag {

// What a segment is held to, by its event's reason (segment_kind).
enum class SegmentKind { flight, contact, rest };
std::string segment_kind_name(SegmentKind kind);  // "flight", "contact", "rest"

// Which odom samples belong to one segment and where its prediction starts.
struct SegmentPlan {
  // For reports: the event's reason's name, or "first odom" / "stamps went backwards (no
  // event)" without an event. Checks go by the event's EventReason.
  std::string reason;
  std::string detail;           // the event's detail (contact events), else empty
  bool from_event = false;      // true: starts at events[event_index], else at odom[first]
  std::size_t event_index = 0;  // valid when from_event
  std::int64_t start_ns = 0;    // sim time of the segment's first state, rounded down to a ns
  double start_offset_s = 0.0;  // [0, 1e-9): the exact start is start_ns + start_offset_s
  std::size_t first = 0;        // odom samples [first, end) belong to this segment
  std::size_t end = 0;
};

// odom and events in bag order. A sample belongs to the latest event at or before its stamp (an
// event with a sub-ns offset lies after a sample at its rounded-down stamp);
// after a backwards jump of the stamps the next event (a time_jump) starts the new segment.
// Samples before any event, or stamps that go backwards without an event, start a segment at
// that sample. Events without samples (for instance after the last odom) are kept, empty.
std::vector<SegmentPlan> plan_segments(const std::vector<OdomSample>& odom,
                                       const std::vector<SegmentEvent>& events);

// The regime a segment starting with this event is in. An impact is a flight unless the next
// event comes at the same exact instant (stamp and offset): the World publishes an impact that
// ends the bouncing (rebound below the Zeno height) as the impact followed at once by the
// sustained contact's event (docs/physics.md, "World"); such an impact's segment holds no
// samples (they belong to the later event), so it is a contact segment of no length. Every
// other reason not listed (slide, roll, rim: contact; rest: rest) starts a flight.
SegmentKind segment_kind(const std::vector<SegmentEvent>& events, std::size_t index);

// Kinetic plus the magnitude of potential energy: the scale the energy figures are relative to,
// non-zero for a stone that starts at rest at the origin (where its energy itself is zero).
double energy_scale(const RigidBody& body, const Eigen::Vector3d& gravity_world);

// The first field of a sample holding a NaN or infinity ("position", "orientation",
// "linear velocity", "angular velocity"; events: "angular momentum", "time offset"), or nullptr.
const char* non_finite_field(const OdomSample& sample);
const char* non_finite_field(const SegmentEvent& event);

// The recorded state of one odom sample: body twist -> world, L from omega via the model.
// Both throw InvalidArgument for a non-finite value or a zero quaternion.
RigidBodyState state_from_odom(const MotionModel& model, const OdomSample& sample);
RigidBodyState state_from_event(const SegmentEvent& event);

// The motion model that ~info describes; throws InvalidArgument naming a bad field.
MotionModel model_from_info(const RecordingInfo& info);

struct PhysicsSample {
  std::size_t segment = 0;
  std::int64_t stamp_ns = 0;
  double t_s = 0.0;                  // since the segment's start
  double quat_norm_error = 0.0;      // | |q| - 1 | of the recorded quaternion
  double energy_drift = 0.0;         // |E - E0| / energy scale of the segment
  double momentum_drift = 0.0;       // |L - L0| / |L0| (world); L0 = 0: / max |L| of the segment
  double orientation_error = 0.0;    // rad vs the closed form; NaN when there is no prediction
  double position_error = 0.0;       // m vs the closed form; NaN when there is no prediction
  double angular_speed_radps = 0.0;  // |omega|, rad/s
  // The lens's gap above the board's top or the table, m (negative: below it); NaN without the
  // board in ~info.
  double gap_m = 0.0;
  // Contact segments: how far the energy lies above the lowest energy of the segment so far
  // (its event and earlier samples), relative to the segment's energy scale; else NaN.
  double energy_rise = 0.0;
  // |J - J0| / (R max|L|), Jellett's integral J = L . (R e_z -/+ d b) of the cap facing down;
  // NaN where it is not conserved.
  double jellett_drift = 0.0;
};

struct SegmentResult {
  SegmentPlan plan;
  bool predicted = false;  // false: the closed form does not apply (note says why)
  std::string note;
  std::size_t samples = 0;
  double duration_s = 0.0;  // last sample's t_s
  double max_angular_speed_radps = 0.0;
  double max_abs_position = 0.0;  // m, largest |x| seen (scales the round-off allowance)
  double max_quat_norm_error = 0.0;
  double max_energy_drift = 0.0;
  double max_momentum_drift = 0.0;
  double max_orientation_error = 0.0;
  double max_position_error = 0.0;
  SegmentKind kind = SegmentKind::flight;
  // The contact figures (PhysicsSample), maxima over the segment's samples (and its event).
  bool board = false;              // the board is in ~info: the gap was measured
  double min_gap_m = 0.0;          // smallest gap, m
  double max_energy_rise = 0.0;    // contact segments
  bool jellett_conserved = false;  // flights; contact on a cap with l_r = l_s = 0
  double max_jellett_drift = 0.0;
  std::size_t rest_moved = 0;    // rest: samples not bitwise equal to the first, or moving
  double rest_max_move_m = 0.0;  // rest: largest |x - x_first|, m (0 when only bits differ)
};

// Messages with a NaN or infinite value. Such an odom sample gets NaN figures and the rest of
// the report goes on; run_checks fails --strict on any of them (the maxima skip NaN).
struct NonFiniteValues {
  std::size_t count = 0;
  std::int64_t first_stamp_ns = 0;
  std::string first_field;  // as non_finite_field() names it
};

struct PhysicsResult {
  std::vector<SegmentResult> segments;
  std::vector<PhysicsSample> samples;  // in odom order
  NonFiniteValues non_finite_odom;
  NonFiniteValues non_finite_events;
};

// Throws InvalidArgument only when ~info cannot describe a motion model (the message says which
// field); bad odom or event values are reported in the result instead.
PhysicsResult check_physics(const RecordingInfo& info, const std::vector<OdomSample>& odom,
                            const std::vector<SegmentEvent>& events);

// Many stones (~stones): each stone is held to the checks above on its own samples and events.

// The events of one stone, in bag order: those naming it, and for the stone of ~info
// (stone_frame) also those naming none (bags recorded before events named their stone).
std::vector<SegmentEvent> events_of_stone(const std::vector<SegmentEvent>& events,
                                          const std::string& name, const RecordingInfo& info);

// ~info as it describes another stone of the run: the same model, gravity, dt, board and
// materials, with the stone's own lens and mass (a uniform lens of that mass: the World's
// stones are) and its name as stone_frame. Throws InvalidArgument naming a bad width, height or
// mass.
RecordingInfo info_of_stone(const RecordingInfo& info, const StoneTrack& track);

struct StonePhysics {
  std::string name;
  std::string color;
  RecordingInfo info;                    // info_of_stone
  std::optional<PhysicsResult> physics;  // none when the stone cannot be checked (note says why)
  std::string note;
};

}  // namespace bag
}  // namespace virtual_go
