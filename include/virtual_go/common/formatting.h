// Numbers and name lists as the package's messages, help texts and reports print them.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace virtual_go {

// The shortest text that reads back as the same double ("0.009", not "0.0089999999999999993").
std::string format_value(double value);
// A limit as texts show it: a power of ten from 1e5 up or 1e-5 down as "1e9", "1e-12" (not
// "1000000000"); anything else as format_value.
std::string format_limit(double value);
// "(x, y, z)", each as format_value prints it.
std::string format_vector(const Eigen::Vector3d& v);
// A string from a user (a frame id, a name, a parameter value) as messages and logs show it:
// control characters as '?', and cut after max_bytes (at a UTF-8 character boundary) with
// "... (N bytes)" added, so a 1 MB name makes a short line. quote_user_text adds single quotes
// around the text (before the note).
std::string cut_user_text(const std::string& text, std::size_t max_bytes = 64);
std::string quote_user_text(const std::string& text, std::size_t max_bytes = 64);
// The names with `separator` between them: join({"a", "b"}, " | ") is "a | b".
std::string join(const std::vector<std::string>& names, const std::string& separator);

}  // namespace virtual_go
