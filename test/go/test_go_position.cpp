// Go's rules as SGF executes a move (red-bean.com/sgf/go.html, and the worked examples of
// red-bean.com/sgf/ff5/m_vs_ax.htm): captures of adjacent groups without liberties, then
// suicide; setup without captures; a stone put on an occupied point. Hand-made positions with
// known outcomes, then the laws every move obeys over random games (stones conserved, no group
// without a liberty left after a move from a legal position).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "virtual_go/go/go_position.h"

namespace vg = virtual_go;

namespace {

vg::GoPoint at(const char* name) { return vg::parse_gtp_point(name); }

std::vector<std::string> names(const std::vector<vg::GoPoint>& points) {
  std::vector<std::string> out;
  for (vg::GoPoint p : points) out.push_back(vg::gtp_name(p));
  return out;
}

using S = std::vector<std::string>;

// A position from a diagram of the board's top-left corner as a Go diagram shows it: the first
// string is row 19, X black, O white, '.' empty, spaces ignored.
vg::GoPosition corner(const std::vector<std::string>& rows) {
  vg::GoPosition position;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    int column = 0;
    for (char c : rows[r]) {
      if (c == ' ') continue;
      const vg::GoPoint p{column++, 18 - static_cast<int>(r)};
      if (c == 'X') position.set(p, vg::StoneColor::black);
      if (c == 'O') position.set(p, vg::StoneColor::white);
    }
  }
  return position;
}

}  // namespace

TEST(GoPosition, OneStoneCapturedInTheCentreOnTheEdgeAndInTheCorner) {
  vg::GoPosition p;
  p.set(at("K10"), vg::StoneColor::white);
  for (const char* b : {"J10", "L10", "K11"}) p.set(at(b), vg::StoneColor::black);
  EXPECT_EQ(p.liberties(at("K10")), 1);
  vg::MoveOutcome o = p.play(vg::StoneColor::black, at("K9"));
  EXPECT_EQ(names(o.captured), S{"K10"});
  EXPECT_TRUE(o.suicide.empty());
  EXPECT_FALSE(o.replaced);
  EXPECT_FALSE(p.at(at("K10")));
  EXPECT_EQ(p.stone_count(), 4);

  vg::GoPosition edge = corner({". . . .", "X . . .", "O X . ."});  // A17 white, on the edge
  o = edge.play(vg::StoneColor::black, at("A16"));
  EXPECT_EQ(names(o.captured), S{"A17"});

  vg::GoPosition c = corner({"O X", ". ."});  // A19 white in the corner: two liberties
  EXPECT_EQ(c.liberties(at("A19")), 1);       // B19 is black: only A18 is left
  o = c.play(vg::StoneColor::black, at("A18"));
  EXPECT_EQ(names(o.captured), S{"A19"});
}

TEST(GoPosition, GroupsAndSeveralGroupsAtOnce) {
  // Two white groups (A19-B19 and A17) share the liberty A18; black A18 takes both.
  vg::GoPosition p = corner({
      "O O X",
      ". X .",
      "O X .",
      "X . .",
  });
  const vg::MoveOutcome o = p.play(vg::StoneColor::black, at("A18"));
  EXPECT_EQ(names(o.captured), (S{"A17", "A19", "B19"}));
  EXPECT_TRUE(o.suicide.empty());
  EXPECT_EQ(p.stones(vg::StoneColor::white).size(), 0u);
  // Black's group A18-B18-B17 now breathes at A19, B19, A17 (the captured points), C18, C17
  // and B16.
  EXPECT_EQ(p.liberties(at("A18")), 6);
}

TEST(GoPosition, CaptureComesBeforeSuicideAndKoIsNotForbidden) {
  // The ko shape. White B18 has one liberty, C18. Black C18 lands without a liberty of its own
  // (B18, D18, C19 and C17 are white) but takes B18 first: not a suicide.
  const vg::GoPosition start = corner({
      ". X O . .",
      "X O . O .",
      ". X O . .",
  });
  vg::GoPosition ko = start;
  vg::MoveOutcome o = ko.play(vg::StoneColor::black, at("C18"));
  EXPECT_EQ(names(o.captured), S{"B18"});
  EXPECT_TRUE(o.suicide.empty());
  EXPECT_EQ(ko.liberties(at("C18")), 1);  // its only liberty is B18
  // White takes back at once (a replay checks no ko rule): C18 goes, the start is back.
  o = ko.play(vg::StoneColor::white, at("B18"));
  EXPECT_EQ(names(o.captured), S{"C18"});
  EXPECT_EQ(ko, start);
}

TEST(GoPosition, SuicideOfAStoneAndOfAGroup) {
  // GNU Go's loadsgf does the same with this position (checked in test_gnugo_replay).
  vg::GoPosition p = corner({
      ". X O",
      "X O .",
      "O . .",
  });
  vg::MoveOutcome o = p.play(vg::StoneColor::black, at("A19"));
  // A19 joins B19 and A18: the group has no liberty and white has none in atari: suicide.
  EXPECT_TRUE(o.captured.empty());
  EXPECT_EQ(names(o.suicide), (S{"A18", "A19", "B19"}));
  EXPECT_EQ(p.stone_count(), 3);
  EXPECT_TRUE(p.stones(vg::StoneColor::black).empty());
  // A single stone into an eye.
  vg::GoPosition eye = corner({". O", "O ."});
  o = eye.play(vg::StoneColor::black, at("A19"));
  EXPECT_EQ(names(o.suicide), S{"A19"});
  EXPECT_FALSE(eye.at(at("A19")));
}

