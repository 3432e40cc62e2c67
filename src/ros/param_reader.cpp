#include "virtual_go/ros/param_reader.h"

#include <XmlRpcValue.h>

#include <algorithm>
#include <sstream>

namespace virtual_go {
namespace {

// Every parameter once, with the field it sets: reading and the list of known names (for the
// unknown-parameter warning) both come from here, so they cannot diverge.
template <class Visit>
void for_each_parameter(StoneConfig& c, Visit&& visit) {
  visit("rate", c.rate);
  visit("dt", c.dt);
  visit("model", c.model);
  visit("integrator", c.integrator);
  visit("gravity", c.gravity);
  visit("stone/size", c.stone.size_number);
  visit("stone/width", c.stone.width);
  visit("stone/height", c.stone.height);
  visit("stone/material", c.stone.material);
  visit("stone/density", c.stone.density);
  visit("stone/mass", c.stone.mass);
  visit("stone/color", c.color);
  visit("initial/position", c.initial_position);
  visit("initial/orientation", c.initial_orientation);
  visit("initial/velocity", c.initial_velocity);
  visit("initial/angular_velocity", c.initial_angular_velocity);
  visit("max_angular_velocity", c.max_angular_velocity);
  visit("auto_reset_period", c.auto_reset_period);
  visit("world_frame", c.world_frame);
  visit("stone_frame", c.stone_frame);
}

const std::vector<std::string>& known_parameters() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    StoneConfig unused;
    for_each_parameter(unused, [&out](const char* name, auto&) { out.push_back(name); });
    return out;
  }();
  return names;
}

std::string describe(XmlRpc::XmlRpcValue& value) {
  std::ostringstream out;
  value.write(out);
  return out.str();
}

class Reader {
 public:
  explicit Reader(const ros::NodeHandle& nh) : nh_(nh) {}

  // False when the parameter is not set.
  bool get(const std::string& name, XmlRpc::XmlRpcValue& value) const {
    return nh_.getParam(name, value);
  }

  static bool is_number(const XmlRpc::XmlRpcValue& v) {
    return v.getType() == XmlRpc::XmlRpcValue::TypeDouble ||
           v.getType() == XmlRpc::XmlRpcValue::TypeInt;
  }

  static double number(XmlRpc::XmlRpcValue& v) {
    return v.getType() == XmlRpc::XmlRpcValue::TypeInt ? static_cast<double>(static_cast<int>(v))
                                                       : static_cast<double>(v);
  }

  [[noreturn]] static void fail(const std::string& name, const std::string& expected,
                                XmlRpc::XmlRpcValue& value) {
    throw ConfigError("~" + name + ": must be " + expected + ", got " + describe(value));
  }

  void read(const std::string& name, double& out) const {
    XmlRpc::XmlRpcValue v;
    if (!get(name, v)) return;
    if (!is_number(v)) fail(name, "a number", v);
    out = number(v);
  }

  void read(const std::string& name, std::optional<double>& out) const {
    XmlRpc::XmlRpcValue v;
    if (!get(name, v)) return;
    if (!is_number(v)) fail(name, "a number", v);
    out = number(v);
  }

  void read(const std::string& name, std::optional<int>& out) const {
    XmlRpc::XmlRpcValue v;
    if (!get(name, v)) return;
    if (v.getType() != XmlRpc::XmlRpcValue::TypeInt) fail(name, "a whole number", v);
    out = static_cast<int>(v);
  }

  void read(const std::string& name, std::string& out) const {
    XmlRpc::XmlRpcValue v;
    if (!get(name, v)) return;
    if (v.getType() != XmlRpc::XmlRpcValue::TypeString) fail(name, "a string", v);
    out = static_cast<std::string>(v);
  }

  template <int N>
  void read(const std::string& name, Eigen::Matrix<double, N, 1>& out) const {
    XmlRpc::XmlRpcValue v;
    if (!get(name, v)) return;
    const std::string expected = "a list of " + std::to_string(N) + " numbers";
    if (v.getType() != XmlRpc::XmlRpcValue::TypeArray || v.size() != N) fail(name, expected, v);
    for (int i = 0; i < N; ++i) {
      if (!is_number(v[i])) fail(name, expected, v);
      out[i] = number(v[i]);
    }
  }

 private:
  const ros::NodeHandle& nh_;
};

}  // namespace

StoneConfig read_stone_config(const ros::NodeHandle& nh) {
  const Reader r(nh);
  StoneConfig c;
  for_each_parameter(c, [&r](const char* name, auto& field) { r.read(name, field); });
  return c;
}

std::vector<std::string> unknown_parameters(const ros::NodeHandle& nh) {
  std::vector<std::string> all, unknown;
  if (!nh.getParamNames(all)) return unknown;
  const std::string prefix = nh.getNamespace() + "/";
  for (const std::string& full : all) {
    if (full.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string name = full.substr(prefix.size());
    const auto& known = known_parameters();
    if (std::find(known.begin(), known.end(), name) == known.end()) unknown.push_back(name);
  }
  return unknown;
}

}  // namespace virtual_go
