// tests/api/toolpath_machine_test.cpp mirrors api/toolpath.hpp: the bounds hold for the
// numbers as written and for what a 5-axis machine runs between them; inverse-time feed.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <map>
#include <qmotion/api/qspline.hpp>
#include <qmotion/api/toolpath.hpp>
#include <regex>
#include <sstream>

#include "api/toolpath_util.hpp"

namespace qmotion::test {
namespace {

/// The numbers a toolpath file states, one row per point: x, y, z and, where written, the
/// axis i, j, k (APT, CSV) or the machine words (G-code: every letter's value).
struct Row {
  V3 point = V3::Zero(), axis = V3::Zero();
  std::map<char, double> words;
};

std::vector<Row> read_rows(const std::string& path) {
  std::ifstream f(path);
  std::stringstream all;
  all << f.rdbuf();
  std::string text = all.str();
  std::vector<Row> rows;
  if (path.size() > 4 && path.substr(path.size() - 4) == ".csv") {
    std::istringstream in(text);
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      std::vector<double> v;
      std::stringstream ss(line);
      for (std::string c; std::getline(ss, c, ',');) v.push_back(std::stod(c));
      rows.push_back({V3(v[1], v[2], v[3]), V3(v[4], v[5], v[6]), {}});
    }
  } else if (path.substr(path.size() - 4) == ".apt") {
    text = std::regex_replace(text, std::regex("\\$\n"), "");
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("GOTO/", 0) != 0) continue;
      std::vector<double> v;
      std::stringstream ss(line.substr(5));
      for (std::string c; std::getline(ss, c, ',');) v.push_back(std::stod(c));
      rows.push_back({V3(v[0], v[1], v[2]), v.size() == 6 ? V3(v[3], v[4], v[5]) : V3::Zero(), {}});
    }
  } else {
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("G0 ", 0) != 0 && line.rfind("G1 ", 0) != 0) continue;
      Row r;
      std::istringstream ws(line.substr(3));
      for (std::string w; ws >> w;) r.words[w[0]] = std::stod(w.substr(1));
      r.point = V3(r.words['X'], r.words['Y'], r.words['Z']);
      rows.push_back(r);
    }
  }
  return rows;
}

/// The exact trajectory of x on [t0, t1] at n + 1 points.
std::vector<V3> arc_points(const qmotion::Motion& m, double t0, double t1, const V3& x, int n) {
  std::vector<V3> out;
  for (int k = 0; k <= n; ++k) out.push_back(place(m, t0 + (t1 - t0) * k / n, x));
  return out;
}

double polyline_distance(const V3& p, const std::vector<V3>& line) {
  double d = HUGE_VAL;
  for (std::size_t i = 0; i + 1 < line.size(); ++i)
    d = std::min(d, segment_distance(p, line[i], line[i + 1]));
  return d;
}

TEST(ToolpathWritten, EveryFormatMeetsTheTolerancesInItsPrintedNumbers) {
  qmotion::QSplineOptions qo;
  qo.scheme = "kks";
  const std::vector<std::pair<std::string, qmotion::Motion>> motions{
      {"bspline", rational("poses/helix_40.json")},
      {"kks", qmotion::qspline(io::read_poses(test_data("helix_10.json")), qo).motion}};
  const V3 x(1, -2, 3), a = V3(0.2, 0.1, 1).normalized();
  for (const auto& [name, m] : motions)
    for (double tol : {1e-1, 1e-2, 1e-3})
      for (const std::string ext : {".apt", ".csv", ".ngc"}) {
        SCOPED_TRACE(name + " " + std::to_string(tol) + " " + ext);
        qmotion::ToolpathOptions o;
        o.output = scratch("written" + ext).string();
        o.point = x;
        o.axis = a;
        o.chord_tol = tol;
        const qmotion::Toolpath tp = qmotion::toolpath(m, o);
        EXPECT_LE(tp.max_chord_bound, tol);
        EXPECT_LE(tp.max_chord_measured, tp.max_chord_bound);
        EXPECT_GT(tp.rounding_bound, 0);
        const auto rows = read_rows(o.output);
        ASSERT_EQ(rows.size(), tp.samples.size());
        double chord = 0, back = 0, ang = 0;
        for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
          const double t0 = tp.samples[i].t, t1 = tp.samples[i + 1].t;
          const auto arc = arc_points(m, t0, t1, x, 64);
          for (const V3& p : arc)
            chord = std::max(chord, segment_distance(p, rows[i].point, rows[i + 1].point));
          for (int s = 0; s <= 16; ++s)  // the written chord's points near the trajectory
            back = std::max(
                back, polyline_distance(
                          rows[i].point + (rows[i + 1].point - rows[i].point) * s / 16.0, arc));
          if (ext != ".ngc" && rows[i].axis.norm() > 0)
            for (int s = 0; s <= 16; ++s) {
              const V3 d = direction(m, t0 + (t1 - t0) * s / 16, a).normalized();
              ang = std::max(
                  ang, angle_to_arc(d, rows[i].axis.normalized(), rows[i + 1].axis.normalized()));
            }
        }
        EXPECT_LE(chord, tol);
        EXPECT_LE(back, tol);
        EXPECT_LE(ang, 0.5 * kPi / 180);
      }
}

