// Texts from users (frame ids, names, parameter values) in messages and logs: cut short with
// their length, control characters masked, UTF-8 never split.
#include <gtest/gtest.h>

#include <string>

#include "virtual_go/common/formatting.h"

namespace vg = virtual_go;

TEST(Formatting, ShortUserTextIsQuotedAsIs) {
  EXPECT_EQ(vg::quote_user_text("base_link"), "'base_link'");
  EXPECT_EQ(vg::cut_user_text("base_link"), "base_link");
  EXPECT_EQ(vg::quote_user_text(""), "''");
  EXPECT_EQ(vg::quote_user_text(std::string(64, 'a')), "'" + std::string(64, 'a') + "'");
}

// issue 8: a refused 1 MB frame name was logged in full (1 MB log lines).
TEST(Formatting, LongUserTextIsCutWithItsLength) {
  const std::string megabyte(1 << 20, 'x');
  const std::string quoted = vg::quote_user_text(megabyte);
  EXPECT_EQ(quoted, "'" + std::string(64, 'x') + "'... (1048576 bytes)");
  EXPECT_EQ(vg::cut_user_text(megabyte, 10), "xxxxxxxxxx... (1048576 bytes)");
}

TEST(Formatting, UserTextKeepsUtf8WholeAndMasksControlCharacters) {
  // "é" is two bytes: a cut after 3 bytes of "aéé" keeps "aé", not half a character.
  EXPECT_EQ(vg::cut_user_text("a\xc3\xa9\xc3\xa9", 4), "a\xc3\xa9... (5 bytes)");
  EXPECT_EQ(vg::quote_user_text("line\nbreak\x1b[2J"), "'line?break?[2J'");
}

TEST(Formatting, LimitsShowPowersOfTenShort) {
  EXPECT_EQ(vg::format_limit(1e9), "1e9");
  EXPECT_EQ(vg::format_limit(1e-12), "1e-12");
  EXPECT_EQ(vg::format_limit(1000.0), "1000");
  EXPECT_EQ(vg::format_limit(299792458.0), "299792458");
  EXPECT_EQ(vg::format_limit(2.5e20), "2.5e+20");
}