TEST(GoPosition, AStoneOnAnOccupiedPointReplacesWhatWasThere) {
  vg::GoPosition p = corner({"O X", "X ."});
  // Black on A19: the white stone is taken off, no prisoner (SGF: "no matter what was there").
  vg::MoveOutcome o = p.play(vg::StoneColor::black, at("A19"));
  EXPECT_EQ(o.replaced, vg::StoneColor::white);
  EXPECT_TRUE(o.captured.empty());
  EXPECT_EQ(p.at(at("A19")), vg::StoneColor::black);
  // White onto its own stone changes nothing but reports it.
  vg::GoPosition q = corner({". O"});
  o = q.play(vg::StoneColor::white, at("B19"));
  EXPECT_EQ(o.replaced, vg::StoneColor::white);
  EXPECT_EQ(q.stone_count(), 1);
  // And a replacing stone captures as any move does: black onto white B18 takes A18.
  vg::GoPosition r = corner({"X . .", "O O X", "X X ."});
  o = r.play(vg::StoneColor::black, at("B18"));
  EXPECT_EQ(o.replaced, vg::StoneColor::white);
  EXPECT_EQ(names(o.captured), S{"A18"});
}

TEST(GoPosition, SetupNeverCapturesAndOnlyAdjacentGroupsAreTaken) {
  // red-bean.com/sgf/ff5/m_vs_ax.htm: breathless stones from setup stay on the board until a
  // move next to them takes them.
  vg::GoPosition p;
  for (const char* b : {"B19", "A18", "J10", "L10", "K11", "K9"}) {
    p.set(at(b), vg::StoneColor::black);
  }
  p.set(at("A19"), vg::StoneColor::white);
  p.set(at("K10"), vg::StoneColor::white);
  EXPECT_EQ(p.stone_count(), 8);
  EXPECT_EQ(p.liberties(at("A19")), 0);
  EXPECT_EQ(p.liberties(at("K10")), 0);
  // Moves next to black's stones but not to the white ones take nothing.
  for (const char* b : {"T1", "A17", "C19", "L11"}) {
    EXPECT_TRUE(p.play(vg::StoneColor::black, at(b)).captured.empty()) << b;
  }
  EXPECT_EQ(p.stones(vg::StoneColor::white).size(), 2u);
  // A move next to A19 (black put again on its own B19) takes it; K10 likewise through K11.
  vg::MoveOutcome o = p.play(vg::StoneColor::black, at("B19"));
  EXPECT_EQ(o.replaced, vg::StoneColor::black);
  EXPECT_EQ(names(o.captured), S{"A19"});
  o = p.play(vg::StoneColor::black, at("K11"));
  EXPECT_EQ(names(o.captured), S{"K10"});
  // Setup clears a point (AE) without anything else.
  p.set(at("J10"), std::nullopt);
  EXPECT_FALSE(p.at(at("J10")));
  EXPECT_EQ(p.stone_count(), 9);
}

TEST(GoPosition, EveryMoveObeysTheLawsOverRandomGames) {
  // From a legal position (every group has a liberty), after any move: stones before + 1 -
  // captured - suicide - replaced = stones after; every group left has a liberty; the captured
  // stones were the opponent's and sat next to the move or next to each other; the new stone is
  // there unless it was a suicide.
  std::mt19937_64 rng(15);
  int captures = 0;
  int suicides = 0;
  int replaced = 0;
  for (int game = 0; game < 20; ++game) {
    vg::GoPosition p;
    for (int move = 0; move < 600; ++move) {
      const vg::StoneColor color = move % 2 ? vg::StoneColor::white : vg::StoneColor::black;
      const vg::GoPoint point = vg::point_at_index(static_cast<int>(rng() % 361));
      const int before = p.stone_count();
      const vg::GoPosition old = p;
      const vg::MoveOutcome o = p.play(color, point);
      captures += static_cast<int>(o.captured.size());
      suicides += static_cast<int>(o.suicide.size());
      replaced += o.replaced ? 1 : 0;
      ASSERT_EQ(p.stone_count(), before + 1 - static_cast<int>(o.captured.size()) -
                                     static_cast<int>(o.suicide.size()) - (o.replaced ? 1 : 0));
      for (vg::GoPoint q : o.captured) {
        ASSERT_EQ(old.at(q), vg::opponent(color));
        ASSERT_FALSE(p.at(q));
      }
      ASSERT_EQ(p.at(point).has_value(), o.suicide.empty());
      for (int i = 0; i < 361; ++i) {
        const vg::GoPoint q = vg::point_at_index(i);
        if (p.at(q)) {
          ASSERT_GT(p.liberties(q), 0) << vg::gtp_name(q);
        }
      }
    }
  }
  // The games did exercise the rules.
  std::printf("20 random games of 600 moves: %d stones captured, %d in suicides, %d replaced\n",
              captures, suicides, replaced);
  EXPECT_GT(captures, 200);
  EXPECT_GT(suicides, 10);
  EXPECT_GT(replaced, 1000);
}
