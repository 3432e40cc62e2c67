// The tests' static balance check (static_balance.h) against the rest condition written out: a
// lens on its bottom cap is held by the rolling couple l_r N exactly while G lies within l_r of
// its contact point (G is d sin(theta) beside it at a tilt theta, d the cap sphere's centre above
// G), a stone lying flat on a flat stone is held, and one pushed off its centre is not.
#include <gtest/gtest.h>

#include <cmath>

#include "world/static_balance.h"
#include "world/world_test_support.h"

namespace {

using namespace worldtest;
using Eigen::Vector3d;

vg::WorldConfig stone_config() {
  vg::WorldConfig c = config();
  c.stone_contact = true;
  return c;
}

// A stone tilted by theta about y on its bottom cap, touching the board at the origin.
vg::RigidBodyState tilted_on_cap(const StoneFacts& f, double theta) {
  const vgtest::LensReference l{f.a_m, f.c_m};
  const Eigen::Quaterniond q(Eigen::AngleAxisd(theta, Vector3d::UnitY()));
  const Vector3d b = q * Vector3d::UnitZ();
  // The bottom cap lies on the sphere of radius r centred d above G along b.
  return at(Vector3d(0, 0, l.sphere_radius()) - l.sphere_offset() * b, q);
}

double tilt_of_offset(const StoneFacts& f, double offset_m) {
  const vgtest::LensReference l{f.a_m, f.c_m};
  return std::asin(offset_m / l.sphere_offset());
}

TEST(StaticBalance, ALensOnItsCapIsHeldExactlyWhileGIsWithinTheRollingLength) {
  const vg::WorldConfig c = stone_config();
  const double l_r = c.board_material.rolling_resistance_m;
  const vg::World probe(c, std::vector<vg::RigidBodyState>{at(Vector3d(0, 0, 0.01))}, 0.0);
  const StoneFacts f = facts_of(probe, 0);
  for (const double share : {0.0, 0.5, 0.9, 1.1, 2.0, 100.0}) {
    const vg::World w(
        c, std::vector<vg::RigidBodyState>{tilted_on_cap(f, tilt_of_offset(f, share * l_r))}, 0.0);
    const BalanceResult b = static_balance(w, kGravity, laws_of(c), 1e-9);
    ASSERT_EQ(b.contacts.size(), 1u);
    const double residual = b.force_residual[0] + b.torque_residual[0];
    if (share < 1.0) {
      EXPECT_LE(residual, 1e-12) << share;
    } else {
      // The weight's moment beyond the couple, (offset - l_r) m g, over m g a: what least
      // squares leaves of it is split between the torque and a force (friction would turn it).
      const double unheld = (share - 1.0) * l_r / f.a_m;
      EXPECT_GT(residual, 0.5 * unheld) << share;
      EXPECT_LT(residual, 2.0 * unheld) << share;
    }
  }
}

TEST(StaticBalance, AStoneFlatOnAFlatStoneIsHeldAndOneOffItsCentreIsNot) {
  const vg::WorldConfig c = stone_config();
  const vg::World probe(c, std::vector<vg::RigidBodyState>{at(Vector3d(0, 0, 0.01))}, 0.0);
  const StoneFacts f = facts_of(probe, 0);
  const auto pile = [&](double shift_m) {
    return vg::World(c,
                     std::vector<vg::RigidBodyState>{at(Vector3d(0, 0, f.c_m)),
                                                     at(Vector3d(shift_m, 0, 3.0 * f.c_m))},
                     0.0);
  };
  const BalanceResult on_top = static_balance(pile(0.0), kGravity, laws_of(c), 1e-9);
  EXPECT_EQ(on_top.contacts.size(), 2u);  // the board under the lower one, the pair
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_LE(on_top.force_residual[i] + on_top.torque_residual[i], 1e-12) << i;
  }
  // Shifted 5 mm and still flat, the upper stone touches the lower one's cap halfway between the
  // axes (both caps are spheres of one radius): 2.5 mm beside its G, a moment that the rolling
  // couple (l_r N) cannot hold, so it would roll off.
  vg::World shifted = pile(0.005);
  vg::RigidBodyState upper = shifted.state(1);
  for (int k = 0; k < 20; ++k) {  // lowered onto the lower one (the gap is along a leaning normal)
    const double gap_m = pair_gap_bound(lens_of(f, shifted.state(0)), lens_of(f, upper));
    if (gap_m < 1e-10) break;
    upper.position_world.z() -= gap_m;
  }
  shifted = vg::World(c, std::vector<vg::RigidBodyState>{shifted.state(0), upper}, 0.0);
  const BalanceResult off = static_balance(shifted, kGravity, laws_of(c), 1e-9);
  EXPECT_EQ(off.contacts.size(), 2u);
  EXPECT_GT(off.force_residual[1] + off.torque_residual[1], 1e-3);
}

}  // namespace
