#include "virtual_go/go/go_point.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "virtual_go/common/formatting.h"
#include "virtual_go/common/validation.h"

namespace virtual_go {

namespace {

// GTP's column letters, A to T without I (I and J look alike).
constexpr char kGtpColumns[] = "ABCDEFGHJKLMNOPQRST";
static_assert(sizeof(kGtpColumns) - 1 == kGoLines, "one letter per line");

void require_on_grid(const char* what, GoPoint p) {
  if (!is_on_grid(p)) {
    throw InvalidArgument("point", std::string("point: ") + what + ": (column " +
                                       std::to_string(p.column) + ", row " + std::to_string(p.row) +
                                       ") is not on the 19 x 19 grid");
  }
}

void require_go_board(const BoardGeometry& board) {
  if (!has_go_points(board)) throw InvalidArgument("board", "board: " + no_go_points_reason(board));
}

// The index of the line nearest to offset d (m) from the centre line, lines `spacing` m apart, or
// -1 when d is more than half a spacing beyond the outer lines or not finite. The limit is
// compared in metres, as a caller computes it (9.5 * spacing).
int nearest_line(double d, double spacing) {
  const double half = 0.5 * (kGoLines - 1);  // 9: the outer lines
  if (!(std::abs(d) <= (half + 0.5) * spacing)) return -1;
  const double k = std::clamp(std::round(d / spacing), -half, half);  // halfway goes outwards
  return static_cast<int>(k + half);
}

}  // namespace

bool has_go_points(const BoardGeometry& board) { return board.lines == kGoLines; }

std::string no_go_points_reason(const BoardGeometry& board) {
  return "Go points need " + std::to_string(kGoLines) + " lines, the board has " +
         std::to_string(board.lines);
}

bool is_on_grid(GoPoint p) {
  return p.column >= 0 && p.column < kGoLines && p.row >= 0 && p.row < kGoLines;
}

int point_index(GoPoint p) {
  require_on_grid("point_index", p);
  return p.row * kGoLines + p.column;
}

GoPoint point_at_index(int index) {
  if (index < 0 || index >= kGoLines * kGoLines) {
    throw InvalidArgument("point", "point: index " + std::to_string(index) + " is not in 0 .. " +
                                       std::to_string(kGoLines * kGoLines - 1));
  }
  return {index % kGoLines, index / kGoLines};
}

GoPoint parse_gtp_point(const std::string& name) {
  auto refuse = [&]() -> GoPoint {
    throw InvalidArgument("point", "point: unknown Go point " + quote_user_text(name) +
                                       " (columns A-T without I, rows 1-19, e.g. A1, K10, T19)");
  };
  // A letter and one or two digits, the first digit not 0.
  if (name.size() < 2 || name.size() > 3) return refuse();
  const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
  const char* at = std::find(kGtpColumns, kGtpColumns + kGoLines, letter);
  if (at == kGtpColumns + kGoLines) return refuse();
  int number = 0;
  for (std::size_t k = 1; k < name.size(); ++k) {
    if (!std::isdigit(static_cast<unsigned char>(name[k]))) return refuse();
    number = 10 * number + (name[k] - '0');
  }
  if (name[1] == '0' || number < 1 || number > kGoLines) return refuse();
  return {static_cast<int>(at - kGtpColumns), number - 1};
}

std::string gtp_name(GoPoint p) {
  require_on_grid("gtp_name", p);
  return kGtpColumns[p.column] + std::to_string(p.row + 1);
}

GoPoint parse_sgf_point(const std::string& letters) {
  // SGF counts rows from the top: its row letter 'a' is GTP row 19.
  const auto in_range = [](char c) { return c >= 'a' && c < 'a' + kGoLines; };
  if (letters.size() != 2 || !in_range(letters[0]) || !in_range(letters[1])) {
    throw InvalidArgument("sgf point", "sgf point: " + quote_user_text(letters) +
                                           " is not a point of a 19 x 19 board (two letters "
                                           "a-s, column then row from the top left, e.g. dd)");
  }
  return {letters[0] - 'a', kGoLines - 1 - (letters[1] - 'a')};
}

std::string sgf_name(GoPoint p) {
  require_on_grid("sgf_name", p);
  return {static_cast<char>('a' + p.column), static_cast<char>('a' + (kGoLines - 1 - p.row))};
}

Eigen::Vector3d go_point_world(const BoardGeometry& board, GoPoint p) {
  require_go_board(board);
  require_on_grid("go_point_world", p);
  return board.point_world(p.column, p.row);
}

std::optional<GoPoint> nearest_go_point(const BoardGeometry& board,
                                        const Eigen::Vector3d& position_world) {
  require_go_board(board);
  // In spacings from tengen, the grid's centre, wherever point_world puts it.
  const Eigen::Vector3d tengen = board.point_world(kGoLines / 2, kGoLines / 2);
  const int column = nearest_line(position_world.x() - tengen.x(), board.spacing_x_m);
  const int row = nearest_line(position_world.y() - tengen.y(), board.spacing_y_m);
  if (column < 0 || row < 0) return std::nullopt;
  return GoPoint{column, row};
}

std::string nearest_go_point_name(const BoardGeometry& board,
                                  const Eigen::Vector3d& position_world) {
  const std::optional<GoPoint> p = nearest_go_point(board, position_world);
  return p ? gtp_name(*p) : std::string();
}

}  // namespace virtual_go
