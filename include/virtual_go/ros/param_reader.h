// Reads the node's private parameters (the table in sim/stone_parameters.h) into a StoneConfig.
// Absent parameters keep their defaults; a parameter of the wrong type or length throws
// ConfigError naming it.
#pragma once

#include <ros/node_handle.h>

#include <string>
#include <vector>

#include "virtual_go/sim/stone_parameters.h"

namespace virtual_go {

StoneConfig read_stone_config(const ros::NodeHandle& private_nh);

// Private parameters set on the server that the node does not know (likely typos).
std::vector<std::string> unknown_parameters(const ros::NodeHandle& private_nh);

}  // namespace virtual_go
