// The plastic impulse of Moreau-Jean's local Coulomb law (coulomb_plastic_impulse.h) against
// physics written here: on random contacts of real stones (one stone on a surface, two stones)
// the impulse satisfies the law in De Saxce's natural-map form, P = proj_C(P - rho u~) with
// u~ = u+ + mu |u+_t| n and C the Coulomb cone (De Saxce & Feng 1991; Acary & Brogliato 2008,
// ch. 12), which the Newton iteration of the code never uses; u+_n = 0; the energy always falls.
// Where K_tn = 0 and K_tt is isotropic the slip keeps its direction, and the impulse is the closed
// form, the same as the impulse-space process's plastic impact (Stronge) on a stone struck
// straight below its centre.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <random>

#include "virtual_go/body/mass_properties.h"
#include "virtual_go/body/motion_model.h"
#include "virtual_go/contact/coulomb_plastic_impulse.h"
#include "virtual_go/contact/impact.h"
#include "virtual_go/geometry/lens_shape.h"

namespace vg = virtual_go;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

constexpr double kRadiusM = 0.0111, kHalfThicknessM = 0.0046;

const vg::MassProperties& stone() {
  static const vg::MassProperties mp =
      vg::MassProperties::of_lens(vg::LensShape{2 * kRadiusM, 2 * kHalfThicknessM}, 2700.0);
  return mp;
}

// The test's own compliance of one stone at lever arm r in orientation q: the contact point's
// velocity change per unit impulse, column by column, from v + P/m and omega = I_world^-1 (r x P).
Matrix3d compliance(const Eigen::Quaterniond& q, const Vector3d& r) {
  const Matrix3d rot = q.toRotationMatrix();
  const Matrix3d inertia_world = rot * stone().inertia_body() * rot.transpose();
  Matrix3d k;
  for (int c = 0; c < 3; ++c) {
    const Vector3d p = Vector3d::Unit(c);
    k.col(c) = p / stone().mass() + inertia_world.ldlt().solve(r.cross(p)).cross(r);
  }
  return 0.5 * (k + k.transpose());
}

// Projection onto the Coulomb cone {x : |x_t| <= mu x_n} around n.
Vector3d project_on_cone(const Vector3d& x, const Vector3d& n, double mu) {
  const double x_n = x.dot(n);
  const Vector3d x_t = x - x_n * n;
  const double r = x_t.norm();
  if (r <= mu * x_n) return x;
  if (mu * r <= -x_n) return Vector3d::Zero();
  const double along = (x_n + mu * r) / (1.0 + mu * mu);
  return along * (n + (r > 0.0 ? Vector3d(mu * x_t / r) : Vector3d::Zero()));
}

struct Random {
  std::mt19937 rng{2026};
  std::normal_distribution<double> normal{0.0, 1.0};
  std::uniform_real_distribution<double> uniform{0.0, 1.0};
  Vector3d unit() { return Vector3d(normal(rng), normal(rng), normal(rng)).normalized(); }
  Eigen::Quaterniond orientation() {
    return Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
  }
  // A lever arm inside the stone's bounding sphere, most on its surface.
  Vector3d lever() { return kRadiusM * std::sqrt(uniform(rng)) * unit(); }
};

}  // namespace

TEST(CoulombPlasticImpulse, SatisfiesTheLawOnRandomStoneContacts) {
  Random random;
  int stick = 0, slip = 0, empty = 0;
  double worst_law = 0.0, worst_normal = 0.0, largest_energy_ratio = -1.0;
  const int trials = 20000;
  for (int trial = 0; trial < trials; ++trial) {
    const Vector3d n = random.unit();
    // One stone on a fixed surface, or two stones: K = K_a + K_b.
    Matrix3d k = compliance(random.orientation(), random.lever());
    if (trial % 2 == 1) k += compliance(random.orientation(), random.lever());
    const double mu = trial % 7 == 0 ? 0.0 : 1.5 * random.uniform(random.rng);
    // Slip over approach from 1e-6 to 1e3, log-uniform; the scale from 1e-6 to 1 m/s.
    const double ratio = std::pow(10.0, -6.0 + 9.0 * random.uniform(random.rng));
    const double speed = std::pow(10.0, -6.0 + 6.0 * random.uniform(random.rng));
    const Vector3d slip_dir = (random.unit().cross(n)).normalized();
    const Vector3d u = speed * (-n + ratio * slip_dir);
    const vg::PlasticImpulse impulse = vg::coulomb_plastic_impulse(n, k, u, mu);
    if (impulse.frictionless) ++empty;
    const Vector3d* p = &impulse.impulse_world;
    const Vector3d u_after = u + k * *p;
    const double scale = u.norm();
    worst_normal = std::max(worst_normal, std::abs(u_after.dot(n)) / scale);
    const Vector3d u_t = u_after - u_after.dot(n) * n;
    (u_t.norm() <= 1e-12 * scale ? stick : slip)++;
    // The natural map with rho = 1 / tr(K), both sides in N s.
    const double rho = 1.0 / k.trace();
    const Vector3d modified = u_after + mu * u_t.norm() * n;
    const Vector3d residual = *p - project_on_cone(*p - rho * modified, n, mu);
    worst_law = std::max(worst_law, residual.norm() / (rho * scale));
    const double energy_change = p->dot(u) + 0.5 * p->dot(k * *p);
    const double energy_scale = 0.5 * scale * scale / k.trace();
    largest_energy_ratio = std::max(largest_energy_ratio, energy_change / energy_scale);
    ASSERT_LT(energy_change, 0.0) << "trial " << trial;
  }
  std::printf(
      "[ measured ] %d random stone contacts: %d stick, %d slip, %d left frictionless; law "
      "residual %.2e, |u+_n| %.2e (of |u-|); largest dE %.2e (of |u-|^2 / 2 tr K)\n",
      trials, stick, slip, empty, worst_law, worst_normal, largest_energy_ratio);
  EXPECT_EQ(empty, 0);
  EXPECT_GT(stick, trials / 20);
  EXPECT_GT(slip, trials / 4);
  EXPECT_LT(worst_law, 1e-12);
  EXPECT_LT(worst_normal, 1e-12);
}

