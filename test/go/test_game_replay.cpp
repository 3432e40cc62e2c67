// A game record as actions on a physical board: each node's actions, performed on a separate
// model of the board (a map from point to stone that only puts stones on empty points and takes
// off the stone that is there), must leave exactly the position the rules give.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "virtual_go/go/game_replay.h"

namespace vg = virtual_go;

namespace {

using Kind = vg::BoardAction::Kind;

// A hand on a board: a stone can only be put on an empty point, and only a stone that is there
// can be taken off (of the colour the action names).
struct PhysicalBoard {
  std::map<vg::GoPoint, vg::StoneColor> stones;

  void perform(const vg::BoardAction& a) {
    if (a.kind == Kind::place) {
      ASSERT_EQ(stones.count(a.point), 0u) << "place onto " << vg::gtp_name(a.point);
      stones[a.point] = a.color;
    } else {
      ASSERT_EQ(stones.count(a.point), 1u) << "remove from empty " << vg::gtp_name(a.point);
      ASSERT_EQ(stones[a.point], a.color) << vg::gtp_name(a.point);
      stones.erase(a.point);
    }
  }

  bool same_as(const vg::GoPosition& position) const {
    for (int i = 0; i < 361; ++i) {
      const vg::GoPoint p = vg::point_at_index(i);
      const auto it = stones.find(p);
      const std::optional<vg::StoneColor> here =
          it == stones.end() ? std::nullopt : std::optional<vg::StoneColor>(it->second);
      if (here != position.at(p)) return false;
    }
    return true;
  }
};

std::string text(const std::vector<vg::BoardAction>& actions) {
  std::string out;
  for (const vg::BoardAction& a : actions) {
    out += std::string(a.kind == Kind::place ? "+" : "-") +
           (a.color == vg::StoneColor::black ? "B" : "W") + vg::gtp_name(a.point) + " ";
  }
  return out;
}

}  // namespace

TEST(GameReplay, ActionsOfEachKindOfNode) {
  const vg::SgfGame game = vg::parse_sgf(
      "(;FF[4]SZ[19]AB[aa][ab]AW[ba][ac]\n"  // A19, A18 black (breathless); B19, A17 white
      ";W[bb]\n"                             // W B18: takes A19-A18 (no liberty left)
      ";B[]\n"                               // a pass
      ";AE[ac]AW[aa]AB[ba][bb]\n"            // setup: A17 off, A19 white, B19 and B18 black
      ";B[ab]\n"                             // B A18: takes A19
      ";W[ab]\n"                             // W onto black A18: replaces it
      ";W[ss])");
  std::vector<vg::ReplayStep> steps = vg::replay_steps(game);
  ASSERT_EQ(steps.size(), 7u);
  EXPECT_EQ(text(steps[0].actions), "+BA19 +BA18 +WB19 +WA17 ");
  EXPECT_EQ(steps[0].move_number, 0);
  EXPECT_EQ(steps[0].line, 1);
  EXPECT_EQ(text(steps[1].actions), "+WB18 -BA18 -BA19 ");
  EXPECT_EQ(steps[1].move_number, 1);
  EXPECT_EQ(steps[1].line, 2);
  EXPECT_EQ(text(steps[2].actions), "");
  EXPECT_TRUE(steps[2].move && !steps[2].move->point);
  EXPECT_EQ(steps[2].move_number, 2);
  // AE first, then AB (B19 and B18 hold white: taken off, black put down), then AW.
  EXPECT_EQ(text(steps[3].actions), "-WA17 -WB19 +BB19 -WB18 +BB18 +WA19 ");
  EXPECT_EQ(steps[3].move_number, 2);
  EXPECT_EQ(text(steps[4].actions), "+BA18 -WA19 ");
  // White onto black A18: black taken off, white put down; it breathes at A19 and A17.
  EXPECT_EQ(text(steps[5].actions), "-BA18 +WA18 ");
  EXPECT_EQ(text(steps[6].actions), "+WT1 ");
  EXPECT_EQ(steps[6].move_number, 5);
}

