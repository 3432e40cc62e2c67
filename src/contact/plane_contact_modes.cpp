// PlaneContact's choice of the mode at an event (plane_contact_laws.h): which parts stick, which
// slide and in which direction, whether the stone lifts off or rests.
#include <algorithm>
#include <array>
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

// Fine grid on which the zeros of the fitted residual are bracketed (no solves).
constexpr int kFitGrid = 360;
// Directions solved for the fit (an exact DFT up to degree 4), and how far degrees 3 and 4 may
// stay from zero relative to the largest sample before the fit is not trusted.
constexpr int kFitSamples = 8;
constexpr double kFitCheck = 1e-8;

Vector3 horizontal_unit(double angle) { return {std::cos(angle), std::sin(angle), 0.0}; }

// a0 + a1 cos t + b1 sin t + a2 cos 2t + b2 sin 2t.
struct TrigPolynomial2 {
  double a0 = 0.0, a1 = 0.0, b1 = 0.0, a2 = 0.0, b2 = 0.0;
  double at(double t) const { return at(std::cos(t), std::sin(t)); }
  double at(double c, double s) const {
    return a0 + a1 * c + b1 * s + a2 * (c * c - s * s) + b2 * (2.0 * s * c);
  }
};

// cos and sin at the fine grid's nodes 2 pi i / kFitGrid, i = 0 .. kFitGrid.
struct GridTable {
  std::array<double, kFitGrid + 1> c, s;
  GridTable() {
    for (int i = 0; i <= kFitGrid; ++i) {
      c[i] = std::cos(2.0 * M_PI * i / kFitGrid);
      s[i] = std::sin(2.0 * M_PI * i / kFitGrid);
    }
  }
};
const GridTable& grid_table() {
  static const GridTable table;
  return table;
}

