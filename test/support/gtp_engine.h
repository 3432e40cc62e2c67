// A Go engine that speaks GTP (the Go Text Protocol, version 2), run as a child process and
// spoken to over pipes: GNU Go (`gnugo --mode gtp`) as the independent referee of the replay
// tests. Test support only.
#pragma once

#include <sys/types.h>

#include <cstdio>
#include <string>
#include <vector>

namespace virtual_go_test {

class GtpEngine {
 public:
  // argv[0] is the program's path. Throws std::runtime_error when it cannot be started.
  explicit GtpEngine(const std::vector<std::string>& argv);
  ~GtpEngine();
  GtpEngine(const GtpEngine&) = delete;
  GtpEngine& operator=(const GtpEngine&) = delete;

  // Sends one command and returns the answer without its "= " (lines joined by '\n'). Throws
  // std::runtime_error naming the command when the engine answers with an error ("? ...") or
  // has gone.
  std::string command(const std::string& line);
  // As command, but an engine error is returned as false with the answer in *answer.
  bool try_command(const std::string& line, std::string* answer);

 private:
  pid_t pid_ = -1;
  std::FILE* to_engine_ = nullptr;
  std::FILE* from_engine_ = nullptr;
};

// GTP vertex "Q16" -> SGF letters "pd" (columns A-T skip I; SGF rows count from the top), written
// here independently of the package's go/go_point so tests can hold that to GNU Go. Throws
// std::runtime_error for anything else.
std::string sgf_letters_of_vertex(const std::string& vertex);

// The words of a GTP answer ("A19 B19 C18" -> {"A19", "B19", "C18"}).
std::vector<std::string> words(const std::string& answer);

}  // namespace virtual_go_test
