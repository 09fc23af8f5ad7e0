// tests/api/toolpath_util.hpp: what the api tests share (the toolpath tests most): scratch
// files, motions from the test data, exact placements, and distances to chords and arcs of
// axes.
#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/api/toolpath.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/motion.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <utility>

#include "io_test_util.hpp"

namespace qmotion::test {
namespace fs = std::filesystem;
using V3 = Eigen::Vector3d;

/// A file in this test process's scratch folder.
inline fs::path scratch(const std::string& name) { return scratch_path("api", name); }

inline constexpr double kPi = 3.14159265358979323846;

inline qmotion::Motion rational(const std::string& poses, const std::string& form = "") {
  qmotion::InterpolateOptions o;
  o.form = form;
  return qmotion::interpolate(io::read_poses(test_data(poses)), o).motion;
}

/// The exact image of x under either kind of motion.
inline V3 place(const qmotion::Motion& m, double t, const V3& x) {
  if (!m.is_rational()) return kernel::rotate(m.spline().rotation(t), x) + m.spline().position(t);
  return kernel::apply_point(kernel::evaluate(m.rational(), t), x);
}
inline V3 direction(const qmotion::Motion& m, double t, const V3& a) {
  return place(m, t, a) - place(m, t, V3::Zero());
}

inline std::pair<double, double> interval(const qmotion::Motion& m) {
  if (!m.is_rational()) return {m.spline().a(), m.spline().b()};
  return {m.rational().a(), m.rational().b()};
}

inline double segment_distance(const V3& x, const V3& a, const V3& b) {
  const V3 ab = b - a;
  const double s = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (x - (a + s * ab)).norm();
}

inline double angle(const V3& u, const V3& v) { return std::atan2(u.cross(v).norm(), u.dot(v)); }

/// The angle from the unit vector x to the nearest normalised blend of the unit vectors u
/// and v (the shorter great-circle arc between them), in closed form.
inline double angle_to_arc(const V3& x, const V3& u, const V3& v) {
  const V3 n = u.cross(v);
  if (n.norm() < 1e-15) return angle(x, u);
  const V3 nn = n.normalized();
  const V3 p = x - x.dot(nn) * nn;  // x projected into the arc's plane
  // Inside the arc when p lies between u and v (on the sides of u and v that face each other).
  if (p.norm() > 0 && u.cross(p).dot(nn) >= 0 && p.cross(v).dot(nn) >= 0)
    return std::atan2(std::abs(x.dot(nn)), p.norm());
  return std::min(angle(x, u), angle(x, v));
}

/// The numbers a toolpath file states, one row per point: x, y, z and, where written, the
/// axis i, j, k (APT, CSV) or the machine words (G-code: every letter's value).
struct Row {
  V3 point = V3::Zero(), axis = V3::Zero();
  std::map<char, double> words;
};

inline std::vector<Row> read_rows(const std::string& path) {
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
inline std::vector<V3> arc_points(const qmotion::Motion& m, double t0, double t1, const V3& x,
                                  int n) {
  std::vector<V3> out;
  for (int k = 0; k <= n; ++k) out.push_back(place(m, t0 + (t1 - t0) * k / n, x));
  return out;
}

inline double polyline_distance(const V3& p, const std::vector<V3>& line) {
  double d = HUGE_VAL;
  for (std::size_t i = 0; i + 1 < line.size(); ++i)
    d = std::min(d, segment_distance(p, line[i], line[i + 1]));
  return d;
}

/// The largest distance of the exact trajectory of the origin (33 points per block) from the
/// written chords `rows` of tp.
inline double written_chord_distance(const qmotion::Motion& m, const qmotion::Toolpath& tp,
                                     const std::vector<Row>& rows) {
  double worst = 0;
  for (std::size_t i = 0; i + 1 < rows.size(); ++i)
    for (const V3& p : arc_points(m, tp.samples[i].t, tp.samples[i + 1].t, V3::Zero(), 32))
      worst = std::max(worst, segment_distance(p, rows[i].point, rows[i + 1].point));
  return worst;
}

/// What the machine runs between the written blocks `rows` of tp (G-code), every axis
/// linear, mapped to the workpiece by qmotion's forward kinematics of tp's machine: the
/// largest distance of the tip from the exact trajectory and of the axis from the exact
/// axis (radians), at 33 steps per block.
inline std::pair<double, double> machine_run(const qmotion::Motion& m, const qmotion::Toolpath& tp,
                                             const std::vector<Row>& rows) {
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
  return {tip, ang};
}

/// A call of qmotion::toolpath on m writing `out` at chord tolerance 0.01 with the options
/// `change` makes, for throws_error.
template <class F>
std::function<void()> toolpath_with(const qmotion::Motion& m, const std::string& out, F change) {
  qmotion::ToolpathOptions o;
  o.output = out;
  o.chord_tol = 1e-2;
  change(o);
  return [m, o] { qmotion::toolpath(m, o); };
}

}  // namespace qmotion::test