/// tests/data/poses/tilt_150.json: 150 mm off the pivot, the tool axis tilting between 20
/// and 60 degrees while its azimuth turns through 120: the rotary axes move a lot.
qmotion::Motion tilting_motion() { return rational("poses/tilt_150.json", "bspline"); }

/// A head-table machine: the head's B about Y with its pivot 120 above the tip, the table's
/// C about Z off the origin.
cam::Machine head_table() {
  cam::Machine m;
  m.name = "head B, table C";
  m.axes = {cam::RotaryAxis{'B', true, V3::UnitY(), V3(0, 0, 120)},
            cam::RotaryAxis{'C', false, V3::UnitZ(), V3(20, -10, 0)}};
  return m;
}

TEST(ToolpathMachine, WhatTheMachineRunsStaysWithinTheTolerances) {
  const qmotion::Motion m = tilting_motion();
  for (double tol : {1e-1, 1e-2, 1e-3}) {
    qmotion::ToolpathOptions o;
    o.output = scratch("three.ngc").string();
    o.chord_tol = tol;
    const std::size_t alone = qmotion::toolpath(m, o).samples.size();
    for (const std::string machine : {"ac", "bc", "file"}) {
      SCOPED_TRACE(machine + " " + std::to_string(tol));
      o.output = scratch(machine + ".ngc").string();
      o.rotary = machine == "file" ? "" : machine;
      if (machine == "file") o.machine = head_table();
      const qmotion::Toolpath tp = qmotion::toolpath(m, o);
      ASSERT_TRUE(tp.machine);
      EXPECT_LE(tp.max_chord_bound, tol);
      EXPECT_LE(tp.max_angle_bound_deg, 0.5);
      EXPECT_LE(tp.tip_measured, tp.max_chord_bound);
      EXPECT_LE(tp.machine_measured, tp.machine_bound * (1 + 1e-9));
      const double ratio = static_cast<double>(tp.samples.size()) / static_cast<double>(alone);
      if (tol >= 1e-2) {
        EXPECT_LE(ratio, 1.5) << tp.samples.size() << " vs " << alone;
      }
      // The machine moves every axis linearly between the printed blocks: map its steps back.
      const auto rows = read_rows(o.output);
      ASSERT_EQ(rows.size(), tp.samples.size());
      const char r0 = tp.machine->axes[0].name, r1 = tp.machine->axes[1].name;
      double tip = 0, ang = 0;
      for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
        const double t0 = tp.samples[i].t, t1 = tp.samples[i + 1].t;
        const auto arc = arc_points(m, t0, t1, V3::Zero(), 128);
        const cam::MachineAxes q0{rows[i].point(0), rows[i].point(1), rows[i].point(2),
                                  rows[i].words.at(r0), rows[i].words.at(r1)};
        const cam::MachineAxes q1{rows[i + 1].point(0), rows[i + 1].point(1), rows[i + 1].point(2),
                                  rows[i + 1].words.at(r0), rows[i + 1].words.at(r1)};
        for (int s = 0; s <= 32; ++s) {
          cam::MachineAxes q;
          for (std::size_t j = 0; j < 5; ++j) q[j] = q0[j] + (q1[j] - q0[j]) * s / 32;
          const auto [p, k] = cam::forward_kinematics(*tp.machine, q);
          tip = std::max(tip, polyline_distance(p, arc));
          const V3 d = direction(m, t0 + (t1 - t0) * s / 32, V3::UnitZ()).normalized();
          ang = std::max(ang, angle(k, d));
        }
      }
      EXPECT_LE(tip, tol);
      EXPECT_LE(ang, 0.5 * kPi / 180);
      std::cout << "[ measured ] " << machine << " T = " << tol << ": " << tp.samples.size()
                << " points, " << ratio << " x the workpiece certificate's " << alone << "; tip "
                << tip / tol << " T, axis " << ang * 180 / kPi << " deg\n";
    }
  }
}

/// The length of the exact trajectory of the origin on [t0, t1]: polylines of 256 and 512
/// chords, extrapolated (Richardson, the error is O(h^2)).
double exact_length(const qmotion::Motion& m, double t0, double t1) {
  auto polyline = [&](int n) {
    double len = 0;
    V3 prev = place(m, t0, V3::Zero());
    for (int k = 1; k <= n; ++k) {
      const V3 p = place(m, t0 + (t1 - t0) * k / n, V3::Zero());
      len += (p - prev).norm();
      prev = p;
    }
    return len;
  };
  return (4 * polyline(512) - polyline(256)) / 3;
}

