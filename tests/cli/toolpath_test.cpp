// tests/cli/toolpath_test.cpp: the program, run as a user runs it: `qmotion toolpath`.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <qmotion/io/poses.hpp>
#include <sstream>
#include <vector>

#include "cli_util.hpp"

namespace qmotion::test {
namespace {

/// The STRAIGHT_TRAVERSE and STRAIGHT_FEED positions LinuxCNC's interpreter prints for a
/// G-code file (x, y, z, a, b, c), or nothing when it is absent (the test then skips).
std::optional<std::vector<std::array<double, 6>>> rs274_moves(const std::string& ngc,
                                                              std::string& log) {
  if (!fs::exists("/usr/bin/rs274")) return std::nullopt;
  const fs::path out = scratch_dir() / "rs274.out";
  const int raw = std::system(
      ("/usr/bin/rs274 -g " + quote(ngc) + " >" + quote(out.string()) + " 2>&1 </dev/null")
          .c_str());
  log = slurp(out);
  EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << log;
  std::vector<std::array<double, 6>> moves;
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);) {
    const auto p = line.find("STRAIGHT_");
    if (p == std::string::npos) continue;
    std::array<double, 6> v{};
    const std::string args = line.substr(line.find('(', p) + 1);
    EXPECT_EQ(std::sscanf(args.c_str(), "%lf, %lf, %lf, %lf, %lf, %lf", &v[0], &v[1], &v[2], &v[3],
                          &v[4], &v[5]),
              6)
        << line;
    moves.push_back(v);
  }
  EXPECT_EQ(log.find("error"), std::string::npos) << log;
  return moves;
}

/// The rows of a toolpath CSV (t, x, y, z, i, j, k).
std::vector<std::vector<double>> csv_rows(const std::string& path) {
  std::ifstream f(path);
  std::vector<std::vector<double>> rows;
  std::string line;
  std::getline(f, line);  // header
  while (std::getline(f, line)) {
    std::vector<double> r;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) r.push_back(std::stod(cell));
    rows.push_back(r);
  }
  return rows;
}

TEST(Cli, ToolpathGcodeRunsInLinuxCncsInterpreter) {
  const std::string m = (scratch_dir() / "tp_motion.json").string();
  ASSERT_EQ(run({"interpolate", test_data("poses/helix_40.json"), "-o", m}).status, 0);
  const std::string csv = (scratch_dir() / "tp.csv").string(),
                    ngc = (scratch_dir() / "tp.ngc").string(),
                    ngc5 = (scratch_dir() / "tp5.ngc").string();
  const std::vector<std::string> common{"--point", "1,0,2",       "--axis",
                                        "1,0,1",   "--chord-tol", "0.01"};
  for (const auto& out : {csv, ngc, ngc5}) {
    std::vector<std::string> args{"toolpath", m, "-o", out};
    args.insert(args.end(), common.begin(), common.end());
    if (out == ngc5) args.insert(args.end(), {"--rotary", "ac"});
    const Result r = run(args);
    ASSERT_EQ(r.status, 0) << r.err;
    const json report = json::parse(r.out);
    EXPECT_LE(report["max_chord_deviation_bound"].get<double>(), 0.01);
    EXPECT_LE(report["max_chord_deviation_measured"].get<double>(),
              report["max_chord_deviation_bound"].get<double>());
    EXPECT_GT(report["machining_time_min"].get<double>(), 0);
  }
  const auto rows = csv_rows(csv);
  // Every CSV point on the exact trajectory (eval at its t).
  for (std::size_t i = 0; i < rows.size(); i += 7) {
    std::ostringstream t;
    t.precision(17);
    t << rows[i][0];
    const json e = run_json({"eval", m, "--t", t.str(), "--point", "1,0,2"});
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(e["point"][c].get<double>(), rows[i][1 + c], 1e-8) << "row " << i;
    }
  }
  std::string log;
  const auto moves = rs274_moves(ngc, log);
  if (!moves) GTEST_SKIP() << "rs274 not installed (linuxcnc-uspace)";
  ASSERT_EQ(moves->size(), rows.size()) << log;
  // The file's 6 decimals, then the interpreter's 4: within 5e-5 + 5e-7.
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR((*moves)[i][c], rows[i][1 + c], 5.1e-5) << "move " << i;
    }
  // 5-axis: machine XYZ = Rx(A) Rz(C) p, and A, C take the axis onto +Z.
  const auto moves5 = rs274_moves(ngc5, log);
  ASSERT_TRUE(moves5);
  ASSERT_EQ(moves5->size(), rows.size()) << log;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& mv = (*moves5)[i];
    const double A = mv[3] * 3.14159265358979323846 / 180, C = mv[5] * 3.14159265358979323846 / 180;
    const Eigen::Matrix3d T = (Eigen::AngleAxisd(A, Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(C, Eigen::Vector3d::UnitZ()))
                                  .toRotationMatrix();
    const Eigen::Vector3d p = T * Eigen::Vector3d(rows[i][1], rows[i][2], rows[i][3]);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(mv[c], p(c), 5.1e-5 + 1e-6 * p.norm()) << "move " << i;
    }
    const Eigen::Vector3d z = T * Eigen::Vector3d(rows[i][4], rows[i][5], rows[i][6]);
    EXPECT_LE(z.cross(Eigen::Vector3d::UnitZ()).norm(), 2e-6) << "move " << i;  // 4 decimals
  }
  // The file's own 9 decimals of A and C reproduce the axis within 1e-9 rad.
  std::ifstream f(ngc5);
  std::size_t k = 0;
  for (std::string line; std::getline(f, line);) {
    const auto a = line.find(" A"), c = line.find(" C");
    if (a == std::string::npos || c == std::string::npos) continue;
    const double A = std::stod(line.substr(a + 2)) * 3.14159265358979323846 / 180;
    const double C = std::stod(line.substr(c + 2)) * 3.14159265358979323846 / 180;
    const Eigen::Matrix3d T = (Eigen::AngleAxisd(A, Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(C, Eigen::Vector3d::UnitZ()))
                                  .toRotationMatrix();
    const Eigen::Vector3d z = T * Eigen::Vector3d(rows[k][4], rows[k][5], rows[k][6]).normalized();
    EXPECT_LE(std::atan2(z.cross(Eigen::Vector3d::UnitZ()).norm(), z(2)), 1e-9) << line;
    ++k;
  }
  EXPECT_EQ(k, rows.size());
}

