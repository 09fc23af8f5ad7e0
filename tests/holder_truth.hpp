// The first instant at which an upright cylinder carried straight from one tip position to
// another is inside a box, worked out apart from qmotion's search (cam::first_contact): the
// cylinder's disc meets the box's rectangle where the distance from its axis to the
// rectangle, a convex function of t along a straight move, is below r (an interval found by
// golden section and bisection to 1e-15), and the heights overlap on an interval of t linear
// in it. Used by tests/cam/collision_test.cpp and tests/bench/verify_peers_fcl.cpp.
#pragma once
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace qmotion::test {

/// The first t in [0, 1] at which the cylinder of radius r over heights [z0, z1] above the
/// tip, the tip moving straight from `from` to `to`, meets the box's interior; -1 if never.
inline double cylinder_box_first_contact(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                         double r, double z0, double z1,
                                         const Eigen::AlignedBox3d& box) {
  const Eigen::Vector3d d = to - from;
  auto f = [&](double t) {
    const Eigen::Vector2d c = (from + t * d).head<2>();
    const Eigen::Vector2d q = c.cwiseMax(box.min().head<2>()).cwiseMin(box.max().head<2>());
    return (c - q).norm();
  };
  double a = 0, b = 1;  // the convex f's least value, by golden section
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  for (int i = 0; i < 200 && b - a > 1e-15; ++i) {
    const double x1 = b - g * (b - a), x2 = a + g * (b - a);
    if (f(x1) < f(x2))
      b = x2;
    else
      a = x1;
  }
  const double tm = 0.5 * (a + b);
  if (f(tm) >= r) return -1;
  double lo_xy = 0, hi_xy = 1;  // where f < r: f falls before tm and rises after it
  if (f(0) >= r) {
    double lo = 0, hi = tm;
    for (int i = 0; i < 200 && hi - lo > 1e-15; ++i)
      (f(0.5 * (lo + hi)) < r ? hi : lo) = 0.5 * (lo + hi);
    lo_xy = hi;
  }
  if (f(1) >= r) {
    double lo = tm, hi = 1;
    for (int i = 0; i < 200 && hi - lo > 1e-15; ++i)
      (f(0.5 * (lo + hi)) < r ? lo : hi) = 0.5 * (lo + hi);
    hi_xy = lo;
  }
  // Heights: the bottom below the box's top, and the top above its bottom.
  double lo_z = 0, hi_z = 1;
  auto below = [&](double h0, double bound, double sign) {  // sign (h0 + t dz - bound) < 0
    if (d.z() == 0) {
      if (sign * (h0 - bound) >= 0) hi_z = -1;
      return;
    }
    const double t = (bound - h0) / d.z();
    if (sign * d.z() > 0)
      hi_z = std::min(hi_z, t);
    else
      lo_z = std::max(lo_z, t);
  };
  below(from.z() + z0, box.max().z(), 1);
  below(from.z() + z1, box.min().z(), -1);
  const double lo = std::max(lo_xy, lo_z), hi = std::min(hi_xy, hi_z);
  return lo < hi ? lo : -1;
}

}  // namespace qmotion::test
