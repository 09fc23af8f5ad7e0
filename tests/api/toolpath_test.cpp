// tests/api/toolpath_test.cpp mirrors api/toolpath.hpp and cam/toolpath.hpp
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/api/qspline.hpp>
#include <qmotion/api/toolpath.hpp>
#include <qmotion/io/poses.hpp>
#include <sstream>

#include "api/toolpath_util.hpp"
#include "sanitized_size.hpp"

namespace qmotion::test {
namespace {
namespace fs = std::filesystem;
using V3 = Eigen::Vector3d;

/// Dense evaluation of every segment against the exact motion (65 points each): the
/// largest chord distance and axis angle from the blends of the end axes (radians).
std::pair<double, double> dense_check(const qmotion::Motion& m, const qmotion::Toolpath& tp,
                                      const V3& x, const V3& a) {
  double chord = 0, angle = 0;
  for (std::size_t i = 0; i + 1 < tp.samples.size(); ++i) {
    const auto &s0 = tp.samples[i], &s1 = tp.samples[i + 1];
    for (int k = 0; k <= 64; ++k) {
      const double u = s0.t + (s1.t - s0.t) * k / 64;
      chord = std::max(chord, segment_distance(place(m, u, x), s0.point, s1.point));
      const V3 ax = direction(m, u, a).normalized();
      angle = std::max(angle, angle_to_arc(ax, s0.axis, s1.axis));
    }
  }
  return {chord, angle};
}

TEST(Toolpath, TolerancesHoldOnEveryKindOfMotion) {
  qmotion::QSplineOptions qo;
  qo.scheme = "kks";
  const std::vector<std::pair<std::string, qmotion::Motion>> motions{
      {"bezier", rational("poses/five_positions.json")},
      {"bspline", rational("poses/helix_40.json")},
      {"c1", rational("poses/helix_40.json", "c1")},
      {"kks", qmotion::qspline(io::read_poses(test_data("helix_10.json")), qo).motion}};
  const V3 x(1, -2, 3), a = V3(0.2, 0.1, 1).normalized();
  for (const auto& [name, m] : motions)
    for (double tol : steps({1e-1, 1e-2, 1e-3, 1e-4})) {
      SCOPED_TRACE(name + " " + std::to_string(tol));
      qmotion::ToolpathOptions o;
      o.output = scratch("tp.csv").string();
      o.point = x;
      o.axis = a;
      o.chord_tol = tol;
      const qmotion::Toolpath tp = qmotion::toolpath(m, o);
      EXPECT_LE(tp.max_chord_bound, tol);
      EXPECT_LE(tp.max_angle_bound_deg, 0.5);
      const auto [chord, angle] = dense_check(m, tp, x, a);
      EXPECT_LE(chord, tol * (1 + 1e-9));
      EXPECT_LE(chord, tp.max_chord_bound * (1 + 1e-6));  // the bound bounds
      EXPECT_LE(angle, 0.5 * kPi / 180 * (1 + 1e-9));
      // The points lie on the trajectory (the fit's tenth of the tolerance for kks).
      for (const auto& s : tp.samples)
        EXPECT_LE((s.point - place(m, s.t, x)).norm(),
                  name == "kks" ? 0.1 * tol : 1e-9 * (1 + s.point.norm()));
      const auto [ta, tb] = interval(m);
      EXPECT_EQ(tp.samples.front().t, ta);
      EXPECT_EQ(tp.samples.back().t, tb);
    }
}

TEST(Toolpath, ACircularArcNeedsAtMostOneAndAHalfTimesTheMinimum) {
  // A pure rotation about z through 120 degrees: the point at radius r runs on a circle;
  // the fewest chords within T number ceil(theta / (2 acos(1 - T / r))).
  const std::string poses = scratch("arc.json").string();
  std::ofstream(poses) << R"({"poses": [
    {"t": 0, "position": [0, 0, 0], "rotation": {"axis_angle": {"axis": [0, 0, 1], "angle_deg": 0}}},
    {"t": 0.5, "position": [0, 0, 0], "rotation": {"axis_angle": {"axis": [0, 0, 1], "angle_deg": 60}}},
    {"t": 1, "position": [0, 0, 0], "rotation": {"axis_angle": {"axis": [0, 0, 1], "angle_deg": 120}}}]})";
  qmotion::InterpolateOptions io_opt;
  const qmotion::Motion m = qmotion::interpolate(io::read_poses(poses), io_opt).motion;
  const double r = 10, theta = 2 * kPi / 3;
  for (double tol : {1e-1, 1e-2, 1e-3, 1e-4}) {
    qmotion::ToolpathOptions o;
    o.output = scratch("arc.csv").string();
    o.point = V3(r, 0, 0);
    o.chord_tol = tol;
    const auto tp = qmotion::toolpath(m, o);
    const double minimum = std::ceil(theta / (2 * std::acos(1 - tol / r)));
    const double segments = static_cast<double>(tp.samples.size() - 1);
    EXPECT_LE(segments, 1.5 * minimum) << "tol " << tol;
    EXPECT_GE(segments, minimum) << "tol " << tol;
    std::cout << "[ arc      ] tol " << tol << ": " << segments << " segments, minimum " << minimum
              << "\n";
    EXPECT_NEAR(tp.path_length, r * theta, 1e-9 * r);
  }
}

