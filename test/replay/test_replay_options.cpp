// sgf_replay's command line: every option read in both spellings, each bad value refused naming
// the option, the value and the limit; --help lists the options and the exit codes from their
// tables.
#include <gtest/gtest.h>

#include "support/readme_tables.h"
#include "virtual_go/replay/replay_options.h"

namespace rp = virtual_go::replay;

namespace {

std::string refusal(const std::vector<std::string>& args) {
  try {
    rp::parse_replay_options(args);
  } catch (const rp::UsageError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(ReplayOptions, DefaultsAndEveryOption) {
  const rp::ReplayOptions d = rp::parse_replay_options({"game.sgf"});
  EXPECT_EQ(d.game_path, "game.sgf");
  EXPECT_EQ(d.interval_s, 1.0);
  EXPECT_FALSE(d.to_move);
  EXPECT_EQ(d.drop_height_m, 0.01);
  EXPECT_EQ(d.node, "/stone");
  EXPECT_EQ(d.timeout_s, 10.0);
  EXPECT_FALSE(d.help);
  const rp::ReplayOptions o =
      rp::parse_replay_options({"--interval", "0.25", "--to-move=100", "g.sgf", "--drop-height",
                                "0", "--node=/board", "--timeout", "2.5"});
  EXPECT_EQ(o.game_path, "g.sgf");
  EXPECT_EQ(o.interval_s, 0.25);
  EXPECT_EQ(o.to_move, 100);
  EXPECT_EQ(o.drop_height_m, 0.0);
  EXPECT_EQ(o.node, "/board");
  EXPECT_EQ(o.timeout_s, 2.5);
  EXPECT_TRUE(rp::parse_replay_options({"--help"}).help);
  EXPECT_TRUE(rp::parse_replay_options({"-h"}).help);
}

TEST(ReplayOptions, BadValuesNameTheOptionAndTheLimit) {
  EXPECT_EQ(refusal({}), "no game record given (see --help)");
  EXPECT_EQ(refusal({"a.sgf", "b.sgf"}), "one game record only: got 'a.sgf' and 'b.sgf'");
  EXPECT_EQ(refusal({"g.sgf", "--speed", "2"}), "unknown option '--speed' (see --help)");
  EXPECT_EQ(refusal({"g.sgf", "--interval"}), "--interval: needs a value");
  EXPECT_EQ(refusal({"g.sgf", "--interval", "-1"}), "--interval '-1': must be between 0 and 3600");
  EXPECT_EQ(refusal({"g.sgf", "--interval", "nan"}), "--interval 'nan': not a number");
  EXPECT_EQ(refusal({"g.sgf", "--interval=1e999"}), "--interval '1e999': not a number");
  EXPECT_EQ(refusal({"g.sgf", "--interval", "1s"}), "--interval '1s': not a number");
  EXPECT_EQ(refusal({"g.sgf", "--to-move", "2.5"}), "--to-move '2.5': not a whole number");
  EXPECT_EQ(refusal({"g.sgf", "--to-move", "-3"}), "--to-move '-3': must be between 0 and 100000");
  EXPECT_EQ(refusal({"g.sgf", "--drop-height", "2"}), "--drop-height '2': must be between 0 and 1");
  EXPECT_EQ(refusal({"g.sgf", "--timeout", ""}), "--timeout '': not a number");
  EXPECT_EQ(refusal({"g.sgf", "--node="}), "--node: needs a node name");
}

TEST(ReplayOptions, HelpListsEveryOptionAndExitCode) {
  const std::string help = rp::replay_usage();
  for (const char* option :
       {"--interval S", "--to-move N", "--drop-height H", "--timeout S", "--node NAME", "--help"}) {
    EXPECT_NE(help.find(option), std::string::npos) << option;
  }
  EXPECT_NE(help.find("(0 to 1; default 0.01)"), std::string::npos) << help;
  for (const rp::ExitCodeText& e : rp::exit_codes()) {
    EXPECT_NE(help.find("  " + std::to_string(e.code) + "  " + e.meaning), std::string::npos)
        << e.code;
  }
  EXPECT_EQ(rp::exit_codes().size(), 6u);
}

TEST(ReplayOptions, TheReadmeTablesMatchTheCode) {
  const auto options = vgtest::readme_table(VG_README, "#### `sgf_replay` options");
  ASSERT_EQ(options.size(), rp::option_texts().size());
  for (std::size_t k = 0; k < options.size(); ++k) {
    const rp::OptionText& o = rp::option_texts()[k];
    EXPECT_EQ(options[k], (std::vector<std::string>{o.option, o.meaning, o.range, o.default_value}))
        << o.option;
  }
  const auto codes = vgtest::readme_table(VG_README, "#### `sgf_replay` exit codes");
  ASSERT_EQ(codes.size(), rp::exit_codes().size());
  for (std::size_t k = 0; k < codes.size(); ++k) {
    const rp::ExitCodeText& e = rp::exit_codes()[k];
    EXPECT_EQ(codes[k], (std::vector<std::string>{std::to_string(e.code), e.meaning}));
  }
}
