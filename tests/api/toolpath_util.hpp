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
#include <functional>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/api/toolpath.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/motion.hpp>
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
