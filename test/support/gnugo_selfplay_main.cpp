// gnugo_selfplay GNUGO SEED OUT.sgf: GNU Go plays a game against itself (level 1, Chinese
// rules, capturing every dead stone before it passes, so the end of the game has captures) and
// the moves are written as an SGF game record. The build runs it once per seed for
// test_gnugo_replay (test/go_tests.cmake); GNU Go's --seed makes the game repeatable.
//
// The GTP vertices are turned into SGF letters here, independently of the package's own
// conversions (go/go_point), which the test then checks against GNU Go reading the same file.
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

#include "support/gtp_engine.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: gnugo_selfplay GNUGO SEED OUT.sgf\n";
    return 2;
  }
  const std::string seed = argv[2];
  const std::string out_path = argv[3];
  const int max_moves = 400;
  try {
    virtual_go_test::GtpEngine gnugo({argv[1], "--mode", "gtp", "--level", "1", "--seed", seed,
                                      "--chinese-rules", "--capture-all-dead"});
    gnugo.command("boardsize 19");
    gnugo.command("clear_board");
    gnugo.command("komi 7.5");
    const std::string version = gnugo.command("version");
    std::string moves;
    int played = 0;
    int passes = 0;
    while (played < max_moves && passes < 2) {
      const bool black = played % 2 == 0;
      std::string vertex = gnugo.command(std::string("genmove ") + (black ? "black" : "white"));
      for (char& c : vertex) c = static_cast<char>(std::toupper(c));
      if (vertex == "RESIGN") break;
      const bool pass = vertex == "PASS";
      passes = pass ? passes + 1 : 0;
      moves += std::string(";") + (black ? "B" : "W") + "[" +
               (pass ? "" : virtual_go_test::sgf_letters_of_vertex(vertex)) + "]";
      if (++played % 12 == 0) moves += "\n";
    }
    const std::string player = "GNU Go " + version + " level 1 seed " + seed;
    const std::string temporary = out_path + ".part";
    {
      std::ofstream out(temporary);
      out << "(;FF[4]GM[1]SZ[19]KM[7.5]RU[Chinese]PB[" << player << "]PW[" << player << "]\n"
          << moves << ")\n";
      if (!out) throw std::runtime_error("cannot write " + temporary);
    }
    if (std::rename(temporary.c_str(), out_path.c_str()) != 0) {
      throw std::runtime_error("cannot write " + out_path + ": " + std::strerror(errno));
    }
    std::cout << "gnugo_selfplay: seed " << seed << ", " << played << " moves, captures by black "
              << gnugo.command("captures black") << ", by white " << gnugo.command("captures white")
              << " -> " << out_path << "\n";
  } catch (const std::exception& e) {
    std::cerr << "gnugo_selfplay: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
