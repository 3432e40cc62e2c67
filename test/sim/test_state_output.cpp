// What the node publishes of a state: finite for every state whose outputs are representable,
// and an error (never a non-finite number) otherwise.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "virtual_go/body/mass_properties.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/sim/state_output.h"
#include "virtual_go/sim/stone_simulation.h"

namespace vg = virtual_go;

namespace {

vg::MotionModel model() {
  return vg::MotionModel(vg::MotionModelKind::rigid_body,
                         vg::MassProperties(0.005, Eigen::Vector3d(1.2e-7, 1.2e-7, 2.0e-7)));
}

// R^T v by the rotation matrix of q, on v scaled to order 1 and scaled back: an independent
// route to the body-frame vector, exact up to rounding for any representable result.
Eigen::Vector3d to_body_reference(const Eigen::Quaterniond& q, const Eigen::Vector3d& v,
                                  double scale) {
  return (q.toRotationMatrix().transpose() * (v / scale)) * scale;
}

}  // namespace

// issue 8: for |v| above about 9e307 the ~odom twist was NaN or inf while /tf was finite: the
// quaternion-vector product's intermediate 2 (u x v) overflows although R^T v (of length |v|)
// does not.
TEST(StateOutput, BodyTwistIsFiniteForTheLargestSpeeds) {
  // Close to a half turn about x, so |u| ~ 1 and u is perpendicular to v.
  const Eigen::Quaterniond q = Eigen::Quaterniond(0.43589, 0.9, 0.0, 0.0).normalized();
  for (const double speed : {9e307, 1.2e308, 1.7e308}) {
    vg::RigidBodyState s;
    s.orientation = q;
    s.velocity_world = Eigen::Vector3d(0.0, speed, 0.0);
    // Above 1e308 the plain product does overflow here (2 |u| |v| > 1.8e308, |u| = 0.9).
    if (speed > 1e308) {
      EXPECT_FALSE(Eigen::Vector3d(q.conjugate() * s.velocity_world).allFinite()) << speed;
    }
    const vg::StateOutput out = vg::state_output(model(), s);
    ASSERT_TRUE(out.velocity_body.allFinite()) << speed;
    const Eigen::Vector3d expected = to_body_reference(q, s.velocity_world, 1e308);
    EXPECT_LT(((out.velocity_body - expected) / speed).norm(), 1e-15) << speed;
    EXPECT_NEAR(vg::norm_without_overflow(out.velocity_body), speed, 1e-15 * speed);
  }
}

// The same through the simulation: a state that fast (reached past the bounds) publishes a
// finite twist at every step, equal to R^T v.
TEST(StateOutput, SimulationPublishesFiniteTwistForTheLargestSpeeds) {
  vg::CheckedConfig checked = vg::check_config(vg::StoneConfig());
  checked.setup.gravity_world.setZero();
  checked.initial_state.orientation = Eigen::Quaterniond(0.43589, 0.9, 0.0, 0.0).normalized();
  checked.initial_state.velocity_world = Eigen::Vector3d(0.0, 1.5e308, 0.0);
  vg::StoneSimulation sim(checked);
  constexpr std::int64_t kStart = 1700000000000000000;
  const vg::UpdateResult first = sim.update(kStart);
  ASSERT_EQ(first.events.size(), 1u);
  EXPECT_TRUE(first.events[0].output.velocity_body.allFinite());
  for (int tick = 1; tick <= 20; ++tick) {
    const vg::UpdateResult r = sim.update(kStart + tick * 16000000);
    ASSERT_TRUE(r.advanced) << r.error;
    const vg::StateOutput& out = sim.output();
    ASSERT_TRUE(out.velocity_body.allFinite()) << "tick " << tick;
    const Eigen::Vector3d expected = to_body_reference(out.orientation, out.velocity_world, 1e308);
    EXPECT_LT(((out.velocity_body - expected) / 1.5e308).norm(), 1e-15);
  }
}

// An output that is not representable is an error naming it, never a published inf.
TEST(StateOutput, NonFiniteOutputIsAnError) {
  vg::RigidBodyState s;
  s.velocity_world = Eigen::Vector3d(std::numeric_limits<double>::infinity(), 0, 0);
  try {
    vg::state_output(model(), s);
    ADD_FAILURE() << "accepted";
  } catch (const vg::IntegrationError& e) {
    EXPECT_NE(std::string(e.what()).find("velocity"), std::string::npos) << e.what();
  }
  s = vg::RigidBodyState();
  s.orientation.coeffs() << 0, 0, 0, 0;
  EXPECT_THROW(vg::state_output(model(), s), vg::IntegrationError);
}
