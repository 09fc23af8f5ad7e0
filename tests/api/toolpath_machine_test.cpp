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
      const auto [tip, ang] = machine_run(m, tp, rows);
      EXPECT_LE(tip, tol);
      EXPECT_LE(ang, 0.5 * kPi / 180);
      if (tol == 1e-3 && machine != "file") {
        // docs/cam.md, "Measured": at 0.001 mm the machine's own interpolation sets the
        // block count, above 1.5x the workpiece certificate's, and the certified program is
        // nearly tight: the tip leaves the trajectory by more than 0.85 T. That deviation grows
        // as the square of the block length, so a program with 1.5x the workpiece count
        // would leave it by (ratio / 1.5)^2 times as much, more than T.
        EXPECT_GT(ratio, 1.5);
        EXPECT_GE(tip, 0.85 * tol);
        EXPECT_GT(tip * (ratio / 1.5) * (ratio / 1.5), tol);
      }
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
