// Number formatting shared by the contact benchmark's peers and report.
#pragma once

#include <cstdio>
#include <string>

namespace vg_bench {

inline std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

inline std::string num17(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace vg_bench