TEST(CoulombPlasticImpulse, IsotropicContactIsTheClosedForm) {
  // K = k_t (1 - n n^T) + k_n n n^T: the slip keeps its direction. Slipping on,
  // P_n = -u_n / k_n and P_t = -mu P_n t; stopped (|u_t| <= mu P_n k_t), P = -K^-1 u.
  Random random;
  const double k_t = 500.0, k_n = 180.0;
  for (int trial = 0; trial < 200; ++trial) {
    const Vector3d n = random.unit();
    const Matrix3d k = k_t * (Matrix3d::Identity() - n * n.transpose()) + k_n * n * n.transpose();
    const Vector3d t = random.unit().cross(n).normalized();
    const double u_n = -0.3, u_t = 0.3 * std::pow(10.0, -3.0 + 4.0 * random.uniform(random.rng));
    const double mu = 0.05 + random.uniform(random.rng);
    const Vector3d u = u_n * n + u_t * t;
    const vg::PlasticImpulse impulse = vg::coulomb_plastic_impulse(n, k, u, mu);
    ASSERT_FALSE(impulse.frictionless);
    const Vector3d* p = &impulse.impulse_world;
    const double p_n = -u_n / k_n;
    const Vector3d expected =
        u_t <= mu * p_n * k_t ? Vector3d(p_n * n - u_t / k_t * t) : Vector3d(p_n * (n - mu * t));
    EXPECT_LT((*p - expected).norm(), 1e-14 * expected.norm()) << "trial " << trial;
  }
}

TEST(CoulombPlasticImpulse, AgreesWithTheImpulseSpaceProcessWhereTheSlipIsStraight) {
  // A flat stone struck straight below its centre (the lever arm along n: K_tn = 0, K_tt
  // isotropic about the symmetry axis): Stronge's plastic impact integrates a slip that keeps its
  // direction, so both laws give the same impulse, slipping through or stopped.
  const vg::MotionModel model(vg::MotionModelKind::rigid_body, stone());
  vg::ContactMaterial plastic;
  plastic.restitution = 0.0;
  for (const double slip_mps : {0.01, 0.05, 0.2, 1.0}) {
    for (const double mu : {0.1, 0.3, 0.8}) {
      plastic.friction = mu;
      vg::RigidBodyState s;
      s.velocity_world = Vector3d(slip_mps, 0.0, -0.4);
      const Vector3d point(0, 0, -kHalfThicknessM), n = Vector3d::UnitZ();
      const vg::Impact stronge =
          vg::resolve_impact(model, s, point, n, plastic, Vector3d(0, 0, -9.81));
      const Matrix3d k = compliance(s.orientation, point - s.position_world);
      const vg::PlasticImpulse impulse = vg::coulomb_plastic_impulse(n, k, s.velocity_world, mu);
      ASSERT_FALSE(impulse.frictionless);
      const Vector3d* p = &impulse.impulse_world;
      EXPECT_LT((*p - stronge.impulse_world).norm(), 1e-12 * stronge.impulse_world.norm())
          << "slip " << slip_mps << " mu " << mu;
    }
  }
}

TEST(CoulombPlasticImpulse, ZeroWhenNotApproaching) {
  const Matrix3d k = compliance(Eigen::Quaterniond::Identity(), Vector3d(0, 0, -kHalfThicknessM));
  const Vector3d n = Vector3d::UnitZ();
  EXPECT_TRUE(vg::coulomb_plastic_impulse(n, k, Vector3d(0.3, 0, 0.0), 0.3).impulse_world.isZero());
  EXPECT_TRUE(vg::coulomb_plastic_impulse(n, k, Vector3d(0.3, 0, 0.1), 0.3).impulse_world.isZero());
  EXPECT_GT(vg::coulomb_plastic_impulse(n, k, Vector3d(0.3, 0, -1e-9), 0.3).impulse_world.z(), 0.0);
}

TEST(CoulombPlasticImpulse, ScalesWithTheVelocityFromDenormalToHuge) {
  // The law is homogeneous: P(c u) = c P(u), also where |u|^2 underflows or overflows.
  Random random;
  for (int trial = 0; trial < 200; ++trial) {
    const Vector3d n = random.unit();
    const Matrix3d k = compliance(random.orientation(), random.lever()) +
                       compliance(random.orientation(), random.lever());
    const Vector3d u = -n + 2.0 * random.uniform(random.rng) * random.unit().cross(n);
    const double mu = 0.8 * random.uniform(random.rng);
    const vg::PlasticImpulse unit = vg::coulomb_plastic_impulse(n, k, u, mu);
    for (const double c : {1e-300, 1e-160, 1e160}) {
      const vg::PlasticImpulse scaled = vg::coulomb_plastic_impulse(n, k, c * u, mu);
      ASSERT_TRUE(scaled.impulse_world.allFinite()) << "scale " << c;
      EXPECT_FALSE(scaled.frictionless);
      EXPECT_LT((scaled.impulse_world / c - unit.impulse_world).norm(),
                1e-13 * unit.impulse_world.norm())
          << "trial " << trial << " scale " << c;
    }
  }
}
