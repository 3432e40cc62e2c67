// sgf_replay without ROS: the calls that put a game record onto the simulator's board, in order,
// made through an interface the executable implements with ROS service clients (and tests with a
// recording fake). Decides every call; knows nothing of ROS.
#pragma once

#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "virtual_go/go/game_replay.h"

namespace virtual_go {
namespace replay {

// A service's answer. `name` is ~place's: the new stone's name.
struct ServiceReply {
  bool success = false;
  std::string message;
  std::string name;
};

// The node's services (std_srvs/Trigger ~clear, virtual_go/PlaceStone ~place with a point,
// virtual_go/RemoveStone ~remove by name) and the pause between moves. An implementation turns a
// call that could not be made (the node gone) into success = false with a message saying so.
class BoardServices {
 public:
  virtual ~BoardServices() = default;
  virtual ServiceReply clear() = 0;
  virtual ServiceReply place(const std::string& point, const std::string& color,
                             double drop_height_m) = 0;
  virtual ServiceReply remove(const std::string& name) = 0;
  // Waits `seconds` of wall time; false when the replay must stop (Ctrl-C, ROS shutdown).
  virtual bool wait(double seconds) = 0;
};

struct ReplayResult {
  int exit_code = 0;  // kExitOk, kExitServiceFailed or kExitInterrupted
  std::string error;  // the failure, naming the move, its line, the call and the answer
  int moves = 0;      // moves played (passes included)
  int placed = 0;     // stones put down
  int removed = 0;    // stones taken off
  std::map<GoPoint, std::pair<std::string, StoneColor>> stones;  // on the board: name, colour
};

// Calls ~clear, then performs each step's actions: ~place with the point's GTP name, the colour
// and drop_height_m (the answer's name is remembered for the point), ~remove with the name of the
// stone on a point. Waits interval_s after each step that did something or was a move, except
// the last. Stops at the first refused or failed call. Writes one line per step to `log`.
ReplayResult run_replay(const std::vector<ReplayStep>& steps, double interval_s,
                        double drop_height_m, BoardServices& board, std::ostream& log);

}  // namespace replay
}  // namespace virtual_go
