#include "virtual_go/sim/update_budget.h"

#include <algorithm>

namespace virtual_go {

std::chrono::nanoseconds update_allowance(double rate_hz) {
  const double half_period_s = rate_hz > 0.0 ? 0.5 / rate_hz : 0.1;
  const double s = std::min(half_period_s, 0.1);
  return std::chrono::nanoseconds(static_cast<std::int64_t>(s * 1e9));
}

}  // namespace virtual_go
