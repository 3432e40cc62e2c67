// PlaneContact's integrator steps, the trajectory it keeps and sampling it (plane_contact_impl.h):
// DOP853 (dop853.h) on the coordinates of plane_contact_laws.h, the events of each step located
// on its dense output, and the energy guard at each step's end.
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <limits>

#include "plane_contact_impl.h"
#include "virtual_go/common/validation.h"

namespace virtual_go {
namespace {

using Vector3 = Eigen::Vector3d;
using plane_contact_detail::EventValues;
using plane_contact_detail::kStateSize;
using plane_contact_detail::kTriggerCount;
using plane_contact_detail::Trigger;

// Integrator steps kept for state_at (about 2.3 kB each): a caller advancing far at once can
// sample at least this many steps back.
constexpr std::size_t kMaxStoredSegments = 4096;
// Rejected trial steps in a row beyond this mean the integrator cannot go on.
constexpr int kMaxRejections = 64;

// Time brackets from TOMS 748 are accepted at this width (s): far below any physical scale,
// a few ulps of a time of hours.
struct TimeTolerance {
  bool operator()(double a, double b) const {
    return std::abs(b - a) <=
           1e-15 + 4 * std::numeric_limits<double>::epsilon() * std::max(std::abs(a), std::abs(b));
  }
};

}  // namespace

PlaneContact::Impl::Segment& PlaneContact::Impl::SegmentRing::push_back(std::size_t limit) {
  if (size_ == slots_.size()) {
    if (slots_.size() >= limit) {
      pop_front();
    } else {
      // Grow geometrically, oldest first again.
      std::vector<Segment> grown;
      grown.reserve(std::min(limit, std::max<std::size_t>(8, 2 * slots_.size())));
      for (std::size_t i = 0; i < size_; ++i) grown.push_back((*this)[i]);
      grown.resize(grown.capacity());
      slots_.swap(grown);
      head_ = 0;
    }
  }
  ++size_;
  return back();
}

void PlaneContact::Impl::push_point(double t) {
  Segment& point = segments_.push_back(kMaxStoredSegments);
  point.t_begin = point.t_end = t;
  point.energy_begin = energy_cap_;
  point.mode = mode_;
  point.point = true;
  point.closed_form = false;
  point.h = 0.0;
  point.dense_ready = false;
  point.y0 = y_;
}

void PlaneContact::Impl::start_mode(const ModeChoice& choice, double t, double energy_cap) {
  mode_ = choice.mode;
  const PlaneContactKinematics k = laws_.capped(choice.kinematics, mode_, energy_cap);
  y_ = laws_.encode(k);
  t_ = t;
  energy_cap_ = std::min(energy_cap, laws_.energy(k));
  rates_ready_ = false;
  if (choice.result == ModeChoice::Result::mode) {
    // The clearance as at a step's end (step_in): its bound while that stays positive.
    const int clearance = static_cast<int>(Trigger::clearance);
    const double clearance_bound = clearance_floor(k);
    const bool bounded = clearance_bound > 0.0;
    g_start_ = laws_.event_values(k, mode_, nullptr, bounded);
    if (bounded) {
      g_start_.g[clearance] = clearance_bound;
      clearance_start_bounded_ = true;
    } else {
      anchor_clearance(k, g_start_);
    }
  }
  push_point(t);
}

double PlaneContact::Impl::clearance_floor(const PlaneContactKinematics& k) const {
  const LensGeometry& lens = laws_.setup().lens;
  // Every point of the lens lies within its bounding cylinder: |P - G| <= hypot(a, c). A turn
  // of the axis from b0 to b1 moves such a point by at most |b1 - b0| |P - G| (the lens is
  // axisymmetric, so the smallest rotation taking b0 to b1 carries it over).
  const double reach = std::hypot(lens.half_width(), lens.half_height());
  return clearance_anchor_.value_m - ((k.position_world - clearance_anchor_.center_world).norm() +
                                      reach * (k.axis_world - clearance_anchor_.axis_world).norm());
}

void PlaneContact::Impl::anchor_clearance(const PlaneContactKinematics& k, const EventValues& g) {
  clearance_start_bounded_ = false;
  const int i = static_cast<int>(Trigger::clearance);
  if (!g.active[i]) return;
  clearance_anchor_.center_world = k.position_world;
  clearance_anchor_.axis_world = k.axis_world;
  clearance_anchor_.value_m = g.g[i];
}

void PlaneContact::Impl::refresh_references() {
  const PlaneContactKinematics k = laws_.decode(mode_, y_, false);
  // Outside the direction layer the reference is the motion's direction; inside it, a part whose
  // direction has a stable zero near the reference is slaved to it for this step (the decision
  // is taken here, once per step, so that the law stays smooth within the step).
  // The side of the layer is taken by speed when the mode begins and changes only at the layer's
  // edge (an event), so a step never straddles it.
  auto refresh = [&](bool tangential, const Vector3& velocity, double layer) {
    ContactLawPart& part = tangential ? mode_.tangential : mode_.rolling;
    part.slaved = false;
    if (part.law != ContactLaw::sliding) return;
    if (part.layer == ContactLawPart::Layer::by_speed) {
      part.layer =
          velocity.norm() > layer ? ContactLawPart::Layer::outside : ContactLawPart::Layer::inside;
    }
    if (part.layer == ContactLawPart::Layer::outside) {
      if (velocity.norm() > 0.0) part.reference_world = velocity.normalized();
      return;
    }
    Vector3 direction;
    if (laws_.slaved_direction(mode_, k, tangential, true, direction)) {
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
  // A mode that just began has its sides now.
  const auto layered = [](const ContactLawPart& p) {
    return p.law == ContactLaw::sliding && p.layer != ContactLawPart::Layer::by_speed;
  };
  auto start_layer = [&](Trigger t, bool active) {
    const int i = static_cast<int>(t);
    if (active && !g_start_.active[i]) {
      g_start_.active[i] = true;
      g_start_.g[i] = laws_.event_value(t, k, mode_);
    }
  };
  start_layer(Trigger::tangential_layer, layered(mode_.tangential));
  start_layer(Trigger::rolling_layer, layered(mode_.rolling));
}

void PlaneContact::Impl::take_step() {
  refresh_references();
  if (flat_closed_form()) return;
  if (!rates_ready_) {
    laws_.rhs(mode_, y_, rates_);
    rates_ready_ = true;
  }

  // The step is built in the slot it will be kept in; a rejected trial overwrites it. Nothing
  // else changes before the step is complete: on an error the slot is dropped and the state
  // stays at the last completed step.
  Segment& segment = segments_.push_back(kMaxStoredSegments);
  if (segments_.size() == kMaxStoredSegments) {
    window_start_ = std::max(window_start_, segments_.front().t_begin);
  }
  try {
    step_in(segment);
  } catch (...) {
    segments_.pop_back();
    throw;
  }
}

void PlaneContact::Impl::step_in(Segment& segment) {
  const plane_contact_detail::PlaneContactLaws& laws = laws_;
  const PlaneContactMode& mode = mode_;
  auto f = [&laws, &mode](double /*t*/, const State& y, State& dydt) { laws.rhs(mode, y, dydt); };
  segment.point = false;
  segment.closed_form = false;
  segment.dense_ready = false;
  segment.mode = mode_;
  segment.energy_begin = energy_cap_;
  segment.y0 = y_;
  segment.k[0] = rates_;
  State err5, err3;
  double h = std::min(h_, laws_.options().max_step_s);
  double error = 0.0;
  bool rejected = false;
  {
    for (int trial = 0;; ++trial) {
      if (trial > kMaxRejections || !(t_ + h > t_)) {
        throw IntegrationError("plane contact: the integrator failed at t = " + format_value(t_) +
                               " s (step size " + format_value(h) + " s rejected " +
                               std::to_string(trial) + " times)");
      }
      dop853::trial_step<kStateSize>(f, t_, h, y_, segment.k, segment.y1, err5, err3);
      error = dop853::error_norm<kStateSize>(h, err5, err3, laws_.error_scale(y_, segment.y1));
      if (error <= 1.0) break;
      h = std::isfinite(error) ? dop853::next_step_size(h, error, true) : h / 3.0;
      rejected = true;
    }
    if (!segment.y1.allFinite()) {
      throw IntegrationError(
          "plane contact: the state became non-finite after t = " + format_value(t_) + " s");
    }
  }
  ++laws_.counters().steps;
  segment.t_begin = t_;
  segment.h = h;
  segment.t_end = t_ + h;
  // The step end's rates: the next step's first stage, and the forces its events need.
  PlaneContactForces forces_end;
  PlaneContactKinematics k_end;
  laws_.rhs(mode_, segment.y1, segment.k[12], &forces_end, &k_end);

  // Events: a value positive at the step start and not positive at its end; or one already not
  // positive at the start that went negative (a part released the wrong way): at the start.
  // The clearance (a distance to the board beside a stone on the table) is only evaluated once
  // the motion since its last value could have used that value up: until then no sign change
  // can have happened, and the bound stands in for it.
  const int clearance = static_cast<int>(Trigger::clearance);
  const double clearance_bound = g_start_.active[clearance] ? clearance_floor(k_end) : 0.0;
  const bool bounded = clearance_bound > 0.0;
  EventValues g_end = laws_.event_values(k_end, mode_, &forces_end, bounded);
  if (bounded) g_end.g[clearance] = clearance_bound;
  // A step longer than the event resolution is also looked at within, on its dense output, at
  // looks no further apart (one force solve each; the clearance only where its bound from the
  // last value found no longer keeps it positive, as at the step end).
  const int pieces = looks_within(h);
  looks_.resize(static_cast<std::size_t>(pieces));
  for (int p = 1; p < pieces; ++p) {
    const PlaneContactKinematics k_p =
        laws_.decode(mode_, state_in(segment, segment.t_begin + h * p / pieces), false);
    const double floor_p = g_start_.active[clearance] ? clearance_floor(k_p) : 0.0;
    EventValues& look = looks_[static_cast<std::size_t>(p - 1)];
    look = laws_.event_values(k_p, mode_, nullptr, floor_p > 0.0);
    if (floor_p > 0.0) look.g[clearance] = floor_p;
  }
  looks_[static_cast<std::size_t>(pieces - 1)] = g_end;
  std::optional<PendingEvent> earliest;
  for (int i = 0; i < kTriggerCount; ++i) {
    if (!g_end.active[i] || !g_start_.active[i]) continue;
    const double g0 = g_start_.g[i], g1 = g_end.g[i];
    double time;
    if (g0 > 0.0) {
      // The first look at which it is no longer positive, if any.
      int p = 1;
      while (p <= pieces && looks_[static_cast<std::size_t>(p - 1)].g[i] > 0.0) ++p;
      if (p > pieces) continue;
      const Trigger trigger = static_cast<Trigger>(i);
      auto g = [&](double t) {
        const State y = state_in(segment, t);
        return laws_.event_value(trigger, laws_.decode(segment.mode, y, false), segment.mode);
      };
      const double t_lo = p == 1 ? segment.t_begin : segment.t_begin + h * (p - 1) / pieces;
      const double t_hi = p == pieces ? segment.t_end : segment.t_begin + h * p / pieces;
      // The bracket's start from the clearance itself, not its bound (both positive).
      const double g_lo = i == clearance ? g(t_lo)
                          : p == 1       ? g0
                                         : looks_[static_cast<std::size_t>(p - 2)].g[i];
      const double g_hi = looks_[static_cast<std::size_t>(p - 1)].g[i];
      if (!(t_hi > t_lo)) {
        time = t_lo;  // a step below the time's resolution: no bracket to search
      } else {
        boost::uintmax_t iterations = 100;
        const auto bracket = boost::math::tools::toms748_solve(g, t_lo, t_hi, g_lo, g_hi,
                                                               TimeTolerance(), iterations);
        time = bracket.second;  // the first time found on the far side
      }
    } else if (g1 < 0.0) {
      time = segment.t_begin;
    } else {
      continue;
    }
    if (!earliest || time < earliest->time) earliest = PendingEvent{time, static_cast<Trigger>(i)};
  }

  // The energy guard at the step end.
  double energy_end = laws_.energy(k_end);
  bool scaled = false;
  PlaneContactKinematics k_next;
  if (energy_end > energy_cap_) {
    const PlaneContactKinematics k_full = laws_.decode(mode_, segment.y1, true);
    k_next = laws_.capped(k_full, mode_, energy_cap_);
    if (k_next.angular_velocity_world != k_full.angular_velocity_world ||
        k_next.velocity_world != k_full.velocity_world) {
      energy_end = laws_.energy(k_next);
      ++laws_.counters().energy_guard_scalings;
      scaled = true;
    }
  }
  if (earliest) {
    segment.t_end = earliest->time;
    pending_ = earliest;
    return;
  }
  t_ = segment.t_end;
  h_ = dop853::next_step_size(h, error, rejected);
  if (scaled) {
    y_ = laws_.encode(k_next);  // restart the integrator from the scaled state
    rates_ready_ = false;
  } else {
    y_ = segment.y1;
    rates_ = segment.k[12];
    laws_.fold_spin(y_, &rates_);
  }
  energy_cap_ = std::min(energy_cap_, energy_end);  // never raised, not even by round-off
  g_start_ = g_end;
  if (bounded) {
    clearance_start_bounded_ = true;
  } else {
    anchor_clearance(k_end, g_end);
  }
}

int PlaneContact::Impl::looks_within(double span_s) const {
  const double resolution = laws_.options().event_resolution_s;
  return span_s > resolution ? static_cast<int>(std::min(1e6, std::ceil(span_s / resolution))) : 1;
}

bool PlaneContact::Impl::flat_closed_form() {
  // A stone lying flat on a cap (axis exactly vertical) with its rolling stuck and gravity
  // along -z: the contact point is the pole, straight below G, so N = m g, the friction
  // -mu m g v/|v| at the pole slides G in a straight line at constant deceleration mu g, and the
  // spinning couple -l_s m g sign(omega_z) spins it down at l_s m g / I3; the friction's couple
  // about G (mu m g c, horizontal) is held by the stuck rolling part, which needs it constant,
  // so it holds throughout (the mode choice checked it where the mode began). Nothing else
  // changes: the axis stays vertical, the pole stays the contact point. Exact to round-off up to
  // the first of: the slip stops (|v0| / (mu g)), the spin stops (I3 |omega0| / (l_s m g)), the
  // contact point leaves the region or the clearance reaches 0 (located on the closed form).
  const PlaneContactSetup& setup = laws_.setup();
  const ContactMaterial& law = setup.material;
  if (mode_.part == LensPart::rim || mode_.rolling.law != ContactLaw::stuck ||
      mode_.tangential.law == ContactLaw::free || mode_.spinning.law == ContactLaw::free ||
      setup.model.kind() != MotionModelKind::rigid_body || setup.gravity_world.x() != 0.0 ||
      setup.gravity_world.y() != 0.0 || !(setup.gravity_world.z() < 0.0)) {
    return false;
  }
  const Vector3 moments = setup.model.mass_properties().principal_moments_body();
  if (moments.x() != moments.y()) return false;  // psi is a quadrature only for I1 = I2
  const PlaneContactKinematics k = laws_.decode(mode_, y_, false);
  const Vector3& w = k.angular_velocity_world;
  if (k.axis_world.x() != 0.0 || k.axis_world.y() != 0.0 || w.x() != 0.0 || w.y() != 0.0 ||
      k.velocity_world.z() != 0.0) {
    return false;
  }
  const Vector3 v(k.velocity_world.x(), k.velocity_world.y(), 0.0);
  const double speed = v.norm(), spin = w.z();
  const bool slides = mode_.tangential.law == ContactLaw::sliding;
  const bool spins = mode_.spinning.law == ContactLaw::sliding;
  if ((slides && !(speed > 0.0)) || (!slides && speed != 0.0) || (spins && !(spin != 0.0)) ||
      (!spins && spin != 0.0) || (!slides && !spins)) {
    return false;
  }
  const double g = -setup.gravity_world.z();
  const double deceleration = slides ? law.friction * g : 0.0;  // m/s^2
  const double spin_down =
      spins ? law.spinning_friction_m * setup.model.mass_properties().mass() * g / moments.z()
            : 0.0;  // rad/s^2
  // The force solve must say the same (it is the law this closed form solves by hand): else the
  // integrator goes on.
  ++laws_.counters().extra_solves;
  const PlaneContactForces f = laws_.solve(laws_.slaved(mode_, k), k);
  const double m = setup.model.mass_properties().mass();
  const Vector3 a_expected = slides ? Vector3(-deceleration * v / speed) : Vector3::Zero();
  const double alpha_expected = spins ? (spin > 0.0 ? -spin_down : spin_down) : 0.0;
  const double tolerance = 1e-9;
  if (!(std::abs(f.normal_force_n - m * g) <= tolerance * m * g) ||
      !((f.linear_acceleration_world - a_expected).norm() <= tolerance * g) ||
      !(std::abs(f.angular_acceleration_world.z() - alpha_expected) <=
        tolerance * (std::abs(alpha_expected) + g / setup.lens.half_width())) ||
      !(f.rolling_couple_world.norm() <
        law.rolling_resistance_m * f.normal_force_n * (1.0 - tolerance))) {
    return false;
  }

  Segment& segment = segments_.push_back(kMaxStoredSegments);
  if (segments_.size() == kMaxStoredSegments) {
    window_start_ = std::max(window_start_, segments_.front().t_begin);
  }
  segment.point = false;
  segment.closed_form = true;
  segment.dense_ready = false;
  segment.mode = mode_;
  segment.energy_begin = energy_cap_;
  segment.y0 = y_;
  segment.rate.setZero();
  segment.accel.setZero();
  using plane_contact_detail::kPsi;
  using plane_contact_detail::kVx;
  using plane_contact_detail::kVy;
  using plane_contact_detail::kWx;
  using plane_contact_detail::kX;
  using plane_contact_detail::kY;
  segment.rate[kX] = v.x();
  segment.rate[kY] = v.y();
  segment.accel[kX] = segment.rate[kVx] = a_expected.x();
  segment.accel[kY] = segment.rate[kVy] = a_expected.y();
  // psi' = omega . b, b = +-e_z.
  const double psi_sign = k.axis_world.z() > 0.0 ? 1.0 : -1.0;
  segment.rate[kPsi] = psi_sign * spin;
  segment.accel[kPsi] = psi_sign * alpha_expected;
  segment.rate[kWx + 2] = alpha_expected;

  // The first stop ends the piece; the region and the clearance are located on it.
  PendingEvent first{std::numeric_limits<double>::infinity(), Trigger::tangential_zero};
  if (slides) first = {t_ + speed / deceleration, Trigger::tangential_zero};
  if (spins && t_ + std::abs(spin) / spin_down < first.time) {
    first = {t_ + std::abs(spin) / spin_down, Trigger::spinning_zero};
  }
  segment.t_begin = t_;
  segment.h = first.time - t_;
  segment.t_end = first.time;
  segment.y1 = state_in(segment, first.time);
  if (slides) {
    for (const Trigger trigger : {Trigger::region, Trigger::clearance}) {
      const int i = static_cast<int>(trigger);
      if (!g_start_.active[i]) continue;
      auto value = [&](double t) {
        return laws_.event_value(trigger, laws_.decode(mode_, state_in(segment, t), false), mode_);
      };
      // Sign changes are looked for on pieces no longer than the event resolution (as in
      // integrated phases), then bracketed.
      const double span = first.time - t_;
      const int pieces = looks_within(span);
      double lo = t_, g_lo = g_start_.g[i], hi = lo, g_hi = g_lo;
      if (trigger == Trigger::clearance && clearance_start_bounded_) g_lo = value(t_);
      bool crossed = false;
      for (int p = 1; p <= std::max(1, pieces) && g_lo > 0.0; ++p) {
        hi = p >= pieces ? first.time : t_ + span * p / pieces;
        g_hi = value(hi);
        if (g_hi <= 0.0) {
          crossed = true;
          break;
        }
        lo = hi;
        g_lo = g_hi;
      }
      if (!crossed) continue;
      boost::uintmax_t iterations = 100;
      const auto bracket =
          boost::math::tools::toms748_solve(value, lo, hi, g_lo, g_hi, TimeTolerance(), iterations);
      if (bracket.second < first.time) first = {bracket.second, trigger};
    }
  }
  segment.t_end = first.time;
  ++laws_.counters().steps;
  pending_ = first;
  return true;
}

plane_contact_detail::State PlaneContact::Impl::state_in(const Segment& segment, double t) const {
  if (segment.point || t <= segment.t_begin) return segment.y0;
  if (segment.closed_form) {
    const double tau = std::min(t, segment.t_begin + segment.h) - segment.t_begin;
    return segment.y0 + tau * segment.rate + (0.5 * tau * tau) * segment.accel;
  }
  if (t >= segment.t_begin + segment.h) return segment.y1;
  if (!segment.dense_ready) {
    // Dense output only for the steps sampled or searched: three more evaluations.
    Segment& s = const_cast<Segment&>(segment);  // the ring is mutable: a cache of the step
    auto f = [this, &s](double /*t*/, const State& y, State& dydt) { laws_.rhs(s.mode, y, dydt); };
    dop853::dense_coefficients<kStateSize>(f, s.t_begin, s.h, s.y0, s.k, s.dense);
    s.dense_ready = true;
  }
  return dop853::interpolate<kStateSize>((t - segment.t_begin) / segment.h, segment.h, segment.y0,
                                         segment.y1, segment.k[0], segment.k[12], segment.dense);
}

PlaneContact::Impl::Sample PlaneContact::Impl::sample(double t) const {
  if (finished_ && t >= finished_->time) return finished_->sample;
  // The latest segment containing t (the state right after an event wins at its instant).
  for (std::size_t i = segments_.size(); i-- > 0;) {
    const Segment& s = segments_[i];
    if (t < s.t_begin || t > s.t_end) continue;
    const PlaneContactKinematics k = laws_.decode(s.mode, state_in(s, t));
    // Never above the guarded energy where the step began. (Not a chord between the step's
    // ends: a dissipation rate growing within the step puts the true energy above the chord.)
    return {laws_.capped(k, s.mode, s.energy_begin), s.mode};
  }
  throw InvalidArgument("t_s", "contact state requested at t = " + format_value(t) +
                                   " s, outside the available range [" +
                                   format_value(window_start_) + ", " + format_value(reached_) +
                                   "] s");
}

}  // namespace virtual_go
