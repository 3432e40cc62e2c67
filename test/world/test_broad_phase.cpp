// The broad phase on the board's grid (issue 15 item 9): swept bounds against a dense sampling of
// the flight's parabola written here (every sample inside, every face reached), candidate pairs
// against brute force over all pairs (awake-awake and awake-resting, never resting-resting), after
// random moves, wakes, sleeps and removals; a fully resting board is never looked at.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "virtual_go/common/validation.h"
#include "virtual_go/world/broad_phase.h"

namespace {

namespace vg = virtual_go;
using Eigen::Vector3d;

constexpr double kSpacingX = 0.022, kSpacingY = 0.0237;  // the board's grid, m
constexpr double kRim = 0.0111;                          // a black stone's rim radius, m

TEST(BroadPhase, SweptBoundsHoldTheFlightAndAreTight) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst_outside = 0, worst_slack = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const Vector3d x0(0.2 * u(rng), 0.2 * u(rng), 0.05 + 0.05 * u(rng));
    const Vector3d v0(2 * u(rng), 2 * u(rng), 3 * u(rng));
    // Earth's gravity, sometimes tilted, sometimes none (the bounds hold for any constant g).
    const Vector3d g = trial % 5 == 0 ? Vector3d::Zero() : Vector3d(u(rng), u(rng), -9.80665);
    const double T = 0.3 * std::abs(u(rng));
    const vg::Bounds b = vg::swept_bounds(x0, v0, g, T, kRim);
    // The test's own sampling of the centre's parabola, 20 001 points.
    Vector3d lo = x0, hi = x0;
    for (int k = 0; k <= 20000; ++k) {
      const double t = T * k / 20000.0;
      const Vector3d x = x0 + v0 * t + 0.5 * g * t * t;
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
    for (int i = 0; i < 3; ++i) {
      worst_outside =
          std::max({worst_outside, b.lower[i] + kRim - lo[i], hi[i] - (b.upper[i] - kRim)});
      // Tight: the sampled extremes reach the faces to within the sampling's resolution.
      worst_slack =
          std::max({worst_slack, lo[i] - (b.lower[i] + kRim), (b.upper[i] - kRim) - hi[i]});
    }
  }
  EXPECT_LE(worst_outside, 1e-15);
  EXPECT_LE(worst_slack, 1e-9);  // (v T / 20000)^2 g / 8 at most, ~1e-11 m here
  // The apex of a vertical throw: v^2 / (2 g) above the start.
  const vg::Bounds up =
      vg::swept_bounds(Vector3d::Zero(), Vector3d(0, 0, 1), Vector3d(0, 0, -10), 1.0, 0.0);
  EXPECT_DOUBLE_EQ(up.upper.z(), 0.05);
  EXPECT_DOUBLE_EQ(up.lower.z(), 1.0 - 5.0);
}

// Brute force: every pair with at least one awake stone whose boxes overlap (the test's own test).
std::set<std::pair<std::size_t, std::size_t>> brute_force(const std::vector<vg::Bounds>& b,
                                                          const std::vector<char>& present,
                                                          const std::vector<char>& awake) {
  auto overlap = [](const vg::Bounds& p, const vg::Bounds& q) {
    for (int i = 0; i < 3; ++i) {
      if (p.upper[i] < q.lower[i] || q.upper[i] < p.lower[i]) return false;
    }
    return true;
  };
  std::set<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t i = 0; i < b.size(); ++i) {
    for (std::size_t j = i + 1; j < b.size(); ++j) {
      if (present[i] && present[j] && (awake[i] || awake[j]) && overlap(b[i], b[j])) {
        out.emplace(i, j);
      }
    }
  }
  return out;
}

// n stones in a grid, with what brute force compares against, and the random numbers.
struct Scene {
  Scene(std::size_t n, unsigned seed) : rng(seed), bounds(n), present(n, 0), awake(n, 0) {}
  std::mt19937 rng;
  std::uniform_real_distribution<double> u{-1.0, 1.0};
  vg::BroadPhase grid{kSpacingX, kSpacingY};
  std::vector<vg::Bounds> bounds;
  std::vector<char> present, awake;
};

