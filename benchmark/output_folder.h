// The benchmarks' --out folder: made before anything runs, since a std::ofstream into a missing
// folder fails without a word and the run would end claiming files it never wrote.
#pragma once

#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>

namespace vg_bench {

// Creates `dir` (and its parents) when missing. False, after a message naming the program, the
// folder and the reason, when it cannot be made.
inline bool make_output_folder(const std::string& program, const std::string& dir) {
  std::error_code failed;
  std::filesystem::create_directories(dir, failed);
  if (failed) {
    std::cerr << program << ": --out " << dir << ": cannot create the folder (" << failed.message()
              << ")\n";
    return false;
  }
  return true;
}

}  // namespace vg_bench
