// Simultaneous impacts by the sequential rule against the analytic Newton's cradle: a row of N
// equal stones touching, struck at one end, frictionless and elastic, sends exactly the last
// stone off (one stone in, one out); with e* < 1 the row matches a cradle of point masses with
// vanishing gaps and Newton's 1-D restitution, computed here; energy never rises, momentum is
// conserved; a stone landing across two neighbours settles with dE <= 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/contact/simultaneous_impacts.h"
#include "virtual_go/geometry/lens_pair_distance.h"

namespace vg = virtual_go;

namespace {

constexpr double kA = 0.0111, kC = 0.0046;

struct Fixture {
  vg::LensShape shape{2 * kA, 2 * kC};
  vg::LensGeometry lens{shape};
  vg::MassProperties mp = vg::MassProperties::of_lens(shape, 2700.0);
  vg::MotionModel model{vg::MotionModelKind::rigid_body, mp};

  // N flat stones in a row along x, touching rim to rim; the first moves at v0 into the row.
  std::pair<std::vector<vg::ImpactBody>, std::vector<vg::BodyContact>> row(int n, double v0) const {
    std::vector<vg::ImpactBody> bodies;
    std::vector<vg::BodyContact> contacts;
    for (int i = 0; i < n; ++i) {
      vg::RigidBodyState s;
      s.position_world = Eigen::Vector3d(2 * kA * i, 0, kC);
      if (i == 0) s.velocity_world = Eigen::Vector3d(v0, 0, 0);
      bodies.push_back({model, s});
      if (i > 0) {
        contacts.push_back(
            {i - 1, i, Eigen::Vector3d(2 * kA * i - kA, 0, kC), Eigen::Vector3d::UnitX()});
      }
    }
    return {bodies, contacts};
  }
  double energy(const std::vector<vg::ImpactBody>& bodies) const {
    double e = 0.0;
    for (const vg::ImpactBody& b : bodies) {
      e += vg::body_energy(model, b.state, Eigen::Vector3d::Zero());
    }
    return e;
  }
};

// The analytic cradle of equal point masses with vanishing gaps: collisions one at a time, the
// fastest approach first, each by Newton's 1-D law for equal masses (v_i, v_j) ->
// ((1 - e) v_i + (1 + e) v_j, (1 + e) v_i + (1 - e) v_j) / 2.
std::vector<double> point_mass_cradle(int n, double v0, double e) {
  std::vector<double> v(n, 0.0);
  v[0] = v0;
  for (int guard = 0; guard < 1000000; ++guard) {
    int k = -1;
    double fastest = 1e-12;
    for (int i = 0; i + 1 < n; ++i) {
      if (v[i] - v[i + 1] > fastest) {
        fastest = v[i] - v[i + 1];
        k = i;
      }
    }
    if (k < 0) break;
    const double vi = v[k], vj = v[k + 1];
    v[k] = 0.5 * ((1 - e) * vi + (1 + e) * vj);
    v[k + 1] = 0.5 * ((1 + e) * vi + (1 - e) * vj);
  }
  return v;
}

}  // namespace

TEST(SimultaneousImpacts, ElasticCradleSendsOneStoneOut) {
  Fixture f;
  vg::ContactMaterial elastic;
  elastic.restitution = 1.0;
  elastic.friction = 0.0;
  for (int n = 2; n <= 7; ++n) {
    auto [bodies, contacts] = f.row(n, 0.5);
    const double e0 = f.energy(bodies);
    const vg::SimultaneousImpacts r = vg::resolve_simultaneous_impacts(bodies, contacts, elastic);
    EXPECT_TRUE(r.settled);
    EXPECT_EQ(r.impacts, n - 1) << n;
    for (int i = 0; i + 1 < n; ++i) {
      EXPECT_NEAR(bodies[i].state.velocity_world.norm(), 0.0, 1e-15) << n << " " << i;
    }
    EXPECT_NEAR(bodies[n - 1].state.velocity_world.x(), 0.5, 1e-15) << n;
    EXPECT_NEAR(f.energy(bodies), e0, 1e-17) << n;
  }
}

