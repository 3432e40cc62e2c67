// Rigid-body derived quantities: the article's RigidBodyMatrix / RigidBodyInverse, point and
// vector transforms, angular velocity from angular momentum, and the energies; each compared
// with quaternion algebra and mechanics written in the test.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "support/physics_reference.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/go/stone.h"

namespace vg = virtual_go;
using vgtest::Quat;

namespace {

vg::MassProperties stone_mass() { return vg::make_stone(vg::StoneSpec{}).mass_properties; }

vg::RigidBodyState sample_state() {
  vg::RigidBodyState s;
  s.position_world = Eigen::Vector3d(0.12, -0.34, 0.56);
  s.orientation = vgtest::to_eigen(vgtest::axis_angle(Eigen::Vector3d(0.7, -1.1, 2.3)));
  s.velocity_world = Eigen::Vector3d(1.5, -0.25, 3.0);
  s.angular_momentum_world = Eigen::Vector3d(2e-6, -5e-6, 7e-6);
  return s;
}

Eigen::Vector4d homogeneous(const Eigen::Vector3d& p, double w) {
  return Eigen::Vector4d(p.x(), p.y(), p.z(), w);
}

}  // namespace

TEST(RigidBody, MatrixTimesInverseIsIdentity) {
  const vg::RigidBody body(vg::MotionModel(vg::MotionModelKind::rigid_body, stone_mass()),
                           sample_state());
  const Eigen::Matrix4d m = body.body_to_world_matrix(), inv = body.world_to_body_matrix();
  EXPECT_TRUE((m * inv).isIdentity(1e-15)) << m * inv;
  EXPECT_TRUE((inv * m).isIdentity(1e-15)) << inv * m;
  // A proper rigid transform: orthonormal rotation block, det +1, bottom row (0 0 0 1).
  const Eigen::Matrix3d r = m.topLeftCorner<3, 3>();
  EXPECT_TRUE((r * r.transpose()).isIdentity(1e-15));
  EXPECT_NEAR(r.determinant(), 1.0, 1e-15);
  EXPECT_TRUE(m.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1)));
  EXPECT_TRUE(m.col(3).head<3>().isApprox(sample_state().position_world));
}

TEST(RigidBody, TransformsAgreeWithQuaternionRotation) {
  const vg::RigidBodyState s = sample_state();
  const vg::RigidBody body(vg::MotionModel(vg::MotionModelKind::rigid_body, stone_mass()), s);
  const Quat q = vgtest::from_eigen(s.orientation);
  const Eigen::Vector3d p_body(0.011, -0.002, 0.0046), v_body(-0.3, 0.8, 0.1);
  // Reference: p_world = q p q* + x, v_world = q v q*.
  const Eigen::Vector3d p_world = vgtest::rotate(q, p_body) + s.position_world;
  const Eigen::Vector3d v_world = vgtest::rotate(q, v_body);
  EXPECT_TRUE(body.point_body_to_world(p_body).isApprox(p_world, 1e-15));
  EXPECT_TRUE(body.vector_body_to_world(v_body).isApprox(v_world, 1e-15));
  EXPECT_TRUE((body.body_to_world_matrix() * homogeneous(p_body, 1))
                  .isApprox(homogeneous(p_world, 1), 1e-15));
  EXPECT_TRUE((body.body_to_world_matrix() * homogeneous(v_body, 0))
                  .isApprox(homogeneous(v_world, 0), 1e-15));
  // And back.
  EXPECT_TRUE(body.point_world_to_body(p_world).isApprox(p_body, 1e-14));
  EXPECT_TRUE(body.vector_world_to_body(v_world).isApprox(v_body, 1e-14));
  EXPECT_TRUE((body.world_to_body_matrix() * homogeneous(p_world, 1))
                  .isApprox(homogeneous(p_body, 1), 1e-14));
  // Round trips.
  EXPECT_TRUE(body.point_world_to_body(body.point_body_to_world(p_body)).isApprox(p_body, 1e-14));
  EXPECT_TRUE(
      body.vector_body_to_world(body.vector_world_to_body(v_world)).isApprox(v_world, 1e-15));
}

