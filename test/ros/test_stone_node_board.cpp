// A flat drop onto the board through ROS (test/ros/config/board_drop.yaml): a real master, the
// node's ~events and a tf2 listener. After ~reset the stone falls h0 = 5 cm flat onto the board
// (e* = 0.5): the n-th impact comes at the closed-form time, each flight between two impacts is
// the parabola of its impact event at every tf sample, and the n-th apex is e^{2n} h0. Then it
// rests, and every transform after the rest event is that event's pose, bit for bit. The
// node's /diagnostics status then counts the stone as resting, at level OK.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <std_srvs/Trigger.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "support/node_observer.h"
#include "support/node_reference.h"

using vgtest::NodeObserver;

namespace {

constexpr double kG = 9.80665;
constexpr double kH0 = 0.05;  // m, the drop's gap (board_drop.yaml)
constexpr double kE = 0.5;    // e* of the board (board_drop.yaml)

// The exact instant of an event, in seconds since `origin`.
double instant_since(const virtual_go::StoneEvent& e, const ros::Time& origin) {
  return vgtest::seconds_between(origin, e.header.stamp) + e.time_offset;
}

}  // namespace

TEST(StoneNodeBoard, FlatDropBouncesToTheClosedFormAndRestsBitwiseStill) {
  NodeObserver o;
  ASSERT_TRUE(o.wait_for_start()) << "no info, marker, events or odom from /stone";
  const virtual_go::StoneInfo& info = *o.info;
  // ~info against board_drop.yaml and the node's documented defaults.
  EXPECT_TRUE(info.board_enabled);
  EXPECT_EQ(vgtest::vec(info.board_size), Eigen::Vector3d(0.4242, 0.4545, 0.1515));
  EXPECT_EQ(info.board_restitution, 0.5);
  EXPECT_EQ(info.board_friction, 0.3);
  EXPECT_EQ(info.table_friction, 0.3);
  EXPECT_EQ(info.table_spinning_friction, 15e-6);
  EXPECT_EQ(info.zeno_height, 1e-6);
  EXPECT_EQ(info.auto_reset_after_rest, 0.0);
  const double z_contact = 0.5 * info.height;  // flat on the top face z = 0
  ASSERT_NEAR(info.initial_pose.position.z - z_contact, kH0, 1e-15);

  // The first drop may have begun before this test listened: wait for its rest, then drop again.
  const auto rest_after = [&](std::size_t from) {
    for (std::size_t i = from; i < o.events.size(); ++i) {
      if (o.events[i].reason == "rest") return i;
    }
    return o.events.size();
  };
  ASSERT_TRUE(o.wait_until([&] { return rest_after(0) < o.events.size(); }, 20.0))
      << "no rest event";
  const std::size_t seen = o.events.size();
  std_srvs::Trigger reset;
  ASSERT_TRUE(o.call("reset", reset));
  ASSERT_TRUE(reset.response.success) << reset.response.message;
  ASSERT_TRUE(o.wait_until([&] { return rest_after(seen) < o.events.size(); }, 20.0))
      << "no rest after the reset";
  const std::size_t rest_index = rest_after(seen);
  const virtual_go::StoneEvent rest = o.events[rest_index];
  // One second of tf after the rest.
  const std::vector<nav_msgs::Odometry> still = o.odom_after(rest.header.stamp, 150, 20.0);
  ASSERT_GE(still.size(), 150u);

  std::vector<virtual_go::StoneEvent> after_reset(o.events.begin() + seen,
                                                  o.events.begin() + rest_index + 1);
  ASSERT_GE(after_reset.size(), 2u);
  EXPECT_EQ(after_reset[0].reason, "wake");  // the stone was resting
  const virtual_go::StoneEvent start = after_reset[1];
  ASSERT_EQ(start.reason, "reset");
  EXPECT_EQ(start.time_offset, 0.0);  // on the dt grid
  std::vector<std::size_t> impacts;
  for (std::size_t i = 0; i < after_reset.size(); ++i) {
    EXPECT_GE(after_reset[i].time_offset, 0.0);
    EXPECT_LT(after_reset[i].time_offset, 1e-9);
    if (i > 0) {
      EXPECT_GE(instant_since(after_reset[i], start.header.stamp),
                instant_since(after_reset[i - 1], start.header.stamp));
    }
    if (after_reset[i].reason == "impact") impacts.push_back(i);
  }
  ASSERT_GE(impacts.size(), 5u);

  const double t1 = std::sqrt(2.0 * kH0 / kG);
  const double v1 = kG * t1;
  double t_impact = t1;
  std::size_t samples_checked = 0;
  for (std::size_t n = 1; n <= impacts.size(); ++n) {
    const virtual_go::StoneEvent& e = after_reset[impacts[n - 1]];
    EXPECT_NEAR(instant_since(e, start.header.stamp), t_impact, 1e-12) << "impact " << n;
    const double rebound = std::pow(kE, n) * v1;
    t_impact += 2.0 * rebound / kG;
    if (n == impacts.size()) break;  // the last bounce is below the Zeno height: contact
    const virtual_go::StoneEvent& next = after_reset[impacts[n - 1] + 1];
    EXPECT_EQ(next.reason, "impact");
    const double z0 = e.pose.position.z, vz = e.twist.linear.z;
    const double apex = z0 + vz * vz / (2.0 * kG) - z_contact;
    EXPECT_NEAR(apex / (std::pow(kE, 2.0 * n) * kH0), 1.0, 1e-9) << "apex " << n;
    // Every tf sample in this flight is on the parabola of its impact event, and none is above
    // the apex.
    const double flight_s = instant_since(next, e.header.stamp) - e.time_offset;
    double highest = -1.0;
    for (const nav_msgs::Odometry& m : o.odom) {
      const double tau = vgtest::seconds_between(e.header.stamp, m.header.stamp) - e.time_offset;
      if (tau <= 0.0 || tau >= flight_s) continue;
      const auto tf = o.tf_at(m.header.stamp);
      ASSERT_TRUE(tf) << "no tf at a published stamp";
      const geometry_msgs::Vector3& p = tf->transform.translation;
      EXPECT_NEAR(p.z, z0 + vz * tau - 0.5 * kG * tau * tau, 1e-12) << "bounce " << n;
      EXPECT_EQ(p.x, 0.0);
      EXPECT_EQ(p.y, 0.0);
      highest = std::max(highest, p.z - z_contact);
      ++samples_checked;
    }
    EXPECT_LE(highest, apex + 1e-12) << "bounce " << n;
  }
  // At 200 Hz the first bounce (2 e v1 / g = 101 ms) alone gives about 20 samples.
  EXPECT_GE(samples_checked, 25u);

  // Rest: every transform after the rest event is its pose, bit for bit.
  for (const nav_msgs::Odometry& m : still) {
    const auto tf = o.tf_at(m.header.stamp);
    ASSERT_TRUE(tf);
    EXPECT_EQ(tf->transform.translation.x, rest.pose.position.x);
    EXPECT_EQ(tf->transform.translation.y, rest.pose.position.y);
    EXPECT_EQ(tf->transform.translation.z, rest.pose.position.z);
    EXPECT_EQ(tf->transform.rotation.x, rest.pose.orientation.x);
    EXPECT_EQ(tf->transform.rotation.y, rest.pose.orientation.y);
    EXPECT_EQ(tf->transform.rotation.z, rest.pose.orientation.z);
    EXPECT_EQ(tf->transform.rotation.w, rest.pose.orientation.w);
  }
  EXPECT_NEAR(rest.pose.position.z, z_contact, 1e-12);  // on the board: no sinking
}

