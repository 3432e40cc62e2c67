// One test binary for all node rostests; each .test file picks its suite with --gtest_filter.
#include <gtest/gtest.h>
#include <ros/ros.h>

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "stone_node_test");
  ros::NodeHandle nh;  // keeps the node up for the whole run
  return RUN_ALL_TESTS();
}
