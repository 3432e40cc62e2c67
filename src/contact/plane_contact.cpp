// PlaneContact (plane_contact.h): set-up and checks, advance() and the handling of events. The
// other rooms are listed in plane_contact_laws.h.
#include "virtual_go/contact/plane_contact.h"

#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "plane_contact_impl.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/validation.h"

namespace virtual_go {
namespace {
using Vector3 = Eigen::Vector3d;
using plane_contact_detail::ModeChoice;
using plane_contact_detail::Trigger;

// Events at one instant beyond this mean the mode cannot be resolved. Events count as at one
// instant while each follows the previous one by at most kSameInstantS: a motion pinned to an
// event surface (the slip speed held at its direction layer's edge, where the law on either
// side pushes it back across: a Filippov sliding motion the event scheme cannot follow) makes
// events a round-off step (~1e-15 s) apart, which would otherwise go on for thousands of steps.
constexpr int kMaxEventsAtOneInstant = 64;
constexpr double kSameInstantS = 1e-12;
}  // namespace

const char* plane_contact_event_name(PlaneContactEvent event) {
  static constexpr std::pair<PlaneContactEvent, const char*> kNames[] = {
      {PlaneContactEvent::none, "none"},
      {PlaneContactEvent::slip_stop, "slip_stop"},
      {PlaneContactEvent::slip_start, "slip_start"},
      {PlaneContactEvent::roll_stop, "roll_stop"},
      {PlaneContactEvent::roll_start, "roll_start"},
      {PlaneContactEvent::spin_stop, "spin_stop"},
      {PlaneContactEvent::spin_start, "spin_start"},
      {PlaneContactEvent::cap_to_rim, "cap_to_rim"},
      {PlaneContactEvent::rim_to_cap, "rim_to_cap"},
      {PlaneContactEvent::lift_off, "lift_off"},
      {PlaneContactEvent::left_region, "left_region"},
      {PlaneContactEvent::obstacle, "obstacle"},
      {PlaneContactEvent::rest, "rest"},
  };
  for (const auto& [e, name] : kNames) {
    if (e == event) return name;
  }
  return "unknown";
}

PlaneContact::Impl::Impl(const PlaneContactSetup& setup, const PlaneRegion& region,
                         const RigidBodyState& state_in, double t0,
                         const PlaneContactOptions& options)
    : laws_(setup, region, options) {
  require_finite("contact start time", t0);
  require_finite("gravity", setup.gravity_world);
  require_finite("plane height", setup.plane_height_m);
  validate_material("contact material", setup.material);
  validate_region("contact region", region);
  require_positive("contact options.relative_tolerance", options.relative_tolerance);
  require_positive("contact options.absolute_tolerance", options.absolute_tolerance);
  require_positive("contact options.max_step_s", options.max_step_s);
  require_positive("contact options.event_resolution_s", options.event_resolution_s);
  require_positive("contact options.initial_step_s", options.initial_step_s);
  require_positive("contact options.gap_tolerance_m", options.gap_tolerance_m);
  require_positive("contact options.normal_velocity_tolerance_mps",
                   options.normal_velocity_tolerance_mps);
  const RigidBodyState state = state_in.validated();
  const LensGeometry& lens = setup.lens;

  const Vector3 axis = state.orientation * Vector3::UnitZ();
  const double gap = state.position_world.z() - setup.plane_height_m - lens.reach(axis.z());
  if (!(std::abs(gap) <= options.gap_tolerance_m)) {
    throw InvalidArgument(
        "state", "contact start state: gap to the plane z = " + format_value(setup.plane_height_m) +
                     " m is " + format_value(gap) + " m, must be within +/-" +
                     format_value(options.gap_tolerance_m) + " m (the stone must touch the plane)");
  }
  const Vector3 omega =
      setup.model.angular_velocity_world(state.orientation, state.angular_momentum_world);
  PlaneContactMode mode;
  mode.part = lens.part_towards_plane(axis.z());
  // The given state with the height imposed and the vertical velocity as given: measure u_n.
  PlaneContactKinematics k =
      plane_contact_kinematics(setup, mode, state.position_world.head<2>(), state.orientation,
                               state.velocity_world.head<2>(), omega);
  k.velocity_world.z() = state.velocity_world.z();
  const double normal_velocity = k.velocity_world.z() + omega.cross(k.offset_world).z();
  if (!(std::abs(normal_velocity) <= options.normal_velocity_tolerance_mps)) {
    throw InvalidArgument("state", "contact start state: normal velocity of the contact point is " +
                                       format_value(normal_velocity) + " m/s, must be within +/-" +
                                       format_value(options.normal_velocity_tolerance_mps) +
                                       " m/s (an impact or a flight, not a sustained contact)");
  }
  const Vector3 contact_point = k.position_world + k.offset_world;
  if (!region.contains(contact_point.head<2>())) {
    throw InvalidArgument("state", "contact start state: the contact point " +
                                       format_vector(contact_point) +
                                       " is outside the plane's region");
  }
  if (options.clearance_m) {
    const double clearance = options.clearance_m(LensPose{k.position_world, k.axis_world});
    if (!(clearance > 0.0)) {
      throw InvalidArgument("state",
                            "contact start state: the clearance to the other obstacles is " +
                                format_value(clearance) +
                                " m, must be positive (the stone touches more than the "
                                "plane)");
    }
  }
  // Remove u_n by a plastic normal impulse (M-orthogonal projection: energy can only fall), then
  // never let the imposed height raise the energy above the given state's.
  const double energy_in = body_energy(setup.model, state, setup.gravity_world);
  k = laws_.projected(k, mode);
  k = laws_.capped(k, mode, energy_in);

  t_ = t0;
  reached_ = t0;
  window_start_ = t0;
  h_ = options.initial_step_s;
  const ModeChoice choice = laws_.choose_mode(k, mode.part, std::nullopt, std::nullopt, mode_);
  mode_ = choice.mode;
  const double cap = std::min(energy_in, laws_.energy(choice.kinematics));
  start_mode(choice, t0, cap);
  if (choice.result != ModeChoice::Result::mode) {
    const PlaneContactEvent event = choice.result == ModeChoice::Result::rest
                                        ? PlaneContactEvent::rest
                                        : PlaneContactEvent::lift_off;
    const Sample s{choice.kinematics, choice.mode};
    finished_ = Finished{event, t0, s};
    initial_outcome_ = outcome(t0, event, s);
  }
}

RigidBodyState PlaneContact::Impl::to_rigid_body_state(const Sample& s) const {
  RigidBodyState out;
  out.position_world = s.kinematics.position_world;
  out.orientation = s.kinematics.orientation;
  out.velocity_world = s.kinematics.velocity_world;
  out.angular_momentum_world = laws_.setup().model.angular_momentum_world(
      out.orientation, s.kinematics.angular_velocity_world);
  return out;
}

PlaneContactOutcome PlaneContact::Impl::outcome(double t, PlaneContactEvent event,
                                                const Sample& s) const {
  PlaneContactOutcome o;
  o.time_s = t;
  o.event = event;
  o.state = to_rigid_body_state(s);
  o.mode = s.mode;
  o.finished = event == PlaneContactEvent::rest || event == PlaneContactEvent::lift_off ||
               event == PlaneContactEvent::left_region || event == PlaneContactEvent::obstacle;
  return o;
}

void PlaneContact::Impl::require_sample_time(double t) const {
  require_finite("contact sample time", t);
  if (finished_ && finished_->event == PlaneContactEvent::rest && t >= finished_->time) return;
  if (!(t >= window_start_ && t <= reached_)) {
    throw InvalidArgument("t_s", "contact state requested at t = " + format_value(t) +
                                     " s, outside the available range [" +
                                     format_value(window_start_) + ", " + format_value(reached_) +
                                     "] s");
  }
}

PlaneContactForces PlaneContact::Impl::forces_at(double t) const {
  require_sample_time(t);
  const Sample s = sample(t);
  return solve_plane_contact(laws_.setup(), laws_.slaved(s.mode, s.kinematics), s.kinematics);
}

std::optional<PlaneContactOutcome> PlaneContact::Impl::process(const PendingEvent& event) {
  ++laws_.counters().events;
  const double t = event.time;
  if (t - last_event_time_ <= kSameInstantS) {
    if (++events_at_instant_ > kMaxEventsAtOneInstant) {
      throw IntegrationError("plane contact: the contact mode cannot be resolved at t = " +
                             format_value(t) + " s (mode changes keep following each other)");
    }
  } else {
    events_at_instant_ = 0;
  }
  last_event_time_ = t;
  const Sample before = sample(t);
  const PlaneContactMode old_mode = mode_;
  const double cap = laws_.energy(before.kinematics);
  auto finish = [&](PlaneContactEvent kind, const Sample& s) {
    finished_ = Finished{kind, t, s};
    return outcome(t, kind, s);
  };
  PlaneContactEvent kind = PlaneContactEvent::none;
  LensPart part = old_mode.part;
  std::optional<Trigger> snap, release;
  switch (event.trigger) {
    case Trigger::lift_off:
      return finish(PlaneContactEvent::lift_off, before);
    case Trigger::region:
      return finish(PlaneContactEvent::left_region, before);
    case Trigger::clearance:
      return finish(PlaneContactEvent::obstacle, before);
    case Trigger::tangential_layer:
    case Trigger::rolling_layer: {
      // The motion crossed the edge of its direction layer: the same mode goes on with the law
      // of the other side (not reported).
      ModeChoice same;
      same.mode = old_mode;
      ContactLawPart& p =
          event.trigger == Trigger::tangential_layer ? same.mode.tangential : same.mode.rolling;
      p.layer = p.layer == ContactLawPart::Layer::inside ? ContactLawPart::Layer::outside
                                                         : ContactLawPart::Layer::inside;
      same.kinematics = before.kinematics;
      while (!segments_.empty() && segments_.back().t_begin > t) segments_.pop_back();
      pending_.reset();
      start_mode(same, t, cap);
      return std::nullopt;
    }
    case Trigger::part_switch:
      if (old_mode.part == LensPart::rim) {
        part = before.kinematics.axis_world.z() > 0.0 ? LensPart::bottom_cap : LensPart::top_cap;
        kind = PlaneContactEvent::rim_to_cap;
      } else {
        part = LensPart::rim;
        kind = PlaneContactEvent::cap_to_rim;
      }
      break;
    case Trigger::tangential_zero:
      snap = event.trigger;
      kind = PlaneContactEvent::slip_stop;
      break;
    case Trigger::rolling_zero:
      snap = event.trigger;
      kind = PlaneContactEvent::roll_stop;
      break;
    case Trigger::spinning_zero:
      snap = event.trigger;
      kind = PlaneContactEvent::spin_stop;
      break;
    case Trigger::tangential_bound:
      release = event.trigger;
      kind = PlaneContactEvent::slip_start;
      break;
    case Trigger::rolling_bound:
      release = event.trigger;
      kind = PlaneContactEvent::roll_start;
      break;
    case Trigger::spinning_bound:
      release = event.trigger;
      kind = PlaneContactEvent::spin_start;
      break;
  }
  const ModeChoice choice = laws_.choose_mode(before.kinematics, part, snap, release, mode_);
  // Drop what lies beyond the event: the trajectory continues from here in the new mode.
  while (!segments_.empty() && segments_.back().t_begin > t) segments_.pop_back();
  pending_.reset();
  start_mode(choice, t, cap);
  const Sample after{laws_.decode(mode_, y_), mode_};
  if (choice.result == ModeChoice::Result::rest) return finish(PlaneContactEvent::rest, after);
  if (choice.result == ModeChoice::Result::lift_off)
    return finish(PlaneContactEvent::lift_off, after);
  auto summary = [](const PlaneContactMode& m) {
    return std::array<int, 4>{static_cast<int>(m.part), static_cast<int>(m.tangential.law),
                              static_cast<int>(m.rolling.law), static_cast<int>(m.spinning.law)};
  };
  if (summary(mode_) == summary(old_mode)) return std::nullopt;  // e.g. a rocking turn
  // Report what the mode became: the part switch, else the trigger's own part if it changed
  // (a stop that holds is a stop), else the first part that changed.
  if (mode_.part != old_mode.part) return outcome(t, kind, after);
  auto changed = [](ContactLaw before_law, ContactLaw after_law, PlaneContactEvent stop,
                    PlaneContactEvent start) -> std::optional<PlaneContactEvent> {
    if (before_law == after_law) return std::nullopt;
    return after_law == ContactLaw::stuck ? stop : start;
  };
  const std::optional<PlaneContactEvent> changes[] = {
      changed(old_mode.tangential.law, mode_.tangential.law, PlaneContactEvent::slip_stop,
              PlaneContactEvent::slip_start),
      changed(old_mode.rolling.law, mode_.rolling.law, PlaneContactEvent::roll_stop,
              PlaneContactEvent::roll_start),
      changed(old_mode.spinning.law, mode_.spinning.law, PlaneContactEvent::spin_stop,
              PlaneContactEvent::spin_start)};
  std::optional<PlaneContactEvent> first;
  for (const auto& c : changes) {
    if (c && *c == kind) return outcome(t, kind, after);
    if (c && !first) first = c;
  }
  return outcome(t, first.value_or(kind), after);
}

PlaneContactOutcome PlaneContact::Impl::advance(double t_end, long max_steps) {
  require_finite("contact advance time", t_end);
  if (t_end < reached_) {
    throw InvalidArgument("t_end_s", "contact advance time " + format_value(t_end) +
                                         " s is before the time already reached, " +
                                         format_value(reached_) + " s");
  }
  if (initial_outcome_) {
    PlaneContactOutcome o = *initial_outcome_;
    initial_outcome_.reset();
    return o;
  }
  if (finished_) {
    if (finished_->event == PlaneContactEvent::rest) {
      // Exact rest: the frozen state, no work.
      reached_ = window_start_ = t_end;
      PlaneContactOutcome o = outcome(t_end, PlaneContactEvent::none, finished_->sample);
      o.finished = true;
      return o;
    }
    if (t_end > finished_->time) {
      throw InvalidArgument(
          "t_end_s", std::string("contact phase ended at t = ") + format_value(finished_->time) +
                         " s (" + plane_contact_event_name(finished_->event) +
                         "); it cannot be advanced to " + format_value(t_end) + " s");
    }
    return outcome(finished_->time, finished_->event, finished_->sample);
  }
  window_start_ = reached_;
  while (segments_.size() > 1 && segments_.front().t_end < window_start_) segments_.pop_front();
  for (long steps = 0;;) {
    if (pending_ && pending_->time <= t_end) {
      const std::optional<PlaneContactOutcome> o = process(*pending_);
      if (o) {
        reached_ = o->time_s;
        return *o;
      }
      continue;
    }
    if (pending_ || t_ >= t_end) {
      reached_ = t_end;
      return outcome(t_end, PlaneContactEvent::none, sample(t_end));
    }
    if (steps++ >= max_steps) {
      // The work budget is spent: return at the last step's end, to be continued.
      reached_ = t_;
      return outcome(t_, PlaneContactEvent::none, sample(t_));
    }
    take_step();
  }
}

// ---------------------------------------------------------------------------------------------

PlaneContact::PlaneContact(const MotionModel& model, const LensGeometry& lens,
                           const Eigen::Vector3d& gravity_world, double plane_height_m,
                           const PlaneRegion& region, const ContactMaterial& material,
                           const RigidBodyState& state, double t0_s,
                           const PlaneContactOptions& options)
    : impl_(std::make_unique<Impl>(
          PlaneContactSetup{model, lens, gravity_world, plane_height_m, material}, region, state,
          t0_s, options)) {}

PlaneContact::~PlaneContact() = default;
PlaneContact::PlaneContact(const PlaneContact& other)
    : impl_(std::make_unique<Impl>(*other.impl_)) {}
PlaneContact& PlaneContact::operator=(const PlaneContact& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
PlaneContact::PlaneContact(PlaneContact&&) noexcept = default;
PlaneContact& PlaneContact::operator=(PlaneContact&&) noexcept = default;

PlaneContactOutcome PlaneContact::advance(double t_end_s, long max_steps) {
  if (max_steps < 0) {
    throw InvalidArgument(
        "max_steps", "contact advance: max_steps must be >= 0, got " + std::to_string(max_steps));
  }
  return impl_->advance(t_end_s, max_steps);
}
RigidBodyState PlaneContact::state_at(double t_s) const { return impl_->state_at(t_s); }
PlaneContactForces PlaneContact::forces_at(double t_s) const { return impl_->forces_at(t_s); }
double PlaneContact::time_reached() const { return impl_->time_reached(); }
bool PlaneContact::finished() const { return impl_->finished(); }
const PlaneContactMode& PlaneContact::mode() const { return impl_->mode(); }
const PlaneContactSetup& PlaneContact::setup() const { return impl_->setup(); }
const PlaneContactCounters& PlaneContact::counters() const { return impl_->counters(); }

}  // namespace virtual_go
