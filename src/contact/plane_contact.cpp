#include "virtual_go/contact/plane_contact.h"

#include <algorithm>
#include <array>
#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <deque>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "virtual_go/common/validation.h"

namespace virtual_go {
namespace {

namespace odeint = boost::numeric::odeint;
using Vector3 = Eigen::Vector3d;

// Integrated coordinates: x_G, y_G; the quaternion (w, x, y, z); v_x, v_y; omega (world). z_G,
// v_z, and whatever the mode holds stuck are derived (plane_contact_kinematics).
constexpr int kStateSize = 11;
using OdeState = std::array<double, kStateSize>;
enum Index { kX = 0, kY = 1, kQw = 2, kQx = 3, kQy = 4, kQz = 5, kVx = 6, kVy = 7, kWx = 8 };
using Dopri5 = odeint::runge_kutta_dopri5<OdeState>;
using DenseStepper = odeint::result_of::make_dense_output<Dopri5>::type;

// Static inequalities are accepted this far past their bound (relative to m |g| and m |g| a):
// round-off of the force solve, not physics.
constexpr double kStaticSlack = 1e-12;
// Directions tried when a stuck part is released with zero velocity.
constexpr int kReleaseDirections = 64;
// Events at one and the same instant beyond this mean the mode cannot be resolved.
constexpr int kMaxEventsAtOneInstant = 64;
// Integrator steps kept for state_at (about 1.4 kB each): a caller advancing far at once can
// sample at least this many steps back.
constexpr std::size_t kMaxStoredSegments = 4096;

enum class Trigger {
  part_switch,
  lift_off,
  region,
  tangential_zero,
  tangential_bound,
  rolling_zero,
  rolling_bound,
  spinning_zero,
  spinning_bound,
  clearance,
};
constexpr int kTriggerCount = 10;

struct EventValues {
  std::array<double, kTriggerCount> g{};
  std::array<bool, kTriggerCount> active{};
};

OdeState encode(const PlaneContactKinematics& k) {
  const Eigen::Quaterniond& q = k.orientation;
  const Vector3& v = k.velocity_world;
  const Vector3& w = k.angular_velocity_world;
  return {k.position_world.x(),
          k.position_world.y(),
          q.w(),
          q.x(),
          q.y(),
          q.z(),
          v.x(),
          v.y(),
          w.x(),
          w.y(),
          w.z()};
}

PlaneContactKinematics decode(const PlaneContactSetup& setup, const PlaneContactMode& mode,
                              const OdeState& y) {
  return plane_contact_kinematics(setup, mode, Eigen::Vector2d(y[kX], y[kY]),
                                  Eigen::Quaterniond(y[kQw], y[kQx], y[kQy], y[kQz]),
                                  Eigen::Vector2d(y[kVx], y[kVy]),
                                  Vector3(y[kWx], y[kWx + 1], y[kWx + 2]));
}

Vector3 horizontal_unit(double angle) { return {std::cos(angle), std::sin(angle), 0.0}; }

// A piece of the trajectory for state_at: one integrator step (or its part before an event), or
// the single state right after an event.
struct Segment {
  double t_begin = 0.0, t_end = 0.0;  // valid range
  double energy_begin = 0.0;  // guarded energy at the step's start, J: the cap of its samples
  PlaneContactMode mode;
  std::shared_ptr<const DenseStepper> dense;  // null: `point` holds the state
  OdeState point{};
};

struct PendingEvent {
  double time = 0.0;
  Trigger trigger = Trigger::lift_off;
};

// Time brackets from TOMS 748 are accepted at this width (s): far below any physical scale,
// a few ulps of a time of hours.
struct TimeTolerance {
  bool operator()(double a, double b) const {
    return std::abs(b - a) <=
           1e-15 + 4 * std::numeric_limits<double>::epsilon() * std::max(std::abs(a), std::abs(b));
  }
};

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

class PlaneContact::Impl {
 public:
  Impl(const PlaneContactSetup& setup, const PlaneRegion& region, const RigidBodyState& state,
       double t0, const PlaneContactOptions& options);

  PlaneContactOutcome advance(double t_end);
  RigidBodyState state_at(double t) const {
    require_sample_time(t);
    return to_rigid_body_state(sample(t));
  }
  PlaneContactForces forces_at(double t) const;
  void require_sample_time(double t) const;

  double time_reached() const { return reached_; }
  bool finished() const { return finished_.has_value(); }
  const PlaneContactMode& mode() const { return mode_; }
  const PlaneContactSetup& setup() const { return setup_; }
  const PlaneContactCounters& counters() const { return counters_; }

 private:
  struct Sample {
    PlaneContactKinematics kinematics;
    PlaneContactMode mode;
  };
  struct Choice {
    enum class Result { mode, lift_off, rest } result = Result::mode;
    PlaneContactMode mode;
    PlaneContactKinematics kinematics;
  };
  struct System {
    Impl* impl;
    void operator()(const OdeState& y, OdeState& dydt, double /*t*/) const { impl->rhs(y, dydt); }
  };

