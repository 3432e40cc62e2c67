// Go's rules for replaying a game record: a position on the 19 x 19 board, moves with captures,
// setup stones without. Pure and fast (an array of 361 points, groups found by flood fill); no
// legality checks: a record is replayed as written, as SGF prescribes.
//
// A move, as SGF's "How to execute a move" puts it (red-bean.com/sgf/go.html): the stone is put
// on its point whatever was there before (a stone already there is taken off: the record says the
// point now holds the mover's stone); then the opponent's groups adjacent to it that have no
// liberty are removed; then the mover's own group, if it has none (suicide). Only groups next to
// the new stone are checked, so a position set up without liberties (setup never captures) keeps
// its breathless stones until a move next to them takes them.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "virtual_go/go/go_point.h"
#include "virtual_go/go/stone_color.h"

namespace virtual_go {

// What a move did besides putting its stone down.
struct MoveOutcome {
  std::optional<StoneColor> replaced;  // the stone that was on the point, taken off first
  std::vector<GoPoint> captured;       // the opponent's stones removed, sorted
  std::vector<GoPoint> suicide;        // the mover's own group removed (the new stone among them)
};

class GoPosition {
 public:
  // The stone on a point, none when it is empty.
  std::optional<StoneColor> at(GoPoint point) const;
  // Setup (SGF's AB, AW, AE): the point holds `stone` afterwards; nothing else changes.
  void set(GoPoint point, std::optional<StoneColor> stone);
  // A move of `color` at `point` (see the file comment).
  MoveOutcome play(StoneColor color, GoPoint point);

  // The points holding `color`, sorted (row by row from A1).
  std::vector<GoPoint> stones(StoneColor color) const;
  int stone_count() const;
  // The liberties of the group on `point` (0 for an empty point).
  int liberties(GoPoint point) const;

  friend bool operator==(const GoPosition& a, const GoPosition& b) { return a.cells_ == b.cells_; }
  friend bool operator!=(const GoPosition& a, const GoPosition& b) { return !(a == b); }

 private:
  // The group on `index` and, through `liberty_count`, its number of distinct liberties.
  std::vector<int> group(int index, int* liberty_count) const;
  void remove(const std::vector<int>& indices, std::vector<GoPoint>* removed);

  std::array<std::int8_t, kGoLines * kGoLines> cells_{};  // 0 empty, 1 black, 2 white
};

}  // namespace virtual_go
