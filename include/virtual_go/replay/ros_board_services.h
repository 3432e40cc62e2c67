// sgf_replay's BoardServices through ROS: service clients of a stone node's ~clear
// (std_srvs/Trigger), ~place (virtual_go/PlaceStone) and ~remove (virtual_go/RemoveStone).
#pragma once

#include <ros/ros.h>

#include <string>
#include <vector>

#include "virtual_go/replay/replay_runner.h"

namespace virtual_go {
namespace replay {

class RosBoardServices : public BoardServices {
 public:
  // `node`: the stone node's name, resolved as ROS resolves names ("/stone").
  explicit RosBoardServices(const std::string& node);

  // Waits up to timeout_s of wall time for the three services; returns those still missing.
  std::vector<std::string> wait_for_services(double timeout_s) const;

  ServiceReply clear() override;
  ServiceReply place(const std::string& point, const std::string& color,
                     double drop_height_m) override;
  ServiceReply remove(const std::string& name) override;
  bool wait(double seconds) override;

 private:
  ros::NodeHandle handle_;
  std::string clear_name_;
  std::string place_name_;
  std::string remove_name_;
  ros::ServiceClient clear_;
  ros::ServiceClient place_;
  ros::ServiceClient remove_;
};

// Waits up to timeout_s of wall time for the ROS master; false when it did not answer. Before a
// NodeHandle exists: roscpp retries the master without end once it has one.
bool wait_for_master(double timeout_s);

}  // namespace replay
}  // namespace virtual_go
