// PlaneContact's energy guard and its plastic projection onto a mode's constraints
// (plane_contact_laws.h): the two ways a state is changed other than by the equations of motion,
// and both can only remove energy.
#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "plane_contact_laws.h"

namespace virtual_go::plane_contact_detail {

double PlaneContactLaws::energy(const PlaneContactKinematics& k) const {
  return plane_contact_energy(setup_, k);
}

PlaneContactKinematics PlaneContactLaws::capped(const PlaneContactKinematics& k,
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

PlaneContactKinematics PlaneContactLaws::projected(const PlaneContactKinematics& k,
                                                   const PlaneContactMode& mode) const {
  // Rows of the velocities the mode holds at zero: the normal velocity at P, and the stuck parts.
  const Eigen::Vector3d& r = k.offset_world;
  Eigen::Matrix<double, Eigen::Dynamic, 6, 0, 6, 6> j(6, 6);
  int n = 0;
  auto translational = [&](const Eigen::Vector3d& e) {
    j.row(n).head<3>() = e.transpose();
    j.row(n++).tail<3>() = r.cross(e).transpose();
  };
  auto angular = [&](const Eigen::Vector3d& e) {
    j.row(n).head<3>().setZero();
    j.row(n++).tail<3>() = e.transpose();
  };
  translational(Eigen::Vector3d::UnitZ());
  if (mode.tangential.law == ContactLaw::stuck) {
    translational(Eigen::Vector3d::UnitX());
    translational(Eigen::Vector3d::UnitY());
  }
  if (mode.rolling.law == ContactLaw::stuck) {
    angular(Eigen::Vector3d::UnitX());
    angular(Eigen::Vector3d::UnitY());
  }
  if (mode.spinning.law == ContactLaw::stuck) angular(Eigen::Vector3d::UnitZ());
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

}  // namespace virtual_go::plane_contact_detail
