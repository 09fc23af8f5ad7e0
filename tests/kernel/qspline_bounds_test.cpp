// tests/kernel/qspline_bounds_test.cpp mirrors kernel/qspline_bounds.hpp
#include <cmath>
#include <qmotion/kernel/outward.hpp>
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

// The coefficients on [x0, x1] hold the exact ones, in every case where de Casteljau's steps
// in plain doubles fall below them too. Coefficients of 36 significant bits and parameters
// of 16 make every blossom exact in binary128 (at most 100 bits a term, 111 a sum), while
// doubles round from the second step on.
TEST(QSplineBounds, RestrictedCoefficientsHoldTheExactOnes) {
  __extension__ typedef __float128 Q;
  std::mt19937_64 g(5);
  std::uniform_int_distribution<long long> mant(1LL << 35, (1LL << 36) - 1);
  std::uniform_int_distribution<int> sign(0, 1), exponent(-4, 3), where(0, 1 << 16);
  int understated = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::array<kernel::Interval, 5> b;
    std::array<Q, 5> exact_b;
    std::array<double, 5> plain_b;
    for (std::size_t i = 0; i < 5; ++i) {
      const double x =
          (sign(g) ? -1.0 : 1.0) * std::ldexp(static_cast<double>(mant(g)), exponent(g) - 35);
      b[i] = kernel::Interval(x);
      exact_b[i] = x;
      plain_b[i] = x;
    }
    double x0 = std::ldexp(where(g), -16), x1 = std::ldexp(where(g), -16);
    if (x0 > x1) std::swap(x0, x1);
    const auto r = kernel::detail::restrict_to(b, x0, x1);
    for (std::size_t i = 0; i < 5; ++i) {
      std::array<Q, 5> w = exact_b;
      std::array<double, 5> p = plain_b;
      for (std::size_t level = 1; level < 5; ++level) {
        const double x = level <= i ? x1 : x0;
        for (std::size_t k = 0; k + level < 5; ++k) {
          w[k] = (1 - Q(x)) * w[k] + Q(x) * w[k + 1];
          p[k] = (1 - x) * p[k] + x * p[k + 1];
        }
      }
      ASSERT_TRUE(Q(r[i].lo) <= w[0] && w[0] <= Q(r[i].hi)) << "trial " << trial << ", " << i;
      if (Q(p[0]) < w[0]) ++understated;
    }
  }
  EXPECT_GT(understated, 1000) << "rounding to nearest never fell below the exact coefficient";
}

// At a knot, and within rounding of one, the bound covers both neighbouring segments and
// stays finite.
TEST(QSplineBounds, AnIntervalAtAKnotTakesBothSegments) {
  for (auto scheme : {kernel::QSplineScheme::kks, kernel::QSplineScheme::quintic,
                      kernel::QSplineScheme::quartic}) {
    const QuaternionSpline s = six_key_spline(scheme);
    SCOPED_TRACE(kernel::to_string(s.scheme));
    const double knot = s.scheme == kernel::QSplineScheme::quintic
                            ? s.knots[2]
                            : s.a() + (s.b() - s.a()) * 2 / s.segments();
    const auto at = kernel::second_derivative_bound(s, knot, knot);
    const auto left = kernel::segment_second_derivative_bound(s, 1, 1, 1);
    const auto right = kernel::segment_second_derivative_bound(s, 2, 0, 0);
    EXPECT_TRUE(std::isfinite(at.position) && std::isfinite(at.rotation));
    EXPECT_GE(at.position, std::max(left.position, right.position));
    EXPECT_GE(at.rotation, std::max(left.rotation, right.rotation));
    const auto near = kernel::second_derivative_bound(s, std::nextafter(knot, s.b()),
                                                      std::nextafter(knot, s.b()));
    EXPECT_GE(near.position, left.position);
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
