// Command line of bag_report.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "virtual_go/bag/thresholds.h"

namespace virtual_go {
namespace bag {

// Exit codes (documented in --help and README.md, "Recording, replay and bag_report").
enum ExitCode : int {
  kExitOk = 0,            // report printed; with --strict every check passed
  kExitChecksFailed = 1,  // --strict and at least one figure over its limit
  kExitUsage = 2,         // bad command line
  kExitUnreadable = 3,    // missing file, not a bag, truncated beyond use
  kExitIncomplete = 4,    // partial report: empty bag, no ~info or ~odom, reading stopped early
  kExitOutput = 5,        // --csv or --plot could not be written
};

struct Options {
  bool help = false;
  std::string bag_path;
  std::string csv_path;   // empty: no CSV
  std::string plot_path;  // empty: no plot
  bool strict = false;
  std::string node_namespace = "/stone";
  LimitOverrides limits;
};

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// args without the program name. Throws UsageError with a one-line message.
Options parse_options(const std::vector<std::string>& args);
std::string usage_text();

}  // namespace bag
}  // namespace virtual_go
