#include "support/gtp_engine.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace virtual_go_test {

GtpEngine::GtpEngine(const std::vector<std::string>& argv) {
  // A write to an engine that died must fail with EPIPE, not kill the test.
  ::signal(SIGPIPE, SIG_IGN);
  int to_child[2];
  int from_child[2];
  if (::pipe(to_child) != 0) throw std::runtime_error("gtp: pipe failed");
  if (::pipe(from_child) != 0) throw std::runtime_error("gtp: pipe failed");
  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error("gtp: fork failed");
  if (pid_ == 0) {
    ::dup2(to_child[0], STDIN_FILENO);
    ::dup2(from_child[1], STDOUT_FILENO);
    ::close(to_child[0]);
    ::close(to_child[1]);
    ::close(from_child[0]);
    ::close(from_child[1]);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  ::close(to_child[0]);
  ::close(from_child[1]);
  to_engine_ = ::fdopen(to_child[1], "w");
  from_engine_ = ::fdopen(from_child[0], "r");
  // The engine answers "name" with its name; an engine that did not start answers nothing.
  std::string name;
  if (!try_command("name", &name)) throw std::runtime_error("gtp: " + argv[0] + " did not start");
}

GtpEngine::~GtpEngine() {
  std::string ignored;
  try {
    try_command("quit", &ignored);
  } catch (const std::exception&) {
  }
  if (to_engine_) std::fclose(to_engine_);
  if (from_engine_) std::fclose(from_engine_);
  if (pid_ > 0) {
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
}

bool GtpEngine::try_command(const std::string& line, std::string* answer) {
  if (std::fprintf(to_engine_, "%s\n", line.c_str()) < 0 || std::fflush(to_engine_) != 0) {
    throw std::runtime_error("gtp: the engine is gone (writing '" + line + "')");
  }
  // An answer: "= text" or "? text", possibly more lines, ended by an empty line.
  std::string text;
  char status = 0;
  char* buffer = nullptr;
  std::size_t size = 0;
  while (true) {
    const ssize_t n = ::getline(&buffer, &size, from_engine_);
    if (n < 0) {
      std::free(buffer);
      throw std::runtime_error("gtp: the engine is gone (answering '" + line + "')");
    }
    std::string got(buffer, static_cast<std::size_t>(n));
    while (!got.empty() && (got.back() == '\n' || got.back() == '\r')) got.pop_back();
    if (status == 0) {
      if (got.empty()) continue;  // GTP allows empty lines before an answer
      status = got[0];
      got = got.size() > 2 ? got.substr(2) : "";
    } else if (got.empty()) {
      break;
    } else {
      text += '\n';
    }
    text += got;
  }
  std::free(buffer);
  *answer = text;
  return status == '=';
}

std::string GtpEngine::command(const std::string& line) {
  std::string answer;
  if (!try_command(line, &answer)) {
    throw std::runtime_error("gtp: '" + line + "' failed: " + answer);
  }
  return answer;
}

std::string sgf_letters_of_vertex(const std::string& vertex) {
  static const std::string columns = "ABCDEFGHJKLMNOPQRST";
  const std::size_t column =
      vertex.empty()
          ? std::string::npos
          : columns.find(static_cast<char>(std::toupper(static_cast<unsigned char>(vertex[0]))));
  const std::string digits = vertex.empty() ? "" : vertex.substr(1);
  const int row = digits.size() >= 1 && digits.size() <= 2 &&
                          digits.find_first_not_of("0123456789") == std::string::npos
                      ? std::stoi(digits)
                      : 0;
  if (column == std::string::npos || row < 1 || row > 19) {
    throw std::runtime_error("gtp: not a vertex: '" + vertex + "'");
  }
  return {static_cast<char>('a' + column), static_cast<char>('a' + 19 - row)};
}

std::vector<std::string> words(const std::string& answer) {
  std::istringstream in(answer);
  std::vector<std::string> out;
  std::string w;
  while (in >> w) out.push_back(w);
  return out;
}

}  // namespace virtual_go_test