TEST(Cli, ToolpathBadInputsExitTwoAndLeaveNoFile) {
  const std::string m = (scratch_dir() / "tp_bad_motion.json").string();
  ASSERT_EQ(run({"interpolate", test_data("poses/five_positions.json"), "-o", m}).status, 0);
  const std::string out = (scratch_dir() / "tp_bad.ngc").string();
  struct Case {
    std::vector<std::string> args;
    std::string needle;
  };
  const std::vector<Case> cases{
      {{"--axis", "0,0,0"}, "--axis"},
      {{"--chord-tol", "0"}, "--chord-tol"},
      {{"--chord-tol", "-1"}, "--chord-tol"},
      {{"--chord-tol", "1e99"}, "--chord-tol"},
      {{"--chord-tol", "0.01", "--rotary", "bc"}, "--rotary bc"},
      {{"--chord-tol", "0.01", "--angle-tol", "120"}, "--angle-tol"},
      {{"--chord-tol", "0.01", "--feed", "0"}, "--feed"},
      {{"--chord-tol", "0.01", "--nurbs", "--rotary", "ac"}, "--nurbs"},
      {{"--chord-tol", "0.01", "--nurbs", "--max-step", "2"}, "--max-step"},
      {{"--chord-tol", "0.01", "--arc-length"}, "--arc-length"},
  };
  for (const auto& c : cases) {
    std::vector<std::string> args{"toolpath", m, "--point", "1,2,3", "-o", out};
    if (c.args.front() != "--chord-tol") args.insert(args.end(), {"--chord-tol", "0.01"});
    args.insert(args.end(), c.args.begin(), c.args.end());
    const Result r = run(args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
  const Result fmt = run({"toolpath", m, "--point", "1,2,3", "--chord-tol", "0.01", "-o",
                          (scratch_dir() / "tp.gcode").string()});
  EXPECT_EQ(fmt.status, 2);
  EXPECT_NE(fmt.err.find(".ngc"), std::string::npos) << fmt.err;
  const std::string csv = (scratch_dir() / "tp_bad.csv").string();
  const Result nurbs_csv =
      run({"toolpath", m, "--point", "1,2,3", "--chord-tol", "0.01", "--nurbs", "-o", csv});
  EXPECT_EQ(nurbs_csv.status, 2);
  EXPECT_NE(nurbs_csv.err.find("--nurbs"), std::string::npos) << nurbs_csv.err;
  EXPECT_FALSE(fs::exists(csv));
}

TEST(Cli, ToolpathNurbsReportsItsCertifiedDeviation) {
  const std::string m = (scratch_dir() / "tpn_motion.json").string();
  ASSERT_EQ(run({"interpolate", test_data("poses/helix_40.json"), "-o", m}).status, 0);
  const std::string ngc = (scratch_dir() / "tpn.ngc").string();
  const Result r = run({"toolpath", m, "--point", "1,0,2", "--chord-tol", "0.001", "--nurbs",
                        "--feed", "600", "-o", ngc});
  ASSERT_EQ(r.status, 0) << r.err;
  const json report = json::parse(r.out);
  EXPECT_TRUE(report["nurbs"].get<bool>());
  EXPECT_LE(report["degree"].get<int>(), 3);
  EXPECT_LE(report["max_deviation_bound"].get<double>(), 0.001);
  EXPECT_LE(report["max_deviation_measured"].get<double>(),
            report["max_deviation_bound"].get<double>());
  EXPECT_NEAR(report["machining_time_min"].get<double>(), report["path_length"].get<double>() / 600,
              1e-12);
  std::ifstream f(ngc);
  std::size_t blocks = 0;
  for (std::string line; std::getline(f, line);) blocks += line.rfind("K", 0) == 0;
  EXPECT_EQ(blocks + 1, report["control_points"].get<std::size_t>() + 4);  // + the G06.2 block
}

}  // namespace
}  // namespace qmotion::test
