// sgf_replay: replays an SGF game record onto a running stone node's board through its ~clear,
// ~place and ~remove services (README.md, "Go points and game records"). The record is read and
// played through Go's rules before the node is contacted, so a file that cannot be replayed
// changes nothing. The decisions are in replay/replay_runner (ROS-free, tested); this wires them.
#include <ros/ros.h>

#include <iostream>

#include "virtual_go/common/formatting.h"
#include "virtual_go/go/game_replay.h"
#include "virtual_go/replay/replay_options.h"
#include "virtual_go/replay/replay_runner.h"
#include "virtual_go/replay/ros_board_services.h"

namespace vg = virtual_go;
namespace rp = virtual_go::replay;

namespace {

int replay(int argc, char** argv) {
  // Takes the ROS remappings (name:=value) out of argv; contacts no master yet.
  ros::init(argc, argv, "sgf_replay", ros::init_options::AnonymousName);
  rp::ReplayOptions options;
  try {
    options = rp::parse_replay_options(std::vector<std::string>(argv + 1, argv + argc));
    std::string why;
    if (!options.help && !ros::names::validate(options.node, why)) {
      throw rp::UsageError("--node " + vg::quote_user_text(options.node) + ": not a ROS name (" +
                           why + ")");
    }
  } catch (const rp::UsageError& e) {
    std::cerr << "sgf_replay: " << e.what() << std::endl;
    return rp::kExitUsage;
  }
  if (options.help) {
    std::cout << rp::replay_usage();
    return rp::kExitOk;
  }

  vg::SgfGame game;
  std::vector<vg::ReplayStep> steps;
  try {
    game = vg::read_sgf_file(options.game_path);
    steps = vg::replay_steps(game, options.to_move);
  } catch (const vg::InvalidArgument& e) {
    if (e.field() == "to_move") {
      std::cerr << "sgf_replay: --to-move " << *options.to_move << ": " << options.game_path
                << " has " << game.move_count() << " moves" << std::endl;
    } else {
      std::cerr << "sgf_replay: " << e.what() << " (nothing was placed)" << std::endl;
    }
    return rp::kExitBadRecord;
  }
  std::cout << options.game_path << ": " << (game.black_player.empty() ? "?" : game.black_player)
            << " (black) - " << (game.white_player.empty() ? "?" : game.white_player) << " (white)"
            << (game.result.empty() ? "" : ", result " + game.result) << ", " << game.move_count()
            << " moves" << std::endl;

  if (!rp::wait_for_master(options.timeout_s)) {
    std::cerr << "sgf_replay: no ROS master at " << ros::master::getURI() << " after "
              << options.timeout_s << " s (nothing was placed)" << std::endl;
    return rp::kExitNoServices;
  }
  rp::RosBoardServices board(options.node);
  const std::vector<std::string> missing = board.wait_for_services(options.timeout_s);
  if (!missing.empty()) {
    std::cerr << "sgf_replay: the node's services are missing after " << options.timeout_s << " s:";
    for (const std::string& s : missing) std::cerr << " " << s;
    std::cerr << " (is the node " << ros::names::resolve(options.node)
              << " running with the board? --node names it; nothing was placed)" << std::endl;
    return rp::kExitNoServices;
  }
  const rp::ReplayResult result =
      rp::run_replay(steps, options.interval_s, options.drop_height_m, board, std::cout);
  if (result.exit_code != rp::kExitOk) std::cerr << "sgf_replay: " << result.error << std::endl;
  return result.exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  // Every expected failure has its exit code above; anything else (a ROS exception, memory) is
  // reported the same way, as a failed replay, rather than as an abort.
  try {
    return replay(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "sgf_replay: " << e.what() << std::endl;
    return rp::kExitServiceFailed;
  }
}
