// Go points: GTP and SGF names against the standards' own examples and each other, world
// positions against the board's grid, and the nearest point against a brute-force search.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <set>

#include "support/readme_tables.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/go/go_point.h"
#include "virtual_go/go/stone_color.h"

namespace vg = virtual_go;

namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const vg::InvalidArgument& e) {
    return e.field() + " | " + e.what();
  }
  return "no error";
}

}  // namespace

TEST(GoPoint, GtpNamesOfTheCornersAndTengen) {
  // GTP (Farnebäck, GTP draft 2, "Vertices"): A1 lower left, columns skip I.
  EXPECT_EQ(vg::parse_gtp_point("A1"), (vg::GoPoint{0, 0}));
  EXPECT_EQ(vg::parse_gtp_point("T1"), (vg::GoPoint{18, 0}));
  EXPECT_EQ(vg::parse_gtp_point("A19"), (vg::GoPoint{0, 18}));
  EXPECT_EQ(vg::parse_gtp_point("T19"), (vg::GoPoint{18, 18}));
  EXPECT_EQ(vg::parse_gtp_point("K10"), (vg::GoPoint{9, 9}));  // tengen
  EXPECT_EQ(vg::parse_gtp_point("H8"), (vg::GoPoint{7, 7}));
  EXPECT_EQ(vg::parse_gtp_point("J8"), (vg::GoPoint{8, 7}));   // the letter after H
  EXPECT_EQ(vg::parse_gtp_point("k10"), (vg::GoPoint{9, 9}));  // either case
  EXPECT_EQ(vg::parse_gtp_point("q16"), (vg::GoPoint{15, 15}));
  EXPECT_EQ(vg::gtp_name({9, 9}), "K10");
  EXPECT_EQ(vg::gtp_name({8, 0}), "J1");
}

TEST(GoPoint, EveryPointRoundTripsThroughBothNamings) {
  std::set<std::string> gtp;
  std::set<std::string> sgf;
  for (int index = 0; index < 361; ++index) {
    const vg::GoPoint p = vg::point_at_index(index);
    EXPECT_EQ(vg::point_index(p), index);
    EXPECT_EQ(vg::parse_gtp_point(vg::gtp_name(p)), p);
    EXPECT_EQ(vg::parse_sgf_point(vg::sgf_name(p)), p);
    gtp.insert(vg::gtp_name(p));
    sgf.insert(vg::sgf_name(p));
  }
  EXPECT_EQ(gtp.size(), 361u);  // all names distinct
  EXPECT_EQ(sgf.size(), 361u);
  EXPECT_EQ(gtp.count("I5"), 0u);
}

TEST(GoPoint, SgfLettersCountFromTheTopLeftWithI) {
  // red-bean.com/sgf/go.html: column then row, from the upper left; B[aa] is A19.
  EXPECT_EQ(vg::gtp_name(vg::parse_sgf_point("aa")), "A19");
  EXPECT_EQ(vg::gtp_name(vg::parse_sgf_point("sa")), "T19");
  EXPECT_EQ(vg::gtp_name(vg::parse_sgf_point("as")), "A1");
  EXPECT_EQ(vg::gtp_name(vg::parse_sgf_point("ss")), "T1");
  EXPECT_EQ(vg::gtp_name(vg::parse_sgf_point("jj")), "K10");
  // SGF uses i: its 9th column is GTP's J, its 9th row from the top GTP's 11.
  EXPECT_EQ(vg::gtp_name(vg::parse_sgf_point("ii")), "J11");
  EXPECT_EQ(vg::gtp_name(vg::parse_sgf_point("pd")), "Q16");  // upper-right star point
  EXPECT_EQ(vg::gtp_name(vg::parse_sgf_point("dp")), "D4");   // lower-left star point
  EXPECT_EQ(vg::sgf_name(vg::parse_gtp_point("C17")), "cc");
}

