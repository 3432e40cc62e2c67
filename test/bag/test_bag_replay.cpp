// Replay: `rosbag play --clock` of a recording with use_sim_time gives tf consumers the recorded
// motion. Writes a bag (test/bag_test_bags.h), plays it, and looks the stone up in tf2 at the
// recorded stamps: every lookup must match the closed form the bag was written from.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <tf2_ros/transform_listener.h>

#include <cstdlib>
#include <thread>

#include "support/test_bags.h"

namespace {

std::string g_bag;

TEST(BagReplay, TfGivesTheRecordedMotion) {
  virtual_go_test::SyntheticRun run;
  run.duration = 3.0;
  const std::size_t written = virtual_go_test::write_run_bag(g_bag, run);
  ASSERT_GT(written, 100u);

  tf2_ros::Buffer buffer(ros::Duration(10.0));
  tf2_ros::TransformListener listener(buffer);
  int play_status = -1;
  std::thread play([&] {
    play_status = std::system(("rosbag play --clock -q " + g_bag + " >/dev/null 2>&1").c_str());
  });

  // Sample the tf at recorded stamps while the bag plays (sim time from /clock).
  const std::int64_t period_ns = 20'000'000;
  std::size_t checked = 0;
  double worst_angle = 0.0, worst_position = 0.0;
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  std::int64_t next_ns = run.start_ns + 10 * period_ns;
  while (ros::ok() && ros::WallTime::now() < deadline &&
         next_ns <= run.start_ns + static_cast<std::int64_t>(run.duration * 1e9)) {
    ros::Time stamp;
    stamp.fromNSec(static_cast<std::uint64_t>(next_ns));
    if (!buffer.canTransform("world", "stone", stamp)) {
      ros::WallDuration(0.005).sleep();
      continue;
    }
    const geometry_msgs::TransformStamped t = buffer.lookupTransform("world", "stone", stamp);
    const virtual_go_test::TrueState s =
        virtual_go_test::true_state(static_cast<double>(next_ns - run.start_ns) * 1e-9);
    const Eigen::Quaterniond q(t.transform.rotation.w, t.transform.rotation.x,
                               t.transform.rotation.y, t.transform.rotation.z);
    const Eigen::Vector3d x(t.transform.translation.x, t.transform.translation.y,
                            t.transform.translation.z);
    worst_angle = std::max(worst_angle, s.orientation.angularDistance(q));
    worst_position = std::max(worst_position, (s.position - x).norm());
    ++checked;
    next_ns += 5 * period_ns;
  }
  play.join();
  EXPECT_EQ(play_status, 0) << "rosbag play failed";
  EXPECT_GE(checked, 20u) << "tf did not follow the replay";
  EXPECT_LT(worst_angle, 1e-9);
  EXPECT_LT(worst_position, 1e-9);
  EXPECT_TRUE(ros::Time::isSimTime()) << "use_sim_time was not set";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_bag_replay");
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("__", 0) != 0 && a.rfind("--", 0) != 0) g_bag = a;
  }
  if (g_bag.empty()) {
    std::cerr << "usage: test_bag_replay BAG (written, then played)\n";
    return 2;
  }
  ros::NodeHandle nh;  // starts the node before the listener needs it
  return RUN_ALL_TESTS();
}