TEST(BroadPhase, CandidatePairsAreExactlyTheBruteForceOnes) {
  const std::size_t n = 361;
  Scene scene(n, 15);
  auto& [rng, u, grid, bounds, present, awake] = scene;
  auto place = [&](std::size_t i) {
    // Resting stones near grid points (neighbours touch or overlap), awake ones anywhere with a
    // swept box, a few of them across much of the board (the large list).
    const bool is_awake = u(rng) > 0.6;
    if (is_awake) {
      const Vector3d x0(0.21 * u(rng), 0.22 * u(rng), 0.02 + 0.02 * u(rng));
      const double T = u(rng) > 0.9 ? 0.3 : 0.01 * std::abs(u(rng));
      bounds[i] =
          vg::swept_bounds(x0, Vector3d(u(rng), u(rng), u(rng)), Vector3d(0, 0, -9.80665), T, kRim);
    } else {
      const int col = static_cast<int>(i % 19), row = static_cast<int>(i / 19);
      const Vector3d x((col - 9) * kSpacingX + 0.002 * u(rng),
                       (row - 9) * kSpacingY + 0.002 * u(rng), 0.0046);
      bounds[i] = vg::sphere_bounds(x, kRim);
    }
    grid.update(i, bounds[i], is_awake);
    present[i] = 1;
    awake[i] = is_awake;
  };
  for (std::size_t i = 0; i < n; ++i) place(i);
  long compared = 0;
  for (int round = 0; round < 30; ++round) {
    const auto pairs = grid.candidate_pairs();
    const std::set<std::pair<std::size_t, std::size_t>> found(pairs.begin(), pairs.end());
    ASSERT_EQ(found.size(), pairs.size()) << "a pair reported twice";
    ASSERT_EQ(found, brute_force(bounds, present, awake)) << "round " << round;
    compared += static_cast<long>(pairs.size());
    // Moves, wakes, sleeps and removals.
    for (int k = 0; k < 40; ++k) {
      const std::size_t i = static_cast<std::size_t>(std::abs(u(rng)) * (n - 1));
      if (u(rng) > 0.8) {
        grid.remove(i);
        present[i] = awake[i] = 0;
      } else {
        place(i);
      }
    }
  }
  EXPECT_GT(compared, 1000);  // the comparison saw many pairs
  std::printf(
      "[ pairs   ] 30 rounds of 361 stones: %ld candidate pairs, all equal to brute force; "
      "%ld bound tests, %ld cell visits\n",
      compared, grid.counters().bound_tests, grid.counters().cell_visits);
}

// An awake stone is entered again every pass, mostly within the cells it covered (update then
// changes only its bounds): tiny moves that make and break overlaps inside the same cells, and
// now and then a wake, a sleep or a jump to other cells, keep the pairs those of brute force.
TEST(BroadPhase, SmallMovesWithinTheSameCellsKeepThePairsExact) {
  const std::size_t n = 60;
  Scene scene(n, 28);
  auto& [rng, u, grid, bounds, present, awake] = scene;
  present.assign(n, 1);
  std::vector<Vector3d> centre(n);
  for (std::size_t i = 0; i < n; ++i) {
    // A 6 x 10 block, neighbours' boxes 0.2 mm apart to 0.2 mm overlapping.
    centre[i] = Vector3d((static_cast<int>(i % 6) - 3) * 2 * kRim + 2e-4 * u(rng),
                         (static_cast<int>(i / 6) - 5) * 2 * kRim + 2e-4 * u(rng), 0.0046);
    awake[i] = u(rng) > 0.3;
    bounds[i] = vg::sphere_bounds(centre[i], kRim);
    grid.update(i, bounds[i], awake[i]);
  }
  long changes = 0;
  for (int round = 0; round < 400; ++round) {
    const auto pairs = grid.candidate_pairs();
    const std::set<std::pair<std::size_t, std::size_t>> found(pairs.begin(), pairs.end());
    ASSERT_EQ(found, brute_force(bounds, present, awake)) << "round " << round;
    const std::size_t before = found.size();
    for (std::size_t i = 0; i < n; ++i) {
      const double r = u(rng);
      if (r > 0.95) awake[i] = !awake[i];
      const double step = r < -0.95 ? 0.03 : 2e-4;  // mostly within the cells, now and then not
      centre[i] += Vector3d(step * u(rng), step * u(rng), 0.0);
      bounds[i] = vg::sphere_bounds(centre[i], kRim * (1.0 + 0.01 * u(rng)));
      grid.update(i, bounds[i], awake[i]);
    }
    const auto next = grid.candidate_pairs();
    changes += std::abs(static_cast<long>(next.size()) - static_cast<long>(before));
  }
  EXPECT_GT(changes, 100);  // overlaps were made and broken
}

