#include "virtual_go/contact/plane_contact_dynamics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/contact/lens_on_plane.h"

namespace virtual_go {
namespace {

using Vector3 = Eigen::Vector3d;

// The world inertia and its inverse at the orientation whose symmetry axis is b. An
// axisymmetric body (I1 = I2, or constant omega) needs only b: I_w = I1 1 + (I3 - I1) b b^T.
void world_inertia(const MotionModel& model, const Eigen::Quaterniond& orientation,
                   const Vector3& axis, Eigen::Matrix3d& inertia, Eigen::Matrix3d& inverse) {
  if (model.kind() == MotionModelKind::constant_omega) {
    inertia = model.isotropic_moment() * Eigen::Matrix3d::Identity();
    inverse = Eigen::Matrix3d::Identity() / model.isotropic_moment();
    return;
  }
  const Vector3& moments = model.mass_properties().principal_moments_body();
  if (moments.x() == moments.y()) {
    // I1 1 + (I3 - I1) b b^T and 1 / I1 + (1/I3 - 1/I1) b b^T element by element: the same
    // arithmetic as the matrix expressions (I1 1 and 1 / I1 hold exactly I1, 1 / I1 and 0) without
    // their temporaries and nine divisions; this runs at every right-hand side.
    // Symmetric: the six distinct products b_i b_j once.
    const double c = moments.z() - moments.x();
    const double inverse_1 = 1.0 / moments.x();
    const double c_inverse = 1.0 / moments.z() - inverse_1;
    for (int i = 0; i < 3; ++i) {
      const double bb = axis[i] * axis[i];
      inertia(i, i) = moments.x() + c * bb;
      inverse(i, i) = inverse_1 + c_inverse * bb;
      for (int j = i + 1; j < 3; ++j) {
        const double bij = axis[i] * axis[j];
        inertia(i, j) = inertia(j, i) = c * bij;
        inverse(i, j) = inverse(j, i) = c_inverse * bij;
      }
    }
    return;
  }
  const Eigen::Matrix3d rotation = orientation.toRotationMatrix();
  inertia = rotation * moments.asDiagonal() * rotation.transpose();
  inverse = rotation * moments.cwiseInverse().asDiagonal() * rotation.transpose();
}

// Solves the 2 x 2 system a x = b by Cramer's rule. False when the determinant is below
// 2 eps max|a_ij|^2: singular to working precision (the scale of the pivot test of Gaussian
// elimination with partial pivoting).
bool solve_2x2(const Eigen::Matrix2d& a, const Eigen::Vector2d& b, Eigen::Vector2d& x) {
  const double det = a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0);
  const double largest = a.cwiseAbs().maxCoeff();
  if (!(std::abs(det) > 2.0 * std::numeric_limits<double>::epsilon() * largest * largest) ||
      !std::isfinite(det)) {
    return false;
  }
  x = Eigen::Vector2d(a(1, 1) * b(0) - a(0, 1) * b(1), a(0, 0) * b(1) - a(1, 0) * b(0)) / det;
  return true;
}

// The same for 3 x 3 (cofactors; 3 eps max|a_ij|^3).
bool solve_3x3(const Eigen::Matrix3d& a, const Eigen::Vector3d& b, Eigen::Vector3d& x) {
  Eigen::Matrix3d adjugate;
  adjugate.row(0) = a.col(1).cross(a.col(2));
  adjugate.row(1) = a.col(2).cross(a.col(0));
  adjugate.row(2) = a.col(0).cross(a.col(1));
  const double det = adjugate.row(0).dot(a.col(0));
  const double largest = a.cwiseAbs().maxCoeff();
  if (!(std::abs(det) >
        3.0 * std::numeric_limits<double>::epsilon() * largest * largest * largest) ||
      !std::isfinite(det)) {
    return false;
  }
  x = adjugate * b / det;
  return true;
}

}  // namespace

Vector3 PlaneContactKinematics::slip_velocity() const {
  const Vector3 u = velocity_world + angular_velocity_world.cross(offset_world);
  return {u.x(), u.y(), 0.0};
}

