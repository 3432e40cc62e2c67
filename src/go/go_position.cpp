#include "virtual_go/go/go_position.h"

#include <algorithm>

namespace virtual_go {

namespace {

constexpr int kPoints = kGoLines * kGoLines;

std::int8_t cell_of(std::optional<StoneColor> stone) {
  if (!stone) return 0;
  return *stone == StoneColor::black ? 1 : 2;
}

std::optional<StoneColor> stone_of(std::int8_t cell) {
  if (cell == 0) return std::nullopt;
  return cell == 1 ? StoneColor::black : StoneColor::white;
}

// The up to four neighbours of a point index; returns how many.
int neighbours(int index, std::array<int, 4>& out) {
  const int column = index % kGoLines;
  const int row = index / kGoLines;
  int n = 0;
  if (column > 0) out[n++] = index - 1;
  if (column < kGoLines - 1) out[n++] = index + 1;
  if (row > 0) out[n++] = index - kGoLines;
  if (row < kGoLines - 1) out[n++] = index + kGoLines;
  return n;
}

}  // namespace

std::optional<StoneColor> GoPosition::at(GoPoint point) const {
  return stone_of(cells_[point_index(point)]);
}

void GoPosition::set(GoPoint point, std::optional<StoneColor> stone) {
  cells_[point_index(point)] = cell_of(stone);
}

std::vector<int> GoPosition::group(int start, int* liberty_count) const {
  const std::int8_t color = cells_[start];
  std::vector<int> members{start};
  std::array<bool, kPoints> visited{};
  std::array<bool, kPoints> liberty{};
  visited[start] = true;
  int liberties = 0;
  std::array<int, 4> next{};
  for (std::size_t k = 0; k < members.size(); ++k) {
    const int count = neighbours(members[k], next);
    for (int m = 0; m < count; ++m) {
      const int q = next[m];
      if (cells_[q] == 0) {
        if (!liberty[q]) {
          liberty[q] = true;
          ++liberties;
        }
      } else if (cells_[q] == color && !visited[q]) {
        visited[q] = true;
        members.push_back(q);
      }
    }
  }
  if (liberty_count) *liberty_count = liberties;
  return members;
}

void GoPosition::remove(const std::vector<int>& indices, std::vector<GoPoint>* removed) {
  for (int i : indices) {
    cells_[i] = 0;
    removed->push_back(point_at_index(i));
  }
}

MoveOutcome GoPosition::play(StoneColor color, GoPoint point) {
  const int index = point_index(point);
  MoveOutcome outcome;
  outcome.replaced = stone_of(cells_[index]);
  cells_[index] = cell_of(color);
  // Opponent groups next to the stone without a liberty. A group touching the stone on two sides
  // is met twice: the first visit empties it, so the second finds an empty point.
  const std::int8_t them = cell_of(opponent(color));
  std::array<int, 4> next{};
  const int count = neighbours(index, next);
  for (int m = 0; m < count; ++m) {
    if (cells_[next[m]] != them) continue;
    int liberties = 0;
    const std::vector<int> members = group(next[m], &liberties);
    if (liberties == 0) remove(members, &outcome.captured);
  }
  int own_liberties = 0;
  const std::vector<int> own = group(index, &own_liberties);
  if (own_liberties == 0) remove(own, &outcome.suicide);
  std::sort(outcome.captured.begin(), outcome.captured.end());
  std::sort(outcome.suicide.begin(), outcome.suicide.end());
  return outcome;
}

std::vector<GoPoint> GoPosition::stones(StoneColor color) const {
  std::vector<GoPoint> points;
  const std::int8_t cell = cell_of(color);
  for (int i = 0; i < kPoints; ++i) {
    if (cells_[i] == cell) points.push_back(point_at_index(i));
  }
  return points;
}

int GoPosition::stone_count() const {
  return static_cast<int>(
      std::count_if(cells_.begin(), cells_.end(), [](std::int8_t c) { return c != 0; }));
}

int GoPosition::liberties(GoPoint point) const {
  const int index = point_index(point);
  if (cells_[index] == 0) return 0;
  int liberties = 0;
  group(index, &liberties);
  return liberties;
}

}  // namespace virtual_go
