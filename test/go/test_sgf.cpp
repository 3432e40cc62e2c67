// The SGF reader: what FF[3] and FF[4] files hold (moves, passes, setup lists and rectangles,
// escapes, variations) read as the standard (red-bean.com/sgf) defines it, and every kind of
// malformed file refused with its line and column.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>

#include "virtual_go/go/sgf.h"

namespace vg = virtual_go;

namespace {

std::vector<std::string> names(const std::vector<vg::GoPoint>& points) {
  std::vector<std::string> out;
  for (vg::GoPoint p : points) out.push_back(vg::gtp_name(p));
  return out;
}

// The main line's moves as "B Q16", "W pass".
std::vector<std::string> moves(const vg::SgfGame& game) {
  std::vector<std::string> out;
  for (const vg::SgfNode& n : game.main_line) {
    if (!n.move) continue;
    out.push_back(std::string(n.move->color == vg::StoneColor::black ? "B " : "W ") +
                  (n.move->point ? vg::gtp_name(*n.move->point) : "pass"));
  }
  return out;
}

// The error's line, column and message, or "no error".
struct Refusal {
  int line = 0;
  int column = 0;
  std::string what = "no error";
};

Refusal refusal(const std::string& text) {
  try {
    vg::parse_sgf(text, "game.sgf");
  } catch (const vg::SgfError& e) {
    EXPECT_EQ(e.field(), "sgf");
    return {e.line(), e.column(), e.what()};
  }
  return {};
}

}  // namespace

TEST(Sgf, MovesAndPassesOfAnFF4Game) {
  const vg::SgfGame game = vg::parse_sgf(
      "(;FF[4]GM[1]SZ[19]PB[Cho Chikun]PW[Ryu Shikun]RE[W+2.5]KM[5.5]\n"
      ";B[qd];W[dd]\n;B[];W[tt];B[jj])");
  EXPECT_EQ(game.file_format, 4);
  EXPECT_EQ(game.black_player, "Cho Chikun");
  EXPECT_EQ(game.white_player, "Ryu Shikun");
  EXPECT_EQ(game.result, "W+2.5");
  EXPECT_EQ(game.handicap, 0);
  ASSERT_EQ(game.main_line.size(), 6u);  // the root and five moves
  EXPECT_FALSE(game.main_line[0].move);
  EXPECT_EQ(moves(game), (std::vector<std::string>{"B R16", "W D16", "B pass", "W pass", "B K10"}));
  EXPECT_EQ(game.move_count(), 5);
  EXPECT_EQ(game.main_line[1].line, 2);
  EXPECT_EQ(game.main_line[3].line, 3);
}

TEST(Sgf, AnFF3GameWithLongPropertyNames) {
  // FF[3] lets property names carry lowercase letters, which are ignored: AddBlack is AB.
  const vg::SgfGame game =
      vg::parse_sgf("(;FF[3]GaMe[1]SiZe[19]HA[2]AddBlack[pd][dp]\n;White[qp];Black[tt];W[cc])");
  EXPECT_EQ(game.file_format, 3);
  EXPECT_EQ(game.handicap, 2);
  EXPECT_EQ(names(game.main_line[0].add_black), (std::vector<std::string>{"Q16", "D4"}));
  EXPECT_EQ(moves(game), (std::vector<std::string>{"W R4", "B pass", "W C17"}));
  // No FF: the standard's default, FF[1].
  EXPECT_EQ(vg::parse_sgf("(;B[aa])").file_format, 1);
}

