// PlaneContact's choice of the mode at an event (plane_contact_laws.h): which parts stick, which
// slide and in which direction, whether the stone lifts off or rests.
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <limits>

#include "plane_contact_laws.h"
#include "virtual_go/common/validation.h"

namespace virtual_go::plane_contact_detail {
namespace {

using Vector3 = Eigen::Vector3d;

// Static inequalities are accepted this far past their bound (relative to m |g| and m |g| a):
// round-off of the force solve, not physics.
constexpr double kStaticSlack = 1e-12;
// Directions tried when a stuck part is released with zero velocity.
constexpr int kReleaseDirections = 64;

Vector3 horizontal_unit(double angle) { return {std::cos(angle), std::sin(angle), 0.0}; }

}  // namespace

bool PlaneContactLaws::is_static(const PlaneContactKinematics& k,
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

Vector3 PlaneContactLaws::release_direction(const PlaneContactMode& mode,
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
      // The sign can also change across a pole of N (a direction with no consistent force,
      // Painleve-type at large l_r); a bracket closing on it may hit the singular direction
      // itself, which is no candidate.
      try {
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
      } catch (const IntegrationError&) {
      }
    }
    previous_angle = angle;
    previous = value;
  }
  return best;
}

ModeChoice PlaneContactLaws::choose_mode(const PlaneContactKinematics& k_in, LensPart part,
                                         std::optional<Trigger> snap,
                                         std::optional<Trigger> release,
                                         const PlaneContactMode& current) const {
  const ContactMaterial& law = setup_.material;
  ModeChoice c;
  c.mode.part = part;
  PlaneContactKinematics k =
      plane_contact_kinematics(setup_, c.mode, k_in.position_world.head<2>(), k_in.orientation,
                               k_in.velocity_world.head<2>(), k_in.angular_velocity_world);
  // The hint for a released part: the reverse of the force it needed while stuck.
  Vector3 release_hint = Vector3::UnitX();
  double spin_release_sign = 1.0;
  if (release) {
    const PlaneContactForces f = solve(current, k_in);
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
      {&c.mode.tangential, current.tangential, law.friction, k.slip_velocity(), kZeroSlipSpeed,
       kSlipDirectionLayer, Trigger::tangential_zero, Trigger::tangential_bound},
      {&c.mode.rolling, current.rolling, law.rolling_resistance_m, k.rolling_velocity(),
       kZeroAngularSpeed, kRollDirectionLayer, Trigger::rolling_zero, Trigger::rolling_bound},
      {&c.mode.spinning, current.spinning, law.spinning_friction_m,
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
    c.result = ModeChoice::Result::rest;
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
      c.result = ModeChoice::Result::lift_off;
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

}  // namespace virtual_go::plane_contact_detail
