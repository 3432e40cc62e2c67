// Numbers and name lists as the package's messages, help texts and reports print them.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace virtual_go {

// The shortest text that reads back as the same double ("0.009", not "0.0089999999999999993").
std::string format_value(double value);
// "(x, y, z)", each as format_value prints it.
std::string format_vector(const Eigen::Vector3d& v);
// The names with `separator` between them: join({"a", "b"}, " | ") is "a | b".
std::string join(const std::vector<std::string>& names, const std::string& separator);

}  // namespace virtual_go
