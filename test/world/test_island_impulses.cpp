// The island sweeps' impulse maths (island_impulses.h) against physics written here: a contact's
// compliance is the change of the contact point's velocity per unit impulse (v + P/m, L + r x P,
// omega = I_world^-1 L with the test's own world inertia); the friction impulse of a slipping
// contact stops the slip when the cone allows it and otherwise ends on the cone's edge, never
// adding energy; the per-sub-step store hands out the compliance of the pose it is asked with,
// also after the pose changed.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <random>

#include "virtual_go/world/island_impulses.h"
#include "world_test_support.h"

namespace {

using namespace worldtest;

// The contact point's velocity change (m/s) when the impulse p (N s) acts at point_world on a
// stone in state s: from the definitions, with I_world = R I_body R^T.
Vector3d velocity_change(const vg::RigidBodyState& s, const Vector3d& point_world,
                         const Vector3d& p) {
  const vg::MassProperties& mp = stone().mass_properties;
  const Eigen::Matrix3d r = s.orientation.toRotationMatrix();
  const Eigen::Matrix3d inertia_world = r * mp.inertia_body() * r.transpose();
  const Vector3d lever = point_world - s.position_world;
  const Vector3d d_omega = inertia_world.ldlt().solve(lever.cross(p));
  return p / mp.mass() + d_omega.cross(lever);
}

// K from its columns: the velocity change per unit impulse along each axis.
Eigen::Matrix3d response(const vg::RigidBodyState& s, const Vector3d& point_world) {
  Eigen::Matrix3d k;
  for (int c = 0; c < 3; ++c) k.col(c) = velocity_change(s, point_world, Vector3d::Unit(c));
  return k;
}

vg::RigidBodyState random_pose(std::mt19937& rng) {
  std::normal_distribution<double> g;
  vg::RigidBodyState s;
  s.position_world = 0.01 * Vector3d(g(rng), g(rng), g(rng));
  s.orientation = Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
  return s;
}

Vector3d rim_point(std::mt19937& rng, const vg::RigidBodyState& s) {
  std::normal_distribution<double> g;
  return s.position_world + s.orientation * Vector3d(kA * Vector3d(g(rng), g(rng), 0).normalized() +
                                                     Vector3d(0, 0, 0.3 * kC * g(rng)));
}

TEST(IslandImpulses, ComplianceIsTheContactPointsVelocityChangePerImpulse) {
  std::mt19937 rng(15);
  std::normal_distribution<double> g;
  const vg::MassProperties& mp = stone().mass_properties;
  double worst = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    const vg::RigidBodyState s = random_pose(rng);
    const Vector3d point = rim_point(rng, s);
    const Eigen::Matrix3d r = s.orientation.toRotationMatrix();
    const Eigen::Matrix3d inverse = r * mp.inverse_inertia_body() * r.transpose();
    const Eigen::Matrix3d k = vg::contact_compliance(mp.mass(), inverse, point - s.position_world);
    const Vector3d p(g(rng), g(rng), g(rng));
    const Vector3d expected = velocity_change(s, point, p);
    worst = std::max(worst, (k * p - expected).norm() / expected.norm());
    // Symmetric positive definite: the impulse always does work against the approach.
    EXPECT_LT((k - k.transpose()).norm(), 1e-12 * k.norm());
    EXPECT_GT(p.dot(k * p), 0.0);
  }
  EXPECT_LT(worst, 1e-12);
}

struct Slip {
  vg::RigidBodyState s;
  Vector3d point, n, u;
  Eigen::Matrix3d k;
};

Slip random_slip(std::mt19937& rng) {
  std::normal_distribution<double> g;
  Slip c;
  c.s = random_pose(rng);
  c.point = rim_point(rng, c.s);
  c.n = Vector3d(g(rng), g(rng), g(rng)).normalized();
  const Vector3d u = Vector3d(g(rng), g(rng), g(rng));
  c.u = u - u.dot(c.n) * c.n + 1e-3 * std::abs(g(rng)) * c.n;  // slipping, separating slowly
  c.k = response(c.s, c.point);
  return c;
}

double energy_change(const Slip& c, const Vector3d& p) {
  // dE = P . u + P . K P / 2 for an impulse on one body (K from the definitions).
  return p.dot(c.u) + 0.5 * p.dot(c.k * p);
}

TEST(IslandImpulses, FrictionStopsTheSlipWhenTheConeAllows) {
  std::mt19937 rng(16);
  const double mu = 0.3;
  for (int trial = 0; trial < 200; ++trial) {
    const Slip c = random_slip(rng);
    // A normal impulse so far large enough for any stopping impulse.
    const Vector3d accumulated = 1e3 * c.n;
    ASSERT_TRUE(vg::may_slip(c.n, c.u, accumulated, mu, 1e-12));
    const Vector3d f = vg::friction_impulse(c.n, c.k, c.u, accumulated, mu, 1e-12);
    const Vector3d after = c.u + c.k * f;
    const Vector3d slip_before = c.u - c.u.dot(c.n) * c.n,
                   slip_after = after - after.dot(c.n) * c.n;
    EXPECT_LT(slip_after.norm(), 1e-12 * slip_before.norm());
    EXPECT_LT(std::abs(f.dot(c.n)), 1e-12 * f.norm());  // tangential
    EXPECT_LT(energy_change(c, f), 0.0);
  }
}

