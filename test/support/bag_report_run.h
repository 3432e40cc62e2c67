// Runs the bag_report executable as a user would (a shell command), for the tests that hold a
// bag to it: its exit code and what it printed.
#pragma once

#include <string>

namespace virtual_go_test {

struct ReportRun {
  int exit_code = -1;  // 128 + signal when it was killed
  std::string out;     // stdout
  std::string err;     // stderr
};

// The whole file as bytes ("" when it cannot be read).
std::string read_text(const std::string& path);

// `bag_report_path args`, its output captured in files of scratch_dir (which must exist).
ReportRun run_bag_report(const std::string& bag_report_path, const std::string& scratch_dir,
                         const std::string& args);

}  // namespace virtual_go_test