// The direction the sliding law of `part` opposes (see ContactLawPart::layer).
static Vector3 law_direction(const ContactLawPart& part, const Vector3& velocity,
                             double layer_speed) {
  switch (part.layer) {
    case ContactLawPart::Layer::inside:
      return part.reference_world;
    case ContactLawPart::Layer::outside:
      return sliding_direction(velocity, part.reference_world, 0.0);
    case ContactLawPart::Layer::by_speed:
    default:
      return sliding_direction(velocity, part.reference_world, layer_speed);
  }
}

Vector3 sliding_direction(const Vector3& velocity, const Vector3& reference, double layer_speed) {
  const double speed = velocity.norm();
  if (!(speed > layer_speed)) return reference;
  return velocity.dot(reference) < 0.0 ? Vector3(-velocity / speed) : Vector3(velocity / speed);
}

PlaneContactKinematics plane_contact_kinematics(const PlaneContactSetup& setup,
                                                const PlaneContactMode& mode,
                                                const Eigen::Vector2d& position_xy_world,
                                                const Eigen::Quaterniond& orientation,
                                                const Eigen::Vector2d& velocity_xy_world,
                                                const Eigen::Vector3d& angular_velocity_world) {
  PlaneContactKinematics k;
  // One division, not four.
  k.orientation = orientation.normalized();
  const Eigen::Quaterniond& q = k.orientation;
  // b = R(q) e_z without the whole rotation matrix.
  k.axis_world =
      Vector3(2.0 * (q.x() * q.z() + q.w() * q.y()), 2.0 * (q.y() * q.z() - q.w() * q.x()),
              1.0 - 2.0 * (q.x() * q.x() + q.y() * q.y()));
  k.angular_velocity_world = angular_velocity_world;
  if (mode.rolling.law == ContactLaw::stuck) {
    k.angular_velocity_world.x() = 0.0;
    k.angular_velocity_world.y() = 0.0;
  }
  if (mode.spinning.law == ContactLaw::stuck) k.angular_velocity_world.z() = 0.0;
  const PlaneContactOffset offset = plane_contact_offset_and_rate_world(
      setup.lens, mode.part, k.axis_world, k.angular_velocity_world);
  k.offset_world = offset.offset_world;
  k.offset_rate_world = offset.offset_rate_world;
  k.position_world = Vector3(position_xy_world.x(), position_xy_world.y(),
                             setup.plane_height_m - k.offset_world.z());
  // The material point at P: u = v_G + omega x r; u_z = 0 always, u_t = 0 when stuck.
  const Vector3 spin_velocity_at_p = k.angular_velocity_world.cross(k.offset_world);
  if (mode.tangential.law == ContactLaw::stuck) {
    k.velocity_world = -spin_velocity_at_p;
  } else {
    k.velocity_world =
        Vector3(velocity_xy_world.x(), velocity_xy_world.y(), -spin_velocity_at_p.z());
  }
  world_inertia(setup.model, k.orientation, k.axis_world, k.inertia_world, k.inverse_inertia_world);
  return k;
}

