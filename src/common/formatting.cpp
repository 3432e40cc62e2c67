#include "virtual_go/common/formatting.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <utility>

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

std::string format_limit(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0e", value);  // "1e+09"
  const char* e = std::strchr(text, 'e');
  if (e == nullptr || std::strtod(text, nullptr) != value) return format_value(value);
  const int exponent = std::atoi(e + 1);
  if (std::abs(exponent) < 5) return format_value(value);
  return std::string(text, static_cast<std::size_t>(e + 1 - text)) + std::to_string(exponent);
}

std::string format_vector(const Eigen::Vector3d& v) {
  return "(" + format_value(v.x()) + ", " + format_value(v.y()) + ", " + format_value(v.z()) + ")";
}

namespace {

// The shown part of a user string and the note on what was cut ("" when nothing was).
std::pair<std::string, std::string> user_text_parts(const std::string& text,
                                                    std::size_t max_bytes) {
  std::size_t end = std::min(text.size(), max_bytes);
  // Back off to the start of a UTF-8 character (continuation bytes are 10xxxxxx).
  if (end < text.size()) {
    while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0u) == 0x80u) --end;
  }
  std::string shown;
  for (std::size_t i = 0; i < end; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    shown += (c < 0x20 || c == 0x7f) ? '?' : static_cast<char>(c);
  }
  return {shown, end < text.size() ? "... (" + std::to_string(text.size()) + " bytes)" : ""};
}

}  // namespace

std::string cut_user_text(const std::string& text, std::size_t max_bytes) {
  const auto [shown, note] = user_text_parts(text, max_bytes);
  return shown + note;
}

std::string quote_user_text(const std::string& text, std::size_t max_bytes) {
  const auto [shown, note] = user_text_parts(text, max_bytes);
  return "'" + shown + "'" + note;
}

std::string join(const std::vector<std::string>& names, const std::string& separator) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : separator) + name;
  return out;
}

}  // namespace virtual_go
