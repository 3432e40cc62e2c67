// bag_report's figures from a Recording, and their outputs: text, CSV, gnuplot PNG.
#pragma once

#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "virtual_go/bag/physics_check.h"
#include "virtual_go/bag/recording.h"
#include "virtual_go/bag/stamp_statistics.h"
#include "virtual_go/bag/stone_island.h"
#include "virtual_go/bag/stone_overlap.h"
#include "virtual_go/bag/thresholds.h"

namespace virtual_go {
namespace bag {

struct Report {
  Recording recording;
  std::vector<StampStatistics> stats;    // one per recording.topics entry
  std::optional<PhysicsResult> physics;  // the stone of ~odom
  // Every other stone of ~stones (all of them when the bag has no ~odom), in the order ~stones
  // first names them; and the overlap of every pair at each ~stones message.
  std::vector<StonePhysics> stones;
  std::optional<StoneOverlapResult> overlap;
  // Stones linked by stone-stone contact events: the islands' total energy (stone_island.h).
  std::optional<StoneIslandResult> islands;
  std::vector<Check> checks;
  std::vector<std::string> problems;  // the recording's, plus what the analysis could not do
  bool partial() const { return !problems.empty(); }
  bool checks_pass() const;
};

// No I/O: everything below the rosbag reader.
Report analyse(Recording recording, const LimitOverrides& limits);

void print_report(std::ostream& out, const Report& report);

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws OutputError with a one-line message naming the file.
void write_csv(const std::string& path, const Report& report);
// Runs gnuplot on the time series (written to csv_path, a temporary file when empty).
void write_plot(const std::string& png_path, const Report& report, const std::string& csv_path);

}  // namespace bag
}  // namespace virtual_go
