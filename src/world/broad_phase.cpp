#include "virtual_go/world/broad_phase.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "virtual_go/common/validation.h"

namespace virtual_go {
namespace {

// Bounds covering more cells than this (a flight across the board) go to the large list.
constexpr std::int64_t kMaxCells = 64;

void require_non_negative(const char* field, double value) {
  require_finite(field, value);
  if (value < 0.0) {
    throw InvalidArgument(field, std::string(field) + " must be >= 0, got " + format_value(value));
  }
}

}  // namespace

Bounds sphere_bounds(const Eigen::Vector3d& centre_world, double radius_m) {
  require_finite("centre", centre_world);
  require_non_negative("radius", radius_m);
  Bounds b;
  b.lower = centre_world.array() - radius_m;
  b.upper = centre_world.array() + radius_m;
  return b;
}

Bounds swept_bounds(const Eigen::Vector3d& position_world, const Eigen::Vector3d& velocity_world,
                    const Eigen::Vector3d& gravity_world, double duration_s, double radius_m) {
  require_finite("position", position_world);
  require_finite("velocity", velocity_world);
  require_finite("gravity", gravity_world);
  require_non_negative("duration", duration_s);
  require_non_negative("radius", radius_m);
  const double T = duration_s;
  Bounds b;
  for (int i = 0; i < 3; ++i) {
    const double x0 = position_world[i], v = velocity_world[i], g = gravity_world[i];
    const double end = x0 + v * T + 0.5 * g * T * T;
    double lo = std::min(x0, end), hi = std::max(x0, end);
    // The vertex, where the velocity v + g t along this axis vanishes inside the window.
    if (g != 0.0) {
      const double t = -v / g;
      if (t > 0.0 && t < T) {
        const double apex = x0 - 0.5 * v * v / g;
        lo = std::min(lo, apex);
        hi = std::max(hi, apex);
      }
    }
    b.lower[i] = lo - radius_m;
    b.upper[i] = hi + radius_m;
  }
  return b;
}

BroadPhase::BroadPhase(double cell_x_m, double cell_y_m) : cell_x_(cell_x_m), cell_y_(cell_y_m) {
  require_positive("cell_x", cell_x_m);
  require_positive("cell_y", cell_y_m);
}

std::uint64_t BroadPhase::key(std::int64_t ix, std::int64_t iy) {
  return (static_cast<std::uint64_t>(ix) << 32) ^ static_cast<std::uint32_t>(iy);
}

void BroadPhase::unlink(std::size_t stone) {
  Entry& e = entries_[stone];
  if (!e.present) return;
  if (e.large) {
    const std::size_t moved = large_.back();
    large_[e.large_index] = moved;
    entries_[moved].large_index = e.large_index;
    large_.pop_back();
  } else {
    for (std::int64_t ix = e.ix0; ix <= e.ix1; ++ix) {
      for (std::int64_t iy = e.iy0; iy <= e.iy1; ++iy) {
        auto cell = cells_.find(key(ix, iy));
        std::vector<std::size_t>& list = cell->second;
        list.erase(std::find(list.begin(), list.end(), stone));
        if (list.empty()) cells_.erase(cell);
      }
    }
  }
  if (e.awake) {
    const std::size_t moved = awake_.back();
    awake_[e.awake_index] = moved;
    entries_[moved].awake_index = e.awake_index;
    awake_.pop_back();
  }
  e.present = e.awake = e.large = false;
}

void BroadPhase::update(std::size_t stone, const Bounds& bounds, bool awake) {
  require_finite("bounds", bounds.lower);
  require_finite("bounds", bounds.upper);
  if (!(bounds.lower.array() <= bounds.upper.array()).all()) {
    throw InvalidArgument("bounds", "bounds: lower corner above the upper corner");
  }
  // Cell ranges as doubles first: far-away bounds must not overflow the integer cells.
  const double fx0 = std::floor(bounds.lower.x() / cell_x_),
               fx1 = std::floor(bounds.upper.x() / cell_x_);
  const double fy0 = std::floor(bounds.lower.y() / cell_y_),
               fy1 = std::floor(bounds.upper.y() / cell_y_);
  const bool large = (fx1 - fx0 + 1.0) * (fy1 - fy0 + 1.0) > static_cast<double>(kMaxCells) ||
                     std::abs(fx0) > 1e9 || std::abs(fx1) > 1e9 || std::abs(fy0) > 1e9 ||
                     std::abs(fy1) > 1e9;
  if (stone >= entries_.size()) entries_.resize(stone + 1);
  Entry& e = entries_[stone];
  // The same cells (or the large list again) and the same state: only the bounds change. An
  // awake stone is entered anew every pass, nearly always within the cells it covered before;
  // unlinking and relinking it cost a free and a malloc per cell (78% of a flying stone's
  // advance_to). The candidate pairs do not depend on the order within cells or lists.
  if (e.present && e.awake == awake && e.large == large &&
      (large ||
       (e.ix0 == static_cast<std::int64_t>(fx0) && e.ix1 == static_cast<std::int64_t>(fx1) &&
        e.iy0 == static_cast<std::int64_t>(fy0) && e.iy1 == static_cast<std::int64_t>(fy1)))) {
    e.bounds = bounds;
    return;
  }
  unlink(stone);
  e.bounds = bounds;
  e.present = true;
  e.large = large;
  if (large) {
    e.large_index = large_.size();
    large_.push_back(stone);
  } else {
    e.ix0 = static_cast<std::int64_t>(fx0);
    e.ix1 = static_cast<std::int64_t>(fx1);
    e.iy0 = static_cast<std::int64_t>(fy0);
    e.iy1 = static_cast<std::int64_t>(fy1);
    for (std::int64_t ix = e.ix0; ix <= e.ix1; ++ix) {
      for (std::int64_t iy = e.iy0; iy <= e.iy1; ++iy) cells_[key(ix, iy)].push_back(stone);
    }
  }
  e.awake = awake;
  if (awake) {
    e.awake_index = awake_.size();
    awake_.push_back(stone);
  }
}

void BroadPhase::remove(std::size_t stone) {
  if (stone < entries_.size()) unlink(stone);
}

std::vector<std::pair<std::size_t, std::size_t>> BroadPhase::candidate_pairs() {
  ++counters_.queries;
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  auto consider = [&](std::size_t a, std::size_t b) {
    if (a == b) return;
    ++counters_.bound_tests;
    if (entries_[a].bounds.overlaps(entries_[b].bounds))
      pairs.emplace_back(std::min(a, b), std::max(a, b));
  };
  for (const std::size_t a : awake_) {
    const Entry& e = entries_[a];
    if (e.large) {
      for (std::size_t b = 0; b < entries_.size(); ++b) {
        if (entries_[b].present) consider(a, b);
      }
      continue;
    }
    for (std::int64_t ix = e.ix0; ix <= e.ix1; ++ix) {
      for (std::int64_t iy = e.iy0; iy <= e.iy1; ++iy) {
        ++counters_.cell_visits;
        const auto cell = cells_.find(key(ix, iy));
        if (cell == cells_.end()) continue;
        for (const std::size_t b : cell->second) consider(a, b);
      }
    }
    for (const std::size_t b : large_) consider(a, b);
  }
  // Two awake stones meet from both sides, stones sharing several cells once per shared cell.
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace virtual_go