TEST(GameReplay, SuicideIsPlacedThenTakenOff) {
  const vg::SgfGame game = vg::parse_sgf("(;AW[ba][ab];B[aa])");
  const std::vector<vg::ReplayStep> steps = vg::replay_steps(game);
  EXPECT_EQ(text(steps[1].actions), "+BA19 -BA19 ");
  EXPECT_EQ(steps[1].outcome.suicide.size(), 1u);
}

TEST(GameReplay, StopsAfterTheRequestedMove) {
  const vg::SgfGame game =
      vg::parse_sgf("(;AB[dd];W[aa];AW[ss];B[bb];W[cc]AB[ee];B[])");  // 4 moves
  vg::GoPosition position;
  EXPECT_EQ(vg::replay_steps(game, 0, &position).size(), 1u);  // the root's setup only
  EXPECT_EQ(position.stone_count(), 1);
  // Move 1, but not the setup node after it (it comes before move 2).
  EXPECT_EQ(vg::replay_steps(game, 1, &position).size(), 2u);
  EXPECT_EQ(position.stone_count(), 2);
  EXPECT_EQ(vg::replay_steps(game, 2, &position).size(), 4u);
  EXPECT_EQ(position.stone_count(), 4);
  EXPECT_EQ(vg::replay_steps(game, 3, &position).size(), 5u);  // W C17 with its AB E15
  EXPECT_EQ(position.stone_count(), 6);
  EXPECT_EQ(vg::replay_steps(game, 4).size(), 6u);
  EXPECT_EQ(vg::replay_steps(game).size(), 6u);
  for (int bad : {-1, 5}) {
    try {
      vg::replay_steps(game, bad);
      FAIL() << bad;
    } catch (const vg::InvalidArgument& e) {
      EXPECT_EQ(e.field(), "to_move");
      EXPECT_NE(std::string(e.what()).find("to_move: move " + std::to_string(bad) +
                                           " is not in the game, which has 4 moves (0 to 4)"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(GameReplay, ActionsOnAPhysicalBoardGiveTheRulesPositionAtEveryStep) {
  // Random records with setup nodes, passes, moves onto occupied points, captures and suicides.
  std::mt19937_64 rng(16);
  int actions = 0;
  int removals = 0;
  for (int game = 0; game < 20; ++game) {
    std::string sgf = "(;FF[4]SZ[19]";
    for (int node = 0; node < 500; ++node) {
      const auto point = [&] {
        return vg::sgf_name(vg::point_at_index(static_cast<int>(rng() % 361)));
      };
      const unsigned kind = rng() % 20;
      if (kind == 0) {
        sgf += ";AE[" + point() + "]";
      } else if (kind == 1) {
        // Distinct points, as the standard requires within a node.
        const std::string a = point();
        std::string b = point();
        while (b == a) b = point();
        sgf += ";AB[" + a + "]AW[" + b + "]";
      } else if (kind == 2) {
        sgf += std::string(";") + (node % 2 ? "W" : "B") + "[]";
      } else {
        sgf += std::string(";") + (node % 2 ? "W" : "B") + "[" + point() + "]";
      }
    }
    sgf += ")";
    const vg::SgfGame record = vg::parse_sgf(sgf);
    PhysicalBoard hand;
    vg::GoPosition rules;
    int moves = 0;
    for (const vg::SgfNode& node : record.main_line) {
      const vg::ReplayStep step = vg::apply_node(node, moves, rules);
      moves = step.move_number;
      for (const vg::BoardAction& a : step.actions) {
        hand.perform(a);
        ++actions;
        removals += a.kind == Kind::remove;
      }
      ASSERT_TRUE(hand.same_as(rules)) << "line " << node.line;
    }
    // replay_steps is the same walk.
    vg::GoPosition end;
    vg::replay_steps(record, {}, &end);
    EXPECT_EQ(end, rules);
  }
  EXPECT_GT(actions, 10000);
  EXPECT_GT(removals, 3000);
}
