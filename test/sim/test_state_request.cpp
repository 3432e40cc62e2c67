// Request validation: bad values are refused with the field named; good ones build a state.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "virtual_go/body/mass_properties.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/sim/state_request.h"

namespace vg = virtual_go;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();
// max_distance 1000 m, max_speed 1000 m/s, max_angular_velocity 100 rad/s; rk4 at 1 ms.
const vg::RequestLimits kLimit{1000.0, 1000.0, 100.0, 1.0, 0.001, "rk4"};
const vg::StateFieldNames kFields{"pose.position", "pose.orientation", "twist.linear",
                                  "twist.angular"};

vg::MotionModel model() {
  return vg::MotionModel(vg::MotionModelKind::rigid_body,
                         vg::MassProperties(0.005, Eigen::Vector3d(1.2e-7, 1.2e-7, 2.0e-7)));
}

std::string refusal(const std::function<void()>& request) {
  try {
    request();
  } catch (const vg::InvalidArgument& e) {
    return e.what();
  }
  return "accepted";
}

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

}  // namespace

TEST(StateRequest, AngularVelocityLimits) {
  EXPECT_NO_THROW(vg::check_angular_velocity("w", Eigen::Vector3d(0, 60, 80), kLimit));
  const std::string over = refusal(
      [] { vg::check_angular_velocity("angular_velocity", Eigen::Vector3d(0, 60, 81), kLimit); });
  EXPECT_TRUE(starts_with(over, "angular_velocity: |w|")) << over;
  EXPECT_NE(over.find("max_angular_velocity"), std::string::npos) << over;
  // The integrator's own limit (1 rad per step at dt 1 ms = 1000 rad/s) binds when lower.
  const vg::RequestLimits slow{1000.0, 1000.0, 5000.0, 1.0, 0.001, "rk4"};
  const std::string fast =
      refusal([&] { vg::check_angular_velocity("w", Eigen::Vector3d(0, 0, 1001), slow); });
  EXPECT_NE(fast.find("rk4"), std::string::npos) << fast;
  for (double bad : {kNaN, kInf, -kInf}) {
    const std::string m = refusal([&] {
      vg::check_angular_velocity("angular_velocity", Eigen::Vector3d(0, bad, 0), kLimit);
    });
    EXPECT_TRUE(starts_with(m, "angular_velocity must be finite")) << m;
  }
}

TEST(StateRequest, Frames) {
  using F = vg::RequestFrame;
  EXPECT_EQ(vg::request_frame("frame", "", "map", "puck"), F::world);
  EXPECT_EQ(vg::request_frame("frame", "world", "map", "puck"), F::world);
  EXPECT_EQ(vg::request_frame("frame", "map", "map", "puck"), F::world);
  EXPECT_EQ(vg::request_frame("frame", "stone", "map", "puck"), F::body);
  EXPECT_EQ(vg::request_frame("frame", "puck", "map", "puck"), F::body);
  const std::string m = refusal([] { vg::request_frame("frame", "base_link", "world", "stone"); });
  EXPECT_TRUE(starts_with(m, "frame: unknown frame 'base_link'")) << m;
}

TEST(StateRequest, StateFromRequestChecksEveryField) {
  const Eigen::Vector3d p(0.1, 0.2, 0.3), v(1, 0, 0), w(0, 0, 10);
  const Eigen::Vector4d q(0, 0, 0, 2);  // not unit: normalised
  const vg::RigidBodyState s = vg::state_from_request(kFields, model(), p, q, v, w, kLimit);
  EXPECT_EQ(s.position_world, p);
  EXPECT_EQ(s.velocity_world, v);
  EXPECT_DOUBLE_EQ(s.orientation.w(), 1.0);
  EXPECT_NEAR(s.angular_momentum_world.z(), 2.0e-7 * 10, 1e-18);  // L = I3 w about the axis

  const Eigen::Vector3d nan(kNaN, 0, 0);
  EXPECT_TRUE(
      starts_with(refusal([&] { vg::state_from_request(kFields, model(), nan, q, v, w, kLimit); }),
                  "pose.position"));
  EXPECT_TRUE(starts_with(refusal([&] {
                            vg::state_from_request(kFields, model(), p, Eigen::Vector4d::Zero(), v,
                                                   w, kLimit);
                          }),
                          "pose.orientation must be a non-zero quaternion"));
  EXPECT_TRUE(starts_with(refusal([&] {
                            vg::state_from_request(kFields, model(), p,
                                                   Eigen::Vector4d(kInf, 0, 0, 1), v, w, kLimit);
                          }),
                          "pose.orientation must be finite"));
  EXPECT_TRUE(starts_with(refusal([&] {
                            vg::state_from_request(kFields, model(), p, q,
                                                   Eigen::Vector3d(0, kInf, 0), w, kLimit);
                          }),
                          "twist.linear"));
  EXPECT_TRUE(starts_with(refusal([&] {
                            vg::state_from_request(kFields, model(), p, q, v,
                                                   Eigen::Vector3d(0, 0, 101), kLimit);
                          }),
                          "twist.angular: |w|"));
}