/// The statements of an APT file, continuation lines joined; every line at most 72 wide.
std::vector<std::string> apt_statements(const std::string& path) {
  std::ifstream f(path);
  std::vector<std::string> out;
  std::string line, cur;
  while (std::getline(f, line)) {
    EXPECT_LE(line.size(), 72u) << line;
    if (!line.empty() && line.back() == '$') {
      cur += line.substr(0, line.size() - 1);
    } else {
      out.push_back(cur + line);
      cur.clear();
    }
  }
  return out;
}

std::vector<double> numbers_after(const std::string& s, char sep) {
  std::vector<double> v;
  std::stringstream ss(s.substr(s.find(sep) + 1));
  for (std::string cell; std::getline(ss, cell, ',');) v.push_back(std::stod(cell));
  return v;
}

TEST(Toolpath, AptGotosLieOnTheTrajectoryWithUnitAxes) {
  const qmotion::Motion m = rational("poses/helix_40.json");
  qmotion::ToolpathOptions o;
  o.output = scratch("tp.apt").string();
  o.point = V3(0, 0, 2);
  o.axis = V3(0, 1, 1);
  o.chord_tol = 1e-3;
  o.feed = 2500;
  const auto tp = qmotion::toolpath(m, o);
  const auto st = apt_statements(o.output);
  ASSERT_GE(st.size(), 5u);
  EXPECT_EQ(st[0].rfind("PARTNO", 0), 0u);
  EXPECT_EQ(st[1], "UNITS/MM");
  EXPECT_EQ(st[2], "MULTAX/ON");
  EXPECT_EQ(st[3], "FEDRAT/2500.0000");
  EXPECT_EQ(st.back(), "FINI");
  std::size_t g = 0;
  for (const auto& s : st) {
    if (s.rfind("GOTO/", 0) != 0) continue;
    const auto v = numbers_after(s, '/');
    ASSERT_EQ(v.size(), 6u) << s;
    ASSERT_LT(g, tp.samples.size());
    const double t = tp.samples[g++].t;
    EXPECT_LE((V3(v[0], v[1], v[2]) - place(m, t, o.point)).norm(), 2e-6) << s;
    EXPECT_NEAR(V3(v[3], v[4], v[5]).norm(), 1.0, 2e-9) << s;
    EXPECT_LE((V3(v[3], v[4], v[5]) - direction(m, t, o.axis).normalized()).norm(), 2e-9);
  }
  EXPECT_EQ(g, tp.samples.size());
}

TEST(Toolpath, RotaryAcAnglesReproduceTheAxisAndStayContinuous) {
  const qmotion::Motion m = rational("poses/helix_40.json");
  qmotion::ToolpathOptions o;
  o.output = scratch("tp5.ngc").string();
  o.point = V3(1, 0, 0);
  o.axis = V3(1, 0, 1);
  o.chord_tol = 1e-2;
  o.rotary = "ac";
  const auto tp = qmotion::toolpath(m, o);
  ASSERT_EQ(tp.machine_axes.size(), tp.samples.size());
  for (std::size_t i = 0; i < tp.samples.size(); ++i) {
    const double A = tp.machine_axes[i][3] * kPi / 180, C = tp.machine_axes[i][4] * kPi / 180;
    const Eigen::Matrix3d T =
        (Eigen::AngleAxisd(A, V3::UnitX()) * Eigen::AngleAxisd(C, V3::UnitZ())).toRotationMatrix();
    const V3 z = T * tp.samples[i].axis;
    EXPECT_LE(std::atan2(z.cross(V3::UnitZ()).norm(), z.dot(V3::UnitZ())), 1e-9) << "sample " << i;
    if (i > 0) {
      EXPECT_LT(std::abs(tp.machine_axes[i][4] - tp.machine_axes[i - 1][4]), 90.0)
          << "C jumps at sample " << i;
      EXPECT_LT(std::abs(tp.machine_axes[i][3] - tp.machine_axes[i - 1][3]), 90.0)
          << "A jumps at sample " << i;
    }
  }
}

