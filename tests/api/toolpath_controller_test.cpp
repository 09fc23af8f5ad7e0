// tests/api/toolpath_controller_test.cpp mirrors the controller's contract of
// api/toolpath.hpp (docs/cam.md): the path mode of every dialect, the part of the tolerance
// left to the controller, travel and the branches, accelerations, the pole of a table, and
// the quaternion-spline fit's proven bound in every budget.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <qmotion/api/qspline.hpp>
#include <qmotion/api/toolpath.hpp>
#include <qmotion/cam/controller.hpp>
#include <string>
#include <vector>

#include "api/toolpath_util.hpp"

namespace qmotion::test {
namespace {

std::vector<std::string> file_lines(const std::string& path) {
  std::ifstream f(path);
  std::vector<std::string> out;
  for (std::string line; std::getline(f, line);) out.push_back(line);
  return out;
}

/// The index of the first line that starts with `prefix`, or the line count.
std::size_t first_line(const std::vector<std::string>& lines, const std::string& prefix) {
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i].rfind(prefix, 0) == 0) return i;
  return lines.size();
}

TEST(ToolpathController, EveryProgramCommandsItsPathModeBeforeTheFirstFeedMove) {
  const qmotion::Motion m = rational("poses/tilt_150.json", "bspline");
  using O = qmotion::ToolpathOptions;
  struct Case {
    std::string name;
    std::function<void(O&)> set;
    std::string mode, units, comment;
  };
  const std::vector<Case> cases{
      {"linuxcnc", [](O&) {}, "G61", "G21", "("},
      {"linuxcnc blending", [](O& o) { o.controller_tol = 0.004; }, "G64 P0.002000 Q0.002000",
       "G21", "("},
      {"fanuc", [](O& o) { o.dialect = "fanuc"; }, "G61", "G21", "("},
      {"siemens", [](O& o) { o.dialect = "siemens"; }, "G60 G601", "G71", "; "},
      {"siemens blending",
       [](O& o) {
         o.dialect = "siemens";
         o.controller_tol = 0.004;
       },
       "G642 CTOL=0.004000", "G71", "; "},
      {"ac inverse time",
       [](O& o) {
         o.rotary = "ac";
         o.feed_mode = "inverse-time";
       },
       "G61", "G21", "("},
      {"bc siemens",
       [](O& o) {
         o.rotary = "bc";
         o.dialect = "siemens";
       },
       "G60 G601", "G71", "; "},
      {"nurbs", [](O& o) { o.nurbs = true; }, "G61", "G21", "("}};
  const double tol = 0.01;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    O o;
    o.output = scratch("mode.ngc").string();
    o.chord_tol = tol;
    c.set(o);
    const qmotion::Toolpath tp = qmotion::toolpath(m, o);
    EXPECT_EQ(tp.path_mode, c.mode);
    const auto lines = file_lines(o.output);
    const std::size_t mode = first_line(lines, c.mode), units = first_line(lines, c.units);
    const std::size_t feed = std::min(first_line(lines, "G1 "), first_line(lines, "G06.2"));
    ASSERT_LT(feed, lines.size());
    EXPECT_LT(mode, feed);
    EXPECT_LT(units, feed);
    // The header states the assumption in one comment line of the dialect's syntax.
    const std::size_t said = first_line(lines, c.comment + "path mode " + c.mode);
    EXPECT_LT(said, mode);
    if (o.controller_tol > 0) {
      // The chords take what the controller leaves: the exact trajectory lies within
      // T - controller_tol of the written polyline (read back from the file).
      EXPECT_LE(tp.max_chord_bound, tol - o.controller_tol + 1e-12);
      EXPECT_NEAR(tp.report()["max_path_deviation_bound"].get<double>(),
                  tp.max_chord_bound + o.controller_tol, 1e-15);
      const auto rows = read_rows(o.output);
      ASSERT_EQ(rows.size(), tp.samples.size());
      EXPECT_LE(written_chord_distance(m, tp, rows), tol - o.controller_tol);
    }
  }
}

