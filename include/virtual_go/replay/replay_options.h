// The command line of sgf_replay (rosrun virtual_go sgf_replay GAME.sgf [options]): one table of
// options from which the parser, the limits and --help are derived.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace virtual_go {
namespace replay {

// Exit codes; their meanings are in exit_codes() (listed by --help and README.md).
enum ExitCode : int {
  kExitOk = 0,
  kExitServiceFailed = 1,
  kExitUsage = 2,
  kExitBadRecord = 3,
  kExitNoServices = 4,
  kExitInterrupted = 5,
};

// Each exit code and its meaning, as --help and the README list them.
struct ExitCodeText {
  int code;
  std::string meaning;
};
const std::vector<ExitCodeText>& exit_codes();

// Each option as --help and the README's table show it.
struct OptionText {
  std::string option;  // "--interval S"
  std::string meaning;
  std::string range;          // "0 to 3600", or "" for options without a number
  std::string default_value;  // "" when there is none
};
const std::vector<OptionText>& option_texts();

struct ReplayOptions {
  bool help = false;
  std::string game_path;
  double interval_s = 1.0;      // wall time between moves
  std::optional<int> to_move;   // the last move to play; none: the whole main line
  double drop_height_m = 0.01;  // from the board's top face to the stone's lowest point
  std::string node = "/stone";  // whose ~clear, ~place and ~remove are called
  double timeout_s = 10.0;      // to wait for those services
};

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// args without the program name (ROS remappings already taken out by ros::init). Throws
// UsageError with a one-line message naming the option, the value and the limit.
ReplayOptions parse_replay_options(const std::vector<std::string>& args);
std::string replay_usage();

}  // namespace replay
}  // namespace virtual_go