TEST(Toolpath, UnitsConvertTheOutputAndTheTolerances) {
  const qmotion::Motion m = rational("poses/five_positions.json");  // mm
  qmotion::ToolpathOptions o;
  o.output = scratch("mm.csv").string();
  o.point = V3(1, 2, 3);
  o.chord_tol = 0.0254;
  const auto mm = qmotion::toolpath(m, o);
  o.output = scratch("in.ngc").string();
  o.units = "in";
  o.chord_tol = 0.001;  // the same length in inches
  const auto in = qmotion::toolpath(m, o);
  EXPECT_EQ(in.units, "in");
  EXPECT_EQ(in.samples.size(), mm.samples.size());
  EXPECT_NEAR(in.path_length * 25.4, mm.path_length, 1e-9 * mm.path_length);
  EXPECT_LE((in.samples.back().point * 25.4 - mm.samples.back().point).norm(), 1e-9);
  std::ifstream f(o.output);
  std::string header, assumption, modes;
  std::getline(f, header);
  std::getline(f, assumption);
  std::getline(f, modes);
  EXPECT_EQ(modes.rfind("G20", 0), 0u) << modes;
  o.units = "cm";
  EXPECT_TRUE(throws_error([&] { qmotion::toolpath(m, o); }, Errc::invalid_input, {"--units cm"}));
}

/// A Fanuc-style G06.2 NURBS as the test reads it back from the G-code file.
struct GNurbs {
  int order = 0;
  std::vector<double> knots, weights;
  std::vector<V3> points;
  V3 start = V3::Constant(NAN);  // the G0 position before the NURBS
};

/// The value of the letter's word in a block ("X1.5" -> 1.5), NaN without it.
double word(const std::string& block, char letter) {
  std::istringstream ss(block);
  for (std::string w; ss >> w;)
    if (w.size() > 1 && w[0] == letter) return std::stod(w.substr(1));
  return NAN;
}

GNurbs read_g06(const std::string& path) {
  std::ifstream f(path);
  GNurbs g;
  bool in = false;
  for (std::string line; std::getline(f, line);) {
    if (line.empty() || line[0] == '(') continue;
    if (line.rfind("G0 ", 0) == 0) g.start = V3(word(line, 'X'), word(line, 'Y'), word(line, 'Z'));
    if (line.rfind("G06.2 ", 0) == 0) {
      in = true;
      g.order = static_cast<int>(word(line, 'P'));
      EXPECT_FALSE(std::isnan(word(line, 'F'))) << "the first block carries the feed";
    }
    if (!in || line.rfind("M2", 0) == 0) continue;
    g.knots.push_back(word(line, 'K'));
    if (!std::isnan(word(line, 'X'))) {
      EXPECT_TRUE(g.knots.size() == g.points.size() + 1) << "a control point after bare knots";
      g.points.emplace_back(word(line, 'X'), word(line, 'Y'), word(line, 'Z'));
      g.weights.push_back(word(line, 'R'));
    }
  }
  return g;
}

/// The test's own rational de Boor evaluation of the G-code NURBS at s.
V3 eval_g06(const GNurbs& g, double s) {
  const int p = g.order - 1, n = static_cast<int>(g.points.size());
  int j = p;
  while (j + 1 < n && g.knots[static_cast<std::size_t>(j + 1)] <= s) ++j;
  std::vector<Eigen::Vector4d> d;
  for (int i = j - p; i <= j; ++i) {
    const double w = g.weights[static_cast<std::size_t>(i)];
    d.emplace_back(w, w * g.points[static_cast<std::size_t>(i)](0),
                   w * g.points[static_cast<std::size_t>(i)](1),
                   w * g.points[static_cast<std::size_t>(i)](2));
  }
  for (int r = 1; r <= p; ++r)
    for (int i = p; i >= r; --i) {
      const double k0 = g.knots[static_cast<std::size_t>(j - p + i)],
                   k1 = g.knots[static_cast<std::size_t>(j + 1 + i - r)];
      const double al = (s - k0) / (k1 - k0);
      d[static_cast<std::size_t>(i)] =
          (1 - al) * d[static_cast<std::size_t>(i - 1)] + al * d[static_cast<std::size_t>(i)];
    }
  const Eigen::Vector4d y = d[static_cast<std::size_t>(p)];
  return y.tail<3>() / y(0);
}

