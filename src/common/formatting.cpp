#include "virtual_go/common/formatting.h"

#include <cstdlib>
#include <sstream>

namespace virtual_go {

std::string format_value(double value) {
  // The shortest precision that reads back as the same double; 17 digits always round-trip.
  std::ostringstream out;
  for (int precision = 15; precision <= 17; ++precision) {
    out.str("");
    out.precision(precision);
    out << value;
    if (std::strtod(out.str().c_str(), nullptr) == value) break;
  }
  return out.str();
}

std::string format_vector(const Eigen::Vector3d& v) {
  return "(" + format_value(v.x()) + ", " + format_value(v.y()) + ", " + format_value(v.z()) + ")";
}

std::string join(const std::vector<std::string>& names, const std::string& separator) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : separator) + name;
  return out;
}

}  // namespace virtual_go
