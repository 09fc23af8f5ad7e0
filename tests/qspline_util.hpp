// tests/qspline_util.hpp: the quaternion spline the qspline bound and fit tests share.
#pragma once
#include <cmath>
#include <qmotion/kernel/qspline.hpp>
#include <vector>

namespace qmotion::test {

/// Six keys turning 1.2 rad apart about changing axes, positions about 10 apart; the quintic
/// on unequal spans (only C0 in u at its keys).
inline kernel::QuaternionSpline six_key_spline(kernel::QSplineScheme scheme) {
  using V3 = Eigen::Vector3d;
  std::vector<kernel::Quaternion<double>> q;
  std::vector<V3> p;
  kernel::Quaternion<double> r(1, 0, 0, 0);
  for (int i = 0; i < 6; ++i) {
    r = r * kernel::from_axis_angle(V3(std::sin(i), std::cos(2.0 * i), 0.5).normalized(), 1.2);
    q.push_back(r);
    p.push_back(V3(10.0 * i, 4 * std::sin(i), 2 * std::cos(3.0 * i)));
  }
  if (scheme == kernel::QSplineScheme::kks) return kernel::kks_spline(q, p, 0, 5);
  if (scheme == kernel::QSplineScheme::quartic) return kernel::quartic_spline(q, p, 0, 5);
  return kernel::quintic_spline(q, p, {0, 0.6, 2, 2.4, 4, 5}, std::vector<double>(6, 0.5));
}

}  // namespace qmotion::test