TEST(Toolpath, NurbsBlocksParseBackAsClampedCubicsWithinTheTolerance) {
  qmotion::QSplineOptions qo;
  qo.scheme = "kks";
  const std::string two = scratch("quarter.json").string();
  std::ofstream(two) << R"({"poses": [
    {"t": 0, "position": [0, 0, 0], "rotation": {"quaternion": [1, 0, 0, 0]}},
    {"t": 1, "position": [0, 0, 4], "rotation": {"axis_angle": {"axis": [0, 0, 1], "angle_deg": 90}}}]})";
  const std::vector<std::pair<std::string, qmotion::Motion>> motions{
      {"quarter", qmotion::interpolate(io::read_poses(two), {}).motion},  // a rational cubic path
      {"bezier", rational("poses/five_positions.json")},
      {"bspline", rational("poses/helix_40.json")},
      {"c1", rational("poses/helix_40.json", "c1")},
      {"kks", qmotion::qspline(io::read_poses(test_data("helix_10.json")), qo).motion}};
  const V3 x(1, -2, 3);
  for (const auto& [name, m] : motions)
    for (double tol : steps({1e-1, 1e-2, 1e-3, 1e-4})) {
      SCOPED_TRACE(name + " " + std::to_string(tol));
      qmotion::ToolpathOptions o;
      o.output = scratch("nurbs.ngc").string();
      o.point = x;
      o.chord_tol = tol;
      o.nurbs = true;
      const qmotion::Toolpath tp = qmotion::toolpath(m, o);
      ASSERT_TRUE(tp.nurbs.has_value());
      const GNurbs g = read_g06(o.output);
      const std::size_t n = g.points.size(), P = static_cast<std::size_t>(g.order);
      ASSERT_GE(g.order, 2);
      EXPECT_LE(g.order, 4);  // degree <= 3
      ASSERT_EQ(g.knots.size(), n + P);
      EXPECT_EQ(g.start, g.points.front());  // the first control point is the current position
      for (std::size_t i = 1; i < P; ++i) {  // clamped
        EXPECT_EQ(g.knots[i], g.knots[0]);
        EXPECT_EQ(g.knots[n + i], g.knots[n]);
      }
      for (std::size_t i = 0; i + 1 < g.knots.size(); ++i) EXPECT_LE(g.knots[i], g.knots[i + 1]);
      for (std::size_t i = 0; i + P < g.knots.size(); ++i) EXPECT_LT(g.knots[i], g.knots[i + P]);
      for (double w : g.weights) {
        EXPECT_GE(w, 0.0001);
        EXPECT_LE(w, 99.9999);
      }
      // The written knots stand for the motion's parameters t_knots (an affine map); the
      // NURBS, evaluated from the file, follows the exact trajectory under the
      // piecewise-affine map between them within the tolerance, which bounds its distance
      // from the trajectory both ways.
      const auto& tk = tp.nurbs->t_knots;
      ASSERT_EQ(tk.size(), g.knots.size());
      const double ta = tk.front(), tb = tk.back();
      for (std::size_t i = 0; i < tk.size(); ++i)
        EXPECT_NEAR(g.knots[i], (tk[i] - ta) / (tb - ta), 1e-8);
      double dev = 0;
      for (std::size_t i = P - 1; i < n; ++i) {
        const double s0 = g.knots[i], s1 = g.knots[i + 1];
        if (!(s1 > s0)) continue;
        for (int k = 0; k <= 200; ++k) {
          const double s = s0 + (s1 - s0) * k / 200;
          const double t = tk[i] + (tk[i + 1] - tk[i]) * k / 200;
          dev = std::max(dev, (eval_g06(g, s) - place(m, t, x)).norm());
        }
      }
      EXPECT_LE(dev, tol);
      EXPECT_LE(dev, tp.nurbs->max_deviation_bound * (1 + 1e-6));  // the bound bounds
      EXPECT_LE(tp.nurbs->max_deviation_bound, tol);
      EXPECT_NEAR(tp.nurbs->max_deviation_measured, dev, 0.05 * dev + 1e-12);
      EXPECT_EQ(tp.nurbs->curve.ctrl().size(), n);
      if (name == "quarter") {  // the trajectory itself: one rational cubic
        EXPECT_TRUE(tp.nurbs->exact);
        EXPECT_EQ(n, 4u);
      }
      // Far fewer blocks than the linear moves for the same tolerance.
      if (name == "bspline") {
        o.nurbs = false;
        o.output = scratch("lines.ngc").string();
        o.angle_tol_deg = 89;  // the chord alone decides
        EXPECT_LT(5 * n, qmotion::toolpath(m, o).samples.size());
      }
    }
}

