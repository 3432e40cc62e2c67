#include "support/bag_report_run.h"

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace virtual_go_test {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

ReportRun run_bag_report(const std::string& bag_report_path, const std::string& scratch_dir,
                         const std::string& args) {
  const std::string out = scratch_dir + "/stdout.txt", err = scratch_dir + "/stderr.txt";
  const std::string cmd = bag_report_path + " " + args + " >" + out + " 2>" + err;
  const int status = std::system(cmd.c_str());
  ReportRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = read_text(out);
  r.err = read_text(err);
  return r;
}

}  // namespace virtual_go_test