// issue 8: an angular velocity with components above ~1.3e154 was reported as |w| = inf (the
// plain norm squares them). The norm is taken without overflow and named as it is.
TEST(StateRequest, HugeAngularVelocityIsReportedWithItsTrueNorm) {
  const std::string m = refusal([] {
    vg::check_angular_velocity("angular_velocity", Eigen::Vector3d(3e154, 0, 4e154), kLimit);
  });
  EXPECT_TRUE(starts_with(m,
                          "angular_velocity: |w| = 5e+154 rad/s exceeds "
                          "~max_angular_velocity 100 rad/s"))
      << m;
  EXPECT_EQ(m.find("inf"), std::string::npos) << m;
  // Even a norm above the largest double is named as such, not as inf.
  const double big = std::numeric_limits<double>::max();
  const std::string beyond =
      refusal([&] { vg::check_angular_velocity("w", Eigen::Vector3d(big, big, big), kLimit); });
  EXPECT_NE(beyond.find("|w| > 1.7976931348623157e+308 rad/s"), std::string::npos) << beyond;
}

// issue 8: states with a finite but absurd position or velocity were accepted (and stopped or
// silenced the node later). Each is refused naming the field, the value and the limit.
TEST(StateRequest, PositionAndVelocityBeyondTheBoundsAreRefused) {
  const Eigen::Vector3d p(0.1, 0.2, 0.3), v(1, 0, 0), w(0, 0, 10);
  const Eigen::Vector4d q(0, 0, 0, 1);
  const std::string fast = refusal([&] {
    vg::state_from_request(kFields, model(), p, q, Eigen::Vector3d(1.7564270946e+308, 0, 0), w,
                           kLimit);
  });
  EXPECT_EQ(fast, "twist.linear: |v| = 1.7564270946e+308 m/s exceeds ~max_speed 1000 m/s");
  const std::string far = refusal([&] {
    vg::state_from_request(kFields, model(), Eigen::Vector3d(0, -1.79e308, 0), q, v, w, kLimit);
  });
  EXPECT_EQ(far,
            "pose.position: distance from the world origin = 1.79e+308 m exceeds ~max_distance "
            "1000 m");
  // At the bounds: accepted.
  EXPECT_NO_THROW(vg::state_from_request(kFields, model(), Eigen::Vector3d(0, 0, 1000), q,
                                         Eigen::Vector3d(600, 800, 0), w, kLimit));
}

// issue 8: a quaternion whose norm exceeds the largest double was refused with a message that
// named an internal field ("orientation") and zeroed values: the norm overflowed and the
// quotient was zero. It is a direction like any other and is normalised.
TEST(StateRequest, QuaternionWithNormAboveTheLargestDoubleIsNormalised) {
  const double big = 1.7e308;
  const vg::RigidBodyState s = vg::state_from_request(
      kFields, model(), Eigen::Vector3d::Zero(), Eigen::Vector4d(big, big, big, big),
      Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 10), kLimit);
  for (int i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ(s.orientation.coeffs()[i], 0.5) << i;
  // L = I w about an axis: finite and as the model gives it.
  EXPECT_TRUE(s.angular_momentum_world.allFinite());
  const vg::RigidBodyState t = vg::state_from_request(
      kFields, model(), Eigen::Vector3d::Zero(), Eigen::Vector4d(-big, 0, big, 0),
      Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), kLimit);
  EXPECT_DOUBLE_EQ(t.orientation.x(), -std::sqrt(0.5));
  EXPECT_DOUBLE_EQ(t.orientation.z(), std::sqrt(0.5));
}

// issue 8: a refused 1 MB frame name was logged in full. The refusal quotes it cut short.
TEST(StateRequest, LongFrameNameIsCutInTheRefusal) {
  const std::string name(1 << 20, 'x');
  const std::string m = refusal([&] { vg::request_frame("frame", name, "world", "stone"); });
  EXPECT_LT(m.size(), 200u) << m.size();
  EXPECT_TRUE(starts_with(m, "frame: unknown frame 'xxxx")) << m;
  EXPECT_NE(m.find("... (1048576 bytes)"), std::string::npos) << m;
}
