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
    const double c = moments.z() - moments.x();
    const double inverse_1 = 1.0 / moments.x();
    const double c_inverse = 1.0 / moments.z() - inverse_1;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const double bb = axis[i] * axis[j];
        inertia(i, j) = (i == j ? moments.x() : 0.0) + c * bb;
        inverse(i, j) = (i == j ? inverse_1 : 0.0) + c_inverse * bb;
      }
    }
    return;
  }
  const Eigen::Matrix3d rotation = orientation.toRotationMatrix();
  inertia = rotation * moments.asDiagonal() * rotation.transpose();
  inverse = rotation * moments.cwiseInverse().asDiagonal() * rotation.transpose();
}

// Solves a x = b for the leading n x n block (n <= 6) by Gaussian elimination with partial
// pivoting (a few dozen operations; Eigen's decompositions of a dynamic-size block cost several
// times the whole right-hand side here). False when a pivot falls below n eps max |a_ij|:
// singular to working precision, the same test as Eigen's FullPivLU::isInvertible.
bool solve_small(Eigen::Matrix<double, 6, 6>& a, Eigen::Matrix<double, 6, 1>& b, int n) {
  double largest = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) largest = std::max(largest, std::abs(a(i, j)));
  }
  const double threshold = n * std::numeric_limits<double>::epsilon() * largest;
  if (!(largest > 0.0) || !std::isfinite(largest)) return false;
  for (int col = 0; col < n; ++col) {
    int pivot = col;
    for (int i = col + 1; i < n; ++i) {
      if (std::abs(a(i, col)) > std::abs(a(pivot, col))) pivot = i;
    }
    if (!(std::abs(a(pivot, col)) > threshold)) return false;
    if (pivot != col) {
      a.row(pivot).swap(a.row(col));
      std::swap(b(pivot), b(col));
    }
    for (int i = col + 1; i < n; ++i) {
      const double factor = a(i, col) / a(col, col);
      for (int j = col + 1; j < n; ++j) a(i, j) -= factor * a(col, j);
      b(i) -= factor * b(col);
    }
  }
  for (int i = n - 1; i >= 0; --i) {
    double sum = b(i);
    for (int j = i + 1; j < n; ++j) sum -= a(i, j) * b(j);
    b(i) = sum / a(i, i);
  }
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
  k.offset_world = plane_contact_offset_world(setup.lens, mode.part, k.axis_world);
  k.offset_rate_world = plane_contact_offset_rate_world(setup.lens, mode.part, k.axis_world,
                                                        k.angular_velocity_world);
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
  const double m = setup.model.mass_properties().mass();
  const ContactMaterial& law = setup.material;
  const Vector3& r = k.offset_world;
  const Vector3& w = k.angular_velocity_world;
  const Eigen::Matrix3d& inverse_inertia = k.inverse_inertia_world;
  const Vector3 ez = Vector3::UnitZ();
  const Vector3 w_cross_r_dot = w.cross(k.offset_rate_world);

  // Every unknown multiplier is a generalized force: a force at P and a couple. Its response is
  // the acceleration of G, the angular acceleration, and the acceleration of the material point at
  // P, p = a + alpha x r. Every constraint row is one component of p (the normal velocity at P,
  // stuck slip) or of alpha (stuck rolling and spinning), so the matrix is read off the responses.
  struct Response {
    Vector3 a, alpha, p;
  };
  // The response to a moment about G (r x force + couple) with the acceleration of G given.
  auto respond_to = [&](const Vector3& a, const Vector3& moment) {
    Response c;
    c.a = a;
    c.alpha = inverse_inertia * moment;
    c.p = c.a + c.alpha.cross(r);
    return c;
  };
  auto respond = [&](const Vector3& force, const Vector3& couple) {
    return respond_to(force / m, r.cross(force) + couple);
  };
  // The unit columns without their divisions by m and products with zero: e_i / m is 1 / m and
  // +0, and r x 0 + couple is the couple, so the values are those of respond() bit for bit.
  const double unit_over_mass = 1.0 / m;
  auto respond_unit_force = [&](int axis) {
    Vector3 a = Vector3::Zero();
    a[axis] = unit_over_mass;
    return respond_to(a, r.cross(Vector3::Unit(axis)) + Vector3::Zero());
  };
  auto respond_couple = [&](const Vector3& couple) { return respond_to(Vector3::Zero(), couple); };
  // Without contact: gravity and the gyroscopic term; p also carries omega x dr/dt.
  Response free;
  free.a = setup.gravity_world;
  free.alpha = -inverse_inertia * w.cross(k.inertia_world * w);
  free.p = free.a + free.alpha.cross(r) + w_cross_r_dot;

  // The normal force's column carries the sliding parts, which are proportional to N.
  Vector3 tangential_direction = Vector3::Zero(), rolling_direction = Vector3::Zero();
  double spin_sign = 0.0;
  Vector3 normal_force = ez, normal_couple = Vector3::Zero();
  if (mode.tangential.law == ContactLaw::sliding) {
    tangential_direction = law_direction(mode.tangential, k.slip_velocity(), kSlipDirectionLayer);
    normal_force -= law.friction * tangential_direction;
  }
  if (mode.rolling.law == ContactLaw::sliding) {
    rolling_direction = law_direction(mode.rolling, k.rolling_velocity(), kRollDirectionLayer);
    normal_couple -= law.rolling_resistance_m * rolling_direction;
  }
  if (mode.spinning.law == ContactLaw::sliding) {
    spin_sign = mode.spinning.reference_world.z() < 0.0 ? -1.0 : 1.0;
    normal_couple.z() -= law.spinning_friction_m * spin_sign;
  }

  // Rows (component `axis` of p, or of alpha when `angular`) and their columns.
  struct Row {
    bool angular;
    int axis;
  };
  Row rows[6];
  Response columns[6];
  int n = 0;
  rows[n] = {false, 2};
  columns[n++] = respond(normal_force, normal_couple);
  const bool tangential_stuck = mode.tangential.law == ContactLaw::stuck;
  const bool rolling_stuck = mode.rolling.law == ContactLaw::stuck;
  const bool spinning_stuck = mode.spinning.law == ContactLaw::stuck;
  if (tangential_stuck) {
    for (int axis = 0; axis < 2; ++axis) {
      rows[n] = {false, axis};
      columns[n++] = respond_unit_force(axis);
    }
  }
  if (rolling_stuck) {
    for (int axis = 0; axis < 2; ++axis) {
      rows[n] = {true, axis};
      columns[n++] = respond_couple(Vector3::Unit(axis));
    }
  }
  if (spinning_stuck) {
    rows[n] = {true, 2};
    columns[n++] = respond_couple(ez);
  }
  auto component = [](const Row& row, const Response& c) {
    return row.angular ? c.alpha[row.axis] : c.p[row.axis];
  };
  Eigen::Matrix<double, 6, 6> a;
  Eigen::Matrix<double, 6, 1> lambda;
  for (int i = 0; i < n; ++i) {
    lambda(i) = -component(rows[i], free);
    for (int j = 0; j < n; ++j) a(i, j) = component(rows[i], columns[j]);
  }
  PlaneContactForces f;
  if (!solve_small(a, lambda, n)) return f;
  if (!lambda.head(n).allFinite()) return f;
  f.solved = true;

  Vector3 p = free.p;
  f.linear_acceleration_world = free.a;
  f.angular_acceleration_world = free.alpha;
  for (int j = 0; j < n; ++j) {
    f.linear_acceleration_world += lambda(j) * columns[j].a;
    f.angular_acceleration_world += lambda(j) * columns[j].alpha;
    p += lambda(j) * columns[j].p;
  }
  const double normal = lambda(0);
  f.normal_force_n = normal;
  int next = 1;
  if (tangential_stuck) {
    f.friction_force_world = Vector3(lambda(next), lambda(next + 1), 0.0);
    next += 2;
  } else if (mode.tangential.law == ContactLaw::sliding) {
    f.friction_force_world = -law.friction * normal * tangential_direction;
  }
  if (rolling_stuck) {
    f.rolling_couple_world = Vector3(lambda(next), lambda(next + 1), 0.0);
    next += 2;
  } else if (mode.rolling.law == ContactLaw::sliding) {
    f.rolling_couple_world = -law.rolling_resistance_m * normal * rolling_direction;
  }
  if (spinning_stuck) {
    f.spinning_couple_nm = lambda(next);
  } else if (mode.spinning.law == ContactLaw::sliding) {
    f.spinning_couple_nm = -law.spinning_friction_m * normal * spin_sign;
  }
  // d/dt of the slip velocity: the material point's acceleration, horizontal.
  f.slip_acceleration_world = Vector3(p.x(), p.y(), 0.0);
  return f;
}

double plane_contact_energy(const PlaneContactSetup& setup, const PlaneContactKinematics& k) {
  return body_energy(setup.model.mass_properties().mass(), k.position_world, k.velocity_world,
                     k.angular_velocity_world, k.inertia_world * k.angular_velocity_world,
                     setup.gravity_world);
}

}  // namespace virtual_go
