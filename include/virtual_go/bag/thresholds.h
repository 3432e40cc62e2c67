// The limits bag_report --strict holds a recording to, and the checks against them.
//
// Physics bounds depend on the integrator named in ~info, its step h = dt, the segment's
// largest angular speed w and its duration T. The order p and the constants K_q, K_E, K_g are the
// integrator's entry in the registry (flight/integrator_registry.h; --help prints them):
//   orientation error  <= floor rad + K_q (h w)^p w T     (global error of an order-p method)
//   energy drift       <= floor + K_E (h w)^p (1 + w T)
//   momentum drift     <= floor (every core integrator keeps L_world as primary state)
//   position error     <= floor m + round-off |x|max + K_g |g| h T / 2
//                         (translation is exact in closed form except for the article's Euler)
//   | |q| - 1 |        <= floor
// floor = kBoundFloor, round-off = kPositionRoundOff. exact has K = 0, so the floor is the
// package's promise for it (docs/physics.md, "Error bounds"). Every bound can be replaced from
// the command line.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "virtual_go/bag/physics_check.h"
#include "virtual_go/bag/recording.h"
#include "virtual_go/bag/stamp_statistics.h"
#include "virtual_go/bag/stone_island.h"
#include "virtual_go/bag/stone_overlap.h"

namespace virtual_go {
namespace bag {

constexpr double kBoundFloor = 1e-9;         // round-off allowance of every figure
constexpr double kPositionRoundOff = 1e-12;  // per m of the segment's largest |x|

// The limits of the contact checks (docs/physics.md, "World": what holds everywhere), one row
// each: --help, the option parser, the checks and README.md's table (checked by
// test_bag_analysis) all read this table.
enum ContactLimitIndex : int {
  kEnergyRise = 0,  // contact segments: energy above the lowest so far
  kPenetration,     // every sample: depth below the board's top or the table
  kJellettDrift,    // flights, cap contact without rolling resistance or spinning friction
  kRestMoves,       // rest segments: samples that moved
  kOverlap,         // two stones at one stamp (~stones): penetration depth of the lenses
  kContactLimitCount
};

struct ContactLimit {
  const char* figure;  // the check's name, and the README table's first cell
  const char* option;  // overrides the default
  double default_limit;
  const char* unit;     // "relative", "m", "samples"
  const char* meaning;  // one line for --help
};
const ContactLimit& contact_limit(int index);

// The "default limits" section of --help, generated from the registry's constants and the
// contact limit table.
std::string default_limits_text();

struct LimitOverrides {
  std::optional<double> contact[kContactLimitCount];  // by ContactLimitIndex
  std::optional<double> orientation_error;            // rad
  std::optional<double> position_error;               // m
  std::optional<double> energy_drift;                 // relative
  std::optional<double> momentum_drift;               // relative
  std::optional<double> quat_norm_error;
  std::size_t max_gaps = 0;     // per periodic topic
  double rate_tolerance = 0.1;  // |mean rate / ~info rate - 1| for the node's periodic topics
};

struct PhysicsBounds {
  double orientation_error = 0.0;
  double position_error = 0.0;
  double energy_drift = 0.0;
  double momentum_drift = 0.0;
  double quat_norm_error = 0.0;
  std::string basis;  // how the bounds were obtained, for the report
};

// Throws InvalidArgument for an integrator name the registry does not know (unless every physics
// bound is overridden).
PhysicsBounds physics_bounds(const std::string& integrator, double dt_s,
                             const SegmentResult& segment, double gravity_norm,
                             const LimitOverrides& overrides);

struct Check {
  std::string figure;   // "orientation error", "repeated stamps", ...
  std::string subject;  // topic or segment it was measured on
  double value = 0.0;
  double limit = 0.0;
  bool pass = true;
  std::string basis;  // where the limit comes from
};

// One check per figure and periodic topic, and per physics figure the worst segment (largest
// value / limit) of every stone: the one of ~odom (physics) and the others of ~stones (stones).
// stats[i] belongs to recording.topics[i]. physics may be null (no ~info/~odom); overlap null
// without ~stones; islands null or empty: no island check (else one, on the worst island, held
// to the energy rise limit).
std::vector<Check> run_checks(const Recording& recording, const std::vector<StampStatistics>& stats,
                              const PhysicsResult* physics, const LimitOverrides& overrides,
                              const std::vector<StonePhysics>& stones = {},
                              const StoneOverlapResult* overlap = nullptr,
                              const StoneIslandResult* islands = nullptr);

}  // namespace bag
}  // namespace virtual_go
