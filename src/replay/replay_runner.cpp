#include "virtual_go/replay/replay_runner.h"

#include "virtual_go/replay/replay_options.h"

namespace virtual_go {
namespace replay {

namespace {

std::string point_list(const std::vector<GoPoint>& points) {
  std::string out;
  for (GoPoint p : points) out += " " + gtp_name(p);
  return out;
}

// "move 57 (line 12): black Q16, captures 2: R16 R17" or "setup (line 1)".
std::string describe(const ReplayStep& step) {
  std::string out = step.move ? "move " + std::to_string(step.move_number) : std::string("setup");
  out += " (line " + std::to_string(step.line) + ")";
  if (!step.move) return out;
  out += ": " + stone_color_name(step.move->color);
  if (!step.move->point) return out + " passes";
  out += " " + gtp_name(*step.move->point);
  if (step.outcome.replaced) {
    out += ", onto a " + stone_color_name(*step.outcome.replaced) + " stone (taken off first)";
  }
  if (!step.outcome.captured.empty()) {
    out += ", captures " + std::to_string(step.outcome.captured.size()) + ":" +
           point_list(step.outcome.captured);
  }
  if (!step.outcome.suicide.empty()) {
    out += ", suicide of " + std::to_string(step.outcome.suicide.size()) + ":" +
           point_list(step.outcome.suicide);
  }
  return out;
}

}  // namespace

ReplayResult run_replay(const std::vector<ReplayStep>& steps, double interval_s,
                        double drop_height_m, BoardServices& board, std::ostream& log) {
  ReplayResult result;
  auto fail = [&](const std::string& what) {
    result.exit_code = kExitServiceFailed;
    result.error = what;
    return result;
  };
  const ServiceReply cleared = board.clear();
  if (!cleared.success) return fail("~clear failed: " + cleared.message);
  log << "board cleared" << std::endl;

  // A step that neither moves nor acts (a root holding only game information) is skipped; the
  // last step that does is not followed by a wait.
  const auto counts = [](const ReplayStep& s) { return s.move || !s.actions.empty(); };
  std::size_t last = steps.size();
  for (std::size_t i = 0; i < steps.size(); ++i) {
    if (counts(steps[i])) last = i;
  }
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const ReplayStep& step = steps[i];
    if (!counts(step)) continue;
    const std::string what = describe(step);
    for (const BoardAction& a : step.actions) {
      const std::string point = gtp_name(a.point);
      const std::string& color = stone_color_name(a.color);
      if (a.kind == BoardAction::Kind::place) {
        const ServiceReply reply = board.place(point, color, drop_height_m);
        if (!reply.success || reply.name.empty()) {
          return fail(what + ": ~place " + color + " at " + point +
                      " failed: " + (reply.success ? "the answer names no stone" : reply.message));
        }
        result.stones[a.point] = {reply.name, a.color};
        ++result.placed;
      } else {
        // The actions take off only stones they put down (game_replay's contract).
        const auto it = result.stones.find(a.point);
        if (it == result.stones.end()) {
          return fail(what + ": no stone of this replay is known at " + point);
        }
        const ServiceReply reply = board.remove(it->second.first);
        if (!reply.success) {
          return fail(what + ": ~remove " + it->second.first + " (" + color + " at " + point +
                      ") failed: " + reply.message);
        }
        result.stones.erase(it);
        ++result.removed;
      }
    }
    result.moves = step.move_number;
    log << what << std::endl;
    if (i != last && !board.wait(interval_s)) {
      result.exit_code = kExitInterrupted;
      result.error = "interrupted after " + what;
      return result;
    }
  }
  log << "replayed " << result.moves << " moves: " << result.placed << " stones placed, "
      << result.removed << " removed, " << result.stones.size() << " on the board" << std::endl;
  return result;
}

}  // namespace replay
}  // namespace virtual_go