TEST(IslandImpulses, FrictionEndsOnTheConesEdge) {
  std::mt19937 rng(17);
  const double mu = 0.3;
  for (int trial = 0; trial < 200; ++trial) {
    const Slip c = random_slip(rng);
    const Vector3d stop = vg::friction_impulse(c.n, c.k, c.u, 1e3 * c.n, mu, 1e-12);
    // A normal impulse so far that allows only part of the stopping impulse, and a tangential
    // impulse so far inside the cone.
    const double normal_ns = 0.5 * stop.norm() / mu;
    const Vector3d t_sum = 0.2 * mu * normal_ns * c.n.cross(stop).normalized();
    const Vector3d accumulated = normal_ns * c.n + t_sum;
    const Vector3d f = vg::friction_impulse(c.n, c.k, c.u, accumulated, mu, 1e-12);
    EXPECT_NEAR((t_sum + f).norm(), mu * normal_ns, 1e-12 * mu * normal_ns);
    // Along the stopping impulse, shortened: alpha in (0, 1).
    const double alpha = f.dot(stop) / stop.squaredNorm();
    EXPECT_GT(alpha, 0.0);
    EXPECT_LT(alpha, 1.0);
    EXPECT_LT((f - alpha * stop).norm(), 1e-12 * stop.norm());
    EXPECT_LT(energy_change(c, f), 0.0);
    // The cone already full: nothing more.
    const Vector3d full = normal_ns * c.n + mu * normal_ns * c.n.cross(stop).normalized() * 1.01;
    EXPECT_TRUE(vg::friction_impulse(c.n, c.k, c.u, full, mu, 1e-12).isZero());
  }
}

TEST(IslandImpulses, NoFrictionWithoutFrictionLoadOrSlip) {
  std::mt19937 rng(18);
  const Slip c = random_slip(rng);
  const Vector3d pressed = c.n;
  EXPECT_FALSE(vg::may_slip(c.n, c.u, pressed, 0.0, 1e-12));
  EXPECT_TRUE(vg::friction_impulse(c.n, c.k, c.u, pressed, 0.0, 1e-12).isZero());
  EXPECT_FALSE(vg::may_slip(c.n, c.u, -c.n, 0.3, 1e-12));  // pulled, not pressed
  EXPECT_TRUE(vg::friction_impulse(c.n, c.k, c.u, -c.n, 0.3, 1e-12).isZero());
  const Vector3d rolling = 1e-13 * c.n.cross(c.u).normalized() + 0.5 * c.n;
  EXPECT_FALSE(vg::may_slip(c.n, rolling, pressed, 0.3, 1e-12));
  EXPECT_TRUE(vg::friction_impulse(c.n, c.k, rolling, pressed, 0.3, 1e-12).isZero());
}

TEST(IslandImpulses, StoreHandsOutThePosesCompliance) {
  std::mt19937 rng(19);
  const vg::MotionModel m = model();
  vg::RigidBodyState a = random_pose(rng), b = random_pose(rng);
  const Vector3d point_a = rim_point(rng, a), point_ab = rim_point(rng, b);
  vg::SweepCompliances store(2, 1);
  auto close = [](const Eigen::Matrix3d& x, const Eigen::Matrix3d& y) {
    return (x - y).norm() <= 1e-12 * y.norm();
  };
  EXPECT_TRUE(close(store.board(0, 1, m, a, point_a), response(a, point_a)));
  EXPECT_TRUE(close(store.pair(0, 0, m, a, 1, m, b, point_ab),
                    response(a, point_ab) + response(b, point_ab)));
  // Velocities change nothing (the sweeps change only those): the entries are kept.
  a.velocity_world = Vector3d(1, 2, 3);
  a.angular_momentum_world = Vector3d(1e-4, 0, 0);
  EXPECT_TRUE(close(store.board(0, 1, m, a, point_a), response(a, point_a)));
  // A new pose takes a new store (one per sub-step's sweep stage): that pose's compliances.
  a.orientation = (a.orientation * Quaterniond(Eigen::AngleAxisd(0.3, Vector3d::UnitX())));
  b.orientation = (b.orientation * Quaterniond(Eigen::AngleAxisd(0.2, Vector3d::UnitY())));
  b.position_world += Vector3d(0.002, 0, 0);
  vg::SweepCompliances fresh(2, 1);
  EXPECT_TRUE(close(fresh.board(0, 1, m, a, point_a), response(a, point_a)));
  EXPECT_TRUE(close(fresh.pair(0, 0, m, a, 1, m, b, point_ab),
                    response(a, point_ab) + response(b, point_ab)));
}

}  // namespace

TEST(IslandImpulses, ASettledContactIsLookedAtAgainOnlyWhenAMemberChanges) {
  // Members 0, 1, 2; board slot 2 (member 1's first), pair 0 (0, 1), obstacle pair 1 (member 2).
  vg::SweepSettled settled(3, 2);
  EXPECT_FALSE(settled.board(2, 1));  // nothing looked at yet
  EXPECT_FALSE(settled.pair(0, 0, 1));
  EXPECT_FALSE(settled.obstacle(1, 2));
  settled.board_idle(2, 1);
  settled.pair_idle(0, 0, 1);
  settled.obstacle_idle(1, 2);
  EXPECT_TRUE(settled.board(2, 1));
  EXPECT_TRUE(settled.pair(0, 0, 1));
  EXPECT_TRUE(settled.obstacle(1, 2));
  settled.changed(2);  // an impulse on member 2: only its obstacle contact is looked at again
  EXPECT_TRUE(settled.board(2, 1));
  EXPECT_TRUE(settled.pair(0, 0, 1));
  EXPECT_FALSE(settled.obstacle(1, 2));
  settled.changed(0);  // on member 0: the pair, either member counts
  EXPECT_FALSE(settled.pair(0, 0, 1));
  EXPECT_TRUE(settled.board(2, 1));
  settled.pair_idle(0, 0, 1);
  settled.changed(1);
  EXPECT_FALSE(settled.pair(0, 0, 1));
  EXPECT_FALSE(settled.board(2, 1));
}
