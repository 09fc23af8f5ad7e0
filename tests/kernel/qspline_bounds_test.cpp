// tests/kernel/qspline_bounds_test.cpp mirrors kernel/qspline_bounds.hpp
#include <cmath>
#include <qmotion/kernel/qspline.hpp>
#include <qmotion/kernel/qspline_bounds.hpp>
#include <random>

#include "qspline_util.hpp"
#include "test_util.hpp"

namespace qmotion::test {
namespace {
using V3 = Eigen::Vector3d;
using kernel::QuaternionSpline;

// The bounds hold: central second differences of the position and of the rotation matrix,
// at 400 points of random intervals (each inside one segment, and some across two), never
// exceed them; and they are not loose beyond a small factor where the intervals are short.
TEST(QSplineBounds, SecondDerivativesStayWithinTheBounds) {
  std::mt19937 rng(11);
  for (auto scheme : {kernel::QSplineScheme::kks, kernel::QSplineScheme::quintic,
                      kernel::QSplineScheme::quartic}) {
    const QuaternionSpline s = six_key_spline(scheme);
    SCOPED_TRACE(kernel::to_string(s.scheme));
    std::uniform_real_distribution<double> where(s.a(), s.b());
    double worst_ratio = 0;
    for (int trial = 0; trial < 40; ++trial) {
      const double len = trial < 30 ? 0.02 : 0.8;  // short ones, then some across segments
      const double u0 = std::min(where(rng), s.b() - len), u1 = u0 + len;
      const auto b = kernel::second_derivative_bound(s, u0, u1);
      double pos = 0, rot = 0;
      const double h = 1e-4;
      for (int i = 0; i <= 400; ++i) {
        const double u = std::clamp(u0 + (u1 - u0) * i / 400, s.a() + h, s.b() - h);
        if (u < u0 + h || u > u1 - h) continue;  // central differences inside the interval
        // (a segment boundary inside the interval: the quintic is only C0 in u there)
        const auto [seg_lo, tlo] = s.locate(u - h);
        const auto [seg_hi, thi] = s.locate(u + h);
        if (seg_lo != seg_hi) continue;
        const V3 p2 = (s.position(u + h) - 2 * s.position(u) + s.position(u - h)) / (h * h);
        const Eigen::Matrix3d R2 = (kernel::rotation_matrix(s.rotation(u + h)) -
                                    2 * kernel::rotation_matrix(s.rotation(u)) +
                                    kernel::rotation_matrix(s.rotation(u - h))) /
                                   (h * h);
        pos = std::max(pos, p2.norm());
        rot = std::max(rot, Eigen::JacobiSVD<Eigen::Matrix3d>(R2).singularValues()(0));
      }
      // Second differences err by about h^2 |f''''| / 12 and by rounding (1e-16 / h^2).
      EXPECT_LE(pos, b.position * (1 + 1e-4) + 1e-5) << "[" << u0 << ", " << u1 << "]";
      EXPECT_LE(rot, b.rotation * (1 + 1e-4) + 1e-5) << "[" << u0 << ", " << u1 << "]";
      if (len < 0.1 && rot > 0) worst_ratio = std::max(worst_ratio, b.rotation / rot);
    }
    EXPECT_LT(worst_ratio, 10) << "the rotation bound is loose";
  }
}

TEST(QSplineBounds, RefusesAnIntervalOutsideTheSpline) {
  const QuaternionSpline s = six_key_spline(kernel::QSplineScheme::kks);
  EXPECT_THROW(kernel::second_derivative_bound(s, 1, 0.5), Error);
  EXPECT_THROW(kernel::second_derivative_bound(s, -1, 0.5), Error);
  EXPECT_THROW(kernel::second_derivative_bound(s, 0, std::nan("")), Error);
}

}  // namespace
}  // namespace qmotion::test