TEST(ToolpathController, ContractsTheControllerCannotKeepAreRefused) {
  const qmotion::Motion m = rational("poses/five_positions.json");
  const std::string out = scratch("refused_mode.ngc").string();
  fs::remove(out);
  auto with = [&](auto change) { return toolpath_with(m, out, change); };
  using O = qmotion::ToolpathOptions;
  EXPECT_TRUE(throws_error(with([](O& o) { o.dialect = "heidenhain"; }), Errc::invalid_input,
                           {"--dialect heidenhain", "linuxcnc, fanuc or siemens"}));
  EXPECT_TRUE(throws_error(with([](O& o) {
                             o.dialect = "fanuc";
                             o.controller_tol = 0.002;
                           }),
                           Errc::invalid_input,
                           {"--controller-tol", "fanuc", "machine parameter"}));
  EXPECT_TRUE(throws_error(with([](O& o) {
                             o.rotary = "ac";
                             o.controller_tol = 0.002;
                           }),
                           Errc::invalid_input, {"--controller-tol", "3-axis", "exact path"}));
  EXPECT_TRUE(throws_error(with([](O& o) { o.controller_tol = 0.005; }), Errc::invalid_input,
                           {"--controller-tol", "half of --chord-tol"}));
  EXPECT_TRUE(throws_error(with([](O& o) { o.controller_tol = -1; }), Errc::invalid_input,
                           {"--controller-tol", ">= 0"}));
  EXPECT_TRUE(throws_error(with([](O& o) {
                             o.nurbs = true;
                             o.dialect = "linuxcnc";
                           }),
                           Errc::invalid_input, {"--dialect linuxcnc", "G06.2"}));
  EXPECT_TRUE(throws_error(with([](O& o) {
                             o.output = "x.csv";
                             o.dialect = "siemens";
                           }),
                           Errc::invalid_input, {"--dialect", "G-code"}));
  EXPECT_FALSE(fs::exists(out));
}

/// The built-in A/C table with the A travel [lo, hi].
cam::Machine ac_with_a_travel(double lo, double hi) {
  cam::Machine m = cam::builtin_machine("ac");
  m.travel[3] = {lo, hi};
  return m;
}

TEST(ToolpathController, TravelKeepsTheBranchWithinItOrRefusesNamingTAndTheAxis) {
  // On tilt_150 the nearer branch runs A from -20 to -60 and the other from 20 to 60.
  const qmotion::Motion m = rational("poses/tilt_150.json", "bspline");
  const double tol = 0.01;
  struct Case {
    std::string name;
    double lo, hi;
  };
  for (const Case& c : {Case{"excludes the start", -10, 90}, Case{"excludes the end", -45, 90},
                        Case{"admits the nearer", -90, 10}}) {
    SCOPED_TRACE(c.name);
    qmotion::ToolpathOptions o;
    o.output = scratch("travel.ngc").string();
    o.chord_tol = tol;
    o.machine = ac_with_a_travel(c.lo, c.hi);
    const qmotion::Toolpath tp = qmotion::toolpath(m, o);
    EXPECT_EQ(tp.branch, c.hi > 20 ? "other" : "nearer");
    const auto rows = read_rows(o.output);
    ASSERT_EQ(rows.size(), tp.samples.size());
    for (const Row& r : rows) {
      EXPECT_GE(r.words.at('A'), c.lo);
      EXPECT_LE(r.words.at('A'), c.hi);
    }
    const auto [tip, ang] = machine_run(m, tp, rows);
    EXPECT_LE(tip, tol);
    EXPECT_LE(ang, 0.5 * kPi / 180);
  }
  const std::string out = scratch("travel_refused.ngc").string();
  fs::remove(out);
  auto with = [&](double lo, double hi) {
    return toolpath_with(
        m, out, [&](qmotion::ToolpathOptions& o) { o.machine = ac_with_a_travel(lo, hi); });
  };
  EXPECT_TRUE(
      throws_error(with(-15, 15), Errc::invalid_input,
                   {"at t = 0.000000", "neither branch", "A = -20", "A = 20", "[-15, 15]"}));
  EXPECT_TRUE(throws_error(
      with(-45, 45), Errc::invalid_input,
      {"at t = ", "A reaches the end of its travel [-45, 45]", "starting on the other branch"}));
  EXPECT_FALSE(fs::exists(out));
}

TEST(ToolpathController, AccelerationsLengthenTheTimeAndUnlimitedOnesDoNot) {
  const qmotion::Motion m = rational("poses/tilt_150.json", "bspline");
  qmotion::ToolpathOptions o;
  o.output = scratch("accel.ngc").string();
  o.chord_tol = 0.01;
  o.feed = 2000;
  o.feed_mode = "inverse-time";
  o.machine = cam::builtin_machine("ac");
  const qmotion::Toolpath free = qmotion::toolpath(m, o);
  EXPECT_NEAR(free.machining_time_accel_min, free.machining_time_min,
              1e-12 * free.machining_time_min);
  o.machine->acceleration = {500, 500, 500, 90, 180};
  const qmotion::Toolpath tp = qmotion::toolpath(m, o);
  EXPECT_EQ(tp.machining_time_min, free.machining_time_min);
  EXPECT_GT(tp.machining_time_accel_min, 1.05 * tp.machining_time_min);
  // An independent account from the file: each block's minutes are 1 / F, its axes move
  // linearly together, and a simulation in 1e-5 s steps accelerates every axis at most at
  // its limit from rest, holds the top speed, and brakes to rest at the block's end (it
  // lags the exact profile by a few steps per block).
  const auto rows = read_rows(o.output);
  const char words[5] = {'X', 'Y', 'Z', 'A', 'C'};
  double minutes = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    double a = HUGE_VAL;  // the block fraction's acceleration, per s^2
    for (int j = 0; j < 5; ++j) {
      const double d = std::abs(rows[i].words.at(words[j]) - rows[i - 1].words.at(words[j]));
      if (d > 0) a = std::min(a, (*o.machine).acceleration[static_cast<std::size_t>(j)] / d);
    }
    const double vmax = rows[i].words.at('F') / 60;  // the block fraction per second
    double s = 0, v = 0, t = 0;
    const double dt = 1e-5;
    while (s < 1 - 1e-12) {
      // Faster by a dt of acceleration, never above the top speed, never faster than it can
      // still stop from before the block's end.
      const double next =
          std::max(std::min({v + a * dt, vmax, std::sqrt(2 * a * (1 - s))}), 1e-3 * a * dt);
      s += 0.5 * (v + next) * dt;
      v = next;
      t += dt;
    }
    minutes += t / 60;
  }
  EXPECT_NEAR(tp.machining_time_accel_min, minutes, 2e-3 * minutes);
  std::cout << "[ time     ] tilt_150 A/C: " << tp.machining_time_min << " min at the feeds, "
            << tp.machining_time_accel_min << " with the accelerations (simulated " << minutes
            << ")\n";
}

