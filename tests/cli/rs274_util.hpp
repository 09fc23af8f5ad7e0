// tests/cli/rs274_util.hpp: G-code as LinuxCNC's interpreter reads it (rs274 -g), and the
// words of a program's G0/G1 blocks.
#pragma once
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_util.hpp"

namespace qmotion::test {

/// The STRAIGHT_TRAVERSE and STRAIGHT_FEED positions LinuxCNC's interpreter prints for a
/// G-code file (x, y, z, a, b, c). Nothing when the build turned real clients off
/// (-DQMOTION_REAL_CLIENTS=OFF: the test skips, RS274_OR_SKIP), or, a failure, when rs274
/// is missing (/usr/bin/rs274, or what QMOTION_RS274 names).
inline std::optional<std::string> rs274_log(const std::string& ngc);

inline std::optional<std::vector<std::array<double, 6>>> rs274_moves(const std::string& ngc,
                                                                     std::string& log) {
  const auto out = rs274_log(ngc);
  if (!out) return std::nullopt;
  log = *out;
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

/// A canonical move as rs274 prints it: STRAIGHT_TRAVERSE, STRAIGHT_FEED (6 numbers: the
/// end's x, y, z, a, b, c) or ARC_FEED (9: the end in the plane, the centre in it, the
/// rotation, the end along the normal, a, b, c), with the plane (17, 18, 19) and the length
/// unit (mm per unit: 1 or 25.4) in force when it was printed.
struct CanonMove {
  std::string kind;
  std::vector<double> v;
  int plane = 17;
  double unit = 1;
};

/// Every canonical move of rs274's output `log`.
inline std::vector<CanonMove> canonical_moves(const std::string& log) {
  std::vector<CanonMove> out;
  int plane = 17;
  double unit = 1;
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);) {
    if (line.find("SELECT_PLANE(CANON_PLANE_") != std::string::npos)
      plane = line.find("_XZ)") != std::string::npos   ? 18
              : line.find("_YZ)") != std::string::npos ? 19
                                                       : 17;
    if (line.find("USE_LENGTH_UNITS(") != std::string::npos)
      unit = line.find("INCHES") != std::string::npos ? 25.4 : 1.0;
    for (const char* kind : {"STRAIGHT_TRAVERSE(", "STRAIGHT_FEED(", "ARC_FEED("}) {
      const auto p = line.find(kind);
      if (p == std::string::npos) continue;
      CanonMove m{std::string(kind, std::strlen(kind) - 1), {}, plane, unit};
      std::istringstream args(line.substr(p + std::strlen(kind)));
      for (std::string a; std::getline(args, a, ',');) m.v.push_back(std::stod(a));
      out.push_back(m);
    }
  }
  return out;
}

/// rs274's output for a G-code file, or nothing when real clients are off (RS274_OR_SKIP)
/// or, a failure, when rs274 is missing.
inline std::optional<std::string> rs274_log(const std::string& ngc) {
  if (!QMOTION_REAL_CLIENTS) return std::nullopt;
  const char* env = std::getenv("QMOTION_RS274");
  const std::string exe = env ? env : "/usr/bin/rs274";
  if (!fs::exists(exe)) {
    ADD_FAILURE() << exe << " not found: LinuxCNC's rs274 is required (scripts/install-deps.sh "
                  << "--test), or configure with -DQMOTION_REAL_CLIENTS=OFF";
    return std::nullopt;
  }
  const fs::path out = scratch_dir() / "rs274.out";
  const int raw = std::system(
      (quote(exe) + " -g " + quote(ngc) + " >" + quote(out.string()) + " 2>&1 </dev/null").c_str());
  EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0);
  return slurp(out);
}

/// Skips the test when real clients are off, stops it when rs274 failed to run.
#define RS274_OR_SKIP(moves)                                                                \
  do {                                                                                      \
    if (!(moves) && !QMOTION_REAL_CLIENTS)                                                  \
      GTEST_SKIP() << "skipped: configured with -DQMOTION_REAL_CLIENTS=OFF, so LinuxCNC's " \
                      "rs274 is not run";                                                   \
    if (!(moves)) return;                                                                   \
  } while (false)

/// The machine words of every G0/G1 block of a G-code file, in order.
inline std::vector<std::map<char, double>> gcode_words(const std::string& path) {
  std::ifstream f(path);
  std::vector<std::map<char, double>> out;
  for (std::string line; std::getline(f, line);) {
    if (line.rfind("G0 ", 0) != 0 && line.rfind("G1 ", 0) != 0) continue;
    std::map<char, double> w;
    std::istringstream ws(line.substr(3));
    for (std::string word; ws >> word;) w[word[0]] = std::stod(word.substr(1));
    out.push_back(w);
  }
  return out;
}

/// LinuxCNC's forward kinematics of a table-rotary-tilting machine (xyzac-trt-kins,
/// xyzbc-trt-kins, as its trtfuncs.c states them, with the rotation points and offsets at
/// zero: the pivots of --rotary ac and bc) for the joints of an rs274 move (x, y, z, a, b, c):
/// the tool tip in workpiece coordinates, and the tool axis (the same linear map applied to
/// the spindle's +Z). Written here from LinuxCNC's formulas, not from qmotion's.
inline std::pair<Eigen::Vector3d, Eigen::Vector3d> trt_forward(char table,
                                                               const std::array<double, 6>& j) {
  const double deg = 3.14159265358979323846 / 180;
  const double c = j[5] * deg, cc = std::cos(c), sc = std::sin(c);
  auto map = [&](const Eigen::Vector3d& v) -> Eigen::Vector3d {
    if (table == 'A') {
      const double a = j[3] * deg, ca = std::cos(a), sa = std::sin(a);
      return {cc * v(0) + sc * ca * v(1) + sc * sa * v(2),
              -sc * v(0) + cc * ca * v(1) + cc * sa * v(2), -sa * v(1) + ca * v(2)};
    }
    const double b = j[4] * deg, cb = std::cos(b), sb = std::sin(b);
    return {cc * cb * v(0) + sc * v(1) - cc * sb * v(2),
            -sc * cb * v(0) + cc * v(1) + sc * sb * v(2), sb * v(0) + cb * v(2)};
  };
  return {map(Eigen::Vector3d(j[0], j[1], j[2])), map(Eigen::Vector3d::UnitZ())};
}

/// Where LinuxCNC's interpreter sets the path mode (SET_MOTION_CONTROL_MODE) in its log, and
/// where its first STRAIGHT_FEED is; npos when absent.
inline std::pair<std::size_t, std::size_t> path_mode_and_first_feed(const std::string& log) {
  return {log.find("SET_MOTION_CONTROL_MODE("), log.find("STRAIGHT_FEED(")};
}

}  // namespace qmotion::test