PlaneContactForces solve_plane_contact(const PlaneContactSetup& setup, const PlaneContactMode& mode,
                                       const PlaneContactKinematics& k) {
  // Each mode's multipliers in closed form (docs/physics.md, "Sustained contact"). With F the
  // force at P and C the couple,
  //   a = g + F / m,   I_w alpha = r x F + C - gamma,   gamma = omega x I_w omega,
  //   p = a + alpha x r + omega x dr/dt = q + F / m + alpha x r,   q = g + omega x dr/dt,
  // p the acceleration of the material point at P. Always p_z = 0, and p_z = q_z + F_z / m +
  // w . alpha with w = r x e_z. A sliding or free part is N times a known vector; a stuck part
  // is unknown but fixes its motion's rate. Eliminating what the stuck parts fix leaves at most a
  // 3 x 3 system (slip stuck, both rotations moving), else 2 x 2, a scalar, or nothing.
  const double m = setup.model.mass_properties().mass();
  const ContactMaterial& law = setup.material;
  const Vector3& r = k.offset_world;
  const Vector3& w = k.angular_velocity_world;
  const Eigen::Matrix3d& inertia = k.inertia_world;
  const Eigen::Matrix3d& inverse_inertia = k.inverse_inertia_world;
  const Vector3 q = setup.gravity_world + w.cross(k.offset_rate_world);
  const Vector3 gamma = w.cross(inertia * w);
  const Vector3 r_cross_ez(r.y(), -r.x(), 0.0);

  const bool tangential_stuck = mode.tangential.law == ContactLaw::stuck;
  const bool rolling_stuck = mode.rolling.law == ContactLaw::stuck;
  const bool spinning_stuck = mode.spinning.law == ContactLaw::stuck;
  // The sliding parts per unit N: force f_t at P, couple c (rolling across, spinning along e_z).
  Vector3 tangential_direction = Vector3::Zero(), rolling_direction = Vector3::Zero();
  double spin_sign = 0.0;
  Vector3 force_per_normal = Vector3::UnitZ(), couple_per_normal = Vector3::Zero();
  if (mode.tangential.law == ContactLaw::sliding) {
    tangential_direction = law_direction(mode.tangential, k.slip_velocity(), kSlipDirectionLayer);
    force_per_normal.x() -= law.friction * tangential_direction.x();
    force_per_normal.y() -= law.friction * tangential_direction.y();
  }
  if (mode.rolling.law == ContactLaw::sliding) {
    rolling_direction = law_direction(mode.rolling, k.rolling_velocity(), kRollDirectionLayer);
    couple_per_normal.x() = -law.rolling_resistance_m * rolling_direction.x();
    couple_per_normal.y() = -law.rolling_resistance_m * rolling_direction.y();
  }
  if (mode.spinning.law == ContactLaw::sliding) {
    spin_sign = mode.spinning.reference_world.z() < 0.0 ? -1.0 : 1.0;
    couple_per_normal.z() = -law.spinning_friction_m * spin_sign;
  }

  PlaneContactForces f;
  Vector3 force, couple, alpha;
  if (tangential_stuck) {
    // p = 0: F = -m (q + alpha x r), so N = -m (q_z + w . alpha) and, with
    // r x (alpha x r) = S alpha, S = |r|^2 1 - r r^T, the moment balance about P:
    //   J alpha = h + C,   J = I_w + m S,   h = -m r x q - gamma.
    const Eigen::Matrix3d inertia_about_p =
        inertia + m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    const Vector3 h = -m * r.cross(q) - gamma;
    const double normal_without_alpha = -m * q.z();
    if (rolling_stuck && spinning_stuck) {
      alpha.setZero();
      couple = -h;
    } else if (rolling_stuck) {
      // alpha = alpha_z e_z, w . alpha = 0: N is known; the z row gives alpha_z, the others C_t.
      const double normal = normal_without_alpha;
      alpha = Vector3(0.0, 0.0, (h.z() + normal * couple_per_normal.z()) / inertia_about_p(2, 2));
      couple = inertia_about_p.col(2) * alpha.z() - h;
      couple.z() = normal * couple_per_normal.z();
    } else if (spinning_stuck) {
      // alpha_z = 0: the x, y rows with N = -m (q_z + w_t . alpha_t); the z row gives C_z.
      const Eigen::Vector2d c_t = couple_per_normal.head<2>();
      const Eigen::Matrix2d a =
          inertia_about_p.topLeftCorner<2, 2>() + m * c_t * r_cross_ez.head<2>().transpose();
      Eigen::Vector2d alpha_t;
      if (!solve_2x2(a, h.head<2>() + normal_without_alpha * c_t, alpha_t)) return f;
      alpha = Vector3(alpha_t.x(), alpha_t.y(), 0.0);
      const double normal = normal_without_alpha - m * r_cross_ez.dot(alpha);
      couple =
          Vector3(normal * c_t.x(), normal * c_t.y(), inertia_about_p.row(2).dot(alpha) - h.z());
    } else {
      // (J + m c w^T) alpha = h - m q_z c: N's couple c depends on alpha through N.
      const Eigen::Matrix3d a = inertia_about_p + m * couple_per_normal * r_cross_ez.transpose();
      if (!solve_3x3(a, h + normal_without_alpha * couple_per_normal, alpha)) return f;
      couple = (normal_without_alpha - m * r_cross_ez.dot(alpha)) * couple_per_normal;
    }
    force = -m * (q + alpha.cross(r));
  } else {
    // F = N f, f = e_z + f_t: the moment per unit N is r x f + c.
    const Vector3 moment_per_normal = r.cross(force_per_normal) + couple_per_normal;
    double normal = 0.0;
    if (rolling_stuck && spinning_stuck) {
      // alpha = 0: p_z = 0 gives N; C balances the rest.
      alpha.setZero();
      normal = -m * q.z();
      couple = gamma - normal * r.cross(force_per_normal);
    } else if (rolling_stuck) {
      // alpha = alpha_z e_z, w . alpha = 0: N from p_z = 0; the z row gives alpha_z, the others
      // C_t.
      normal = -m * q.z();
      alpha = Vector3(0.0, 0.0, (normal * moment_per_normal.z() - gamma.z()) / inertia(2, 2));
      couple = inertia.col(2) * alpha.z() - normal * r.cross(force_per_normal) + gamma;
      couple.z() = normal * couple_per_normal.z();
    } else {
      // alpha = alpha_0 + N beta (+ C_z W e_z when spinning is stuck).
      const Vector3 alpha_free = -(inverse_inertia * gamma);
      const Vector3 beta = inverse_inertia * moment_per_normal;
      const double p_z_free = q.z() + r_cross_ez.dot(alpha_free);
      const double p_z_per_normal = 1.0 / m + r_cross_ez.dot(beta);
      if (spinning_stuck) {
        // Unknowns N and C_z: alpha_z = 0 and p_z = 0.
        const Vector3 spin_column = inverse_inertia.col(2);
        Eigen::Matrix2d a;
        a << p_z_per_normal, r_cross_ez.dot(spin_column), beta.z(), spin_column.z();
        Eigen::Vector2d unknowns;
        if (!solve_2x2(a, Eigen::Vector2d(-p_z_free, -alpha_free.z()), unknowns)) return f;
        normal = unknowns(0);
        alpha = alpha_free + normal * beta + unknowns(1) * spin_column;
        alpha.z() = 0.0;
        couple = normal * couple_per_normal;
        couple.z() = unknowns(1);
      } else {
        // A scalar: N p_z_per_normal = -p_z_free.
        if (!(p_z_per_normal != 0.0) || !std::isfinite(p_z_per_normal)) return f;
        normal = -p_z_free / p_z_per_normal;
        alpha = alpha_free + normal * beta;
        couple = normal * couple_per_normal;
      }
    }
    force = normal * force_per_normal;
  }
  if (!force.allFinite() || !couple.allFinite() || !alpha.allFinite()) return f;
  f.solved = true;
  f.normal_force_n = force.z();
  f.friction_force_world = Vector3(force.x(), force.y(), 0.0);
  f.rolling_couple_world = Vector3(couple.x(), couple.y(), 0.0);
  f.spinning_couple_nm = couple.z();
  f.linear_acceleration_world = setup.gravity_world + force / m;
  f.angular_acceleration_world = alpha;
  // d/dt of the slip velocity: the material point's acceleration, horizontal.
  const Vector3 p = q + force / m + alpha.cross(r);
  f.slip_acceleration_world = Vector3(p.x(), p.y(), 0.0);
  return f;
}

double plane_contact_energy(const PlaneContactSetup& setup, const PlaneContactKinematics& k) {
  return body_energy(setup.model.mass_properties().mass(), k.position_world, k.velocity_world,
                     k.angular_velocity_world, k.inertia_world * k.angular_velocity_world,
                     setup.gravity_world);
}

}  // namespace virtual_go