TEST(ToolpathController, NearThePoleTheTableStaysWithinTheToleranceTurningCOnlyAsNeeded) {
  const double tol = 0.01;
  for (const std::string poses : {"far_pole", "near_pole", "through_pole"}) {
    const qmotion::Motion m = rational("poses/" + poses + ".json", "bspline");
    qmotion::ToolpathOptions three;
    three.output = scratch("pole3.ngc").string();
    three.chord_tol = tol;
    const std::size_t alone = qmotion::toolpath(m, three).samples.size();
    for (const std::string rotary : {"ac", "bc"})
      for (const bool hold : {false, true}) {
        SCOPED_TRACE(poses + " " + rotary + (hold ? " --c-hold" : ""));
        qmotion::ToolpathOptions o = three;
        o.output = scratch("pole.ngc").string();
        o.rotary = rotary;
        o.c_hold = hold;
        const qmotion::Toolpath tp = qmotion::toolpath(m, o);
        const auto rows = read_rows(o.output);
        const auto [tip, ang] = machine_run(m, tp, rows);
        EXPECT_LE(tip, tol);
        EXPECT_LE(ang, 0.5 * kPi / 180);
        // C turns monotonically and no further than the azimuth of the tool axis does: by
        // less than 180 degrees across the pole (0 straight through it, where A changes sign).
        double turn = 0, net = 0;
        for (std::size_t i = 1; i < rows.size(); ++i) {
          const double d = rows[i].words.at('C') - rows[i - 1].words.at('C');
          turn += std::abs(d);
          net += d;
        }
        EXPECT_NEAR(turn, std::abs(net), 1e-6);
        EXPECT_LT(turn, 180);
        if (poses == "through_pole") {
          EXPECT_LT(turn, 1e-6);
        }
        std::cout << "[ pole     ] " << poses << " " << rotary << (hold ? " --c-hold" : "") << ": "
                  << tp.samples.size() << " blocks (3-axis " << alone << "), C turns " << turn
                  << " deg, tip within " << tip / tol << " T\n";
      }
  }
}

TEST(ToolpathController, QuaternionSplinesSpendTheFitsProvenBound) {
  qmotion::QSplineOptions qo;
  qo.scheme = "kks";
  const qmotion::Motion m =
      qmotion::qspline(io::read_poses(test_data("poses/tilt_150.json")), qo).motion;
  const double tol = 0.01;
  for (const std::string mode : {"g1", "ac", "nurbs"}) {
    SCOPED_TRACE(mode);
    qmotion::ToolpathOptions o;
    o.output = scratch("kks.ngc").string();
    o.chord_tol = tol;
    o.rotary = mode == "ac" ? "ac" : "";
    o.nurbs = mode == "nurbs";
    const qmotion::Toolpath tp = qmotion::toolpath(m, o);
    const auto report = tp.report();
    if (mode != "nurbs") {
      EXPECT_GT(tp.fit_bound, 0);
      EXPECT_LE(tp.fit_measured, tp.fit_bound);
      EXPECT_LE(tp.fit_bound, 0.1 * tol);
      EXPECT_LE(tp.max_chord_bound, tol);
      // The sampled check beside the proof: the exact motion against the written chords.
      const auto rows = read_rows(o.output);
      ASSERT_EQ(rows.size(), tp.samples.size());
      const double worst =
          mode == "g1" ? written_chord_distance(m, tp, rows) : machine_run(m, tp, rows).first;
      EXPECT_LE(worst, tol);
      EXPECT_NEAR(report["fit_deviation_bound"].get<double>(), tp.fit_bound, 1e-15);
    } else {
      ASSERT_TRUE(tp.nurbs);
      EXPECT_LE(tp.nurbs->max_deviation_bound, tol);
      EXPECT_LE(tp.nurbs->max_deviation_measured, tp.nurbs->max_deviation_bound);
    }
  }
}

}  // namespace
}  // namespace qmotion::test
