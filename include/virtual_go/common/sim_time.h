// Simulated time is whole nanoseconds, as ROS stamps are, so every stamp is the exact time of the
// state it carries. This is the package's only arithmetic between nanoseconds and seconds.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

namespace virtual_go {

constexpr std::int64_t kNanosecondsPerSecond = 1000000000;

// ns -> s. The double the integrators see for a step of dt_ns.
inline double to_seconds(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }
// Seconds from one stamp to another; subtracts in integers first (absolute stamps in double
// lose nanoseconds).
inline double seconds_between(std::int64_t from_ns, std::int64_t to_ns) {
  return to_seconds(to_ns - from_ns);
}
// s -> ns, unrounded (to check that a duration is a whole number of nanoseconds).
inline double to_nanoseconds(double s) { return s * 1e9; }
// s -> the nearest whole ns. Finite s with |s| < 9.2e9 only (the int64 range).
inline std::int64_t round_to_ns(double s) { return std::llround(to_nanoseconds(s)); }
// A ROS stamp's (sec, nsec) pair -> ns.
inline std::int64_t stamp_to_ns(std::uint32_t sec, std::uint32_t nsec) {
  return static_cast<std::int64_t>(sec) * kNanosecondsPerSecond + nsec;
}

// "1700000001.146456789": a stamp in seconds with all nine digits of its nanoseconds (a double
// of seconds since 1970 keeps only about seven of them).
inline std::string stamp_text(std::int64_t ns) {
  const std::int64_t magnitude = ns < 0 ? -ns : ns;
  char text[32];
  std::snprintf(text, sizeof text, "%s%lld.%09lld", ns < 0 ? "-" : "",
                static_cast<long long>(magnitude / kNanosecondsPerSecond),
                static_cast<long long>(magnitude % kNanosecondsPerSecond));
  return text;
}

}  // namespace virtual_go
