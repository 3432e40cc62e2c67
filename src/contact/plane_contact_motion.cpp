// PlaneContact's integrated coordinates, its right-hand side, and the sliding directions slaved
// to the motion near zero (plane_contact_laws.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "plane_contact_laws.h"
#include "virtual_go/common/validation.h"

namespace virtual_go::plane_contact_detail {
namespace {

using Vector3 = Eigen::Vector3d;

Vector3 horizontal_unit(double angle) { return {std::cos(angle), std::sin(angle), 0.0}; }

Eigen::Quaterniond spin_rotation(double psi) {
  return Eigen::Quaterniond(std::cos(0.5 * psi), 0.0, 0.0, std::sin(0.5 * psi));
}

Eigen::Quaterniond quaternion_of(const State& y) {
  return Eigen::Quaterniond(y[kQw], y[kQx], y[kQy], y[kQz]);
}

}  // namespace

PlaneContactLaws::PlaneContactLaws(const PlaneContactSetup& setup, const PlaneRegion& region,
                                   const PlaneContactOptions& options)
    : setup_(setup),
      region_(region),
      options_(options),
      axisymmetric_(setup.model.kind() == MotionModelKind::constant_omega ||
                    setup.model.mass_properties().principal_moments_body().x() ==
                        setup.model.mass_properties().principal_moments_body().y()) {}

State PlaneContactLaws::encode(const PlaneContactKinematics& k) const {
  const Eigen::Quaterniond& q = k.orientation;
  const Vector3& v = k.velocity_world;
  const Vector3& w = k.angular_velocity_world;
  State y;
  y << k.position_world.x(), k.position_world.y(), q.w(), q.x(), q.y(), q.z(), 0.0, v.x(), v.y(),
      w.x(), w.y(), w.z();
  return y;
}

PlaneContactKinematics PlaneContactLaws::decode(const PlaneContactMode& mode, const State& y,
                                                bool full_orientation) const {
  Eigen::Quaterniond q = quaternion_of(y);
  if (full_orientation && y[kPsi] != 0.0) q = q * spin_rotation(y[kPsi]);
  return plane_contact_kinematics(setup_, mode, Eigen::Vector2d(y[kX], y[kY]), q,
                                  Eigen::Vector2d(y[kVx], y[kVy]),
                                  Vector3(y[kWx], y[kWx + 1], y[kWx + 2]));
}

void PlaneContactLaws::rhs(const PlaneContactMode& mode, const State& y, State& dydt,
                           PlaneContactForces* forces, PlaneContactKinematics* kinematics) const {
  ++counters_.rhs_evaluations;
  // psi is 0 at a step's start and only an axisymmetric stone moves it, so q~ alone is the
  // orientation the forces need.
  const PlaneContactKinematics k = decode(mode, y, false);
  // The mode is copied only when a part is slaved (rare: inside the direction layer).
  const bool any_slaved = (mode.tangential.slaved && mode.tangential.law == ContactLaw::sliding) ||
                          (mode.rolling.slaved && mode.rolling.law == ContactLaw::sliding);
  const PlaneContactForces f = any_slaved ? solve(slaved(mode, k), k) : solve(mode, k);
  const Vector3& v = k.velocity_world;
  const Vector3& w = k.angular_velocity_world;
  dydt[kX] = v.x();
  dydt[kY] = v.y();
  // dq~/dt = 1/2 (0, omega~) q~ on the integrated (not renormalised) quaternion, omega~ the part
  // of omega across b when psi carries the rest.
  const double spin = axisymmetric_ ? w.dot(k.axis_world) : 0.0;
  const Vector3 turning = w - spin * k.axis_world;
  const Eigen::Quaterniond q_dot =
      Eigen::Quaterniond(0.0, turning.x(), turning.y(), turning.z()) * quaternion_of(y);
  dydt[kQw] = 0.5 * q_dot.w();
  dydt[kQx] = 0.5 * q_dot.x();
  dydt[kQy] = 0.5 * q_dot.y();
  dydt[kQz] = 0.5 * q_dot.z();
  dydt[kPsi] = spin;
  dydt[kVx] = f.linear_acceleration_world.x();
  dydt[kVy] = f.linear_acceleration_world.y();
  for (int i = 0; i < 3; ++i) dydt[kWx + i] = f.angular_acceleration_world[i];
  if (forces) *forces = f;
  if (kinematics) *kinematics = k;
}

void PlaneContactLaws::fold_spin(State& y, State* dydt) const {
  const double psi = y[kPsi];
  if (psi == 0.0) return;
  const Eigen::Quaterniond turn = spin_rotation(psi);
  const Eigen::Quaterniond q = quaternion_of(y) * turn;
  y[kQw] = q.w();
  y[kQx] = q.x();
  y[kQy] = q.y();
  y[kQz] = q.z();
  y[kPsi] = 0.0;
  if (dydt) {
    // The rates are (1/2 omega~ q~) (x) turn: linear in q~, and b does not change.
    const Eigen::Quaterniond rate =
        Eigen::Quaterniond((*dydt)[kQw], (*dydt)[kQx], (*dydt)[kQy], (*dydt)[kQz]) * turn;
    (*dydt)[kQw] = rate.w();
    (*dydt)[kQx] = rate.x();
    (*dydt)[kQy] = rate.y();
    (*dydt)[kQz] = rate.z();
  }
}

State PlaneContactLaws::error_scale(const State& y0, const State& y1) const {
  const double atol = options_.absolute_tolerance, rtol = options_.relative_tolerance;
  State scale = (atol + rtol * y0.cwiseAbs().cwiseMax(y1.cwiseAbs()).array()).matrix();
  // The angular velocity's error against its length, as a vector's: the across-axis part of a
  // precessing stone's omega turns with the precession, so each of its world components passes
  // through zero twice a turn, where a component's own scale asked for atol (1e-14 rad/s) out of
  // 20 rad/s. Measured against |omega|, the tossed stone takes 23 % fewer steps (21,720 ->
  // 16,779 in the benchmark's toss); the horizontal velocity measured the same way gained 2 % more
  // there and cost 4 % in the edge scenario, so it keeps its per-component scale.
  const double omega = std::max(y0.segment<3>(kWx).norm(), y1.segment<3>(kWx).norm());
  scale.segment<3>(kWx).setConstant(atol + rtol * omega);
  // psi restarts from 0 at every step: measure its error as an angle, as the quaternion's unit
  // components measure half the orientation's.
  scale[kPsi] = 2.0 * (atol + rtol);
  return scale;
}

PlaneContactForces PlaneContactLaws::solve(const PlaneContactMode& mode,
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

bool PlaneContactLaws::slaved_direction(const PlaneContactMode& mode,
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
  auto residual = [&](double angle) {
    PlaneContactMode trial = mode;
    ContactLawPart& p = tangential ? trial.tangential : trial.rolling;
    p.reference_world = horizontal_unit(angle);
    ++counters_.extra_solves;
    const PlaneContactForces f = solve_plane_contact(setup_, trial, k);
    const Vector3 acc = tangential ? f.slip_acceleration_world
                                   : Vector3(f.angular_acceleration_world.x(),
                                             f.angular_acceleration_world.y(), 0.0);
    const Vector3 s = p.reference_world;
    return f.solved ? s.x() * acc.y() - s.y() * acc.x() : std::numeric_limits<double>::quiet_NaN();
  };
  const double start = std::atan2(part.reference_world.y(), part.reference_world.x());
  double angle = start;
  constexpr double kDelta = 1e-7;  // rad, for the derivative
  bool converged = false;
  for (int i = 0; i < 8 && !converged; ++i) {
    const double r = residual(angle);
    const double slope = (residual(angle + kDelta) - r) / kDelta;
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

PlaneContactMode PlaneContactLaws::slaved(const PlaneContactMode& mode,
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

}  // namespace virtual_go::plane_contact_detail
