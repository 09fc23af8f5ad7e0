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
#include <qmotion/api/toolpath.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/io/qspline_file.hpp>
#include <sstream>
#include <vector>

#include "cli_util.hpp"
#include "rs274_util.hpp"

namespace qmotion::test {
namespace {

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
  // The library writes the same files and knows each point's t and exact place.
  qmotion::ToolpathOptions o;
  o.point = Eigen::Vector3d(1, 0, 2);
  o.axis = Eigen::Vector3d(1, 0, 1);
  o.chord_tol = 0.01;
  o.output = (scratch_dir() / "tp_lib.ngc").string();
  const qmotion::Toolpath tp3 = qmotion::toolpath(io::load_motion(m), o);
  ASSERT_EQ(slurp(o.output), slurp(ngc));
  o.rotary = "ac";
  o.output = (scratch_dir() / "tp5_lib.ngc").string();
  const qmotion::Toolpath tp5 = qmotion::toolpath(io::load_motion(m), o);
  ASSERT_EQ(slurp(o.output), slurp(ngc5));
  std::string log;
  const auto moves = rs274_moves(ngc, log);
  RS274_OR_SKIP(moves);
  {  // exact path before the first feed move
    const auto [mode, feed] = path_mode_and_first_feed(log);
    EXPECT_LT(mode, feed) << log;
    EXPECT_NE(log.find("SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)"), std::string::npos) << log;
  }
  {  // blending within what the chords leave: P and Q of 0.002 each
    const std::string blended = (scratch_dir() / "tp_blend.ngc").string();
    std::vector<std::string> args{"toolpath", m, "-o", blended, "--controller-tol", "0.004"};
    args.insert(args.end(), common.begin(), common.end());
    const Result r = run(args);
    ASSERT_EQ(r.status, 0) << r.err;
    const json report = json::parse(r.out);
    EXPECT_LE(report["max_chord_deviation_bound"].get<double>(), 0.006);
    EXPECT_LE(report["max_path_deviation_bound"].get<double>(), 0.01);
    std::string blog;
    const auto bmoves = rs274_moves(blended, blog);
    RS274_OR_SKIP(bmoves);
    const auto [mode, feed] = path_mode_and_first_feed(blog);
    EXPECT_LT(mode, feed) << blog;
    EXPECT_NE(blog.find("SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, 0.002000)"), std::string::npos)
        << blog;
    EXPECT_NE(blog.find("SET_NAIVECAM_TOLERANCE(0.0020)"), std::string::npos) << blog;
  }
  const auto words = gcode_words(ngc);
  ASSERT_EQ(moves->size(), words.size()) << log;
  ASSERT_EQ(words.size(), tp3.samples.size());
  // The interpreter's 4 decimals are the file's 6; the file's are the exact points rounded.
  for (std::size_t i = 0; i < words.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const char w = static_cast<char>('X' + c);
      EXPECT_NEAR((*moves)[i][static_cast<std::size_t>(c)], words[i].at(w), 5.1e-5) << i;
      EXPECT_NEAR(words[i].at(w), tp3.samples[i].point(c), 5.1e-7) << "move " << i;
    }
  // 5-axis: machine XYZ = Rx(A) Rz(C) p, and A, C take the axis onto +Z.
  const auto moves5 = rs274_moves(ngc5, log);
  RS274_OR_SKIP(moves5);
  const auto words5 = gcode_words(ngc5);
  ASSERT_EQ(moves5->size(), words5.size()) << log;
  ASSERT_EQ(words5.size(), tp5.samples.size());
  for (std::size_t i = 0; i < words5.size(); ++i) {
    const auto& mv = (*moves5)[i];
    EXPECT_NEAR(mv[3], words5[i].at('A'), 5.1e-5);
    EXPECT_NEAR(mv[5], words5[i].at('C'), 5.1e-5);
    // The file's own 9 decimals of A and C: T p and T k from them.
    const double A = words5[i].at('A') * 3.14159265358979323846 / 180,
                 C = words5[i].at('C') * 3.14159265358979323846 / 180;
    const Eigen::Matrix3d T = (Eigen::AngleAxisd(A, Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(C, Eigen::Vector3d::UnitZ()))
                                  .toRotationMatrix();
    const Eigen::Vector3d p = T * tp5.samples[i].point;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(mv[static_cast<std::size_t>(c)], p(c), 5.1e-5 + 1e-6 * p.norm()) << "move " << i;
      EXPECT_NEAR(words5[i].at(static_cast<char>('X' + c)), p(c), 5.1e-7 + 1e-9 * p.norm());
    }
    const Eigen::Vector3d z = T * tp5.samples[i].axis;
    EXPECT_LE(std::atan2(z.cross(Eigen::Vector3d::UnitZ()).norm(), z(2)), 1e-9) << "move " << i;
  }
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

TEST(Cli, ToolpathMachinesAndInverseTimeRunInLinuxCncsInterpreter) {
  // 150 mm off the pivot, the axis tilting by tens of degrees: A/C and B/C tables, a
  // head-table machine file, each with inverse-time feed and axis limits; and an A/C table
  // with the tool axis passing 0.2 degrees from its pole.
  auto motion_file = [](const std::string& poses) {
    const std::string m = (scratch_dir() / (poses + "_motion.json")).string();
    EXPECT_EQ(
        run({"interpolate", test_data("poses/" + poses + ".json"), "--form", "bspline", "-o", m})
            .status,
        0);
    return m;
  };
  const double tol = 0.01;
  struct Case {
    std::string name;
    std::vector<std::string> args;
    std::string poses = "tilt_150";
  };
  const std::vector<Case> cases{
      {"ac", {"--rotary", "ac", "--feed-mode", "inverse-time", "--axis-limits", "A=4000,C=4000"}},
      {"bc", {"--rotary", "bc", "--feed-mode", "inverse-time"}},
      {"file", {"--machine", test_data("machines/head_table.json"), "--feed-mode", "inverse-time"}},
      {"heads", {"--machine", test_data("machines/head_head.json")}},
      {"near", {"--rotary", "ac", "--feed-mode", "inverse-time"}, "near_pole"}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string m = motion_file(c.poses);
    const qmotion::Motion motion = io::load_motion(m);
    const std::string ngc = (scratch_dir() / ("tilt_" + c.name + ".ngc")).string();
    std::vector<std::string> args{"toolpath", m,        "--point", "0,0,0", "--chord-tol",
                                  "0.01",     "--feed", "800",     "-o",    ngc};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const Result r = run(args);
    ASSERT_EQ(r.status, 0) << r.err;
    const json report = json::parse(r.out);
    EXPECT_LE(report["max_chord_deviation_bound"].get<double>(), tol);
    EXPECT_FALSE(report["machine"]["name"].get<std::string>().empty());
    const bool inverse = c.name != "heads";
    EXPECT_EQ(report["feed_mode"].get<std::string>(),
              inverse ? "inverse-time" : "units-per-minute");
    // The library makes the same file; it knows each block's t.
    qmotion::ToolpathOptions o;
    o.output = (scratch_dir() / ("tilt_lib_" + c.name + ".ngc")).string();
    o.chord_tol = tol;
    o.feed = 800;
    if (c.name == "ac" || c.name == "bc") o.rotary = c.name;
    if (c.name == "near") o.rotary = "ac";
    if (c.name == "file") o.machine_file = test_data("machines/head_table.json");
    if (c.name == "heads") o.machine_file = test_data("machines/head_head.json");
    if (inverse) o.feed_mode = "inverse-time";
    if (c.name == "ac") o.axis_limits = {{'A', 4000.0}, {'C', 4000.0}};
    const qmotion::Toolpath tp = qmotion::toolpath(motion, o);
    ASSERT_EQ(slurp(o.output), slurp(ngc));
    const auto words = gcode_words(ngc);
    ASSERT_EQ(words.size(), tp.samples.size());
    std::string log;
    const auto moves = rs274_moves(ngc, log);
    RS274_OR_SKIP(moves);
    ASSERT_EQ(moves->size(), words.size()) << log;
    const auto [mode, feed] = path_mode_and_first_feed(log);
    EXPECT_LT(mode, feed) << log;
    EXPECT_NE(log.find("CANON_EXACT_PATH"), std::string::npos) << log;
    if (inverse) {
      EXPECT_NE(log.find("inverse time"), std::string::npos) << log;
    }
    // rs274's moves (4 decimals) are the file's; interpolated linearly in the machine axes
    // and mapped to the workpiece, the tip stays within T of the exact trajectory (plus what
    // rs274's printing moves it: 5e-5 per word) and the axis within the angle tolerance.
    std::vector<double> feeds;  // the feed rate rs274 sets before each STRAIGHT_FEED
    {
      std::istringstream in(log);
      double last = 0;
      for (std::string line; std::getline(in, line);) {
        const auto p = line.find("SET_FEED_RATE(");
        if (p != std::string::npos) last = std::stod(line.substr(p + 14));
        if (line.find("STRAIGHT_FEED(") != std::string::npos) feeds.push_back(last);
      }
    }
    ASSERT_EQ(feeds.size() + 1, moves->size());
    const char r0 = tp.machine->axes[0].name, r1 = tp.machine->axes[1].name;
    auto column = [](char w) { return w == 'A' ? 3 : w == 'B' ? 4 : 5; };
    double tip = 0, ang = 0;
    for (std::size_t i = 0; i < moves->size(); ++i) {
      const auto& mv = (*moves)[i];
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(mv[static_cast<std::size_t>(k)], words[i].at(static_cast<char>('X' + k)),
                    5.1e-5);
      }
      EXPECT_NEAR(mv[static_cast<std::size_t>(column(r0))], words[i].at(r0), 5.1e-5);
      EXPECT_NEAR(mv[static_cast<std::size_t>(column(r1))], words[i].at(r1), 5.1e-5);
      if (i == 0) continue;
      const auto& mp = (*moves)[i - 1];
      const cam::MachineAxes q0{mp[0], mp[1], mp[2], mp[static_cast<std::size_t>(column(r0))],
                                mp[static_cast<std::size_t>(column(r1))]};
      const cam::MachineAxes q1{mv[0], mv[1], mv[2], mv[static_cast<std::size_t>(column(r0))],
                                mv[static_cast<std::size_t>(column(r1))]};
      const double t0 = tp.samples[i - 1].t, t1 = tp.samples[i].t;
      std::vector<Eigen::Vector3d> arc;
      for (int k = 0; k <= 128; ++k)
        arc.push_back(motion.place(t0 + (t1 - t0) * k / 128, Eigen::Vector3d::Zero()));
      for (int s = 0; s <= 32; ++s) {
        cam::MachineAxes q;
        for (std::size_t j = 0; j < 5; ++j) q[j] = q0[j] + (q1[j] - q0[j]) * s / 32;
        auto [p, k] = cam::forward_kinematics(*tp.machine, q);
        if (c.name == "ac" || c.name == "bc" || c.name == "near") {
          // LinuxCNC's own trt kinematics is the reference for its tables.
          const std::array<double, 6> j{
              q[0], q[1], q[2], r0 == 'A' ? q[3] : 0.0, r0 == 'B' ? q[3] : 0.0, q[4]};
          const auto [pl, kl] = trt_forward(r0, j);
          EXPECT_LE((pl - p).norm(), 1e-9 * (1 + p.norm()));
          EXPECT_LE((kl - k).norm(), 1e-12);
          p = pl;
          k = kl;
        }
        double d = HUGE_VAL;
        for (std::size_t e = 0; e + 1 < arc.size(); ++e) {
          const Eigen::Vector3d ab = arc[e + 1] - arc[e];
          const double u = std::clamp((p - arc[e]).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
          d = std::min(d, (p - arc[e] - u * ab).norm());
        }
        tip = std::max(tip, d);
        const Eigen::Vector3d z = (motion.place(t0 + (t1 - t0) * s / 32, Eigen::Vector3d::UnitZ()) -
                                   motion.place(t0 + (t1 - t0) * s / 32, Eigen::Vector3d::Zero()));
        ang = std::max(ang, std::atan2(k.cross(z).norm(), k.dot(z)));
      }
      // Inverse time: rs274 turns F into the feed that takes the block 1/F minutes over
      // the machine's XYZ move.
      if (inverse) {
        const double xyz = Eigen::Vector3d(words[i].at('X') - words[i - 1].at('X'),
                                           words[i].at('Y') - words[i - 1].at('Y'),
                                           words[i].at('Z') - words[i - 1].at('Z'))
                               .norm();
        EXPECT_NEAR(feeds.at(i - 1), xyz * words[i].at('F'), 5e-5 + 1e-7 * feeds.at(i - 1))
            << "block " << i;
      }
    }
    // What rs274 prints moves the tip by up to 5e-5 per XYZ word and 5e-5 degrees per angle.
    const double printing = std::sqrt(3.0) * 5e-5 + 2 * 250 * 5e-5 * 3.14159265358979323846 / 180;
    EXPECT_LE(tip, tol + printing);
    EXPECT_LE(ang, 0.5 * 3.14159265358979323846 / 180 + 2e-6);
    std::cout << "[ rs274    ] " << c.name << ": " << words.size() << " blocks, tip within "
              << tip / tol << " T, axis within " << ang * 180 / 3.14159265358979323846 << " deg\n";
  }
}

}  // namespace
}  // namespace qmotion::test
