// sgf_replay's calls, made against a recording fake of the node's services: ~clear first, a
// ~place per stone put down (point, colour, drop height), a ~remove per stone taken off naming the
// stone ~place answered for that point, waits between moves only; a refused call stops the
// replay naming the move and the answer; an interruption stops it too.
#include <gtest/gtest.h>

#include <sstream>

#include "virtual_go/replay/replay_options.h"
#include "virtual_go/replay/replay_runner.h"

namespace vg = virtual_go;
namespace rp = virtual_go::replay;

namespace {

// Records every call as a line; answers ~place with names stone_1, stone_2, ... and can refuse
// the n-th call or stop at the n-th wait.
class RecordingBoard : public rp::BoardServices {
 public:
  std::vector<std::string> calls;
  int refuse_call = 0;  // 1-based; 0: never
  int stop_at_wait = 0;
  std::map<std::string, std::string> stones;  // name -> point, as the node would hold them

  rp::ServiceReply clear() override { return answer("clear"); }
  rp::ServiceReply place(const std::string& point, const std::string& color,
                         double drop_height_m) override {
    std::ostringstream line;
    line << "place " << point << " " << color << " " << drop_height_m;
    rp::ServiceReply r = answer(line.str());
    if (r.success) {
      r.name = "stone_" + std::to_string(++placed_);
      stones[r.name] = point;
    }
    return r;
  }
  rp::ServiceReply remove(const std::string& name) override {
    rp::ServiceReply r = answer("remove " + name);
    if (r.success) {
      EXPECT_EQ(stones.count(name), 1u) << name;
      stones.erase(name);
    }
    return r;
  }
  bool wait(double seconds) override {
    std::ostringstream line;
    line << "wait " << seconds;
    calls.push_back(line.str());
    return ++waits_ != stop_at_wait;
  }

 private:
  rp::ServiceReply answer(const std::string& call) {
    calls.push_back(call);
    if (static_cast<int>(calls.size()) == refuse_call) {
      return {false, "refused by the test", ""};
    }
    return {true, "ok", ""};
  }
  int placed_ = 0;
  int waits_ = 0;
};

std::vector<vg::ReplayStep> steps_of(const std::string& sgf) {
  return vg::replay_steps(vg::parse_sgf(sgf));
}

}  // namespace

TEST(ReplayRunner, CallsInOrderWithCapturesSetupAndPasses) {
  // Root with game information only (skipped), handicap setup, a capture, a pass, a suicide.
  const auto steps = steps_of(
      "(;FF[4]SZ[19]PB[b]PW[w];AB[ab][ba]AW[cb]\n"
      ";W[bb];B[aa]\n"  // W B18; B A19 (its group A19-B19-A18 breathes at C19)
      ";W[];B[cc])");
  RecordingBoard board;
  std::ostringstream log;
  const rp::ReplayResult r = rp::run_replay(steps, 0.5, 0.02, board, log);
  EXPECT_EQ(r.exit_code, rp::kExitOk) << r.error;
  const std::vector<std::string> expected = {
      "clear",
      "place A18 black 0.02",
      "place B19 black 0.02",
      "place C18 white 0.02",
      "wait 0.5",
      "place B18 white 0.02",
      "wait 0.5",
      "place A19 black 0.02",
      "wait 0.5",
      "wait 0.5",  // white passes
      "place C17 black 0.02",
  };
  EXPECT_EQ(board.calls, expected);
  EXPECT_EQ(r.moves, 4);
  EXPECT_EQ(r.placed, 6);
  EXPECT_EQ(r.removed, 0);
  EXPECT_EQ(r.stones.size(), 6u);
  EXPECT_NE(log.str().find("move 3 (line 3): white passes"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("replayed 4 moves: 6 stones placed, 0 removed, 6 on the board"),
            std::string::npos)
      << log.str();
}

TEST(ReplayRunner, CapturedStonesAreRemovedByTheNamesThePlaceCallsGave) {
  // White A19 alone in the corner; black B19, then A18 takes it; white back into A19 is a
  // suicide.
  const auto steps = steps_of("(;AW[aa];B[ba];W[jj];B[ab];W[aa])");
  RecordingBoard board;
  std::ostringstream log;
  const rp::ReplayResult r = rp::run_replay(steps, 0, 0, board, log);
  EXPECT_EQ(r.exit_code, rp::kExitOk) << r.error;
  const std::vector<std::string> expected = {
      "clear",
      "place A19 white 0",
      "wait 0",  // stone_1
      "place B19 black 0",
      "wait 0",  // stone_2
      "place K10 white 0",
      "wait 0",             // stone_3
      "place A18 black 0",  // stone_4: takes A19 ...
      "remove stone_1",
      "wait 0",
      "place A19 white 0",  // stone_5: W A19 back into the corner: a suicide
      "remove stone_5",
  };
  EXPECT_EQ(board.calls, expected);
  EXPECT_NE(log.str().find("move 3 (line 1): black A18, captures 1: A19"), std::string::npos)
      << log.str();
  EXPECT_NE(log.str().find("move 4 (line 1): white A19, suicide of 1: A19"), std::string::npos)
      << log.str();
  // What the fake node holds is what the replay says is on the board.
  EXPECT_EQ(board.stones.size(), r.stones.size());
  for (const auto& [point, stone] : r.stones) {
    EXPECT_EQ(board.stones.at(stone.first), vg::gtp_name(point));
  }
}

TEST(ReplayRunner, AMoveOntoAStoneTakesItOffFirst) {
  const auto steps = steps_of("(;B[jj];W[jj])");
  RecordingBoard board;
  std::ostringstream log;
  rp::run_replay(steps, 0, 0, board, log);
  EXPECT_EQ(board.calls, (std::vector<std::string>{"clear", "place K10 black 0", "wait 0",
                                                   "remove stone_1", "place K10 white 0"}));
  EXPECT_NE(log.str().find("white K10, onto a black stone (taken off first)"), std::string::npos);
}

TEST(ReplayRunner, ARefusedCallStopsTheReplayNamingTheMove) {
  const auto steps = steps_of("(;B[pd];W[dd];B[pp])");
  for (int refuse : {1, 4}) {
    RecordingBoard board;
    board.refuse_call = refuse;
    std::ostringstream log;
    const rp::ReplayResult r = rp::run_replay(steps, 0, 0.01, board, log);
    EXPECT_EQ(r.exit_code, rp::kExitServiceFailed);
    EXPECT_EQ(board.calls.size(), static_cast<std::size_t>(refuse));  // nothing after it
    if (refuse == 1) {
      EXPECT_EQ(r.error, "~clear failed: refused by the test");
    } else {
      EXPECT_EQ(r.error,
                "move 2 (line 1): white D16: ~place white at D16 failed: refused by the test");
    }
  }
}

TEST(ReplayRunner, AnInterruptedWaitStops) {
  const auto steps = steps_of("(;B[pd];W[dd];B[pp])");
  RecordingBoard board;
  board.stop_at_wait = 2;
  std::ostringstream log;
  const rp::ReplayResult r = rp::run_replay(steps, 1, 0, board, log);
  EXPECT_EQ(r.exit_code, rp::kExitInterrupted);
  EXPECT_EQ(r.error, "interrupted after move 2 (line 1): white D16");
  EXPECT_EQ(r.moves, 2);
}