TEST(GoPoint, UnknownNamesAreRefusedNamingTheInputAndTheRange) {
  for (const char* bad : {"I5", "i5", "A0", "A20", "U1", "Z9", "A", "", "10", "A01", "K 10", " K10",
                          "K10 ", "AA1", "K1O", "K-1", "T191", "pass"}) {
    const std::string e = error_of([&] { vg::parse_gtp_point(bad); });
    EXPECT_NE(e.find("point | point: unknown Go point '" + std::string(bad) + "'"),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("columns A-T without I, rows 1-19"), std::string::npos) << e;
  }
  for (const char* bad : {"", "tt", "a", "aaa", "Aa", "at", "ta", "a1", "  "}) {
    const std::string e = error_of([&] { vg::parse_sgf_point(bad); });
    EXPECT_NE(e.find("sgf point | sgf point: '" + std::string(bad) + "'"), std::string::npos) << e;
    EXPECT_NE(e.find("two letters a-s"), std::string::npos) << e;
  }
  // A long name is cut in the message.
  const std::string e = error_of([] { vg::parse_gtp_point(std::string(10000, 'K')); });
  EXPECT_LT(e.size(), 200u) << e;
  EXPECT_NE(vg::gtp_name({9, 9}), "");
  EXPECT_NE(error_of([] {
              vg::gtp_name({19, 0});
            }).find("not on the 19 x 19 grid"),
            std::string::npos);
  EXPECT_NE(error_of([] { vg::sgf_name({0, -1}); }), "no error");
  EXPECT_NE(error_of([] { vg::point_at_index(361); }), "no error");
}

TEST(GoPoint, WorldPositionsFollowTheBoardGrid) {
  const vg::BoardGeometry board;
  // x across the columns, y along the rows, tengen at the origin, A1 at the lower left (-x, -y).
  const Eigen::Vector3d a1 = vg::go_point_world(board, vg::parse_gtp_point("A1"));
  EXPECT_NEAR(a1.x(), -9 * 0.022, 1e-15);
  EXPECT_NEAR(a1.y(), -9 * 0.0237, 1e-15);
  EXPECT_EQ(a1.z(), 0.0);
  const Eigen::Vector3d t19 = vg::go_point_world(board, vg::parse_gtp_point("T19"));
  EXPECT_NEAR(t19.x(), 9 * 0.022, 1e-15);
  EXPECT_NEAR(t19.y(), 9 * 0.0237, 1e-15);
  EXPECT_NEAR(vg::go_point_world(board, vg::parse_gtp_point("K10")).norm(), 0.0, 1e-15);
  // Neighbours one spacing apart: B1 right of A1, A2 above it.
  const Eigen::Vector3d b1 = vg::go_point_world(board, vg::parse_gtp_point("B1"));
  const Eigen::Vector3d a2 = vg::go_point_world(board, vg::parse_gtp_point("A2"));
  EXPECT_NEAR((b1 - a1).x(), 0.022, 1e-15);
  EXPECT_NEAR((a2 - a1).y(), 0.0237, 1e-15);
  // The star points are the board's own (D4, K10, Q16, ...).
  const auto stars = board.star_points_world();
  for (const char* star : {"D4", "K4", "Q4", "D10", "K10", "Q10", "D16", "K16", "Q16"}) {
    const Eigen::Vector3d p = vg::go_point_world(board, vg::parse_gtp_point(star));
    bool found = false;
    for (const Eigen::Vector3d& s : stars) found = found || (s - p).norm() < 1e-15;
    EXPECT_TRUE(found) << star;
  }
  vg::BoardGeometry small = board;
  small.lines = 13;
  EXPECT_NE(error_of([&] {
              vg::go_point_world(small, {0, 0});
            }).find("board | board: Go points need 19 lines, the board has 13"),
            std::string::npos);
}

TEST(GoPoint, NearestPointAgreesWithABruteForceSearch) {
  const vg::BoardGeometry board;
  std::mt19937_64 rng(16);
  std::uniform_real_distribution<double> x(-0.2, 0.2);    // the grid's +-9.5 spacings: +-209 mm
  std::uniform_real_distribution<double> y(-0.23, 0.23);  // +-225.15 mm
  int checked = 0;
  int off = 0;
  for (int k = 0; k < 20000; ++k) {
    const Eigen::Vector3d p(x(rng), y(rng), 0.01);
    // Brute force: the intersection at the smallest Euclidean distance in the board plane.
    double best = 1e9;
    double second = 1e9;
    vg::GoPoint best_point;
    for (int index = 0; index < 361; ++index) {
      const vg::GoPoint q = vg::point_at_index(index);
      const double d = (vg::go_point_world(board, q) - p).head<2>().norm();
      if (d < best) {
        second = best;
        best = d;
        best_point = q;
      } else if (d < second) {
        second = d;
      }
    }
    const bool inside = std::abs(p.x()) <= 9.5 * 0.022 && std::abs(p.y()) <= 9.5 * 0.0237;
    const std::optional<vg::GoPoint> got = vg::nearest_go_point(board, p);
    if (!inside) {
      EXPECT_FALSE(got.has_value());
      ++off;
      continue;
    }
    if (second - best < 1e-12) continue;  // a tie: the rule below decides
    ASSERT_TRUE(got.has_value()) << p.transpose();
    EXPECT_EQ(*got, best_point) << p.transpose();
    ++checked;
  }
  EXPECT_GT(checked, 15000);
  EXPECT_GT(off, 100);
}