// /diagnostics: one status from the node, hardware_id its name, with every documented value;
// once the dropped stone rests it is counted so, and the status is OK (not behind, not held).
// Waits (with a timeout) for a message showing the rest; values measured in wall time are only
// checked to be there, never against a wall-clock figure.
TEST(StoneNodeBoard, DiagnosticsCountTheRestingStoneAtLevelOk) {
  ros::NodeHandle nh;
  std::vector<diagnostic_msgs::DiagnosticStatus> statuses;
  const ros::Subscriber sub = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const diagnostic_msgs::DiagnosticStatus& s : m->status) {
          if (s.hardware_id == "/stone") statuses.push_back(s);
        }
      });
  const auto values = [](const diagnostic_msgs::DiagnosticStatus& s) {
    std::map<std::string, std::string> out;
    for (const diagnostic_msgs::KeyValue& kv : s.values) out[kv.key] = kv.value;
    return out;
  };
  const auto resting_ok = [&] {
    for (const diagnostic_msgs::DiagnosticStatus& s : statuses) {
      const auto v = values(s);
      if (s.level == diagnostic_msgs::DiagnosticStatus::OK && v.count("stones resting") &&
          v.at("stones resting") == "1") {
        return true;
      }
    }
    return false;
  };
  NodeObserver o;
  ASSERT_TRUE(o.wait_until(resting_ok, 30.0))
      << "no OK /diagnostics status with the stone resting; " << statuses.size() << " seen";
  for (const diagnostic_msgs::DiagnosticStatus& s : statuses) {
    const auto v = values(s);
    if (v.empty()) continue;  // diagnostic_updater's placeholder before the first update
    for (const char* key : {"stones awake", "stones resting", "events per s", "step cost mean (ms)",
                            "step cost max (ms)", "real-time factor", "pending requests",
                            "steps deferred", "behind (s)", "held", "period (s)"}) {
      EXPECT_EQ(v.count(key), 1u) << key;
    }
    EXPECT_EQ(v.at("held"), "false");
    EXPECT_NE(s.level, diagnostic_msgs::DiagnosticStatus::ERROR) << s.message;
    EXPECT_EQ(std::stoi(v.at("stones awake")) + std::stoi(v.at("stones resting")), 1);
  }
}
