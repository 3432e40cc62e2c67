// bag_report: figures, a CSV and a plot from a rosbag of the virtual_go stone node.
// See --help and README.md, "Recording, replay and bag_report". Every failure is one line on stderr
// and an exit code.
#include <exception>
#include <iostream>

#include "virtual_go/bag/bag_reader.h"
#include "virtual_go/bag/options.h"
#include "virtual_go/bag/report.h"

namespace {

int run(const virtual_go::bag::Options& options) {
  using namespace virtual_go::bag;
  Report report;
  try {
    report = analyse(read_recording(options.bag_path, options.node_namespace), options.limits);
  } catch (const BagReadError& e) {
    std::cerr << "bag_report: " << e.what() << "\n";
    return kExitUnreadable;
  }
  print_report(std::cout, report);
  try {
    if (!options.csv_path.empty()) write_csv(options.csv_path, report);
    if (!options.plot_path.empty()) write_plot(options.plot_path, report, options.csv_path);
  } catch (const OutputError& e) {
    std::cerr << "bag_report: " << e.what() << "\n";
    return kExitOutput;
  }
  if (options.strict && !report.checks_pass()) return kExitChecksFailed;
  if (report.partial()) {
    std::cerr << "bag_report: partial report: " << report.problems.front() << "\n";
    return kExitIncomplete;
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace virtual_go::bag;
  try {
    const Options options = parse_options(std::vector<std::string>(argv + 1, argv + argc));
    if (options.help) {
      std::cout << usage_text();
      return kExitOk;
    }
    return run(options);
  } catch (const UsageError& e) {
    std::cerr << "bag_report: " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::exception& e) {
    // Nothing should get here; if it does, still one line and no core dump.
    std::cerr << "bag_report: unexpected error: " << e.what() << "\n";
    return kExitUnreadable;
  }
}