TEST(GoPoint, NearestPointAtTheEdgesOfItsRule) {
  const vg::BoardGeometry board;
  const double sx = board.spacing_x_m;
  const double sy = board.spacing_y_m;
  const auto name = [&](double x, double y) {
    return vg::nearest_go_point_name(board, Eigen::Vector3d(x, y, 0.0));
  };
  EXPECT_EQ(name(0, 0), "K10");
  EXPECT_EQ(name(-9 * sx, -9 * sy), "A1");
  // Up to half a spacing beyond the outer lines still belongs to them, beyond that: none.
  EXPECT_EQ(name(-9.5 * sx, -9.5 * sy), "A1");
  EXPECT_EQ(name(9.5 * sx, 9.5 * sy), "T19");
  EXPECT_EQ(name(std::nextafter(9.5 * sx, 1.0), 0), "");
  EXPECT_EQ(name(0, std::nextafter(-9.5 * sy, -1.0)), "");
  EXPECT_EQ(name(0.3, 0), "");
  // Halfway between two lines: the one farther from tengen.
  EXPECT_EQ(name(0.5 * sx, 0), "L10");
  EXPECT_EQ(name(-0.5 * sx, -0.5 * sy), "J9");
  EXPECT_EQ(name(std::nextafter(0.5 * sx, 0.0), 0), "K10");
  // Height does not matter: a stone in flight belongs to the point below it.
  EXPECT_EQ(vg::nearest_go_point_name(board, Eigen::Vector3d(3 * sx, -2 * sy, 0.5)), "N8");
  // Not finite: no point, no exception.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(name(nan, 0), "");
  EXPECT_EQ(name(0, inf), "");
  EXPECT_EQ(name(1e308, -1e308), "");
}

TEST(StoneColor, NamesAndOpponents) {
  EXPECT_EQ(vg::parse_stone_color("black"), vg::StoneColor::black);
  EXPECT_EQ(vg::parse_stone_color("white"), vg::StoneColor::white);
  EXPECT_EQ(vg::stone_color_name(vg::StoneColor::white), "white");
  EXPECT_EQ(vg::opponent(vg::StoneColor::black), vg::StoneColor::white);
  EXPECT_EQ(vg::opponent(vg::StoneColor::white), vg::StoneColor::black);
  EXPECT_EQ(vg::stone_color_names(), (std::vector<std::string>{"black", "white"}));
  const std::string e = error_of([] { vg::parse_stone_color("Black"); });
  EXPECT_NE(e.find("color | unknown stone color 'Black' (known: black white)"), std::string::npos)
      << e;
}

TEST(GoPoint, TheReadmeTableMatchesTheCode) {
  const auto rows = vgtest::readme_table(VG_README, "### Go points");
  ASSERT_EQ(rows.size(), 5u);
  const vg::BoardGeometry board;
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), 4u);
    const vg::GoPoint p = vg::parse_gtp_point(row[1]);
    EXPECT_EQ(vg::sgf_name(p), row[2]) << row[1];
    double x_mm = 0;
    double y_mm = 0;
    ASSERT_EQ(std::sscanf(row[3].c_str(), "%lf, %lf", &x_mm, &y_mm), 2) << row[3];
    const Eigen::Vector3d at = vg::go_point_world(board, p);
    EXPECT_NEAR(at.x() * 1000, x_mm, 1e-9) << row[1];
    EXPECT_NEAR(at.y() * 1000, y_mm, 1e-9) << row[1];
  }
}
