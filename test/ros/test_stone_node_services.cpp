// Each service, observed on tf afterwards; bad input refused with the node unchanged and alive.
// The node starts at rest without gravity, exact integrator, max_angular_velocity 100 rad/s.
#include <gtest/gtest.h>
#include <std_srvs/Trigger.h>

#include <cmath>
#include <limits>

#include "support/node_observer.h"
#include "support/node_reference.h"
#include "virtual_go/SetAngularVelocity.h"
#include "virtual_go/SetState.h"

using vgtest::ClosedForm;
using vgtest::NodeObserver;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// Worst orientation and position error of tf, at `count` stamps after the event, against the
// closed form started from the event.
std::pair<double, double> tf_error_after(NodeObserver& o, const virtual_go::StoneEvent& event,
                                         std::size_t count = 10) {
  const ClosedForm reference = ClosedForm::from_event(*o.info, event);
  double angle = 0.0, position = 0.0;
  const auto odom = o.odom_after(event.header.stamp, count);
  EXPECT_GE(odom.size(), count);
  for (const auto& m : odom) {
    const auto tf = o.tf_at(m.header.stamp);
    EXPECT_TRUE(tf);
    if (!tf) continue;
    const vgtest::MotionState s =
        reference.at(vgtest::seconds_between(event.header.stamp, m.header.stamp));
    angle =
        std::max(angle, vgtest::angle_between(s.orientation, vgtest::quat(tf->transform.rotation)));
    position = std::max(position, (s.position - vgtest::vec(tf->transform.translation)).norm());
  }
  return {angle, position};
}

virtual_go::SetAngularVelocity angular_velocity(double x, double y, double z,
                                                const std::string& frame = "") {
  virtual_go::SetAngularVelocity srv;
  srv.request.angular_velocity.x = x;
  srv.request.angular_velocity.y = y;
  srv.request.angular_velocity.z = z;
  srv.request.frame = frame;
  return srv;
}

virtual_go::SetState state(double x, double y, double z, double qx, double qy, double qz,
                           double qw) {
  virtual_go::SetState srv;
  srv.request.pose.position.x = x;
  srv.request.pose.position.y = y;
  srv.request.pose.position.z = z;
  srv.request.pose.orientation.x = qx;
  srv.request.pose.orientation.y = qy;
  srv.request.pose.orientation.z = qz;
  srv.request.pose.orientation.w = qw;
  return srv;
}

}  // namespace