  void rhs(const OdeState& y, OdeState& dydt);
  PlaneContactForces solve(const PlaneContactMode& mode, const PlaneContactKinematics& k) const;
  // The mode with the reference of each part marked `slaved` replaced by the direction its
  // motion is slaved to at k (see slaved_direction).
  PlaneContactMode slaved(const PlaneContactMode& mode, const PlaneContactKinematics& k) const;
  // Newton's method for the zero of the direction residual near the part's reference. `decide`:
  // also require what makes a part slaved at a step's start (a stable zero); within a step only
  // convergence is required, so the law stays smooth.
  bool slaved_direction(const PlaneContactMode& mode, const PlaneContactKinematics& k,
                        bool tangential, bool decide, Vector3& direction) const;
  double energy(const PlaneContactKinematics& k) const { return plane_contact_energy(setup_, k); }
  PlaneContactKinematics capped(const PlaneContactKinematics& k, const PlaneContactMode& mode,
                                double cap) const;
  PlaneContactKinematics projected(const PlaneContactKinematics& k,
                                   const PlaneContactMode& mode) const;
  EventValues event_values(const PlaneContactKinematics& k, const PlaneContactMode& mode) const;
  // The event function of `trigger` (positive while the mode holds); `forces` if already solved.
  double event_value(Trigger trigger, const PlaneContactKinematics& k, const PlaneContactMode& mode,
                     const PlaneContactForces* forces = nullptr) const;
  Choice choose_mode(const PlaneContactKinematics& k, LensPart part, std::optional<Trigger> snap,
                     std::optional<Trigger> release) const;
  Vector3 release_direction(const PlaneContactMode& mode, const PlaneContactKinematics& k,
                            bool tangential, const Vector3& hint) const;
  bool is_static(const PlaneContactKinematics& k, PlaneContactMode* stuck_mode) const;
  void refresh_references();
  void take_step();
  std::optional<PlaneContactOutcome> process(const PendingEvent& event);
  void start_mode(const Choice& choice, double t, double energy_cap);
  Sample sample(double t) const;
  RigidBodyState to_rigid_body_state(const Sample& s) const;
  PlaneContactOutcome outcome(double t, PlaneContactEvent event, const Sample& s) const;

  PlaneContactSetup setup_;
  PlaneRegion region_;
  PlaneContactOptions options_;
  mutable PlaneContactCounters counters_;  // also counts the solves of const look-ups

  PlaneContactMode mode_;
  OdeState y_{};             // integrated state at t_ (the end of the last step)
  double t_ = 0.0;           // integrator time
  double energy_cap_ = 0.0;  // guarded energy at t_, J
  EventValues g_start_;      // event values at t_
  DenseStepper dense_;
  bool stepper_ready_ = false;
  double dt_ = 0.0;
  std::deque<Segment> segments_;
  std::optional<PendingEvent> pending_;
  double reached_ = 0.0;       // time of the last outcome
  double window_start_ = 0.0;  // state_at covers [window_start_, reached_]
  double last_event_time_ = -std::numeric_limits<double>::infinity();
  int events_at_instant_ = 0;

