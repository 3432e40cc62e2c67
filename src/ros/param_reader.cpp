#include "virtual_go/ros/param_reader.h"

#include <XmlRpcValue.h>

#include <sstream>
#include <string>
#include <vector>

#include "virtual_go/common/formatting.h"

namespace virtual_go {
namespace {

// The value as the parameter server holds it, cut short: it comes from the user. A string is
// quoted, so the string "true" does not read as the boolean true; a list shows its elements.
std::string describe(XmlRpc::XmlRpcValue& value) {
  if (value.getType() == XmlRpc::XmlRpcValue::TypeString) {
    return quote_user_text(static_cast<std::string>(value));
  }
  if (value.getType() == XmlRpc::XmlRpcValue::TypeArray) {
    std::vector<std::string> elements;
    for (int i = 0; i < value.size() && i < 8; ++i) elements.push_back(describe(value[i]));
    if (value.size() > 8) elements.push_back("... (" + std::to_string(value.size()) + " elements)");
    return "[" + join(elements, ", ") + "]";
  }
  std::ostringstream out;
  value.write(out);
  return cut_user_text(out.str());
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
    throw ConfigError("~" + name,
                      "~" + name + ": must be " + expected + ", got " + describe(value));
  }

  void read(const std::string& name, bool* out) const {
    XmlRpc::XmlRpcValue v;
    if (!get(name, v)) return;
    if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean) fail(name, "true or false", v);
    *out = static_cast<bool>(v);
  }

  void read(const std::string& name, double* out) const {
    XmlRpc::XmlRpcValue v;
    if (!get(name, v)) return;
    if (!is_number(v)) fail(name, "a number", v);
    *out = number(v);
  }

  void read(const std::string& name, std::optional<double>* out) const {
    XmlRpc::XmlRpcValue v;
    if (!get(name, v)) return;
    if (!is_number(v)) fail(name, "a number", v);
    *out = number(v);
  }

  void read(const std::string& name, std::optional<int>* out) const {
    XmlRpc::XmlRpcValue v;
    if (!get(name, v)) return;
    if (v.getType() != XmlRpc::XmlRpcValue::TypeInt) fail(name, "a whole number", v);
    *out = static_cast<int>(v);
  }

  void read(const std::string& name, std::string* out) const {
    XmlRpc::XmlRpcValue v;
    if (!get(name, v)) return;
    if (v.getType() != XmlRpc::XmlRpcValue::TypeString) fail(name, "a string", v);
    *out = static_cast<std::string>(v);
  }

  template <int N>
  void read(const std::string& name, Eigen::Matrix<double, N, 1>* out) const {
    XmlRpc::XmlRpcValue v;
    if (!get(name, v)) return;
    const std::string expected = "a list of " + std::to_string(N) + " numbers";
    if (v.getType() != XmlRpc::XmlRpcValue::TypeArray || v.size() != N) fail(name, expected, v);
    for (int i = 0; i < N; ++i) {
      if (!is_number(v[i])) fail(name, expected, v);
      (*out)[i] = number(v[i]);
    }
  }

 private:
  const ros::NodeHandle& nh_;
};

}  // namespace

StoneConfig read_stone_config(const ros::NodeHandle& nh) {
  const Reader r(nh);
  StoneConfig c;
  for (const BoundParameter& p : bind_parameters(c)) {
    std::visit([&](auto* field) { r.read(p.info.name, field); }, p.field);
  }
  return c;
}

std::vector<std::string> unknown_parameters(const ros::NodeHandle& nh) {
  std::vector<std::string> all, unknown;
  if (!nh.getParamNames(all)) return unknown;
  const std::string prefix = nh.getNamespace() + "/";
  for (const std::string& full : all) {
    if (full.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string name = full.substr(prefix.size());
    if (name == "diagnostic_period") continue;  // diagnostic_updater reads it (/diagnostics)
    if (find_parameter(name) == nullptr) unknown.push_back(name);
  }
  return unknown;
}

}  // namespace virtual_go
