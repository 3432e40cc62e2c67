// point_speed_from_energy, the bound on a stone's surface-point speeds from its kinetic energy
// behind the World's reach and join distances and the island's keep margin, against the test's
// own lens surface (its support points) and inertia: no surface point of any motion with kinetic
// energy K moves faster than the bound, and the motion that Cauchy-Schwarz's equality picks (the
// spin about a transverse axis, the centre's velocity along the rim point's) reaches it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "virtual_go/geometry/lens_geometry.h"
#include "virtual_go/world/world_body.h"
#include "world_test_support.h"

namespace {

using namespace worldtest;

constexpr double kKineticJ = 1e-4;

double kinetic_energy(const Vector3d& v, const Vector3d& omega, const Quaterniond& q) {
  return 0.5 * mass() * v.squaredNorm() + 0.5 * omega.dot(inertia_world(q) * omega);
}

// The fastest of n surface points (support points in random directions) of a stone at x with
// axis q * e_z moving at v and omega.
double fastest_sampled_point(const Quaterniond& q, const Vector3d& v, const Vector3d& omega, int n,
                             std::mt19937& rng) {
  std::normal_distribution<double> g;
  vg::RigidBodyState s = at(Vector3d(0.01, -0.02, 0.3), q);
  const vgtest::LensReference lens = lens_ref(s);
  double fastest = 0.0;
  for (int k = 0; k < n; ++k) {
    const Vector3d r = lens.support(Vector3d(g(rng), g(rng), g(rng))) - lens.x;
    fastest = std::max(fastest, (v + omega.cross(r)).norm());
  }
  return fastest;
}

TEST(WorldBody, NoSurfacePointOfAMotionWithKineticEnergyKMovesFasterThanTheBound) {
  const double bound =
      vg::point_speed_from_energy(model(), vg::LensGeometry(stone().shape), kKineticJ);
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> share(0.0, 1.0);
  double fastest = 0.0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Quaterniond q = Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
    // The energy split between translation and rotation at random, then scaled to K.
    Vector3d v = share(rng) * Vector3d(g(rng), g(rng), g(rng));
    Vector3d omega = 300.0 * share(rng) * Vector3d(g(rng), g(rng), g(rng));
    const double scale = std::sqrt(kKineticJ / kinetic_energy(v, omega, q));
    v *= scale;
    omega *= scale;
    fastest = std::max(fastest, fastest_sampled_point(q, v, omega, 200, rng));
  }
  std::printf("[ measured ] K = %g J: bound %.6f m/s, fastest of 2000 random motions %.6f m/s\n",
              kKineticJ, bound, fastest);
  EXPECT_LE(fastest, bound * (1.0 + 1e-12));
  EXPECT_GT(fastest, 0.5 * bound);  // the random motions are not all slow
}

TEST(WorldBody, TheBoundIsReachedByCauchySchwarzsMotion) {
  // Axis along e_z; the smallest moment is the transverse one (a flat lens). Spin about e_x at
  // omega0, the centre along e_z at v0: the rim point a e_y moves at v0 + a omega0 along e_z,
  // which is largest for m v0^2 + I1 omega0^2 = 2 K at v0 = lambda / m, omega0 = lambda a / I1.
  const Vector3d moments = stone().mass_properties.principal_moments_body();
  const double i1 = moments.minCoeff();
  ASSERT_EQ(i1, moments.x());
  const double lambda = std::sqrt(2.0 * kKineticJ / (1.0 / mass() + kA * kA / i1));
  const Vector3d v(0.0, 0.0, lambda / mass()), omega(lambda * kA / i1, 0.0, 0.0);
  ASSERT_NEAR(kinetic_energy(v, omega, Quaterniond::Identity()), kKineticJ, 1e-15 * kKineticJ);
  const Vector3d rim_point = Vector3d(0.0, kA, 0.0);
  const double speed = (v + omega.cross(rim_point)).norm();
  const double bound =
      vg::point_speed_from_energy(model(), vg::LensGeometry(stone().shape), kKineticJ);
  EXPECT_NEAR(speed, bound, 1e-12 * bound);
  // At four times the energy, twice the speed (it is a speed from an energy).
  EXPECT_NEAR(vg::point_speed_from_energy(model(), vg::LensGeometry(stone().shape), 4 * kKineticJ),
              2.0 * bound, 1e-12 * bound);
}

}  // namespace
