#include "virtual_go/go/game_replay.h"

namespace virtual_go {

namespace {

void take_off(GoPosition& position, GoPoint point, std::vector<BoardAction>& actions) {
  if (const std::optional<StoneColor> there = position.at(point)) {
    actions.push_back({BoardAction::Kind::remove, point, *there});
    position.set(point, std::nullopt);
  }
}

void put_down(GoPosition& position, GoPoint point, StoneColor color,
              std::vector<BoardAction>& actions) {
  if (position.at(point) == color) return;  // already there
  take_off(position, point, actions);
  actions.push_back({BoardAction::Kind::place, point, color});
  position.set(point, color);
}

}  // namespace

ReplayStep apply_node(const SgfNode& node, int moves_before, GoPosition& position) {
  ReplayStep step;
  step.line = node.line;
  step.move_number = moves_before;
  // The setup lists hold distinct points (the reader refuses a point set twice in one node), so
  // their order does not change the position; taking stones off first frees the points.
  for (GoPoint p : node.add_empty) take_off(position, p, step.actions);
  for (GoPoint p : node.add_black) put_down(position, p, StoneColor::black, step.actions);
  for (GoPoint p : node.add_white) put_down(position, p, StoneColor::white, step.actions);
  if (!node.move) return step;
  step.move = node.move;
  ++step.move_number;
  if (!node.move->point) return step;  // a pass
  const GoPoint p = *node.move->point;
  const StoneColor color = node.move->color;
  // What play() does, as actions: it reports the stone it replaced, the captures and a suicide.
  step.outcome = position.play(color, p);
  if (step.outcome.replaced)
    step.actions.push_back({BoardAction::Kind::remove, p, *step.outcome.replaced});
  step.actions.push_back({BoardAction::Kind::place, p, color});
  for (GoPoint q : step.outcome.captured) {
    step.actions.push_back({BoardAction::Kind::remove, q, opponent(color)});
  }
  for (GoPoint q : step.outcome.suicide)
    step.actions.push_back({BoardAction::Kind::remove, q, color});
  return step;
}

std::vector<ReplayStep> replay_steps(const SgfGame& game, std::optional<int> last_move,
                                     GoPosition* position) {
  const int moves = game.move_count();
  if (last_move && (*last_move < 0 || *last_move > moves)) {
    throw InvalidArgument("to_move", "to_move: move " + std::to_string(*last_move) +
                                         " is not in the game, which has " + std::to_string(moves) +
                                         " moves (0 to " + std::to_string(moves) + ")");
  }
  GoPosition board;
  std::vector<ReplayStep> steps;
  int played = 0;
  for (const SgfNode& node : game.main_line) {
    // After move last_move every node belongs to later moves (setup too); before the first
    // move, setup nodes come along and the first node with a move stops.
    if (last_move && played == *last_move && (played > 0 || node.move)) break;
    steps.push_back(apply_node(node, played, board));
    played = steps.back().move_number;
  }
  if (position) *position = board;
  return steps;
}

}  // namespace virtual_go
