// tests/io/toolpath_files_test.cpp: <qmotion/io/toolpath_files.hpp>: each format's rules on
// small inputs, the expected text worked out by hand. Whole programs are run through
// LinuxCNC's interpreter and read back within their tolerances in tests/api/toolpath_test.cpp
// and tests/cli.
#include <gtest/gtest.h>

#include <cstdlib>
#include <qmotion/io/toolpath_files.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace qmotion::test {
namespace {

std::vector<cam::ToolpathSample> line_samples(int n) {
  std::vector<cam::ToolpathSample> s(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    s[static_cast<std::size_t>(i)].t = i / double(n - 1);
    s[static_cast<std::size_t>(i)].point = Eigen::Vector3d(i, -0.5 * i, 2);
    s[static_cast<std::size_t>(i)].axis = Eigen::Vector3d::UnitZ();
    s[static_cast<std::size_t>(i)].written.point = s[static_cast<std::size_t>(i)].point;
    s[static_cast<std::size_t>(i)].written.axis = Eigen::Vector3d::UnitZ();
  }
  return s;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

TEST(ToolpathFiles, NumbersPrintFixedAndReadBack) {
  EXPECT_EQ(io::fixed(-1e-9, 6), "0.000000");  // never "-0"
  EXPECT_EQ(io::fixed(-0.0000006, 6), "-0.000001");
  EXPECT_EQ(io::fixed(2.5, 2), "2.50");
  EXPECT_EQ(io::rounded(0.1234567, 3), 0.123);
  EXPECT_EQ(io::exact_decimals({0.5, 0.25}, 0), 2);
  // The fewest: x reads back at those decimals and not at one fewer.
  for (double x : {0.1, 1.0 / 3, 12345.678901234}) {
    const int d = io::exact_decimals({x}, 0);
    EXPECT_EQ(std::strtod(io::fixed(x, d).c_str(), nullptr), x) << x;
    EXPECT_NE(std::strtod(io::fixed(x, d - 1).c_str(), nullptr), x) << x;
  }
}

TEST(ToolpathFiles, GcodeStatesItsHeaderAndOneBlockPerSample) {
  io::ToolpathHeader h;
  h.feed = 500;
  h.chord_tol = 0.01;
  cam::PathMode mode;
  mode.words = "G64 P0.001";
  mode.assumption = "blended within 0.001";
  std::ostringstream os;
  io::write_gcode(os, h, line_samples(3), {}, {}, 9, cam::Dialect::linuxcnc, mode);
  const auto l = lines(os.str());
  ASSERT_EQ(l.size(), 9u);
  EXPECT_NE(l[0].find("3 points, chord tolerance 0.010000 mm"), std::string::npos);
  EXPECT_NE(l[1].find("blended within 0.001"), std::string::npos);
  EXPECT_EQ(std::vector<std::string>(l.begin() + 2, l.end()),
            (std::vector<std::string>{
                "G21 G90 G17 G94", "G64 P0.001", "F500.0000", "G0 X0.000000 Y0.000000 Z2.000000",
                "G1 X1.000000 Y-0.500000 Z2.000000", "G1 X2.000000 Y-1.000000 Z2.000000", "M2"}));
}

TEST(ToolpathFiles, InverseTimeGivesEachBlockItsFeedAndRestoresG94) {
  io::ToolpathHeader h;
  h.units = "in";
  h.inverse_time = true;
  std::ostringstream os;
  io::write_gcode(os, h, line_samples(3), {}, {{2.5, 1}, {0.125, 3}}, 9, cam::Dialect::linuxcnc,
                  cam::PathMode{});
  const std::string t = os.str();
  EXPECT_NE(t.find("G20 G90 G17 G93\n"), std::string::npos);
  EXPECT_EQ(t.find("\nF"), std::string::npos);  // no modal feed under G93
  EXPECT_NE(t.find("G1 X1.000000 Y-0.500000 Z2.000000 F2.5\n"), std::string::npos);
  EXPECT_NE(t.find("G1 X2.000000 Y-1.000000 Z2.000000 F0.125\n"), std::string::npos);
  EXPECT_NE(t.find("G94\nM2\n"), std::string::npos);
}

TEST(ToolpathFiles, AptFoldsAtSeventyTwoColumnsAndTurnsMultaxOnWithTheAxis) {
  io::ToolpathHeader h;
  h.feed = 250;
  auto s = line_samples(2);
  s[1].axis = s[1].written.axis = Eigen::Vector3d(0, 0.6, 0.8);
  s[1].written.point = Eigen::Vector3d(123456.123456, -123456.123456, 123456.123456);
  std::ostringstream os;
  io::write_apt(os, h, s, 9);
  const auto l = lines(os.str());
  EXPECT_EQ(l[0], "PARTNO/QMOTION TOOLPATH");
  EXPECT_EQ(l[1], "UNITS/MM");
  EXPECT_EQ(l[2], "MULTAX/ON");
  EXPECT_EQ(l[3], "FEDRAT/250.0000");
  EXPECT_EQ(l.back(), "FINI");
  // Each line within 72 columns; a folded line ends after a comma with '$'.
  std::vector<std::string> statements;
  std::string cur;
  for (const auto& x : l) {
    EXPECT_LE(x.size(), 72u) << x;
    if (!x.empty() && x.back() == '$') {
      EXPECT_EQ(x[x.size() - 2], ',') << x;
      cur += x.substr(0, x.size() - 1);
    } else {
      statements.push_back(cur + x);
      cur.clear();
    }
  }
  ASSERT_EQ(statements.size(), 7u);  // PARTNO UNITS MULTAX FEDRAT GOTO GOTO FINI
  EXPECT_GT(l.size(), statements.size());
  EXPECT_EQ(statements[4], "GOTO/0.000000,0.000000,2.000000,0.000000000,0.000000000,1.000000000");
  EXPECT_EQ(statements[5],
            "GOTO/123456.123456,-123456.123456,123456.123456,0.000000000,0.600000000,"
            "0.800000000");
}

TEST(ToolpathFiles, CsvHasTheArcLengthColumnOnlyWhenGiven) {
  std::ostringstream without, with;
  io::write_csv(without, line_samples(2), {}, 9, 12);
  io::write_csv(with, line_samples(2), {0, 1.118033989}, 9, 12);
  EXPECT_EQ(lines(without.str())[0], "t,x,y,z,i,j,k");
  EXPECT_EQ(lines(without.str())[2],
            "1.000000000000,1.000000000,-0.500000000,2.000000000,0.000000000000,"
            "0.000000000000,1.000000000000");
  EXPECT_EQ(lines(with.str())[0], "t,x,y,z,i,j,k,s");
  EXPECT_EQ(lines(with.str())[2].substr(lines(with.str())[2].rfind(',') + 1), "1.118033989");
}

TEST(ToolpathFiles, NurbsBlocksCarryEveryKnotAndWeight) {
  // A quadratic arc-like curve with one interior knot: 4 poles, 7 knots.
  const auto c = kernel::BSpline<Eigen::Vector4d>::make(
      2, {0, 0, 0, 0.5, 1, 1, 1},
      {Eigen::Vector4d(1, 0, 0, 0), Eigen::Vector4d(0.5, 0.5, 0.5, 0), Eigen::Vector4d(1, 2, 2, 0),
       Eigen::Vector4d(2, 6, 0, 0)});
  io::ToolpathHeader h;
  h.feed = 100;
  io::NurbsHeader n;
  n.spans = 2;
  n.bound = 0.001;
  std::ostringstream os;
  io::write_nurbs_gcode(os, h, c, n, cam::PathMode{});
  const auto l = lines(os.str());
  EXPECT_NE(l[0].find("NURBS of degree 2, 4 control points, 2 spans, a fit"), std::string::npos);
  ASSERT_EQ(l.size(), 13u);
  // The order P = 3 and the feed on the first block; the last three knots alone.
  EXPECT_EQ(std::vector<std::string>(l.begin() + 4, l.end()),
            (std::vector<std::string>{
                "G0 X0.000000 Y0.000000 Z0.000000",
                "G06.2 P3 K0.000000000 X0.000000 Y0.000000 Z0.000000 R1.000000 F100.0000",
                "K0.000000000 X1.000000 Y1.000000 Z0.000000 R0.500000",
                "K0.000000000 X2.000000 Y2.000000 Z0.000000 R1.000000",
                "K0.500000000 X3.000000 Y0.000000 Z0.000000 R2.000000", "K1.000000000",
                "K1.000000000", "K1.000000000", "M2"}));
}

}  // namespace
}  // namespace qmotion::test