TEST(Sgf, SetupListsAndCompressedRectangles) {
  const vg::SgfGame game =
      vg::parse_sgf("(;SZ[19:19]AB[aa:cb][ss]AW[dd:dd];AE[ba][ss]AW[pp];B[ee])");
  // aa:cb is the rectangle A19-C18 (columns a-c, rows a-b from the top), read row by row.
  EXPECT_EQ(names(game.main_line[0].add_black),
            (std::vector<std::string>{"A19", "B19", "C19", "A18", "B18", "C18", "T1"}));
  EXPECT_EQ(names(game.main_line[0].add_white), (std::vector<std::string>{"D16"}));
  EXPECT_EQ(names(game.main_line[1].add_empty), (std::vector<std::string>{"B19", "T1"}));
  EXPECT_EQ(names(game.main_line[1].add_white), (std::vector<std::string>{"Q4"}));
  // The corners may come in any order.
  EXPECT_EQ(vg::parse_sgf("(;AB[cb:aa])").main_line[0].add_black,
            vg::parse_sgf("(;AB[aa:cb])").main_line[0].add_black);
  EXPECT_EQ(vg::parse_sgf("(;AB[as:sa])").main_line[0].add_black.size(), 361u);
}

TEST(Sgf, EscapedTextAndSkippedProperties) {
  const vg::SgfGame game = vg::parse_sgf(
      "(;PB[Black \\] bracket \\\\ backslash]PW[soft\\\nbreak]\n"
      "C[a comment with \\] inside, and ( ; ) B[aa\\] as text]\n"
      "GN[x]XX[unknown][values]LB[dd:a][pp:b];B[aa]C[\n(;W[bb\\])\n])");
  EXPECT_EQ(game.black_player, "Black ] bracket \\ backslash");
  EXPECT_EQ(game.white_player, "softbreak");
  // The comment's "( ; ) B[aa]" and the second comment's "(;W[bb])" are text, not nodes.
  EXPECT_EQ(moves(game), (std::vector<std::string>{"B A19"}));
  EXPECT_EQ(vg::parse_sgf("(;PB[two\nlines])").black_player, "two lines");
}

TEST(Sgf, TheMainLineIsTheFirstVariationAtEveryBranch) {
  const vg::SgfGame game =
      vg::parse_sgf("(;SZ[19];B[aa];W[ba](;B[ca];W[da](;B[ea])(;B[zz]))(;B[sa]))\n(;B[ss])");
  EXPECT_EQ(moves(game), (std::vector<std::string>{"B A19", "W B19", "B C19", "W D19", "B E19"}));
  // Each move nested as a variation, as some programs write: 100000 levels, no recursion.
  std::string nested = "(;SZ[19]";
  for (int k = 0; k < 100000; ++k) nested += std::string("(;") + (k % 2 ? "W" : "B") + "[aa]";
  nested += std::string(100001, ')');
  EXPECT_EQ(vg::parse_sgf(nested).move_count(), 100000);
}

