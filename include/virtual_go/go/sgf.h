// A reader of Go game records in SGF (Smart Game Format, FF[3] and FF[4]; red-bean.com/sgf):
// the main line of the first game of a file, as the moves and setup stones a replay needs.
//
// Read: the main line (the first variation at every branch, as GNU Go's loadsgf and every SGF
// viewer take it); B and W moves, including passes ([] and, on 19 x 19, [tt]); the setup
// properties AB, AW and AE with point lists and FF[4]'s compressed rectangles ([aa:cc]); SZ (only
// 19, also as 19:19); HA; FF (1-4) and GM (1, Go); PB, PW and RE for messages. Skipped: every other
// property (comments, labels, times, ...), after its values were read with their escapes (\] and
// \\); variations, checked for syntax only; further games of a collection. FF[3] property names
// with lowercase letters ("AddBlack") are read by their capitals ("AB"), as FF[3] prescribes.
//
// A malformed file throws SgfError naming the line and column and what was wrong; nothing is
// returned partially.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "virtual_go/common/validation.h"
#include "virtual_go/go/go_point.h"
#include "virtual_go/go/stone_color.h"

namespace virtual_go {

struct SgfMove {
  StoneColor color = StoneColor::black;
  std::optional<GoPoint> point;  // none: a pass
};

// One node of the main line.
struct SgfNode {
  int line = 0;                    // of the node's ';' in the file, from 1
  std::vector<GoPoint> add_black;  // AB, compressed lists expanded, in file order
  std::vector<GoPoint> add_white;  // AW
  std::vector<GoPoint> add_empty;  // AE
  std::optional<SgfMove> move;     // B or W
};

struct SgfGame {
  int file_format = 1;             // FF; 1 when absent, as the standard says
  int handicap = 0;                // HA; 0 when absent (the stones themselves come as AB)
  std::string black_player;        // PB, "" when absent
  std::string white_player;        // PW
  std::string result;              // RE
  std::vector<SgfNode> main_line;  // the root node first

  // B and W properties on the main line, passes included.
  int move_count() const;
};

// A malformed file. what() is "<source>:<line>:<column>: <what was wrong>"; field() is "sgf".
class SgfError : public InvalidArgument {
 public:
  SgfError(const std::string& source, int line, int column, const std::string& what);
  int line() const { return line_; }
  int column() const { return column_; }

 private:
  int line_;
  int column_;
};

// The largest file read_sgf_file reads: a game is a few kB, a large collection a few MB.
constexpr std::size_t kMaxSgfBytes = 16u << 20;

// Parses SGF text. `source` names it in errors (a file name).
SgfGame parse_sgf(const std::string& text, const std::string& source = "sgf");
// Reads and parses a file; a file that cannot be read or is larger than kMaxSgfBytes throws
// InvalidArgument (field "sgf") naming the path and the cause or the limit.
SgfGame read_sgf_file(const std::string& path);

}  // namespace virtual_go
