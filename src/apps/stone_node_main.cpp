// stone_node: the Go stone simulator as a ROS node (see stone_node --help).
#include <ros/ros.h>

#include <cstdio>
#include <cstring>
#include <exception>

#include "virtual_go/ros/stone_node.h"
#include "virtual_go/ros/stone_node_help.h"

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "-h") == 0 || std::strcmp(argv[i], "--help") == 0) {
      std::fputs(virtual_go::stone_node_help().c_str(), stdout);
      return 0;
    }
  }
  ros::init(argc, argv, "stone");
  // Outlives the node: when the last NodeHandle goes, roscpp shuts down and drops log output,
  // which would swallow the FATAL below.
  ros::NodeHandle nh, private_nh("~");
  try {
    virtual_go::StoneNode node(nh, private_nh);
    ros::spin();
  } catch (const virtual_go::ConfigError& e) {
    ROS_FATAL("stone_node: invalid parameter %s", e.what());
    return 1;
  } catch (const std::exception& e) {
    // Anything else (roscpp, tf2, the core) must still end with a message and a failure code,
    // not std::terminate.
    ROS_FATAL("stone_node: %s", e.what());
    return 1;
  }
  return 0;
}
