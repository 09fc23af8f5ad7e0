// Outward rounding (<qmotion/kernel/outward.hpp>): every operation's interval holds the exact
// result, checked in binary128, where products and (here) sums of doubles are exact; and the
// cases where rounding to nearest alone would understate the bound are among them.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <qmotion/kernel/outward.hpp>
#include <random>

namespace {

using qmotion::kernel::Interval;
__extension__ typedef __float128 Q;  // binary128: exact for these sums and products

bool holds(const Interval& i, Q exact) { return Q(i.lo) <= exact && exact <= Q(i.hi); }

/// Doubles of magnitude 2^-20 to 2^20, either sign, with full random significands: sums of
/// two of them differ in exponent by at most 40, so binary128 (113 bits) holds them exactly.
double random_double(std::mt19937_64& g) {
  std::uniform_real_distribution<double> m(1, 2);
  std::uniform_int_distribution<int> e(-20, 20), s(0, 1);
  return (s(g) ? -1 : 1) * std::ldexp(m(g), e(g));
}

TEST(Outward, EachOperationHoldsTheExactResult) {
  std::mt19937_64 g(7);
  int understated_sum = 0, understated_product = 0;
  for (int k = 0; k < 200000; ++k) {
    const double a = random_double(g), b = random_double(g);
    const Interval A(a), B(b);
    ASSERT_TRUE(holds(A + B, Q(a) + Q(b))) << a << " + " << b;
    ASSERT_TRUE(holds(A - B, Q(a) - Q(b))) << a << " - " << b;
    ASSERT_TRUE(holds(A * B, Q(a) * Q(b))) << a << " * " << b;
    // Quotient and root: the exact one is the x with x b = a, x^2 = |a|.
    const Interval D = A / B;
    if (b > 0)
      ASSERT_TRUE(Q(D.lo) * Q(b) <= Q(a) && Q(a) <= Q(D.hi) * Q(b)) << a << " / " << b;
    else
      ASSERT_TRUE(Q(D.hi) * Q(b) <= Q(a) && Q(a) <= Q(D.lo) * Q(b)) << a << " / " << b;
    const Interval R = qmotion::kernel::sqrt(Interval(std::abs(a)));
    ASSERT_TRUE(Q(R.lo) * Q(R.lo) <= Q(std::abs(a)) && Q(std::abs(a)) <= Q(R.hi) * Q(R.hi));
    // The same on intervals of two points: every combination of ends is held.
    const Interval AB(std::min(a, b), std::max(a, b));
    for (double x : {a, b})
      for (double y : {a, b}) ASSERT_TRUE(holds(AB * AB, Q(x) * Q(y)));
    ASSERT_TRUE(holds(qmotion::kernel::square(AB), Q(a) * Q(a)));
    understated_sum += Q(a + b) < Q(a) + Q(b);
    understated_product += Q(a * b) < Q(a) * Q(b);
  }
  // Rounding to nearest falls below the exact value about a third of the time each: the
  // cases where a bound taken as computed would not be one.
  EXPECT_GT(understated_sum, 20000);
  EXPECT_GT(understated_product, 20000);
}

TEST(Outward, ALongSumThatRoundingToNearestLosesStaysABound) {
  // 1 + 2^-53 + 2^-53 + ...: each sum rounds back to 1 (a tie, to even), so the plain sum
  // stays 1 while the exact one is 1 + n 2^-53.
  const int n = 100000;
  double plain = 1;
  Interval s(1.0);
  Q exact = 1;
  for (int i = 0; i < n; ++i) {
    plain += std::ldexp(1.0, -53);
    s += Interval(std::ldexp(1.0, -53));
    exact += Q(std::ldexp(1.0, -53));
  }
  EXPECT_EQ(plain, 1.0);
  EXPECT_LT(Q(plain), exact);
  EXPECT_TRUE(holds(s, exact));
  // Outward by an ulp a step: the width grows with n, and stays far below the size.
  EXPECT_LT(s.hi - s.lo, 1e-9);
}

TEST(Outward, NormUpIsAnUpperBoundOfTheExactNorm) {
  std::mt19937_64 g(11);
  int understated = 0;
  for (int k = 0; k < 100000; ++k) {
    const Eigen::Vector3d v(random_double(g), random_double(g), random_double(g));
    const Q sq = Q(v.x()) * Q(v.x()) + Q(v.y()) * Q(v.y()) + Q(v.z()) * Q(v.z());
    const double up =
        qmotion::kernel::norm_up(qmotion::kernel::difference(v, Eigen::Vector3d::Zero()));
    ASSERT_GE(Q(up) * Q(up), sq) << v.transpose();
    understated += Q(v.norm()) * Q(v.norm()) < sq;
  }
  EXPECT_GT(understated, 1000);  // Eigen's norm() is not a bound
}

TEST(Outward, GrowAndStepsAreOutward) {
  EXPECT_GT(qmotion::kernel::up(1.0), 1.0);
  EXPECT_LT(qmotion::kernel::down(1.0), 1.0);
  EXPECT_EQ(qmotion::kernel::up(HUGE_VAL), HUGE_VAL);
  EXPECT_GE(Q(qmotion::kernel::grow(3.0, 1e-12)), Q(3.0) * (Q(1) + Q(1e-12)));
  const Interval w = Interval(-1.0, 2.0) / Interval(-1.0, 1.0);
  EXPECT_EQ(w.lo, -HUGE_VAL);  // a divisor about 0: the whole line
  EXPECT_EQ(w.hi, HUGE_VAL);
  const Interval m = qmotion::kernel::abs(Interval(-3.0, 2.0));
  EXPECT_EQ(m.lo, 0.0);
  EXPECT_EQ(m.hi, 3.0);
}

/// a + b against c decided exactly: on random sums, and where fl(a + b) == c hides which
/// side the exact sum is on, the case round to nearest gets wrong.
TEST(Outward, SumComparisonsAreExact) {
  using qmotion::kernel::sum_at_least;
  using qmotion::kernel::sum_at_most;
  const double tiny = std::ldexp(1.0, -60);
  EXPECT_EQ(1.0 + tiny, 1.0);                 // the sum rounds onto c...
  EXPECT_TRUE(sum_at_least(1.0, tiny, 1.0));  // ...from above
  EXPECT_FALSE(sum_at_most(1.0, tiny, 1.0));
  EXPECT_FALSE(sum_at_least(1.0, -tiny, 1.0));  // ...from below
  EXPECT_TRUE(sum_at_most(1.0, -tiny, 1.0));
  EXPECT_TRUE(sum_at_least(-5.0, 10.0, 5.0));  // exact sums both ways
  EXPECT_TRUE(sum_at_most(-5.0, 10.0, 5.0));
  std::mt19937_64 g(17);
  for (int k = 0; k < 100000; ++k) {
    const double a = random_double(g), b = random_double(g);
    const double c = k % 2 ? a + b : random_double(g);
    const Q exact = Q(a) + Q(b);
    ASSERT_EQ(sum_at_least(a, b, c), exact >= Q(c)) << a << " " << b << " " << c;
    ASSERT_EQ(sum_at_most(a, b, c), exact <= Q(c)) << a << " " << b << " " << c;
  }
}

}  // namespace