TEST(Toolpath, BadOptionsAreRefusedAndWriteNothing) {
  const qmotion::Motion m = rational("poses/five_positions.json");
  const std::string out = scratch("bad.ngc").string();
  auto with = [&](auto change) { return toolpath_with(m, out, change); };
  EXPECT_TRUE(throws_error(with([](qmotion::ToolpathOptions& o) { o.axis = V3::Zero(); }),
                           Errc::invalid_input, {"--axis"}));
  EXPECT_TRUE(throws_error(with([](qmotion::ToolpathOptions& o) { o.chord_tol = 0; }),
                           Errc::invalid_input, {"--chord-tol"}));
  EXPECT_TRUE(throws_error(with([](qmotion::ToolpathOptions& o) { o.chord_tol = 1e300; }),
                           Errc::invalid_input, {"--chord-tol"}));
  EXPECT_TRUE(throws_error(with([](qmotion::ToolpathOptions& o) { o.output = "x.gcode"; }),
                           Errc::invalid_input, {".ngc"}));
  EXPECT_TRUE(throws_error(with([](qmotion::ToolpathOptions& o) { o.angle_tol_deg = 0; }),
                           Errc::invalid_input, {"--angle-tol"}));
  EXPECT_TRUE(throws_error(with([](qmotion::ToolpathOptions& o) {
                             o.nurbs = true;
                             o.output = "x.csv";
                           }),
                           Errc::invalid_input, {"--nurbs", "G-code"}));
  EXPECT_TRUE(throws_error(with([](qmotion::ToolpathOptions& o) {
                             o.nurbs = true;
                             o.rotary = "ac";
                           }),
                           Errc::invalid_input, {"--nurbs", "--rotary"}));
  EXPECT_TRUE(throws_error(with([](qmotion::ToolpathOptions& o) {
                             o.nurbs = true;
                             o.max_step = 1;
                           }),
                           Errc::invalid_input, {"--max-step", "--nurbs"}));
  EXPECT_TRUE(throws_error(with([](qmotion::ToolpathOptions& o) {
                             o.nurbs = true;
                             o.chord_tol = 1e-6;
                           }),
                           Errc::invalid_input, {"--chord-tol 1e-06", "6 decimals"}));
  EXPECT_TRUE(throws_error(with([](qmotion::ToolpathOptions& o) { o.arc_length = true; }),
                           Errc::invalid_input, {"--arc-length", "CSV"}));
  // A pure rotation about z keeps the axis (0, 0, 1) vertical: C is undefined there.
  const std::string poses = scratch("spin.json").string();
  std::ofstream(poses) << R"({"poses": [
    {"t": 0, "position": [0, 0, 0], "rotation": {"quaternion": [1, 0, 0, 0]}},
    {"t": 1, "position": [5, 0, 0], "rotation": {"axis_angle": {"axis": [0, 0, 1], "angle_deg": 40}}},
    {"t": 2, "position": [9, 2, 0], "rotation": {"axis_angle": {"axis": [0, 0, 1], "angle_deg": 80}}}]})";
  const qmotion::Motion spin = qmotion::interpolate(io::read_poses(poses), {}).motion;
  qmotion::ToolpathOptions o;
  o.output = out;
  o.chord_tol = 1e-2;
  o.rotary = "ac";
  EXPECT_TRUE(throws_error([&] { qmotion::toolpath(spin, o); }, Errc::invalid_input,
                           {"vertical", "--c-hold"}));
  EXPECT_FALSE(fs::exists(out));
  o.c_hold = true;
  const auto tp = qmotion::toolpath(spin, o);
  for (const auto& q : tp.machine_axes) EXPECT_NEAR(q[3], 0.0, 1e-12);
  EXPECT_TRUE(fs::exists(out));
}

}  // namespace
}  // namespace qmotion::test
