// The --help text of stone_node: usage, topics, services, and the parameters from their table
// (sim/stone_parameters.h), so the help cannot disagree with what the node reads.
#pragma once

#include <string>

namespace virtual_go {

std::string stone_node_help();

}  // namespace virtual_go
