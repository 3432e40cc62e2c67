// Simulated time: whole nanoseconds, with seconds derived in one place. Differences of absolute
// stamps are taken in integers, so nanoseconds survive where a double of the stamp would not.
#include <gtest/gtest.h>

#include "virtual_go/common/sim_time.h"

namespace vg = virtual_go;

TEST(SimTime, DifferencesOfLargeStampsKeepTheirNanoseconds) {
  // 2024 in ns since 1970: a double holds it only to 256 ns.
  const std::int64_t t0 = 1'700'000'000'123'456'789;
  EXPECT_NE(static_cast<double>(t0 + 1) - static_cast<double>(t0), 1.0);
  EXPECT_EQ(vg::seconds_between(t0, t0 + 1), 1e-9);
  EXPECT_EQ(vg::seconds_between(t0, t0 + 1'000'000), 1e-3);
  EXPECT_EQ(vg::seconds_between(t0 + 5, t0), -5e-9);
}

TEST(SimTime, ConversionsRoundTripOnWholeNanoseconds) {
  for (const std::int64_t ns : {1000LL, 1'000'000LL, 1'666'666LL, 16'666'667LL, 1'000'000'000LL}) {
    EXPECT_EQ(vg::round_to_ns(vg::to_seconds(ns)), ns) << ns;
  }
  EXPECT_EQ(vg::round_to_ns(0.001), 1'000'000);
  // 1/1024 s is 976562.5 ns: not whole, and to_nanoseconds shows it unrounded.
  EXPECT_EQ(vg::to_nanoseconds(1.0 / 1024), 976562.5);
  EXPECT_EQ(vg::stamp_to_ns(3, 999'999'999), 3'999'999'999);
  EXPECT_EQ(vg::stamp_to_ns(4'294'967'295U, 0), 4'294'967'295LL * 1'000'000'000);
}
