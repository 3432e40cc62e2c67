// The broad phase on the board's own grid (issue 15 item 9; ../shared/CONTACT.md §8): which pairs
// of stones can touch, before any exact distance or time of impact is computed.
//
// Every stone has axis-aligned bounds: a resting stone the box of its rim sphere (a lens lies
// within the sphere of its rim radius about its centre, in every orientation), a flying stone the
// box swept by that sphere over a time window. In flight the centre moves on a parabola,
// x(t) = x0 + v0 t + g t^2 / 2, so each axis's extremes over [0, T] are closed form: the two ends
// and, when 0 < -v0_i / g_i < T, the vertex. The bounds go into a uniform grid in the board's
// plane whose cells are the board's spacing (22 x 23.7 mm: a stone's bounds cover at most 2 x 2
// cells at rest). Candidate pairs are found from the awake stones only: each looks at the cells
// its bounds cover, so an awake-awake or awake-resting pair is found and a resting-resting pair is
// never looked at. A full resting board costs nothing; the work is the awake stones' neighbours.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace virtual_go {

struct Bounds {
  Eigen::Vector3d lower = Eigen::Vector3d::Zero(), upper = Eigen::Vector3d::Zero();  // world, m
  bool overlaps(const Bounds& o) const {
    return (lower.array() <= o.upper.array()).all() && (o.lower.array() <= upper.array()).all();
  }
};

// The box of the sphere of radius_m (m) about centre_world. Throws InvalidArgument ("centre",
// "radius") for non-finite input or a negative radius.
Bounds sphere_bounds(const Eigen::Vector3d& centre_world, double radius_m);

// The box swept over [0, duration_s] by the sphere of radius_m whose centre flies
// x(t) = x0 + v0 t + g t^2 / 2 (closed form: the ends and the vertex per axis). Throws
// InvalidArgument ("position", "velocity", "gravity", "duration", "radius") for non-finite input
// or a negative duration or radius.
Bounds swept_bounds(const Eigen::Vector3d& position_world, const Eigen::Vector3d& velocity_world,
                    const Eigen::Vector3d& gravity_world, double duration_s, double radius_m);

struct BroadPhaseCounters {
  long bound_tests = 0;  // pairs of bounds compared
  long cell_visits = 0;  // grid cells looked at by the queries
  long queries = 0;      // candidate_pairs calls
};

class BroadPhase {
 public:
  // Cells of cell_x_m x cell_y_m in the board's plane. Throws InvalidArgument ("cell_x",
  // "cell_y") unless both are positive and finite.
  BroadPhase(double cell_x_m, double cell_y_m);

  // Enters a stone (or moves it) with its bounds and whether it is awake. Throws InvalidArgument
  // ("bounds") for non-finite or inverted bounds, changing nothing.
  void update(std::size_t stone, const Bounds& bounds, bool awake);
  // Takes a stone out (nothing happens for a stone that is not in).
  void remove(std::size_t stone);
  bool contains(std::size_t stone) const {
    return stone < entries_.size() && entries_[stone].present;
  }

  // The pairs (a < b, sorted, each once) whose bounds overlap with at least one stone awake.
  std::vector<std::pair<std::size_t, std::size_t>> candidate_pairs();

  std::size_t awake_count() const { return awake_.size(); }
  const BroadPhaseCounters& counters() const { return counters_; }

 private:
  struct Entry {
    Bounds bounds;
    bool present = false, awake = false, large = false;
    std::int64_t ix0 = 0, ix1 = -1, iy0 = 0, iy1 = -1;  // cells covered (not for large ones)
    std::size_t awake_index = 0;                        // in awake_, when awake
    std::size_t large_index = 0;                        // in large_, when large
  };
  static std::uint64_t key(std::int64_t ix, std::int64_t iy);
  void unlink(std::size_t stone);

  double cell_x_, cell_y_;
  std::vector<Entry> entries_;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
  std::vector<std::size_t> awake_;
  // Stones whose bounds cover too many cells (a long flight) are kept in a list instead and
  // compared with every stone.
  std::vector<std::size_t> large_;
  BroadPhaseCounters counters_;
};

}  // namespace virtual_go
