// What the sim tests of the board scene share: the wall-clock stamps they tick with and the
// scene itself.
#pragma once

#include <cstdint>

#include "virtual_go/sim/stone_config.h"

namespace simtest {

inline constexpr std::int64_t kStart = 1700000000123456789;  // a realistic wall-clock stamp, ns
inline constexpr std::int64_t kMs = 1000000;                 // ns per ms
inline constexpr double kG = 9.80665;                        // m/s^2, the default gravity

// The board scene with no automatic reset: the initial stone falls onto K10 (tengen) and rests
// there for good.
inline virtual_go::StoneConfig board_scene() {
  virtual_go::StoneConfig c;
  c.board_enabled = true;
  c.auto_reset_period_s = 0.0;
  c.auto_reset_after_rest_s = 0.0;
  return c;
}

}  // namespace simtest
