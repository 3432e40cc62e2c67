// Timing figures of one topic from its message stamps: rate, period percentiles, gaps and
// stamps that repeat or go backwards.
#pragma once

#include <cstdint>
#include <vector>

namespace virtual_go {
namespace bag {

struct StampEvent {
  std::size_t index;      // message index within the topic
  std::int64_t stamp_ns;  // the stamp of that message
  std::int64_t step_ns;   // stamp minus the previous stamp (<= 0 for repeats, > 2 p50 for gaps)
};

struct StampStatistics {
  std::size_t count = 0;
  double span_s = 0.0;        // last minus first stamp, in stamp order
  double mean_rate_hz = 0.0;  // (count - 1) / span; 0 with fewer than two distinct stamps
  // Over the positive steps between consecutive stamps; 0 when there are none.
  double period_p50_s = 0.0;
  double period_p99_s = 0.0;
  double period_max_s = 0.0;
  std::vector<StampEvent> gaps;            // steps over kGapFactor x p50
  std::vector<StampEvent> repeated;        // step == 0
  std::vector<StampEvent> non_increasing;  // step < 0 (went backwards)
};

// A step longer than this many median periods counts as a gap (at least one missed message).
constexpr double kGapFactor = 2.0;

// stamps_ns in the order the messages were recorded.
StampStatistics compute_stamp_statistics(const std::vector<std::int64_t>& stamps_ns);

// Nearest-rank percentile (p in [0, 100]) of unsorted values; 0 for an empty vector.
double percentile(std::vector<double> values, double p);

}  // namespace bag
}  // namespace virtual_go
