#include "virtual_go/replay/ros_board_services.h"

#include <std_srvs/Trigger.h>

#include <algorithm>

#include "virtual_go/PlaceStone.h"
#include "virtual_go/RemoveStone.h"

namespace virtual_go {
namespace replay {

namespace {

constexpr double kPollS = 0.05;  // wall time between checks while waiting

ServiceReply no_answer(const std::string& service) {
  return {false, "service " + service + " did not answer (has the node stopped?)", ""};
}

}  // namespace

RosBoardServices::RosBoardServices(const std::string& node)
    : clear_name_(ros::names::append(ros::names::resolve(node), "clear")),
      place_name_(ros::names::append(ros::names::resolve(node), "place")),
      remove_name_(ros::names::append(ros::names::resolve(node), "remove")),
      clear_(handle_.serviceClient<std_srvs::Trigger>(clear_name_)),
      place_(handle_.serviceClient<virtual_go::PlaceStone>(place_name_)),
      remove_(handle_.serviceClient<virtual_go::RemoveStone>(remove_name_)) {}

std::vector<std::string> RosBoardServices::wait_for_services(double timeout_s) const {
  std::vector<std::string> missing{clear_name_, place_name_, remove_name_};
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (true) {
    missing.erase(
        std::remove_if(missing.begin(), missing.end(),
                       [](const std::string& s) { return ros::service::exists(s, false); }),
        missing.end());
    if (missing.empty() || !ros::ok() || ros::WallTime::now() >= deadline) return missing;
    ros::WallDuration(kPollS).sleep();
  }
}

ServiceReply RosBoardServices::clear() {
  std_srvs::Trigger call;
  if (!clear_.call(call)) return no_answer(clear_name_);
  return {call.response.success != 0, call.response.message, ""};
}

ServiceReply RosBoardServices::place(const std::string& point, const std::string& color,
                                     double drop_height_m) {
  virtual_go::PlaceStone call;
  call.request.point = point;
  call.request.color = color;
  call.request.drop_height = drop_height_m;
  // pose and twist stay at the message defaults: the point gives the position, lying flat, at
  // rest.
  if (!place_.call(call)) return no_answer(place_name_);
  return {call.response.success != 0, call.response.message, call.response.name};
}

ServiceReply RosBoardServices::remove(const std::string& name) {
  virtual_go::RemoveStone call;
  call.request.name = name;
  if (!remove_.call(call)) return no_answer(remove_name_);
  return {call.response.success != 0, call.response.message, ""};
}

bool RosBoardServices::wait(double seconds) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::ok()) {
    const double left = (end - ros::WallTime::now()).toSec();
    if (left <= 0.0) return true;
    ros::WallDuration(std::min(left, kPollS)).sleep();
  }
  return false;
}

bool wait_for_master(double timeout_s) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (!ros::master::check()) {
    if (!ros::ok() || ros::WallTime::now() >= deadline) return false;
    ros::WallDuration(kPollS).sleep();
  }
  return true;
}

}  // namespace replay
}  // namespace virtual_go
