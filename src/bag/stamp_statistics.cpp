#include "virtual_go/bag/stamp_statistics.h"

#include <algorithm>
#include <cmath>

#include "virtual_go/common/sim_time.h"

namespace virtual_go {
namespace bag {

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  // Nearest rank: the smallest value with at least p% of the values at or below it.
  const double rank = std::ceil(p / 100.0 * static_cast<double>(values.size()));
  const std::size_t index = rank < 1.0 ? 0 : static_cast<std::size_t>(rank) - 1;
  return values[std::min(index, values.size() - 1)];
}

StampStatistics compute_stamp_statistics(const std::vector<std::int64_t>& stamps_ns) {
  StampStatistics s;
  s.count = stamps_ns.size();
  if (stamps_ns.empty()) return s;

  std::vector<double> periods;
  periods.reserve(stamps_ns.size());
  for (std::size_t i = 1; i < stamps_ns.size(); ++i) {
    const std::int64_t step = stamps_ns[i] - stamps_ns[i - 1];
    if (step > 0) {
      periods.push_back(to_seconds(step));
    } else if (step == 0) {
      s.repeated.push_back({i, stamps_ns[i], step});
    } else {
      s.non_increasing.push_back({i, stamps_ns[i], step});
    }
  }
  const auto [lo, hi] = std::minmax_element(stamps_ns.begin(), stamps_ns.end());
  s.span_s = seconds_between(*lo, *hi);
  if (s.span_s > 0.0) s.mean_rate_hz = static_cast<double>(s.count - 1) / s.span_s;
  s.period_p50_s = percentile(periods, 50.0);
  s.period_p99_s = percentile(periods, 99.0);
  s.period_max_s = periods.empty() ? 0.0 : *std::max_element(periods.begin(), periods.end());

  // Gaps are measured against the median so that a few long steps cannot hide themselves.
  if (s.period_p50_s > 0.0) {
    const double limit_s = kGapFactor * s.period_p50_s;
    for (std::size_t i = 1; i < stamps_ns.size(); ++i) {
      const std::int64_t step = stamps_ns[i] - stamps_ns[i - 1];
      if (to_seconds(step) > limit_s) s.gaps.push_back({i, stamps_ns[i], step});
    }
  }
  return s;
}

}  // namespace bag
}  // namespace virtual_go