TEST(SimultaneousImpacts, InelasticCradleMatchesPointMassesWithVanishingGaps) {
  Fixture f;
  double worst = 0.0;
  for (double e : {0.0, 0.3, 0.5, 0.8, 0.95}) {
    vg::ContactMaterial mat;
    mat.restitution = e;
    mat.friction = 0.3;  // no slip in a central row: friction does nothing
    for (int n = 2; n <= 6; ++n) {
      auto [bodies, contacts] = f.row(n, 0.5);
      const double e0 = f.energy(bodies);
      const vg::SimultaneousImpacts r = vg::resolve_simultaneous_impacts(bodies, contacts, mat);
      EXPECT_TRUE(r.settled) << e << " " << n;
      const std::vector<double> expected = point_mass_cradle(n, 0.5, e);
      double momentum = 0.0;
      for (int i = 0; i < n; ++i) {
        worst = std::max(worst, std::abs(bodies[i].state.velocity_world.x() - expected[i]));
        momentum += bodies[i].state.velocity_world.x();
      }
      EXPECT_NEAR(momentum, 0.5, 1e-14) << e << " " << n;
      EXPECT_LE(f.energy(bodies), e0) << e << " " << n;
      EXPECT_NEAR(f.energy(bodies) - e0, r.energy_change_j, 1e-16) << e << " " << n;
      if (e == 0.8 && n == 6) {
        std::printf("[ measured ] e* 0.8, 6 stones: %d impacts, velocities", r.impacts);
        for (int i = 0; i < n; ++i) std::printf(" %.6f", bodies[i].state.velocity_world.x());
        std::printf(" m/s, energy kept %.4f\n", f.energy(bodies) / e0);
      }
    }
  }
  std::printf(
      "[ measured ] cradle rows (e* 0..0.95, 2..6 stones) vs point masses: max |dv| %.3g "
      "m/s\n",
      worst);
  EXPECT_LT(worst, 1e-12);
}

TEST(SimultaneousImpacts, StoneLandingAcrossTwoNeighboursNeverGainsEnergy) {
  // Two flat stones side by side with a 4 mm gap, a third tilted stone falling onto both at
  // once (the contacts from lens_pair_distance), spinning, with friction: the rule settles with
  // dE <= 0, momentum conserved, no contact approaching at the end.
  Fixture f;
  int settled = 0;
  double worst_gain = -1.0;
  for (int k = 0; k < 200; ++k) {
    std::vector<vg::ImpactBody> bodies;
    vg::RigidBodyState left, right, top;
    left.position_world = Eigen::Vector3d(-kA - 0.002, 0, kC);
    right.position_world = Eigen::Vector3d(kA + 0.002, 0, kC);
    const double tilt = 0.2 * std::sin(1.7 * k);
    top.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitY()));
    top.position_world = Eigen::Vector3d(0.0005 * std::cos(3.1 * k), 0, 3 * kC);
    // Lower the top stone until it touches the nearer neighbour.
    for (int side = 0; side < 2; ++side) {
      const vg::RigidBodyState& below = side == 0 ? left : right;
      const vg::LensPairContact c =
          vg::lens_pair_distance(f.lens, vg::lens_pose(below), f.lens, vg::lens_pose(top));
      if (c.gap_m > 0.0) top.position_world.z() -= std::min(c.gap_m / c.normal_world.z(), 1.0);
    }
    top.velocity_world = Eigen::Vector3d(0.1 * std::sin(k), 0.05, -1.0);
    top = vg::with_angular_velocity_world(f.model, top,
                                          Eigen::Vector3d(10 * std::cos(k), 20, 5 * std::sin(k)));
    bodies.push_back({f.model, left});
    bodies.push_back({f.model, right});
    bodies.push_back({f.model, top});
    std::vector<vg::BodyContact> contacts;
    for (int side = 0; side < 2; ++side) {
      const vg::LensPairContact c = vg::lens_pair_distance(
          f.lens, vg::lens_pose(bodies[side].state), f.lens, vg::lens_pose(top));
      if (c.gap_m > 1e-6) continue;  // touches only the nearer one
      contacts.push_back({side, 2, 0.5 * (c.point_a_world + c.point_b_world), c.normal_world});
    }
    ASSERT_FALSE(contacts.empty()) << k;
    vg::ContactMaterial mat;
    mat.restitution = 0.5 + 0.5 * std::sin(k) * std::sin(k);
    mat.friction = 0.5;
    const double e0 = f.energy(bodies);
    Eigen::Vector3d p0 = Eigen::Vector3d::Zero();
    for (const vg::ImpactBody& b : bodies) p0 += f.mp.mass() * b.state.velocity_world;
    const vg::SimultaneousImpacts r = vg::resolve_simultaneous_impacts(bodies, contacts, mat);
    settled += r.settled;
    worst_gain = std::max(worst_gain, (f.energy(bodies) - e0) / e0);
    Eigen::Vector3d p1 = Eigen::Vector3d::Zero();
    for (const vg::ImpactBody& b : bodies) p1 += f.mp.mass() * b.state.velocity_world;
    EXPECT_LT((p1 - p0).norm(), 1e-16) << k;
    EXPECT_LE(r.energy_change_j, 0.0) << k;
  }
  std::printf("[ measured ] landing across two: %d of 200 settled, largest dE/E %.3g\n", settled,
              worst_gain);
  EXPECT_EQ(settled, 200);
  EXPECT_LE(worst_gain, 1e-15);
}

TEST(SimultaneousImpacts, BadContactIsNamed) {
  Fixture f;
  auto [bodies, contacts] = f.row(2, 0.5);
  contacts.push_back({1, 1, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()});
  try {
    vg::resolve_simultaneous_impacts(bodies, contacts, {});
    FAIL();
  } catch (const vg::InvalidArgument& e) {
    EXPECT_EQ(e.field(), "contacts");
  }
  EXPECT_EQ(bodies[0].state.velocity_world.x(), 0.5);  // unchanged
}