TEST(ToolpathMachine, InverseTimeFeedsMoveTheTipAtTheFeedWithinTheAxisLimits) {
  const qmotion::Motion m = tilting_motion();
  qmotion::ToolpathOptions o;
  o.output = scratch("g93.ngc").string();
  o.chord_tol = 1e-2;
  o.rotary = "ac";
  o.feed = 2000;
  o.feed_mode = "inverse-time";
  for (const bool limited : {false, true}) {
    SCOPED_TRACE(limited ? "limited" : "free");
    if (limited) o.axis_limits = {{'C', 1500.0}, {'X', 5000.0}};
    const qmotion::Toolpath tp = qmotion::toolpath(m, o);
    std::ifstream f(o.output);
    std::stringstream all;
    all << f.rdbuf();
    EXPECT_NE(all.str().find("G93"), std::string::npos);
    const auto rows = read_rows(o.output);
    ASSERT_EQ(rows.size(), tp.samples.size());
    double minutes = 0;
    std::size_t slowed = 0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
      ASSERT_TRUE(rows[i].words.count('F')) << "block " << i;
      const double fv = rows[i].words.at('F'), block = 1 / fv;
      minutes += block;
      const double tip_feed = exact_length(m, tp.samples[i - 1].t, tp.samples[i].t) / block;
      for (const auto& [w, v] : o.axis_limits)
        EXPECT_LE(std::abs(rows[i].words.at(w) - rows[i - 1].words.at(w)) / block, v * (1 + 1e-12))
            << w << " in block " << i;
      if (std::abs(tip_feed - o.feed) > 1e-6 * o.feed) {
        ++slowed;
        EXPECT_TRUE(limited) << "block " << i << ": tip feed " << tip_feed;
        EXPECT_LT(tip_feed, o.feed);
      }
    }
    EXPECT_EQ(slowed, tp.limited_blocks);
    if (limited) {
      EXPECT_GT(slowed, 0u);
    }
    EXPECT_NEAR(minutes, tp.machining_time_min, 1e-9 * minutes);
    if (!limited) {
      EXPECT_NEAR(tp.machining_time_min, tp.path_length / o.feed, 1e-6 * minutes);
    }
  }
}

TEST(ToolpathMachine, BadMachineAndFeedOptionsAreRefusedAndWriteNothing) {
  const qmotion::Motion m = rational("poses/five_positions.json");
  const std::string out = scratch("refused.ngc").string();
  fs::remove(out);
  auto with = [&](auto change) { return toolpath_with(m, out, change); };
  using O = qmotion::ToolpathOptions;
  EXPECT_TRUE(throws_error(with([](O& o) { o.rotary = "xy"; }), Errc::invalid_input,
                           {"--rotary xy", "ac or bc"}));
  EXPECT_TRUE(throws_error(with([](O& o) {
                             o.rotary = "ac";
                             o.machine_file = "m.json";
                           }),
                           Errc::invalid_input, {"--rotary and --machine"}));
  EXPECT_TRUE(throws_error(with([](O& o) {
                             o.machine = head_table();
                             o.machine->axes[1].direction = V3::UnitY();
                           }),
                           Errc::invalid_input, {"parallel"}));
  EXPECT_TRUE(throws_error(with([](O& o) {
                             o.feed_mode = "inverse-time";
                             o.output = "x.apt";
                           }),
                           Errc::invalid_input, {"inverse-time", "APT"}));
  EXPECT_TRUE(throws_error(with([](O& o) {
                             o.feed_mode = "inverse-time";
                             o.nurbs = true;
                           }),
                           Errc::invalid_input, {"inverse-time", "--nurbs"}));
  EXPECT_TRUE(throws_error(with([](O& o) { o.feed_mode = "per-rev"; }), Errc::invalid_input,
                           {"--feed-mode per-rev"}));
  EXPECT_TRUE(throws_error(with([](O& o) {
                             o.axis_limits = {{'X', 100.0}};
                           }),
                           Errc::invalid_input, {"--axis-limits", "inverse-time"}));
  EXPECT_TRUE(throws_error(with([](O& o) {
                             o.feed_mode = "inverse-time";
                             o.axis_limits = {{'X', -100.0}};
                           }),
                           Errc::invalid_input, {"--axis-limits X", "positive"}));
  EXPECT_TRUE(throws_error(with([](O& o) {
                             o.feed_mode = "inverse-time";
                             o.rotary = "ac";
                             o.axis_limits = {{'B', 100.0}};
                           }),
                           Errc::invalid_input, {"--axis-limits B", "XYZAC"}));
  EXPECT_TRUE(throws_error(with([](O& o) {
                             o.output = "x.apt";
                             o.chord_tol = 5e-6;
                           }),
                           Errc::invalid_input, {"--chord-tol", "6 decimals"}));
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace qmotion::test
