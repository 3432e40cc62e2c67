// The stone node's parameters, each written once: name, unit, help and the StoneConfig field it
// sets, whose initial value in StoneConfig is the default. Reading (ros/param_reader), the
// warning about unknown names and stone_node --help all come from here; README.md's parameter
// table restates it (test_stone_parameters compares the two).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "virtual_go/sim/stone_config.h"

namespace virtual_go {

struct ParameterInfo {
  std::string name;          // below the node's private namespace: "rate", "stone/size"
  std::string unit;          // SI unit; "" for names, counts and frames
  std::string default_text;  // as --help and README.md show it; "" when unset by default
  std::string help;          // one line, no '|' (README.md shows it in a table)
};

// The StoneConfig field a parameter sets, by its type.
using ParameterField = std::variant<bool*, double*, std::optional<double>*, std::optional<int>*,
                                    std::string*, Eigen::Vector3d*, Eigen::Vector4d*>;

struct BoundParameter {
  ParameterInfo info;
  ParameterField field;  // points into the config passed to bind_parameters
};

// Every parameter, in --help order, bound to its field in `config`.
std::vector<BoundParameter> bind_parameters(StoneConfig& config);
// Every parameter with its default (from a default StoneConfig).
const std::vector<ParameterInfo>& stone_parameters();
// nullptr for a name the node does not know.
const ParameterInfo* find_parameter(const std::string& name);

}  // namespace virtual_go
