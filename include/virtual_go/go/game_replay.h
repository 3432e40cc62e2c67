// A game record replayed on a physical board: what a hand (or the simulator's ~place and
// ~remove) does for each node of the main line, in order.
//
// Per node: setup first (SGF allows setup and a move in one node in FF[3]; setup never captures):
// AE takes stones off, AB and AW put stones down (taking off a stone of the other colour first;
// a stone of the same colour stays). Then the move: a stone already on its point is taken off,
// the mover's stone is put down, the captured stones are taken off, and then the mover's own
// group if it was a suicide (the new stone among them). A pass does nothing on the board.
#pragma once

#include <optional>
#include <vector>

#include "virtual_go/go/go_position.h"
#include "virtual_go/go/sgf.h"

namespace virtual_go {

struct BoardAction {
  enum class Kind { place, remove };
  Kind kind = Kind::place;
  GoPoint point;
  StoneColor color = StoneColor::black;  // of the stone put down or taken off

  friend bool operator==(const BoardAction& a, const BoardAction& b) {
    return a.kind == b.kind && a.point == b.point && a.color == b.color;
  }
};

struct ReplayStep {
  int line = 0;                      // the node's line in the file
  int move_number = 0;               // moves played up to and including this node
  std::optional<SgfMove> move;       // the node's move, if it has one
  MoveOutcome outcome;               // of the move (empty without one)
  std::vector<BoardAction> actions;  // in the order to perform them
};

// Applies one node to `position` and returns its step; `moves_before` counts the earlier moves.
ReplayStep apply_node(const SgfNode& node, int moves_before, GoPosition& position);

// The steps of the main line from an empty board, up to and including the node of move
// `last_move` (every node when none; 0: only the setup before the first move). A `last_move`
// beyond the game's moves throws InvalidArgument (field "to_move") naming both numbers.
// `position`, when given, receives the position after the last step.
std::vector<ReplayStep> replay_steps(const SgfGame& game, std::optional<int> last_move = {},
                                     GoPosition* position = nullptr);

}  // namespace virtual_go