  struct Finished {
    PlaneContactEvent event;
    double time;
    Sample sample;
  };
  std::optional<Finished> finished_;
  std::optional<PlaneContactOutcome> initial_outcome_;
};

// ---------------------------------------------------------------------------------------------
// Construction

PlaneContact::Impl::Impl(const PlaneContactSetup& setup, const PlaneRegion& region,
                         const RigidBodyState& state_in, double t0,
                         const PlaneContactOptions& options)
    : setup_(setup), region_(region), options_(options) {
  require_finite("contact start time", t0);
  require_finite("gravity", setup.gravity_world);
  require_finite("plane height", setup.plane_height_m);
  validate_material("contact material", setup.material);
  validate_region("contact region", region);
  require_positive("contact options.relative_tolerance", options.relative_tolerance);
  require_positive("contact options.absolute_tolerance", options.absolute_tolerance);
  require_positive("contact options.max_step_s", options.max_step_s);
  require_positive("contact options.initial_step_s", options.initial_step_s);
  require_positive("contact options.gap_tolerance_m", options.gap_tolerance_m);
  require_positive("contact options.normal_velocity_tolerance_m_s",
                   options.normal_velocity_tolerance_m_s);
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
      plane_contact_kinematics(setup_, mode, state.position_world.head<2>(), state.orientation,
                               state.velocity_world.head<2>(), omega);
  k.velocity_world.z() = state.velocity_world.z();
  const double normal_velocity = k.velocity_world.z() + omega.cross(k.offset_world).z();
  if (!(std::abs(normal_velocity) <= options.normal_velocity_tolerance_m_s)) {
    throw InvalidArgument("state", "contact start state: normal velocity of the contact point is " +
                                       format_value(normal_velocity) + " m/s, must be within +/-" +
                                       format_value(options.normal_velocity_tolerance_m_s) +
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
  const double m = setup.model.mass_properties().mass();
  const double energy_in = 0.5 * m * state.velocity_world.squaredNorm() +
                           0.5 * omega.dot(k.inertia_world * omega) -
                           m * setup.gravity_world.dot(state.position_world);
  k = projected(k, mode);
  k = capped(k, mode, energy_in);

  t_ = t0;
  reached_ = t0;
  window_start_ = t0;
  dt_ = options.initial_step_s;
  const Choice choice = choose_mode(k, mode.part, std::nullopt, std::nullopt);
  mode_ = choice.mode;
  const double cap = std::min(energy_in, energy(choice.kinematics));
  start_mode(choice, t0, cap);
  if (choice.result != Choice::Result::mode) {
    const PlaneContactEvent event = choice.result == Choice::Result::rest
                                        ? PlaneContactEvent::rest
                                        : PlaneContactEvent::lift_off;
    const Sample s{choice.kinematics, choice.mode};
    finished_ = Finished{event, t0, s};
    initial_outcome_ = outcome(t0, event, s);
  }
}

// ---------------------------------------------------------------------------------------------
// Dynamics pieces

PlaneContactForces PlaneContact::Impl::solve(const PlaneContactMode& mode,
                                             const PlaneContactKinematics& k) const {
  PlaneContactForces f = solve_plane_contact(setup_, mode, k);
  if (!f.solved) {
    // A singular constraint system (for instance Painleve's paradox at an absurd friction
    // coefficient): no consistent contact force exists in this mode.
    throw IntegrationError(
        "plane contact: no consistent contact force (singular constraint "
        "system) at axis " +
        format_vector(k.axis_world));
  }
  return f;
}

bool PlaneContact::Impl::slaved_direction(const PlaneContactMode& mode,
                                          const PlaneContactKinematics& k, bool tangential,
                                          bool decide, Vector3& direction) const {
  // Near zero motion the direction of a sliding part is a fast variable: with the law opposing
  // v / |v|, theta' = residual(theta) / |v| where residual = (s x a(s))_z is the part's
  // acceleration a across the direction s. As |v| -> 0 the direction is slaved to the stable
  // zero of the residual (the consistent sliding direction, residual' < 0) and the equations for
  // theta become stiff (rate ~ mu N / (m |v|)). Inside the direction layer the law therefore
  // opposes that direction itself, found by Newton's method from the reference: a motion growing
  // there leaves the layer already aligned with it, one shrinking there stops along it (the
  // stop event, v . reference = 0, is located as before). Without a stable zero near the
  // reference (Newton diverging or a repelling zero) the part keeps its fixed reference.
  const ContactLawPart& part = tangential ? mode.tangential : mode.rolling;
  auto residual = [&](double angle, double* along) {
    PlaneContactMode trial = mode;
    ContactLawPart& p = tangential ? trial.tangential : trial.rolling;
    p.reference_world = horizontal_unit(angle);
    ++counters_.extra_solves;
    const PlaneContactForces f = solve_plane_contact(setup_, trial, k);
    const Vector3 acc = tangential ? f.slip_acceleration_world
                                   : Vector3(f.angular_acceleration_world.x(),
                                             f.angular_acceleration_world.y(), 0.0);
    const Vector3 s = p.reference_world;
    if (along) *along = s.dot(acc);
    return f.solved ? s.x() * acc.y() - s.y() * acc.x() : std::numeric_limits<double>::quiet_NaN();
  };
  const double start = std::atan2(part.reference_world.y(), part.reference_world.x());
  double angle = start;
  constexpr double kDelta = 1e-7;  // rad, for the derivative
  bool converged = false;
  for (int i = 0; i < 8 && !converged; ++i) {
    const double r = residual(angle, nullptr);
    const double slope = (residual(angle + kDelta, nullptr) - r) / kDelta;
    if (decide ? !(slope < 0.0) : !(slope != 0.0)) return false;
    const double step = -r / slope;
    angle += step;
    if (!(std::abs(angle - start) < 0.5)) return false;  // not near the reference
    converged = std::abs(step) <= 1e-12;
  }
  if (!converged) return false;
  direction = horizontal_unit(angle);
  return true;
}

PlaneContactMode PlaneContact::Impl::slaved(const PlaneContactMode& mode,
                                            const PlaneContactKinematics& k) const {
  PlaneContactMode out = mode;
  if (mode.tangential.law == ContactLaw::sliding && mode.tangential.slaved) {
    slaved_direction(mode, k, true, false, out.tangential.reference_world);
  }
  if (mode.rolling.law == ContactLaw::sliding && mode.rolling.slaved) {
    slaved_direction(out, k, false, false, out.rolling.reference_world);
  }
  return out;
}

void PlaneContact::Impl::rhs(const OdeState& y, OdeState& dydt) {
  ++counters_.rhs_evaluations;
  const PlaneContactKinematics k = decode(setup_, mode_, y);
  const PlaneContactForces f = solve(slaved(mode_, k), k);
  const Vector3& v = k.velocity_world;
  const Vector3& w = k.angular_velocity_world;
  dydt[kX] = v.x();
  dydt[kY] = v.y();
  // dq/dt = 1/2 (0, omega) q on the integrated (not renormalised) quaternion.
  const Eigen::Quaterniond q(y[kQw], y[kQx], y[kQy], y[kQz]);
  const Eigen::Quaterniond q_dot = Eigen::Quaterniond(0.0, w.x(), w.y(), w.z()) * q;
  dydt[kQw] = 0.5 * q_dot.w();
  dydt[kQx] = 0.5 * q_dot.x();
  dydt[kQy] = 0.5 * q_dot.y();
  dydt[kQz] = 0.5 * q_dot.z();
  dydt[kVx] = f.linear_acceleration_world.x();
  dydt[kVy] = f.linear_acceleration_world.y();
  for (int i = 0; i < 3; ++i) dydt[kWx + i] = f.angular_acceleration_world[i];
}

PlaneContactKinematics PlaneContact::Impl::capped(const PlaneContactKinematics& k,
                                                  const PlaneContactMode& mode, double cap) const {
  const double e = energy(k);
  if (e <= cap) return k;
  const double m = setup_.model.mass_properties().mass();
  const double potential = -m * setup_.gravity_world.dot(k.position_world);
  const double kinetic = e - potential;
  // Differences at the round-off of the energy's own evaluation are not a rise.
  const double round_off =
      8 * std::numeric_limits<double>::epsilon() * (std::abs(potential) + std::abs(kinetic));
  if (e <= cap + round_off) return k;
  // Scale (v_t, omega): every derived velocity is linear and homogeneous in them, so u = 0 holds.
  // When even zero motion would exceed the cap (at a turning point), the energy removed is at
  // most the excess itself.
  const double target = cap - potential;
  const double scale = target > 0.0 && kinetic > 0.0 ? std::sqrt(target / kinetic) : 0.0;
  return plane_contact_kinematics(setup_, mode, k.position_world.head<2>(), k.orientation,
                                  scale * k.velocity_world.head<2>(),
                                  scale * k.angular_velocity_world);
}

PlaneContactKinematics PlaneContact::Impl::projected(const PlaneContactKinematics& k,
                                                     const PlaneContactMode& mode) const {
  // Rows of the velocities the mode holds at zero: the normal velocity at P, and the stuck parts.
  const Vector3& r = k.offset_world;
  Eigen::Matrix<double, Eigen::Dynamic, 6, 0, 6, 6> j(6, 6);
  int n = 0;
  auto translational = [&](const Vector3& e) {
    j.row(n).head<3>() = e.transpose();
    j.row(n++).tail<3>() = r.cross(e).transpose();
  };
  auto angular = [&](const Vector3& e) {
    j.row(n).head<3>().setZero();
    j.row(n++).tail<3>() = e.transpose();
  };
  translational(Vector3::UnitZ());
  if (mode.tangential.law == ContactLaw::stuck) {
    translational(Vector3::UnitX());
    translational(Vector3::UnitY());
  }
  if (mode.rolling.law == ContactLaw::stuck) {
    angular(Vector3::UnitX());
    angular(Vector3::UnitY());
  }
  if (mode.spinning.law == ContactLaw::stuck) angular(Vector3::UnitZ());
  j.conservativeResize(n, 6);
  Eigen::Matrix<double, 6, 6> m_inv = Eigen::Matrix<double, 6, 6>::Zero();
  m_inv.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() / setup_.model.mass_properties().mass();
  m_inv.bottomRightCorner<3, 3>() = k.inverse_inertia_world;
  Eigen::Matrix<double, 6, 1> nu;
  nu << k.velocity_world, k.angular_velocity_world;
  // The plastic impulse that stops the constrained velocities: nu -= M^-1 J^T (J M^-1 J^T)^-1 J nu
  // removes 1/2 (J nu)^T (J M^-1 J^T)^-1 (J nu) >= 0 of kinetic energy.
  const auto w = (j * m_inv * j.transpose()).eval();
  const auto impulse = w.fullPivLu().solve(j * nu).eval();
  nu -= m_inv * j.transpose() * impulse;
  PlaneContactKinematics out = plane_contact_kinematics(setup_, mode, k.position_world.head<2>(),
                                                        k.orientation, nu.head<2>(), nu.tail<3>());
  return capped(out, mode, energy(k));
}

double PlaneContact::Impl::event_value(Trigger trigger, const PlaneContactKinematics& k,
                                       const PlaneContactMode& mode,
                                       const PlaneContactForces* forces) const {
  const double cos_beta = setup_.lens.cos_cap_cone();
  const ContactMaterial& law = setup_.material;
  switch (trigger) {
    case Trigger::part_switch:
      switch (mode.part) {
        case LensPart::bottom_cap:
          return k.axis_world.z() - cos_beta;
        case LensPart::top_cap:
          return -k.axis_world.z() - cos_beta;
        case LensPart::rim:
        default:
          return cos_beta - std::abs(k.axis_world.z());
      }
    case Trigger::region:
      return region_.margin_m((k.position_world + k.offset_world).head<2>());
    case Trigger::clearance:
      return options_.clearance_m(LensPose{k.position_world, k.axis_world});
    case Trigger::tangential_zero:
      return k.slip_velocity().dot(mode.tangential.reference_world);
    case Trigger::rolling_zero:
      return k.rolling_velocity().dot(mode.rolling.reference_world);
    case Trigger::spinning_zero:
      return k.spin_velocity() * mode.spinning.reference_world.z();
    default:
      break;
  }
  const PlaneContactForces f = forces ? *forces : solve(slaved(mode, k), k);
  switch (trigger) {
    case Trigger::lift_off:
      return f.normal_force_n;
    case Trigger::tangential_bound:
      return law.friction * f.normal_force_n - f.friction_force_world.norm();
    case Trigger::rolling_bound:
      return law.rolling_resistance_m * f.normal_force_n - f.rolling_couple_world.norm();
    case Trigger::spinning_bound:
      return law.spinning_friction_m * f.normal_force_n - std::abs(f.spinning_couple_nm);
    default:
      return 0.0;
  }
}

EventValues PlaneContact::Impl::event_values(const PlaneContactKinematics& k,
                                             const PlaneContactMode& mode) const {
  // Which events the mode can meet: a sliding part can stop, a stuck part can start.
  EventValues e;
  auto activate = [&](Trigger t) { e.active[static_cast<int>(t)] = true; };
  activate(Trigger::part_switch);
  activate(Trigger::lift_off);
  if (region_.kind != PlaneRegion::Kind::whole_plane) activate(Trigger::region);
  if (options_.clearance_m) activate(Trigger::clearance);
  const std::pair<ContactLaw, std::pair<Trigger, Trigger>> parts[] = {
      {mode.tangential.law, {Trigger::tangential_zero, Trigger::tangential_bound}},
      {mode.rolling.law, {Trigger::rolling_zero, Trigger::rolling_bound}},
      {mode.spinning.law, {Trigger::spinning_zero, Trigger::spinning_bound}}};
  for (const auto& [law, triggers] : parts) {
    if (law == ContactLaw::sliding) activate(triggers.first);
    if (law == ContactLaw::stuck) activate(triggers.second);
  }
  const PlaneContactForces f = solve(slaved(mode, k), k);
  for (int i = 0; i < kTriggerCount; ++i) {
    if (e.active[i]) e.g[i] = event_value(static_cast<Trigger>(i), k, mode, &f);
  }
  return e;
}

// ---------------------------------------------------------------------------------------------
// Mode choice

bool PlaneContact::Impl::is_static(const PlaneContactKinematics& k,
                                   PlaneContactMode* stuck_mode) const {
  // Rest needs no motion at all (within the zero speeds) and every part able to hold it.
  if (k.slip_velocity().norm() > kZeroSlipSpeed ||
      k.rolling_velocity().norm() > kZeroAngularSpeed ||
      std::abs(k.spin_velocity()) > kZeroAngularSpeed) {
    return false;
  }
  PlaneContactMode all = *stuck_mode;
  all.tangential.law = all.rolling.law = all.spinning.law = ContactLaw::stuck;
  const PlaneContactKinematics still = projected(k, all);
  const PlaneContactForces f = solve_plane_contact(setup_, all, still);
  if (!f.solved || !(f.normal_force_n >= 0.0)) return false;
  const double m = setup_.model.mass_properties().mass();
  const double force_slack = kStaticSlack * m * setup_.gravity_world.norm();
  const double couple_slack = force_slack * setup_.lens.half_width();
  const ContactMaterial& law = setup_.material;
  const double n = f.normal_force_n;
  if (f.friction_force_world.norm() > law.friction * n + force_slack) return false;
  if (f.rolling_couple_world.norm() > law.rolling_resistance_m * n + couple_slack) return false;
  if (std::abs(f.spinning_couple_nm) > law.spinning_friction_m * n + couple_slack) return false;
  *stuck_mode = all;
  return true;
}

Vector3 PlaneContact::Impl::release_direction(const PlaneContactMode& mode,
                                              const PlaneContactKinematics& k, bool tangential,
                                              const Vector3& hint) const {
  // The released part starts from zero motion, sliding along s with its force at the bound
  // against s. Consistency: the part's acceleration must point along +s. Scan the circle for
  // zeros of (s x acceleration)_z, refine them, keep those with s . acceleration > 0, and take
  // the one nearest the hint (the reverse of the force the stuck part needed).
  auto residual = [&](double angle, double* along) {
    PlaneContactMode trial = mode;
    ContactLawPart& part = tangential ? trial.tangential : trial.rolling;
    part.law = ContactLaw::sliding;
    part.reference_world = horizontal_unit(angle);
    ++counters_.extra_solves;
    const PlaneContactForces f = solve(trial, k);
    const Vector3 acc = tangential ? f.slip_acceleration_world
                                   : Vector3(f.angular_acceleration_world.x(),
                                             f.angular_acceleration_world.y(), 0.0);
    const Vector3 s = part.reference_world;
    if (along) *along = s.dot(acc);
    return s.x() * acc.y() - s.y() * acc.x();
  };
  Vector3 best = hint;
  double best_alignment = -2.0;
  double previous_angle = 0.0;
  double previous = residual(previous_angle, nullptr);
  for (int i = 1; i <= kReleaseDirections; ++i) {
    const double angle = 2.0 * M_PI * i / kReleaseDirections;
    const double value = residual(angle, nullptr);
    if ((previous <= 0.0) != (value <= 0.0)) {
      boost::uintmax_t iterations = 60;
      const auto bracket = boost::math::tools::toms748_solve(
          [&](double a) { return residual(a, nullptr); }, previous_angle, angle, previous, value,
          [](double a, double b) { return std::abs(b - a) <= 1e-13; }, iterations);
      const double root = 0.5 * (bracket.first + bracket.second);
      double along = 0.0;
      residual(root, &along);
      const Vector3 s = horizontal_unit(root);
      if (along > 0.0 && s.dot(hint) > best_alignment) {
        best_alignment = s.dot(hint);
        best = s;
      }
    }
    previous_angle = angle;
    previous = value;
  }
  return best;
}

PlaneContact::Impl::Choice PlaneContact::Impl::choose_mode(const PlaneContactKinematics& k_in,
                                                           LensPart part,
                                                           std::optional<Trigger> snap,
                                                           std::optional<Trigger> release) const {
  const ContactMaterial& law = setup_.material;
  Choice c;
  c.mode.part = part;
  PlaneContactKinematics k =
      plane_contact_kinematics(setup_, c.mode, k_in.position_world.head<2>(), k_in.orientation,
                               k_in.velocity_world.head<2>(), k_in.angular_velocity_world);
  // The hint for a released part: the reverse of the force it needed while stuck.
  Vector3 release_hint = Vector3::UnitX();
  double spin_release_sign = 1.0;
  if (release) {
    const PlaneContactForces f = solve(mode_, k_in);
    if (*release == Trigger::tangential_bound && f.friction_force_world.norm() > 0.0) {
      release_hint = -f.friction_force_world.normalized();
    } else if (*release == Trigger::rolling_bound && f.rolling_couple_world.norm() > 0.0) {
      release_hint = -f.rolling_couple_world.normalized();
    }
    spin_release_sign = f.spinning_couple_nm > 0.0 ? -1.0 : 1.0;
  }

  struct PartInfo {
    ContactLawPart* part;
    const ContactLawPart& before;  // the part in the current mode
    double bound;
    Vector3 velocity;
    double zero_speed, layer_speed;
    Trigger zero, bound_trigger;
  };
  PartInfo parts[3] = {
      {&c.mode.tangential, mode_.tangential, law.friction, k.slip_velocity(), kZeroSlipSpeed,
       kSlipDirectionLayer, Trigger::tangential_zero, Trigger::tangential_bound},
      {&c.mode.rolling, mode_.rolling, law.rolling_resistance_m, k.rolling_velocity(),
       kZeroAngularSpeed, kRollDirectionLayer, Trigger::rolling_zero, Trigger::rolling_bound},
      {&c.mode.spinning, mode_.spinning, law.spinning_friction_m,
       Vector3(0.0, 0.0, k.spin_velocity()), kZeroAngularSpeed, 0.0, Trigger::spinning_zero,
       Trigger::spinning_bound},
  };
  for (int i = 0; i < 3; ++i) {
    PartInfo& p = parts[i];
    p.part->reference_world.setZero();
    if (p.bound == 0.0) {
      p.part->law = ContactLaw::free;
    } else if (release && *release == p.bound_trigger) {
      p.part->law = ContactLaw::sliding;
      p.part->reference_world =
          i == 2 ? Vector3(0.0, 0.0, spin_release_sign) : release_hint;  // refined below
    } else if ((snap && *snap == p.zero) || p.velocity.norm() <= p.zero_speed) {
      p.part->law = ContactLaw::stuck;
    } else {
      p.part->law = ContactLaw::sliding;
      // Inside the direction layer the velocity's direction is not trusted: keep the reference.
      const bool keep = p.before.law == ContactLaw::sliding && p.velocity.norm() <= p.layer_speed;
      p.part->reference_world = keep ? p.before.reference_world : p.velocity.normalized();
    }
  }
  // Rest: nothing moves and every part can hold it.
  PlaneContactMode still = c.mode;
  if (is_static(k, &still)) {
    c.result = Choice::Result::rest;
    c.mode = still;
    c.kinematics = projected(k, still);
    return c;
  }
  k = projected(k, c.mode);
  if (release && *release != Trigger::spinning_bound) {
    const bool tangential = *release == Trigger::tangential_bound;
    ContactLawPart& p = tangential ? c.mode.tangential : c.mode.rolling;
    p.reference_world = release_direction(c.mode, k, tangential, release_hint);
  }
  for (int round = 0; round < 3; ++round) {
    ++counters_.extra_solves;
    const PlaneContactForces f = solve(c.mode, k);
    if (f.normal_force_n < 0.0) {
      c.result = Choice::Result::lift_off;
      c.kinematics = k;
      return c;
    }
    // The stuck part whose needed force or couple exceeds its bound the most.
    const double n = f.normal_force_n;
    const double needed[3] = {f.friction_force_world.norm(), f.rolling_couple_world.norm(),
                              std::abs(f.spinning_couple_nm)};
    int worst = -1;
    double worst_ratio = 1.0;
    for (int i = 0; i < 3; ++i) {
      if (parts[i].part->law != ContactLaw::stuck) continue;
      const double limit = parts[i].bound * n;
      const double ratio = limit > 0.0
                               ? needed[i] / limit
                               : (needed[i] > 0.0 ? std::numeric_limits<double>::max() : 0.0);
      if (ratio > worst_ratio) {
        worst_ratio = ratio;
        worst = i;
      }
    }
    if (worst < 0) break;
    ContactLawPart& p = *parts[worst].part;
    p.law = ContactLaw::sliding;
    if (worst == 2) {
      p.reference_world = Vector3(0.0, 0.0, f.spinning_couple_nm > 0.0 ? -1.0 : 1.0);
    } else {
      const Vector3 force = worst == 0 ? f.friction_force_world : f.rolling_couple_world;
      const Vector3 hint = force.norm() > 0.0 ? Vector3(-force.normalized()) : Vector3::UnitX();
      p.reference_world = release_direction(c.mode, k, worst == 0, hint);
    }
  }
  c.kinematics = k;
  return c;
}

// ---------------------------------------------------------------------------------------------
// Integration

void PlaneContact::Impl::start_mode(const Choice& choice, double t, double energy_cap) {
  mode_ = choice.mode;
  const PlaneContactKinematics k = capped(choice.kinematics, mode_, energy_cap);
  y_ = encode(k);
  t_ = t;
  energy_cap_ = std::min(energy_cap, energy(k));
  stepper_ready_ = false;
  if (choice.result == Choice::Result::mode) g_start_ = event_values(k, mode_);
  Segment point;
  point.t_begin = point.t_end = t;
  point.energy_begin = energy_cap_;
  point.mode = mode_;
  point.point = y_;
  segments_.push_back(point);
}

void PlaneContact::Impl::refresh_references() {
  const PlaneContactKinematics k = decode(setup_, mode_, y_);
  // Outside the direction layer the reference is the motion's direction; inside it, a part whose
  // direction has a stable zero near the reference is slaved to it for this step (the decision
  // is taken here, once per step, so that the law stays smooth within the step).
  auto refresh = [&](bool tangential, const Vector3& velocity, double layer) {
    ContactLawPart& part = tangential ? mode_.tangential : mode_.rolling;
    part.slaved = false;
    if (part.law != ContactLaw::sliding) return;
    if (velocity.norm() > layer) {
      part.reference_world = velocity.normalized();
      return;
    }
    Vector3 direction;
    if (slaved_direction(mode_, k, tangential, true, direction)) {
      part.reference_world = direction;
      part.slaved = true;
    }
  };
  refresh(true, k.slip_velocity(), kSlipDirectionLayer);
  refresh(false, k.rolling_velocity(), kRollDirectionLayer);
  if (mode_.spinning.law == ContactLaw::sliding &&
      std::abs(k.spin_velocity()) > kZeroAngularSpeed) {
    mode_.spinning.reference_world = Vector3(0.0, 0.0, k.spin_velocity() > 0.0 ? 1.0 : -1.0);
  }
  // The zero-crossing events restart from |v| > 0 with the new references.
  auto restart = [&](Trigger t, double value) {
    if (g_start_.active[static_cast<int>(t)]) g_start_.g[static_cast<int>(t)] = value;
  };
  restart(Trigger::tangential_zero, k.slip_velocity().dot(mode_.tangential.reference_world));
  restart(Trigger::rolling_zero, k.rolling_velocity().dot(mode_.rolling.reference_world));
  restart(Trigger::spinning_zero, k.spin_velocity() * mode_.spinning.reference_world.z());
}

void PlaneContact::Impl::take_step() {
  refresh_references();
  if (!stepper_ready_) {
    dense_ = odeint::make_dense_output(options_.absolute_tolerance, options_.relative_tolerance,
                                       options_.max_step_s, Dopri5());
    dense_.initialize(y_, t_, std::min(dt_, options_.max_step_s));
    stepper_ready_ = true;
  }
  std::pair<double, double> step;
  try {
    step = dense_.do_step(System{this});
  } catch (const IntegrationError&) {
    throw;
  } catch (const std::exception& e) {  // odeint gives up after 500 rejected step sizes
    throw IntegrationError(std::string("plane contact: the integrator failed at t = ") +
                           format_value(t_) + " s: " + e.what());
  }
  ++counters_.steps;
  dt_ = dense_.current_time_step();
  const OdeState y_end = dense_.current_state();
  for (double v : y_end) {
    if (!std::isfinite(v)) {
      throw IntegrationError(
          "plane contact: the state became non-finite after t = " + format_value(t_) + " s");
    }
  }
  const PlaneContactKinematics k_end = decode(setup_, mode_, y_end);

  Segment segment;
  segment.t_begin = step.first;
  segment.t_end = step.second;
  segment.energy_begin = energy_cap_;
  segment.mode = mode_;
  segment.dense = std::make_shared<const DenseStepper>(dense_);

  // Events: a value positive at the step start and not positive at its end; or one already not
  // positive at the start that went negative (a part released the wrong way): at the start.
  const EventValues g_end = event_values(k_end, mode_);
  ++counters_.extra_solves;
  std::optional<PendingEvent> earliest;
  for (int i = 0; i < kTriggerCount; ++i) {
    if (!g_end.active[i] || !g_start_.active[i]) continue;
    const double g0 = g_start_.g[i], g1 = g_end.g[i];
    double time;
    if (g0 > 0.0 && g1 <= 0.0) {
      const Trigger trigger = static_cast<Trigger>(i);
      const PlaneContactMode mode = mode_;
      auto g = [&](double t) {
        OdeState y;
        segment.dense->calc_state(t, y);
        ++counters_.extra_solves;
        return event_value(trigger, decode(setup_, mode, y), mode);
      };
      boost::uintmax_t iterations = 100;
      const auto bracket = boost::math::tools::toms748_solve(g, step.first, step.second, g0, g1,
                                                             TimeTolerance(), iterations);
      time = bracket.second;  // the first time found on the far side
    } else if (g0 <= 0.0 && g1 < 0.0) {
      time = step.first;
    } else {
      continue;
    }
    if (!earliest || time < earliest->time) earliest = PendingEvent{time, static_cast<Trigger>(i)};
  }

  // The energy guard at the step end.
  double energy_end = energy(k_end);
  PlaneContactKinematics k_next = k_end;
  if (energy_end > energy_cap_) {
    k_next = capped(k_end, mode_, energy_cap_);
    if (k_next.angular_velocity_world != k_end.angular_velocity_world ||
        k_next.velocity_world != k_end.velocity_world) {
      energy_end = energy(k_next);
      ++counters_.energy_guard_scalings;
      stepper_ready_ = false;  // restart the integrator from the scaled state
    }
  }
  if (earliest) {
    segment.t_end = earliest->time;
    segments_.push_back(segment);
    pending_ = earliest;
    return;
  }
  segments_.push_back(segment);
  if (segments_.size() > kMaxStoredSegments) {
    segments_.pop_front();
    window_start_ = std::max(window_start_, segments_.front().t_begin);
  }
  t_ = step.second;
  y_ = encode(k_next);
  energy_cap_ = std::min(energy_cap_, energy_end);  // never raised, not even by round-off
  g_start_ = g_end;
}

PlaneContact::Impl::Sample PlaneContact::Impl::sample(double t) const {
  if (finished_ && t >= finished_->time) return finished_->sample;
  // The latest segment containing t (the state right after an event wins at its instant).
  for (auto it = segments_.rbegin(); it != segments_.rend(); ++it) {
    if (t < it->t_begin || t > it->t_end) continue;
    OdeState y = it->point;
    if (it->dense) it->dense->calc_state(t, y);
    const PlaneContactKinematics k = decode(setup_, it->mode, y);
    // Never above the guarded energy where the step began. (Not a chord between the step's
    // ends: a dissipation rate growing within the step puts the true energy above the chord.)
    return {capped(k, it->mode, it->energy_begin), it->mode};
  }
  throw InvalidArgument("t_s", "contact state requested at t = " + format_value(t) +
                                   " s, outside the available range [" +
                                   format_value(window_start_) + ", " + format_value(reached_) +
                                   "] s");
}

RigidBodyState PlaneContact::Impl::to_rigid_body_state(const Sample& s) const {
  RigidBodyState out;
  out.position_world = s.kinematics.position_world;
  out.orientation = s.kinematics.orientation;
  out.velocity_world = s.kinematics.velocity_world;
  out.angular_momentum_world =
      setup_.model.angular_momentum_world(out.orientation, s.kinematics.angular_velocity_world);
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
  return solve_plane_contact(setup_, slaved(s.mode, s.kinematics), s.kinematics);
}

std::optional<PlaneContactOutcome> PlaneContact::Impl::process(const PendingEvent& event) {
  ++counters_.events;
  const double t = event.time;
  if (t == last_event_time_) {
    if (++events_at_instant_ > kMaxEventsAtOneInstant) {
      throw IntegrationError("plane contact: the contact mode cannot be resolved at t = " +
                             format_value(t) + " s (mode changes keep following each other)");
    }
  } else {
    last_event_time_ = t;
    events_at_instant_ = 0;
  }
  const Sample before = sample(t);
  const PlaneContactMode old_mode = mode_;
  const double cap = energy(before.kinematics);
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
  const Choice choice = choose_mode(before.kinematics, part, snap, release);
  // Drop what lies beyond the event: the trajectory continues from here in the new mode.
  while (!segments_.empty() && segments_.back().t_begin > t) segments_.pop_back();
  pending_.reset();
  start_mode(choice, t, cap);
  const Sample after{decode(setup_, mode_, y_), mode_};
  if (choice.result == Choice::Result::rest) return finish(PlaneContactEvent::rest, after);
  if (choice.result == Choice::Result::lift_off) return finish(PlaneContactEvent::lift_off, after);
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

PlaneContactOutcome PlaneContact::Impl::advance(double t_end) {
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
  for (;;) {
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
PlaneContact::PlaneContact(PlaneContact&&) noexcept = default;
PlaneContact& PlaneContact::operator=(PlaneContact&&) noexcept = default;

PlaneContactOutcome PlaneContact::advance(double t_end_s) { return impl_->advance(t_end_s); }
RigidBodyState PlaneContact::state_at(double t_s) const { return impl_->state_at(t_s); }
PlaneContactForces PlaneContact::forces_at(double t_s) const { return impl_->forces_at(t_s); }
double PlaneContact::time_reached() const { return impl_->time_reached(); }
bool PlaneContact::finished() const { return impl_->finished(); }
const PlaneContactMode& PlaneContact::mode() const { return impl_->mode(); }
const PlaneContactSetup& PlaneContact::setup() const { return impl_->setup(); }
const PlaneContactCounters& PlaneContact::counters() const { return impl_->counters(); }

}  // namespace virtual_go