TEST(StoneNodeServices, SetAngularVelocityChangesTheRate) {
  NodeObserver o;
  ASSERT_TRUE(o.wait_for_start());
  // About world z, which is the stone's axis at the identity start: a pure spin at 20 rad/s.
  auto srv = angular_velocity(0.0, 0.0, 20.0, "world");
  ASSERT_TRUE(o.call("set_angular_velocity", srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  auto event = o.wait_for_event(1);
  ASSERT_TRUE(event);
  EXPECT_EQ(event->reason, "set_angular_velocity");
  EXPECT_EQ(event->segment, 1u);
  EXPECT_NEAR(event->twist.angular.z, 20.0, 1e-12);

  const auto odom = o.odom_after(event->header.stamp, 10);
  ASSERT_GE(odom.size(), 10u);
  const auto tf1 = o.tf_at(odom.front().header.stamp), tf2 = o.tf_at(odom.back().header.stamp);
  ASSERT_TRUE(tf1 && tf2);
  const double dt = vgtest::seconds_between(tf1->header.stamp, tf2->header.stamp);
  // The relative rotation over dt is exp(dt * 20 e_z).
  const Eigen::Quaterniond relative =
      vgtest::quat(tf2->transform.rotation) * vgtest::quat(tf1->transform.rotation).conjugate();
  EXPECT_LT(vgtest::angle_between(vgtest::exp_map(Eigen::Vector3d(0, 0, 20.0 * dt)), relative),
            1e-9);
  auto [angle, position] = tf_error_after(o, *event);
  EXPECT_LT(angle, 1e-9);

  // In the stone frame, off its axis: the rigid body wobbles, as computed.
  srv = angular_velocity(3.0, 0.0, 10.0, "stone");
  ASSERT_TRUE(o.call("set_angular_velocity", srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  event = o.wait_for_event(2);
  ASSERT_TRUE(event);
  const Eigen::Vector3d w_world = vgtest::quat(event->pose.orientation) * Eigen::Vector3d(3, 0, 10);
  EXPECT_LT((vgtest::vec(event->twist.angular) - w_world).norm(), 1e-9);
  std::tie(angle, position) = tf_error_after(o, *event);
  EXPECT_LT(angle, 1e-9);
  EXPECT_LT(position, 1e-12);
}

TEST(StoneNodeServices, SetStateTeleports) {
  NodeObserver o;
  ASSERT_TRUE(o.wait_for_start());
  const std::size_t seen = o.events.size();
  auto srv = state(0.1, -0.2, 0.3, 0.0, 0.0, 0.0, 2.0);  // not unit: normalised
  srv.request.twist.linear.x = 0.05;
  srv.request.twist.angular.y = 5.0;
  ASSERT_TRUE(o.call("set_state", srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  const auto event = o.wait_for_event(seen);
  ASSERT_TRUE(event);
  EXPECT_EQ(event->reason, "set_state");
  EXPECT_EQ(vgtest::vec(event->pose.position), Eigen::Vector3d(0.1, -0.2, 0.3));
  EXPECT_EQ(event->pose.orientation.w, 1.0);
  const auto [angle, position] = tf_error_after(o, *event);
  EXPECT_LT(angle, 1e-9);
  EXPECT_LT(position, 1e-12);
}

TEST(StoneNodeServices, ResetRestoresTheInitialPose) {
  NodeObserver o;
  ASSERT_TRUE(o.wait_for_start());
  auto moving = state(0.5, 0.5, 0.5, 0.1, 0.2, 0.3, 0.9);
  moving.request.twist.linear.z = 1.0;
  moving.request.twist.angular.x = 4.0;
  ASSERT_TRUE(o.call("set_state", moving));
  ASSERT_TRUE(o.wait_for_event(o.events.size()));
  const std::size_t seen = o.events.size();
  std_srvs::Trigger reset;
  ASSERT_TRUE(o.call("reset", reset));
  ASSERT_TRUE(reset.response.success) << reset.response.message;
  const auto event = o.wait_for_event(seen);
  ASSERT_TRUE(event);
  EXPECT_EQ(event->reason, "reset");
  EXPECT_EQ(event->pose, o.info->initial_pose);
  // The initial state is at rest without gravity: tf shows the initial pose from then on.
  const auto odom = o.odom_after(event->header.stamp, 5);
  ASSERT_GE(odom.size(), 5u);
  for (const auto& m : odom) {
    const auto tf = o.tf_at(m.header.stamp);
    ASSERT_TRUE(tf);
    EXPECT_LT((vgtest::vec(tf->transform.translation) - vgtest::vec(o.info->initial_pose.position))
                  .norm(),
              1e-15);
    EXPECT_LT(vgtest::angle_between(vgtest::quat(o.info->initial_pose.orientation),
                                    vgtest::quat(tf->transform.rotation)),
              1e-12);
  }
}

TEST(StoneNodeServices, BadInputIsRefusedAndChangesNothing) {
  NodeObserver o;
  ASSERT_TRUE(o.wait_for_start());
  // Give the stone a known motion to compare against afterwards.
  auto spin = angular_velocity(1.0, 2.0, 30.0);
  ASSERT_TRUE(o.call("set_angular_velocity", spin));
  const auto spun = o.wait_for_event(o.events.size());
  ASSERT_TRUE(spun);
  const virtual_go::StoneEvent last = *spun;
  const std::size_t seen = o.events.size();

  struct Case {
    std::string field;
    std::function<bool(std::string&)> call;
  };
  const auto av = [&](double x, double y, double z, const std::string& frame) {
    return [&o, x, y, z, frame](std::string& message) {
      auto srv = angular_velocity(x, y, z, frame);
      EXPECT_TRUE(o.call("set_angular_velocity", srv));
      message = srv.response.message;
      return static_cast<bool>(srv.response.success);
    };
  };
  const auto st = [&](virtual_go::SetState srv) {
    return [&o, srv](std::string& message) mutable {
      EXPECT_TRUE(o.call("set_state", srv));
      message = srv.response.message;
      return static_cast<bool>(srv.response.success);
    };
  };
  auto nan_twist = state(0, 0, 0, 0, 0, 0, 1);
  nan_twist.request.twist.linear.y = kNaN;
  auto fast_twist = state(0, 0, 0, 0, 0, 0, 1);
  fast_twist.request.twist.angular.x = 150.0;
  const std::vector<Case> cases = {
      {"angular_velocity", av(kNaN, 0, 0, "")},
      {"angular_velocity", av(0, kInf, 0, "world")},
      {"angular_velocity", av(0, 0, -kInf, "stone")},
      {"angular_velocity", av(0, 0, 150.0, "")},  // over max_angular_velocity 100
      {"frame", av(0, 0, 1.0, "base_link")},
      {"pose.orientation", st(state(0, 0, 0, 0, 0, 0, 0))},
      {"pose.orientation", st(state(0, 0, 0, kNaN, 0, 0, 1))},
      {"pose.position", st(state(kInf, 0, 0, 0, 0, 0, 1))},
      {"twist.linear", st(nan_twist)},
      {"twist.angular", st(fast_twist)},
  };
  for (const Case& c : cases) {
    std::string message;
    EXPECT_FALSE(c.call(message)) << c.field;
    EXPECT_EQ(message.rfind(c.field, 0), 0u)
        << "message does not start with " << c.field << ": " << message;
  }
  // No new segment, the motion carries on as before, and the node still answers.
  const std::size_t so_far = o.odom_after(last.header.stamp, 0).size();
  const auto [angle, position] = tf_error_after(o, last, so_far + 10);
  EXPECT_EQ(o.events.size(), seen);
  EXPECT_LT(angle, 1e-9);
  EXPECT_LT(position, 1e-12);
  std_srvs::Trigger reset;
  ASSERT_TRUE(o.call("reset", reset));
  EXPECT_TRUE(reset.response.success);
}
