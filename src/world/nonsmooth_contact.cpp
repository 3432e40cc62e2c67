#include "virtual_go/world/nonsmooth_contact.h"

#include <algorithm>
#include <cmath>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/contact/impact.h"
#include "virtual_go/contact/time_of_impact.h"
#include "virtual_go/flight/exact_motion.h"

namespace virtual_go {
namespace {

// Contact-point normal speeds above -this (m/s) are not approaching: they move a contact by less
// than 1e-16 m in a sub-step.
constexpr double kApproachToleranceMps = 1e-12;
// A position correction moves this much (m) beyond the touching pose, so that the recomputed
// gap, whose round-off is ~1e-17 m, comes out non-negative.
constexpr double kCorrectionSlackM = 1e-15;
constexpr int kMaxCorrections = 16;
// The plane model accepts |u_n| <= 1e-6 m/s; hand over only well inside that.
constexpr double kPlaneNormalSpeedMps = 1e-7;

ContactMaterial plastic(ContactMaterial m) {
  m.restitution = 0.0;
  return m;
}

}  // namespace

void validate_nonsmooth_options(const NonsmoothContactOptions& o) {
  require_positive("nonsmooth/step_s", o.step_s);
  require_positive("nonsmooth/contact_margin_m", o.contact_margin_m);
  require_positive("nonsmooth/separation_time_s", o.separation_time_s);
  require_positive("nonsmooth/plane_margin_m", o.plane_margin_m);
  require_positive("nonsmooth/rest_speed_m_s", o.rest_speed_m_s);
  require_positive("nonsmooth/rest_time_s", o.rest_time_s);
  if (o.step_s > 0.01) {
    throw InvalidArgument("nonsmooth/step_s",
                          "nonsmooth/step_s must be at most 0.01 s, got " + format_value(o.step_s));
  }
  if (o.max_sweeps < 1) {
    throw InvalidArgument("nonsmooth/max_sweeps", "nonsmooth/max_sweeps must be at least 1, got " +
                                                      std::to_string(o.max_sweeps));
  }
}

NonsmoothContact::NonsmoothContact(const BoardDistance& board, const MotionSetup& setup,
                                   const ContactMaterial& board_material,
                                   const ContactMaterial& table_material,
                                   const RigidBodyState& state, double t0_s,
                                   const NonsmoothContactOptions& options)
    : board_(board),
      setup_(setup),
      board_plastic_(plastic(board_material)),
      table_plastic_(plastic(table_material)),
      options_(options),
      t0_(t0_s),
      state_(state.validated()),
      reached_(t0_s) {
  require_finite("contact start time", t0_s);
  require_finite("gravity", setup.gravity_world);
  validate_material("contact/board", board_material);
  validate_material("contact/table", table_material);
  validate_nonsmooth_options(options);
  energy_ = energy(state_);
}

double NonsmoothContact::energy(const RigidBodyState& s) const {
  return body_energy(setup_.model, s, setup_.gravity_world);
}

double NonsmoothContact::scale_kinetic_energy(RigidBodyState& s, double energy_j) const {
  // Velocity and angular momentum scaled together: the kinetic energy is quadratic in both, the
  // potential energy and the pose do not change.
  const double m = setup_.model.mass_properties().mass();
  const double potential = -m * setup_.gravity_world.dot(s.position_world);
  const double kinetic = energy(s) - potential;
  const double target = energy_j - potential;
  const double scale = target > 0.0 && kinetic > 0.0 ? std::sqrt(target / kinetic) : 0.0;
  s.velocity_world *= scale;
  s.angular_momentum_world *= scale;
  return scale;
}

NonsmoothContact::SubStep NonsmoothContact::sub_step(const RigidBodyState& from, double h_s,
                                                     double energy_cap_j, bool commit) {
  SubStep out;
  // 1. Exact free flight.
  RigidBodyState s = ExactMotion(setup_, from).state_at(h_s);

  // 2. Out of any overlap: translate along the deeper contact's normal, Gauss-Seidel over the
  // box and the table (their normals are the separating directions, so one correction along
  // one of them makes that gap zero).
  for (int i = 0; i < kMaxCorrections; ++i) {
    const LensPose pose = lens_pose(s);
    const BoardContact box = board_.box(pose), table = board_.table(pose);
    const BoardContact& deeper = table.lens.gap_m < box.lens.gap_m ? table : box;
    if (deeper.lens.gap_m >= 0.0) break;
    if (commit) {
      counters_.deepest_overlap_m = std::max(counters_.deepest_overlap_m, -deeper.lens.gap_m);
      ++counters_.projections;
    }
    s.position_world += (kCorrectionSlackM - deeper.lens.gap_m) * deeper.lens.normal_world;
    out.loaded = true;
  }

  // 3. Plastic impulses at the contacts within the margin, Gauss-Seidel until none approaches.
  const LensPose pose = lens_pose(s);
  const BoardContact candidates[2] = {board_.box(pose), board_.table(pose)};
  for (const BoardContact& c : candidates) {
    if (c.lens.gap_m <= options_.contact_margin_m) out.contact[out.contacts++] = c;
  }
  for (int sweep = 0; sweep < options_.max_sweeps; ++sweep) {
    bool acted = false;
    for (int i = 0; i < out.contacts; ++i) {
      const BoardContact& c = out.contact[i];
      const double u_n =
          c.lens.normal_world.dot(point_velocity_world(setup_.model, s, c.lens.point_world));
      if (!(u_n < -kApproachToleranceMps)) continue;
      const Impact impact =
          resolve_impact(setup_.model, s, c.lens.point_world, c.lens.normal_world,
                         c.on_table() ? table_plastic_ : board_plastic_, setup_.gravity_world);
      s = impact.state;
      acted = true;
      out.loaded = true;
      if (commit) ++counters_.impulses;
    }
    if (!acted) break;
  }

  // 4. The energy guard: never above the previous committed state's energy.
  if (energy(s) > energy_cap_j) {
    const double scale = scale_kinetic_energy(s, energy_cap_j);
    if (commit) {
      ++counters_.energy_guard_scalings;
      if (scale == 0.0) {
        counters_.largest_energy_excess_j =
            std::max(counters_.largest_energy_excess_j, energy(s) - energy_cap_j);
      }
    }
  }
  out.state = s;
  return out;
}

std::optional<NonsmoothOutcome> NonsmoothContact::ending(const SubStep& step, double t) {
  NonsmoothOutcome o;
  o.time_s = t;
  o.state = step.state;
  const RigidBodyState& s = step.state;
  if (step.loaded && step.contacts == 1) {
    const BoardContact& c = step.contact[0];
    const double u_n =
        c.lens.normal_world.dot(point_velocity_world(setup_.model, s, c.lens.point_world));
    const std::optional<SupportPlane> plane =
        support_plane(board_, c, lens_pose(s), options_.plane_margin_m);
    if (plane && std::abs(u_n) <= kPlaneNormalSpeedMps) {
      o.end = NonsmoothEnd::plane;
      o.plane = plane;
      o.contact = c;
      return o;
    }
  }
  const Eigen::Vector3d omega =
      setup_.model.angular_velocity_world(s.orientation, s.angular_momentum_world);
  const double rim_speed = omega.norm() * board_.lens().half_width();
  const bool calm =
      s.velocity_world.norm() <= options_.rest_speed_m_s && rim_speed <= options_.rest_speed_m_s;
  calm_steps_ = calm ? calm_steps_ + 1 : 0;
  if (step.contacts > 0 &&
      static_cast<double>(calm_steps_) * options_.step_s >= options_.rest_time_s) {
    o.end = NonsmoothEnd::rest;
    o.state.velocity_world.setZero();
    o.state.angular_momentum_world.setZero();
    return o;
  }
  if (!step.loaded) {
    ++counters_.separation_searches;
    const TimeOfImpact toi =
        board_time_of_impact(board_, setup_, s, t, t, t + options_.separation_time_s);
    if (!toi.hit && !toi.exhausted) {
      o.end = NonsmoothEnd::separated;
      return o;
    }
  }
  return std::nullopt;
}

NonsmoothOutcome NonsmoothContact::advance(double t_end_s, long max_steps) {
  require_finite("nonsmooth advance time", t_end_s);
  if (max_steps < 0) {
    throw InvalidArgument(
        "max_steps", "nonsmooth advance: max_steps must be >= 0, got " + std::to_string(max_steps));
  }
  if (finished_) {
    if (t_end_s != finished_->time_s) {
      throw InvalidArgument("t_end_s",
                            "nonsmooth contact ended at t = " + format_value(finished_->time_s) +
                                " s; it cannot be advanced to " + format_value(t_end_s) + " s");
    }
    return *finished_;
  }
  if (t_end_s < reached_) {
    throw InvalidArgument("t_end_s", "nonsmooth advance time " + format_value(t_end_s) +
                                         " s is before the time already reached, " +
                                         format_value(reached_) + " s");
  }
  for (long taken = 0; lattice(steps_ + 1) <= t_end_s; ++taken) {
    const double t = lattice(steps_ + 1);
    if (taken >= max_steps) {
      // The budget is spent: stop at the last lattice point (or where the previous call
      // stopped, if later), to be continued.
      t_end_s = std::max(reached_, lattice(steps_));
      break;
    }
    const SubStep step = sub_step(state_, t - lattice(steps_), energy_, true);
    ++steps_;
    ++counters_.steps;
    state_ = step.state;
    energy_ = std::min(energy_, energy(state_));
    if (std::optional<NonsmoothOutcome> end = ending(step, t)) {
      state_ = end->state;
      finished_ = end;
      reached_ = t;
      return *end;
    }
  }
  reached_ = t_end_s;
  NonsmoothOutcome o;
  o.time_s = t_end_s;
  const double since = t_end_s - lattice(steps_);
  if (since <= 0.0) {
    o.state = state_;
    return o;
  }
  ++counters_.samples;
  o.state = sub_step(state_, since, energy_, false).state;
  // A partial sub-step can dissipate more than the lattice path it samples (its impulses act
  // over a shorter step), so the next lattice state could come out above the sample: the
  // sample's kinetic energy is raised to that state's energy (never above the last committed
  // one), and the energies handed out never rise. The pose is the partial step's.
  const double next_j =
      energy(sub_step(state_, lattice(steps_ + 1) - lattice(steps_), energy_, false).state);
  if (energy(o.state) < next_j) scale_kinetic_energy(o.state, next_j);
  return o;
}

}  // namespace virtual_go