// residual / N sampled at kFitSamples directions: the degree-2 polynomial, or nothing when a
// sample is not finite, N vanishes somewhere or degrees 3 and 4 do not vanish.
template <class Residual>
std::optional<TrigPolynomial2> fitted_residual(Residual& residual) {
  std::array<double, kFitSamples> q{};
  double scale = 0.0;
  for (int j = 0; j < kFitSamples; ++j) {
    double normal = 0.0;
    const double r = residual(2.0 * M_PI * j / kFitSamples, nullptr, &normal);
    if (!(normal != 0.0) || !std::isfinite(r) || !std::isfinite(normal)) return std::nullopt;
    q[j] = r / normal;
    scale = std::max(scale, std::abs(q[j]));
  }
  auto coefficient = [&](int degree, bool sine) {
    double sum = 0.0;
    for (int j = 0; j < kFitSamples; ++j) {
      const double t = 2.0 * M_PI * degree * j / kFitSamples;
      sum += q[j] * (sine ? std::sin(t) : std::cos(t));
    }
    return sum * (degree == 0 || 2 * degree == kFitSamples ? 1.0 : 2.0) / kFitSamples;
  };
  TrigPolynomial2 p;
  p.a0 = coefficient(0, false);
  p.a1 = coefficient(1, false);
  p.b1 = coefficient(1, true);
  p.a2 = coefficient(2, false);
  p.b2 = coefficient(2, true);
  const double high =
      std::hypot(coefficient(3, false), coefficient(3, true), coefficient(4, false));
  if (!(high <= kFitCheck * scale)) return std::nullopt;
  return p;
}

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
  // against s. Consistency: the part's acceleration must point along +s. Of the zeros of the
  // residual (s x acceleration)_z with s . acceleration > 0, take the one nearest the hint (the
  // reverse of the force the stuck part needed).
  //
  // The constraint equations are linear in the unknown forces with the released force
  // -bound N s: N = N0 / (1 + w . s) (Sherman-Morrison) and acceleration / N is affine in s, so
  // residual / N is a trigonometric polynomial of degree 2 in the angle of s. Five solves fix it;
  // eight (an exact discrete Fourier transform up to degree 4) also check that degrees 3 and 4
  // vanish. Its zeros are then bracketed on a fine grid without further solves and only the
  // chosen one is refined on the full residual. Where the check fails (a force law that does not
  // have this structure) the circle is scanned with a solve per direction, as before.
  auto trial_forces = [&](double angle) {
    PlaneContactMode trial = mode;
    ContactLawPart& part = tangential ? trial.tangential : trial.rolling;
    part.law = ContactLaw::sliding;
    part.reference_world = horizontal_unit(angle);
    ++counters_.extra_solves;
    return solve(trial, k);
  };
  auto residual = [&](double angle, double* along, double* normal) {
    const PlaneContactForces f = trial_forces(angle);
    const Vector3 acc = tangential ? f.slip_acceleration_world
                                   : Vector3(f.angular_acceleration_world.x(),
                                             f.angular_acceleration_world.y(), 0.0);
    const Vector3 s = horizontal_unit(angle);
    if (along) *along = s.dot(acc);
    if (normal) *normal = f.normal_force_n;
    return s.x() * acc.y() - s.y() * acc.x();
  };
  // The zero of the full residual in a bracket, with s . acceleration there.
  auto refine = [&](double lo, double hi, double g_lo, double g_hi, double* along) {
    boost::uintmax_t iterations = 60;
    const auto bracket = boost::math::tools::toms748_solve(
        [&](double a) { return residual(a, nullptr, nullptr); }, lo, hi, g_lo, g_hi,
        [](double a, double b) { return std::abs(b - a) <= 1e-13; }, iterations);
    const double root = 0.5 * (bracket.first + bracket.second);
    residual(root, along, nullptr);
    return root;
  };

  // A trial direction on a pole of N (see the scan below) makes the fit or its refinement throw:
  // then the scan decides, skipping that bracket.
  std::optional<TrigPolynomial2> fit;
  try {
    fit = fitted_residual(residual);
  } catch (const IntegrationError&) {
  }
  if (fit) {
    try {
      // Candidates: sign changes of the fitted residual, nearest the hint first.
      struct Candidate {
        double angle, alignment;
      };
      std::array<Candidate, kFitGrid> candidates;
      int count = 0;
      const GridTable& grid = grid_table();
      double previous = fit->at(grid.c[0], grid.s[0]);
      for (int i = 1; i <= kFitGrid; ++i) {
        const double angle = 2.0 * M_PI * i / kFitGrid;
        const double value = fit->at(grid.c[i], grid.s[i]);
        if ((previous <= 0.0) != (value <= 0.0) && count < kFitGrid) {
          boost::uintmax_t iterations = 60;
          const double lo = 2.0 * M_PI * (i - 1) / kFitGrid;
          const auto bracket = boost::math::tools::toms748_solve(
              [&](double a) { return fit->at(a); }, lo, angle, previous, value,
              [](double a, double b) { return std::abs(b - a) <= 1e-15; }, iterations);
          const double root = 0.5 * (bracket.first + bracket.second);
          candidates[count++] = {root, horizontal_unit(root).dot(hint)};
        }
        previous = value;
      }
      std::sort(candidates.begin(), candidates.begin() + count,
                [](const Candidate& a, const Candidate& b) { return a.alignment > b.alignment; });
      for (int c = 0; c < count && fit; ++c) {
        // A bracket of the full residual around the fitted zero, widened until it holds.
        double half = 1e-9;
        for (; half <= 1e-2; half *= 10.0) {
          const double lo = candidates[c].angle - half, hi = candidates[c].angle + half;
          const double g_lo = residual(lo, nullptr, nullptr), g_hi = residual(hi, nullptr, nullptr);
          if ((g_lo <= 0.0) == (g_hi <= 0.0)) continue;
          double along = 0.0;
          const double root = refine(lo, hi, g_lo, g_hi, &along);
          if (along > 0.0) return horizontal_unit(root);
          break;
        }
        if (half > 1e-2) fit.reset();  // the fit misplaced a zero: scan instead
      }
      if (fit) return hint;  // no consistent direction: the hint, as the scan gives
    } catch (const IntegrationError&) {
    }
  }

  Vector3 best = hint;
  double best_alignment = -2.0;
  double previous_angle = 0.0;
  double previous = residual(previous_angle, nullptr, nullptr);
  for (int i = 1; i <= kReleaseDirections; ++i) {
    const double angle = 2.0 * M_PI * i / kReleaseDirections;
    const double value = residual(angle, nullptr, nullptr);
    if ((previous <= 0.0) != (value <= 0.0)) {
      // The sign can also change across a pole of N (a direction with no consistent force,
      // Painleve-type at large l_r); a bracket closing on it may hit the singular direction
      // itself, which is no candidate.
      try {
        double along = 0.0;
        const double root = refine(previous_angle, angle, previous, value, &along);
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
  const auto rests = [&](const auto& kinematics) {
    PlaneContactMode still = c.mode;
    if (!is_static(kinematics, &still)) return false;
    c.result = ModeChoice::Result::rest;
    c.mode = still;
    c.kinematics = projected(kinematics, still);
    return true;
  };
  if (rests(k)) return c;
  k = projected(k, c.mode);
  // A snapped part is still by its event, though its speed at the event's root may lie above
  // the zero speed: the rest test again on the motion the snap leaves (a thrown stone that had
  // stopped sliding, then stopped rolling, stayed exactly still for ever without a rest).
  if (snap && rests(k)) return c;
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