TEST(BroadPhase, AFullRestingBoardIsNeverLookedAt) {
  vg::BroadPhase grid(kSpacingX, kSpacingY);
  for (std::size_t i = 0; i < 361; ++i) {
    const Vector3d x((static_cast<int>(i % 19) - 9) * kSpacingX,
                     (static_cast<int>(i / 19) - 9) * kSpacingY, 0.0046);
    grid.update(i, vg::sphere_bounds(x, kRim), false);  // neighbours' boxes overlap: 22 < 22.2
  }
  for (int k = 0; k < 1000; ++k) EXPECT_TRUE(grid.candidate_pairs().empty());
  EXPECT_EQ(grid.counters().bound_tests, 0);
  EXPECT_EQ(grid.counters().cell_visits, 0);
  // One stone wakes in the middle (point 180, K10): only its neighbourhood is looked at, and its
  // two neighbours along the row are its candidates (22 mm apart, their boxes 22.2 mm wide
  // overlap; along the column 23.7 mm apart they do not).
  const Vector3d centre(0, 0, 0.0046);
  grid.update(180, vg::sphere_bounds(centre, kRim), true);
  const auto pairs = grid.candidate_pairs();
  const std::vector<std::pair<std::size_t, std::size_t>> expected = {{179, 180}, {180, 181}};
  EXPECT_EQ(pairs, expected);
  // Its box covers 2 x 2 cells, each holding at most 4 stones' boxes.
  EXPECT_LE(grid.counters().bound_tests, 4 * 4);
  std::printf(
      "[ board   ] 361 resting: 1000 queries, 0 bound tests; one awake: %ld bound tests, "
      "%ld cell visits\n",
      grid.counters().bound_tests, grid.counters().cell_visits);
}

TEST(BroadPhase, BadInputIsRefusedByNameAndChangesNothing) {
  EXPECT_THROW(vg::BroadPhase(0.0, kSpacingY), vg::InvalidArgument);
  vg::BroadPhase grid(kSpacingX, kSpacingY);
  grid.update(0, vg::sphere_bounds(Vector3d::Zero(), kRim), true);
  vg::Bounds bad = vg::sphere_bounds(Vector3d(0.001, 0, 0), kRim);
  bad.lower.x() = std::nan("");
  try {
    grid.update(1, bad, true);
    FAIL();
  } catch (const vg::InvalidArgument& e) {
    EXPECT_EQ(e.field(), "bounds");
  }
  EXPECT_FALSE(grid.contains(1));
  EXPECT_TRUE(grid.candidate_pairs().empty());
  try {
    vg::swept_bounds(Vector3d::Zero(), Vector3d::Zero(), Vector3d::Zero(), -1.0, kRim);
    FAIL();
  } catch (const vg::InvalidArgument& e) {
    EXPECT_EQ(e.field(), "duration");
  }
}

}  // namespace
