// tests/io/gcode_test.cpp: <qmotion/io/gcode.hpp>: G-code read as an interpreter reads it.
// The moves of whole programs are compared with LinuxCNC's rs274 in tests/cli/verify_test.cpp;
// here, each rule on its own, with the figures worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <qmotion/io/gcode.hpp>
#include <string>
#include <utility>
#include <vector>

#include "io/refusal_expect.hpp"

namespace qmotion::test {
namespace {

using Kind = cam::Move::Kind;

TEST(Gcode, ModalMotionUnitsAndDistanceMode) {
  const cam::Program p = io::parse_gcode(
      "G21 G90\nG0 X1 Y2 Z3\nG1 X4 F100\nY5\nG91 X1 Y1 Z-1\nG20 G90 X1\nG0 Z0\nM2\nG1 X99\n",
      "t.ngc");
  ASSERT_EQ(p.moves.size(), 6u);  // nothing after M2
  EXPECT_EQ(p.moves[0].kind, Kind::traverse);
  EXPECT_EQ(p.moves[0].line, 2);
  EXPECT_EQ(p.moves[0].from, Eigen::Vector3d::Zero());  // the tool starts at the origin
  EXPECT_EQ(p.moves[1].kind, Kind::feed);
  EXPECT_DOUBLE_EQ(p.moves[1].feed, 100);
  EXPECT_EQ(p.moves[2].kind, Kind::feed);  // G1 stays in force
  EXPECT_EQ(p.moves[2].to, Eigen::Vector3d(4, 5, 3));
  EXPECT_EQ(p.moves[3].to, Eigen::Vector3d(5, 6, 2));     // G91: from where it was
  EXPECT_EQ(p.moves[4].to, Eigen::Vector3d(25.4, 6, 2));  // G20: inches to millimetres
  EXPECT_DOUBLE_EQ(p.moves[4].feed, 100);                 // the rate given in mm/min stays
  EXPECT_EQ(p.moves[5].to, Eigen::Vector3d(25.4, 6, 0));
}

TEST(Gcode, ArcsByCentreByRadiusAndWithTurns) {
  const cam::Program p = io::parse_gcode(
      "G17 G2 X1 Y1 R1 F10\nG2 X1 Y-1 R-1\nG3 X1 Y-1 I0 J1 P3\nG18 G2 X3 Z0 I1 K0\n", "a.ngc");
  ASSERT_EQ(p.moves.size(), 4u);
  // From the origin to (1, 1), clockwise, the short way: the centre is (1, 0).
  EXPECT_NEAR((p.moves[0].centre - Eigen::Vector3d(1, 0, 0)).norm(), 0, 1e-12);
  EXPECT_EQ(p.moves[0].turns, -1);
  // From (1, 1) to (1, -1) clockwise, the long way (R < 0): the centre is (1, 0) again, the
  // chord's midpoint; a half circle either way, through x = 2 clockwise.
  EXPECT_NEAR((p.moves[1].centre - Eigen::Vector3d(1, 0, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR(cam::position(p.moves[1], 0.5).x(), 2, 1e-12);
  // A full circle about (1, 0) three times: P3.
  EXPECT_EQ(p.moves[2].turns, 3);
  EXPECT_NEAR(cam::speed_bound(p.moves[2]), 3 * 2 * 3.14159265358979323846, 1e-9);
  // G18: the plane ZX, the centre by I (x) and K (z), the turn about +Y from Z towards X.
  EXPECT_EQ(p.moves[3].plane, 18);
  EXPECT_NEAR((p.moves[3].centre - Eigen::Vector3d(2, -1, 0)).norm(), 0, 1e-12);
  // Clockwise seen from +Y (from X towards Z) from (1, -1, 0), the centre 1 mm towards +X:
  // the tool passes z = -1 (x = 2) half way.
  const Eigen::Vector3d half = cam::position(p.moves[3], 0.5);
  EXPECT_NEAR(half.x(), 2, 1e-12);
  EXPECT_NEAR(half.z(), -1, 1e-12);
}

TEST(Gcode, InverseTimeNeedsItsFeedOnEveryBlock) {
  const cam::Program p = io::parse_gcode("G93 G1 X1 F2\nG1 X2 F3\n", "f.ngc");
  EXPECT_TRUE(p.moves[0].inverse_time);
  EXPECT_DOUBLE_EQ(p.moves[1].feed, 3);
  expect_refused([] { io::parse_gcode("G93 G1 X1 F2\nG1 X2\n", "f.ngc"); },
                 "f.ngc: line 2: a feed move under G93 (inverse time) without its F word");
}

TEST(Gcode, CommentsBlanksLineNumbersAndPercent) {
  const cam::Program p =
      io::parse_gcode("%\n(a comment)\nN10 g1 x 1 . 5 F100 (inside) ; after\n\n%\n", "c.ngc");
  ASSERT_EQ(p.moves.size(), 1u);
  EXPECT_EQ(p.moves[0].line, 3);
  EXPECT_DOUBLE_EQ(p.moves[0].to.x(), 1.5);
}

TEST(Gcode, RefusesWhatItDoesNotReadNamingTheLine) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"G0 Z1\nM3 S1000\n", "p.ngc: line 2: M3 is not read by verify"},
      {"G0 Z1\nS1000\n", "p.ngc: line 2: the word S is not read by verify"},
      {"G0 Z1\nG1 X#1 F1\n", "p.ngc: line 2: the word X holds a parameter or an expression"},
      {"G0 Z1\nG1 X[1+1] F1\n", "p.ngc: line 2: the word X holds a parameter"},
      {"G0 Z1\nG64 P0.01\n", "p.ngc: line 2: G64 is not read by verify"},
      {"G0 Z1\nG91.1\n", "p.ngc: line 2: G91.1 is not read by verify"},
      {"G0 Z1\nG99999999999\n", "p.ngc: line 2: G1e+11 is not read by verify"},
      {"X1\n", "p.ngc: line 1: axis words with no motion mode"},
      {"G1 X1\n", "p.ngc: line 1: a feed move with no feed rate"},
      {"G2 X1 Y1 F1\n", "p.ngc: line 1: an arc with neither R nor the centre's offsets"},
      {"G2 X1 Y1 R0.1 F1\n", "p.ngc: line 1: the arc's radius R is too small"},
      {"G2 X2 Y0 I1.1 J0 F1\n", "p.ngc: line 1: the arc's radius differs from start"},
      {"G2 X1 Y1 I1 J0 K1 F1\n", "p.ngc: line 1: the word K names the axis normal"},
      {"G1 X1 I1 F1\n", "p.ngc: line 1: the word I belongs to an arc"},
      {"G0 G1 X1 F1\n", "p.ngc: line 1: G0 and G1 on one line belong to the same modal group"},
      {"G1 X1 X2 F1\n", "p.ngc: line 1: two X words on one line"},
      {"G1 X F1\n", "p.ngc: line 1: the word X has no number"},
      {"G1 X1" + std::string(400, '0') + " F1\n",
       "p.ngc: line 1: the word X's number is beyond 10^12"},
      {"G1 X2000000000000 F1\n", "p.ngc: line 1: the word X's number is beyond 10^12"},
      {"G1 X1 F1 (open\n", "p.ngc: line 1: a comment that is not closed on its line"},
      {"/G1 X1 F1\n", "p.ngc: line 1: block delete"},
      {"G2 X1 Y1 R1 P0 F1\n", "p.ngc: line 1: P, the arc's turns, must be a whole number"},
      {"G2 X1 Y1 R1 P1001 F1\n", "p.ngc: line 1: P, the arc's turns, must be a whole number"},
      {"G2 X1 Y1 R1 P1.5 F1\n", "p.ngc: line 1: P, the arc's turns, must be a whole number"},
      {"(nothing)\nG21\n", "p.ngc: no move"},
  };
  for (const auto& item : bad)
    expect_refused([&item] { io::parse_gcode(item.first, "p.ngc"); }, item.second);
}

}  // namespace
}  // namespace qmotion::test
