// Per-stone flight state: an integrator keeps nothing between steps, so one instance advances
// any number of stones, each on its own FlightCache; the caller says when it replaced a state.
// Judged against the closed form of the symmetric top written in support/physics_reference.h.
#include <gtest/gtest.h>

#include <vector>

#include "support/physics_reference.h"
#include "support/stone_setup.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/flight/flight_cache.h"
#include "virtual_go/flight/integrator_registry.h"
#include "virtual_go/go/stone.h"

namespace vg = virtual_go;

namespace {

vg::MotionSetup setup() { return vgtest::stone_setup(); }
const vg::MassProperties kStone = setup().model.mass_properties();

vg::RigidBodyState stone(const Eigen::Vector3d& x, const Eigen::Vector3d& axis_angle,
                         const Eigen::Vector3d& omega_world) {
  vg::RigidBodyState s;
  s.position_world = x;
  s.velocity_world = Eigen::Vector3d(0.3, -0.1, 2.0);
  s.orientation = vgtest::to_eigen(vgtest::axis_angle(axis_angle));
  return vg::with_angular_velocity_world(setup().model, s, omega_world);
}

// Orientation error (rad) and position error (m) at t against the closed form from s0.
std::pair<double, double> error_at(const vg::RigidBodyState& s0, const vg::RigidBodyState& s,
                                   double t) {
  const Eigen::Vector3d& i = kStone.principal_moments_body();
  const vgtest::AxisymmetricTop top{i.x(), i.z(), vgtest::from_eigen(s0.orientation),
                                    s0.angular_momentum_world};
  const Eigen::Vector3d x =
      s0.position_world + s0.velocity_world * t + 0.5 * vg::kStandardGravity * t * t;
  return {vgtest::angle_between(top.orientation_at(t), vgtest::from_eigen(s.orientation)),
          (s.position_world - x).norm()};
}

}  // namespace

TEST(FlightCache, OneExactIntegratorAdvancesManyStonesEachOnItsOwnCache) {
  const auto exact = vg::make_integrator("exact", setup());
  const std::vector<vg::RigidBodyState> starts{
      stone({0, 0, 0.5}, {0.3, -0.5, 0.7}, {20, 5, 40}),
      stone({1, 0, 0.2}, {-1.1, 0.2, 0.4}, {-3, 8, 15}),
      stone({0, 2, 0.9}, {0.0, 0.9, -0.3}, {0.5, 0.0, -60}),
  };
  std::vector<vg::RigidBodyState> states = starts;
  std::vector<vg::FlightCache> caches(states.size());
  const double dt = 1.0 / 60.0;
  const int n = 3000;  // 50 s, re-anchored twice, the stones' steps interleaved
  for (int k = 0; k < n; ++k) {
    for (std::size_t i = 0; i < states.size(); ++i) exact->advance(states[i], dt, caches[i]);
  }
  for (std::size_t i = 0; i < states.size(); ++i) {
    const auto [orientation, position] = error_at(starts[i], states[i], n * dt);
    EXPECT_LT(orientation, 1e-11) << "stone " << i;
    EXPECT_LT(position, 1e-12 * (1.0 + states[i].position_world.norm())) << "stone " << i;
    EXPECT_TRUE(caches[i].holds_anchor());
  }
}

TEST(FlightCache, IntegratorsKeepNothingBetweenSteps) {
  // The same stone advanced by one integrator instance interleaved with other work, and by a
  // fresh instance: bit for bit the same states, for every integrator.
  for (const std::string& name : vg::integrator_names()) {
    const auto shared = vg::make_integrator(name, setup());
    const vg::RigidBodyState start = stone({0, 0, 0.5}, {0.3, -0.5, 0.7}, {4, 1, 8});
    vg::RigidBodyState a = start, b = start, other = stone({5, 5, 5}, {1, 1, 1}, {9, -9, 3});
    vg::FlightCache cache_a, cache_b, cache_other;
    const auto alone = vg::make_integrator(name, setup());
    for (int k = 0; k < 2000; ++k) {
      shared->advance(a, 1e-3, cache_a);
      shared->advance(other, 2e-3, cache_other);  // another stone and another dt in between
      alone->advance(b, 1e-3, cache_b);
    }
    EXPECT_TRUE(a == b) << name;
  }
}

TEST(FlightCache, InvalidateStartsAfreshFromTheReplacedState) {
  const auto exact = vg::make_integrator("exact", setup());
  vg::FlightCache cache;
  vg::RigidBodyState s = stone({0, 0, 0.5}, {0.3, -0.5, 0.7}, {20, 5, 40});
  for (int k = 0; k < 100; ++k) exact->advance(s, 1e-3, cache);
  // A teleport: the caller replaces the state and says so.
  const vg::RigidBodyState teleported = stone({2, -1, 0.1}, {-0.8, 0.1, 0.2}, {-7, 2, 30});
  s = teleported;
  cache.invalidate();
  EXPECT_FALSE(cache.holds_anchor());
  for (int k = 0; k < 1500; ++k) exact->advance(s, 1e-3, cache);
  const auto [orientation, position] = error_at(teleported, s, 1.5);
  EXPECT_LT(orientation, 1e-12);
  EXPECT_LT(position, 1e-13);
}

TEST(FlightCache, AStepThatFailsLeavesNothingBehind) {
  const auto exact = vg::make_integrator("exact", setup());
  vg::FlightCache cache;
  vg::RigidBodyState s = stone({0, 0, 0.5}, {0.3, -0.5, 0.7}, {20, 5, 40});
  exact->advance(s, 1e-3, cache);
  ASSERT_TRUE(cache.holds_anchor());
  // Overflowing the parabola fails the step; state and cache start over cleanly.
  vg::RigidBodyState huge = s;
  huge.velocity_world.x() = 1.7e308;
  huge.position_world.x() = 1.7e308;
  cache.invalidate();  // replaced by the caller
  const vg::RigidBodyState before = huge;
  EXPECT_THROW(exact->advance(huge, 1.0, cache), vg::IntegrationError);
  EXPECT_TRUE(huge == before);
  EXPECT_FALSE(cache.holds_anchor());
}