TEST(Sgf, MalformedFilesAreRefusedWithLineAndColumn) {
  struct Case {
    std::string text;
    int line;
    int column;
    std::string what;
  };
  const std::vector<Case> cases = {
      {"", 1, 1, "no game: an SGF file starts with '(;'"},
      {"  \n ", 2, 2, "no game"},
      {"x(;B[aa])", 1, 1, "expected '(' to start a game, found 'x'"},
      {"(;B[aa]", 1, 1, "the game tree opened here is not closed with ')'"},
      {"(;B[aa", 1, 4, "the value opened here is not closed with ']'"},
      {"(;C[text\\", 1, 4, "the value opened here is not closed with ']'"},
      {"()", 1, 2, "an empty game tree"},
      {"(B[aa])", 1, 2, "expected ';' (a node), '(' (a variation) or ')', found 'B'"},
      {"((;B[aa]))", 1, 2, "a variation before the first node"},
      {"(;B[aa](;W[bb]);B[cc])", 1, 16, "a node after a variation"},
      {"(;B[aa])x", 1, 9, "expected '(' (another game) or the end of the file, found 'x'"},
      {"(;b[aa])", 1, 3, "property 'b' has no capital letter"},
      {"(;B)", 1, 4, "property B has no value: expected '[', found ')'"},
      {"(;B[aa]W[bb])", 1, 8, "B and W in one node"},
      {"(;B[aa][bb])", 1, 8, "B takes one value, got 2"},
      {"(;B[aa];C[x]C[y])", 1, 13, "C appears twice in one node"},
      {"(;\n;B[zz])", 2, 3, "B[zz]: 'zz' is not a point of a 19 x 19 board"},
      {"(;\n;W[ad:zz])", 2, 3, "W[ad:zz]: 'ad:zz' is not a point"},
      {"(;AB[dd]\n  AW[ee][dd])", 2, 9, "AW[dd]: point D16 is set twice in one node (AB and AW)"},
      {"(;AB[aa:bb]AE[bb])", 1, 14, "AE[bb]: point B18 is set twice in one node (AB and AE)"},
      {"(;AB[])", 1, 5, "AB[]: '' is not a point"},
      {"(;AB[aa:])", 1, 5, "AB[aa:]: '' is not a point"},
      {"(;SZ[13];B[aa])", 1, 5, "SZ[13]: a board of 13 x 13; only 19 x 19 games are read"},
      {"(;SZ[19:13])", 1, 5, "SZ[19:13]: a board of 19 x 13"},
      {"(;SZ[big])", 1, 5, "SZ[big]: not a board size"},
      {"(;FF[5])", 1, 5, "FF[5]: unknown file format (FF[1] to FF[4] are read)"},
      {"(;GM[2])", 1, 5, "GM[2]: not a game of Go (GM[1])"},
      {"(;HA[two])", 1, 5, "HA[two]: not a number of handicap stones"},
      {"(;FF[4]\r\n;B[aa]\r\n;W[Bb])", 3, 3, "W[Bb]: 'Bb' is not a point"},
      // Columns count characters, not bytes: the two Japanese characters are 6 bytes.
      {"(;PB[\xE5\xB1\xB1\xE7\x94\xB0]B[zz])", 1, 10, "B[zz]"},
  };
  for (const Case& c : cases) {
    const Refusal r = refusal(c.text);
    EXPECT_EQ(r.line, c.line) << c.text << "\n" << r.what;
    EXPECT_EQ(r.column, c.column) << c.text << "\n" << r.what;
    const std::string prefix =
        "game.sgf:" + std::to_string(c.line) + ":" + std::to_string(c.column) + ": ";
    EXPECT_EQ(r.what.rfind(prefix, 0), 0u) << r.what;
    EXPECT_NE(r.what.find(c.what), std::string::npos) << c.text << "\n" << r.what;
  }
}

TEST(Sgf, AByteOrderMarkAndACollectionOfGames) {
  const vg::SgfGame game = vg::parse_sgf("\xEF\xBB\xBF(;B[aa])\n(;B[bb];W[cc])\n");
  EXPECT_EQ(moves(game), (std::vector<std::string>{"B A19"}));  // the first game
  // A later game of the collection is checked for syntax too.
  EXPECT_EQ(refusal("(;B[aa])(;B[bb]").line, 1);
}

TEST(Sgf, FilesThatCannotBeReadNameThePath) {
  auto error = [](const std::string& path) -> std::string {
    try {
      vg::read_sgf_file(path);
    } catch (const vg::InvalidArgument& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(error("/nonexistent/game.sgf").find("sgf: cannot open '/nonexistent/game.sgf'"),
            std::string::npos);
  EXPECT_NE(error("/").find("sgf: cannot read '/': not a regular file"), std::string::npos)
      << error("/");
  const std::string path = ::testing::TempDir() + "test_sgf_game.sgf";
  {
    std::ofstream out(path);
    out << "(;FF[4]\n;B[pd]\n;W[dp\n";
  }
  const std::string e = error(path);
  EXPECT_EQ(e.rfind(path + ":3:3: the value opened here is not closed with ']'", 0), 0u) << e;
  {
    std::ofstream out(path);
    out << "(;FF[4];B[pd];W[dp])";
  }
  EXPECT_EQ(vg::read_sgf_file(path).move_count(), 2);
  {
    std::ofstream out(path);
    out << "(;C[" << std::string(vg::kMaxSgfBytes, 'x') << "])";
  }
  EXPECT_NE(error(path).find("more than the 16777216 this reader takes"), std::string::npos);
  std::remove(path.c_str());
}