TEST(RigidBody, IdentityIsALyingStoneAndQuarterTurnsMapAxes) {
  vg::RigidBodyState s;
  const vg::MotionModel model(vg::MotionModelKind::rigid_body, stone_mass());
  EXPECT_TRUE(vg::RigidBody(model, s)
                  .vector_body_to_world(Eigen::Vector3d::UnitZ())
                  .isApprox(Eigen::Vector3d::UnitZ()));
  // 90 degrees about world z (right-handed): body x -> world y, body y -> world -x.
  s.orientation = vgtest::to_eigen(vgtest::axis_angle(Eigen::Vector3d(0, 0, M_PI / 2)));
  const vg::RigidBody turned(model, s);
  EXPECT_LT(
      (turned.vector_body_to_world(Eigen::Vector3d::UnitX()) - Eigen::Vector3d::UnitY()).norm(),
      1e-15);
  EXPECT_LT(
      (turned.vector_body_to_world(Eigen::Vector3d::UnitY()) + Eigen::Vector3d::UnitX()).norm(),
      1e-15);
}

TEST(RigidBody, AngularVelocityFollowsFromMomentumAndInertia) {
  const vg::MassProperties mp = stone_mass();
  const vg::RigidBodyState s = sample_state();
  const Quat q = vgtest::from_eigen(s.orientation);
  const Eigen::Vector3d inertia = mp.principal_moments_body();

  // rigid_body: omega_body = I^-1 R^T L, omega_world = R omega_body.
  const vg::MotionModel rigid(vg::MotionModelKind::rigid_body, mp);
  const vg::RigidBody body(rigid, s);
  const Eigen::Vector3d omega_body =
      vgtest::rotate(vgtest::qconj(q), s.angular_momentum_world).cwiseQuotient(inertia);
  EXPECT_TRUE(body.angular_velocity_body().isApprox(omega_body, 1e-14));
  EXPECT_TRUE(body.angular_velocity_world().isApprox(vgtest::rotate(q, omega_body), 1e-14));
  // Energy: 1/2 omega_body . I omega_body, 1/2 m v^2, and m g z for standard gravity.
  const double rot = 0.5 * omega_body.dot(inertia.cwiseProduct(omega_body));
  const double trans = 0.5 * mp.mass() * s.velocity_world.squaredNorm();
  const double pot = mp.mass() * 9.80665 * s.position_world.z();
  EXPECT_NEAR(body.rotational_kinetic_energy(), rot, 1e-14 * rot);
  EXPECT_NEAR(body.translational_kinetic_energy(), trans, 1e-15 * trans);
  EXPECT_NEAR(body.kinetic_energy(), rot + trans, 1e-15 * (rot + trans));
  EXPECT_NEAR(body.potential_energy(vg::kStandardGravity), pot, 1e-15 * std::abs(pot));
  EXPECT_NEAR(body.total_energy(vg::kStandardGravity), rot + trans + pot, 1e-15 * (rot + trans));
  EXPECT_EQ(body.potential_energy(Eigen::Vector3d::Zero()), 0.0);
  // World inertia R I R^T: symmetric with the principal moments as eigenvalues, L = I_w omega.
  const Eigen::Matrix3d iw = rigid.inertia_world(s.orientation);
  EXPECT_TRUE(iw.isApprox(iw.transpose(), 1e-15));
  Eigen::Vector3d eig = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(iw).eigenvalues();
  Eigen::Vector3d sorted = inertia;
  std::sort(sorted.data(), sorted.data() + 3);
  EXPECT_TRUE(eig.isApprox(sorted, 1e-12)) << eig.transpose();
  EXPECT_TRUE((iw * body.angular_velocity_world()).isApprox(s.angular_momentum_world, 1e-14));

  // constant_omega: the article's body, L = I_iso omega with I_iso = trace(I) / 3.
  const vg::MotionModel article(vg::MotionModelKind::constant_omega, mp);
  const double iso = inertia.sum() / 3;
  EXPECT_NEAR(article.isotropic_moment(), iso, 1e-15 * iso);
  EXPECT_TRUE(vg::RigidBody(article, s)
                  .angular_velocity_world()
                  .isApprox(s.angular_momentum_world / iso, 1e-15));
}

TEST(RigidBody, SettingAngularVelocitySetsTheMatchingMomentum) {
  const vg::MassProperties mp = stone_mass();
  const Eigen::Vector3d omega_world(20.0, 5.0, 40.0);
  vg::RigidBodyState s = sample_state();
  const Quat q = vgtest::from_eigen(s.orientation);
  const vg::MotionModel rigid(vg::MotionModelKind::rigid_body, mp);
  s = vg::with_angular_velocity_world(rigid, s, omega_world);
  // L = R I R^T omega, by hand.
  const Eigen::Vector3d l = vgtest::rotate(
      q, mp.principal_moments_body().cwiseProduct(vgtest::rotate(vgtest::qconj(q), omega_world)));
  EXPECT_TRUE(s.angular_momentum_world.isApprox(l, 1e-14));
  EXPECT_TRUE(vg::RigidBody(rigid, s).angular_velocity_world().isApprox(omega_world, 1e-14));
}
