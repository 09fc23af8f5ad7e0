// tests/kernel/bernstein_test.cpp mirrors kernel/bernstein.hpp
#include <qmotion/kernel/bernstein.hpp>

#include "test_util.hpp"

namespace qmotion::test {
namespace {
using kernel::Bernstein;

template <typename C>
Bernstein<C> rand_poly(std::mt19937& g, int n, kernel::coef_scalar_t<C> a,
                       kernel::coef_scalar_t<C> b) {
  std::vector<C> c;
  for (int i = 0; i <= n; ++i) c.push_back(rand_coef<C>(g));
  return Bernstein<C>(std::move(c), a, b);
}

/// Power-basis evaluation of the Bernstein basis, independent of de Casteljau.
template <typename C>
C direct_eval(const Bernstein<C>& p, const kernel::coef_scalar_t<C>& t) {
  using S = kernel::coef_scalar_t<C>;
  const int n = p.degree();
  const S s = p.local(t);
  C sum = kernel::coef_zero<C>();
  for (int i = 0; i <= n; ++i) {
    S w = kernel::binomial<S>(n, i);
    for (int k = 0; k < i; ++k) w *= s;
    for (int k = 0; k < n - i; ++k) w *= S(S(1) - s);
    sum += kernel::scale(w, p[i]);
  }
  return sum;
}

// Every coefficient ring of the issue, for both scalars.
template <typename S>
using Rings = std::tuple<S, Eigen::Matrix<S, 3, 1>, kernel::Quaternion<S>,
                         kernel::DualQuaternion<S>, Eigen::Matrix<S, 4, 4>>;

template <typename S>
class BernsteinTest : public ::testing::Test {};
TYPED_TEST_SUITE(BernsteinTest, Scalars);

template <typename C>
void check_product_pointwise(std::mt19937& g, int trials) {
  using S = kernel::coef_scalar_t<C>;
  const S a = S(-1) / S(2), b = S(3);
  for (int k = 0; k <= 12; ++k) {
    const int l = (k * 7 + 3) % 13;  // degrees 0..12 on both sides, varied pairs
    const auto p = rand_poly<C>(g, k, a, b), q = rand_poly<C>(g, l, a, b);
    const auto pq = kernel::product(p, q);
    ASSERT_EQ(pq.degree(), k + l);
    for (int s = 0; s < trials; ++s) {
      const S t = S(a + (b - a) * rand_unit<S>(g));
      const C lhs = kernel::evaluate(pq, t);
      const C rhs = kernel::ring_mul(kernel::evaluate(p, t), kernel::evaluate(q, t));
      ASSERT_TRUE(coef_near(lhs, rhs, 1e-11)) << "degrees " << k << "," << l;
    }
  }
}

TYPED_TEST(BernsteinTest, ProductEqualsPointwiseProductInEveryRing) {
  using S = TypeParam;
  std::mt19937 g(42);
  const int trials = 100;
  check_product_pointwise<S>(g, trials);
  check_product_pointwise<Eigen::Matrix<S, 4, 4>>(g, trials);
  check_product_pointwise<kernel::Quaternion<S>>(g, trials);
  check_product_pointwise<kernel::DualQuaternion<S>>(g, trials);
  // Scalar polynomial times vector polynomial.
  const auto p = rand_poly<S>(g, 4, S(0), S(1));
  const auto v = rand_poly<Eigen::Matrix<S, 3, 1>>(g, 5, S(0), S(1));
  const auto pv = kernel::product(p, v);
  const S t = S(2) / S(7);
  EXPECT_TRUE(coef_near(kernel::evaluate(pv, t),
                        Eigen::Matrix<S, 3, 1>(kernel::evaluate(v, t) * kernel::evaluate(p, t))));
}

template <typename C>
void check_elevation_subdivision(std::mt19937& g) {
  using S = kernel::coef_scalar_t<C>;
  for (int n = 0; n <= 10; ++n) {
    const auto p = rand_poly<C>(g, n, S(1), S(4));
    const auto e = kernel::elevate(p, 3);
    ASSERT_EQ(e.degree(), n + 3);
    const S c = S(S(5) / S(2));
    auto halves = kernel::subdivide(p, c);
    const auto dp = kernel::derivative(p);
    for (int k = 0; k < 12; ++k) {
      const S t = S(S(1) + S(3) * rand_unit<S>(g));
      const C v = kernel::evaluate(p, t);
      ASSERT_TRUE(coef_near(kernel::evaluate(e, t), v));
      ASSERT_TRUE(coef_near(direct_eval(p, t), v, 1e-11));
      ASSERT_TRUE(coef_near(kernel::evaluate(t < c ? halves.first : halves.second, t), v, 1e-11));
      ASSERT_TRUE(coef_near(kernel::evaluate(kernel::restrict_to(p, S(2), S(3)), t), v, 1e-10));
      if constexpr (kernel::is_exact_v<S>) {
        // Derivative against an exact difference quotient of the power form is not
        // available; use the product rule identity d(p*p)/dt = p' p + p p' instead.
        if constexpr (kernel::is_scalar_coef_v<C>) {
          const auto d2 = kernel::derivative(kernel::product(p, p));
          ASSERT_EQ(kernel::evaluate(d2, t), S(S(2) * kernel::evaluate(dp, t) * v));
        }
      } else {
        const double h = 1e-6;
        const C fd = kernel::scale(
            S(1 / (2 * h)), C(kernel::evaluate(p, S(t + h)) - kernel::evaluate(p, S(t - h))));
        ASSERT_TRUE(coef_near(kernel::evaluate(dp, t), fd, 1e-6));
      }
    }
  }
}

TYPED_TEST(BernsteinTest, ElevationSubdivisionAndDerivativeKeepTheFunction) {
  using S = TypeParam;
  std::mt19937 g(8);
  check_elevation_subdivision<S>(g);
  check_elevation_subdivision<Eigen::Matrix<S, 3, 1>>(g);
  check_elevation_subdivision<kernel::DualQuaternion<S>>(g);
}

/// De Casteljau's blossom with every step taken (no shortcut at the interval's ends).
template <typename C>
C reference_blossom(const Bernstein<C>& p, const std::vector<kernel::coef_scalar_t<C>>& u) {
  using S = kernel::coef_scalar_t<C>;
  std::vector<C> c = p.coeffs();
  for (std::size_t r = 1; r < c.size(); ++r) {
    const S s = p.local(u[r - 1]);
    for (std::size_t i = 0; i + r < c.size(); ++i)
      c[i] = kernel::scale(S(S(1) - s), c[i]) + kernel::scale(s, c[i + 1]);
  }
  return c[0];
}

template <typename C>
void check_blossom_at_ends(std::mt19937& g) {
  using S = kernel::coef_scalar_t<C>;
  const S a = S(-1) / S(2), b = S(3), inside = S(5) / S(4), outside = S(7);
  for (int n = 1; n <= 9; ++n) {
    const auto p = rand_poly<C>(g, n, a, b);
    std::vector<C> work;
    // Every argument list of a, b, an inner and an outer parameter, in every order the
    // generator gives: the same as every step taken, and a^(n-m) b^m is coefficient m.
    for (int trial = 0; trial < 40; ++trial) {
      std::vector<S> u;
      int at_b = 0, others = 0;
      for (int i = 0; i < n; ++i) {
        const int pick = static_cast<int>(g() % 4);
        u.push_back(pick == 0 ? a : pick == 1 ? b : pick == 2 ? inside : outside);
        at_b += pick == 1;
        others += pick >= 2;
      }
      const C got = kernel::blossom(p, u.begin(), work);
      ASSERT_TRUE(coef_near(got, reference_blossom(p, u), 1e-11)) << "degree " << n;
      if (others == 0) {
        ASSERT_TRUE(coef_near(got, p[at_b], 0.0)) << "degree " << n;
      }
      std::sort(u.begin(), u.end());
      ASSERT_TRUE(coef_near(kernel::blossom(p, u.begin(), work), got, 1e-11));  // symmetric
    }
    ASSERT_TRUE(coef_near(kernel::blossom(p, std::vector<S>(static_cast<std::size_t>(n), inside)),
                          direct_eval(p, inside), 1e-11));  // the diagonal is p
  }
}

TYPED_TEST(BernsteinTest, BlossomArgumentsAtTheEndsAreStepsSavedNotChanges) {
  using S = TypeParam;
  std::mt19937 g(21);
  check_blossom_at_ends<S>(g);
  check_blossom_at_ends<Eigen::Matrix<S, 4, 1>>(g);
  check_blossom_at_ends<Eigen::Matrix<S, 4, 4>>(g);
}

TYPED_TEST(BernsteinTest, DegreeReductionDetectsElevation) {
  using S = TypeParam;
  using Q = kernel::Quaternion<S>;
  std::mt19937 g(9);
  for (int n = 0; n <= 8; ++n) {
    const auto p = rand_poly<Q>(g, n, S(0), S(1));
    for (int r : {0, 1, 4}) {
      const auto e = kernel::elevate(p, r);
      const auto red = kernel::reduce_degree(e);
      EXPECT_EQ(red.degree(), n) << "n=" << n << " r=" << r;
      for (int i = 0; i <= n; ++i) EXPECT_TRUE(coef_near(red[i], p[i], 1e-9));
    }
  }
  // A genuine degree-5 polynomial is not reduced.
  EXPECT_EQ(kernel::exact_degree(rand_poly<S>(g, 5, S(0), S(1))), 5);
}

TYPED_TEST(BernsteinTest, ExactDivisionByAKnownFactor) {
  using S = TypeParam;
  using Q = kernel::Quaternion<S>;
  using DQ = kernel::DualQuaternion<S>;
  std::mt19937 g(10);
  for (int n = 0; n <= 6; ++n)
    for (int f = 0; f <= 4; ++f) {
      const auto gq = rand_poly<Q>(g, n, S(-1), S(2));
      const auto fq = rand_poly<Q>(g, f, S(-1), S(2));
      const auto right = kernel::divide_exact(kernel::product(gq, fq), fq, kernel::Side::right);
      const auto left = kernel::divide_exact(kernel::product(fq, gq), fq, kernel::Side::left);
      ASSERT_EQ(right.degree(), n);
      for (int i = 0; i <= n; ++i) {
        EXPECT_TRUE(coef_near(right[i], gq[i], 1e-9));
        EXPECT_TRUE(coef_near(left[i], gq[i], 1e-9));
      }
      // Dual quaternion dividend, quaternion divisor (Q = Q_trans * Q_rot).
      const auto dq = rand_poly<DQ>(g, n, S(-1), S(2));
      const auto quo = kernel::divide_exact(kernel::product(dq, fq), fq);
      for (int i = 0; i <= n; ++i) EXPECT_TRUE(coef_near(quo[i], dq[i], 1e-9));
    }
  // Not a factor: refused.
  const auto p = rand_poly<S>(g, 4, S(0), S(1));
  const auto f = Bernstein<S>({S(1), S(3)}, S(0), S(1));
  EXPECT_THROW(kernel::divide_exact(p, f), Error);
}

#ifdef QMOTION_WITH_CGAL
TEST(BernsteinRational, ExactDivisionAndReductionAreExact) {
  using S = Rational;
  std::mt19937 g(12);
  const auto a = rand_poly<S>(g, 7, S(0), S(1)), b = rand_poly<S>(g, 5, S(0), S(1));
  const auto q = kernel::divide_exact(kernel::product(a, b), b);
  for (int i = 0; i <= 7; ++i) EXPECT_EQ(q[i], a[i]);
  const auto r = kernel::reduce_degree(kernel::elevate(a, 6));
  ASSERT_EQ(r.degree(), 7);
  for (int i = 0; i <= 7; ++i) EXPECT_EQ(r[i], a[i]);
}
#endif

TEST(BernsteinDouble, RefusesBadConstruction) {
  EXPECT_THROW(Bernstein<double>(std::vector<double>{}), Error);
  EXPECT_THROW(Bernstein<double>({1.0}, 1.0, 1.0), Error);
  const Bernstein<double> p({1.0, 2.0}, 0.0, 1.0);
  EXPECT_THROW(kernel::subdivide(p, 1.0), Error);
  EXPECT_THROW(kernel::product(p, Bernstein<double>({1.0}, 0.0, 2.0)), Error);
}

}  // namespace
}  // namespace qmotion::test
