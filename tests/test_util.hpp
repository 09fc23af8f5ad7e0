// tests/test_util.hpp: helpers shared by the typed kernel tests.
#pragma once
#include <gtest/gtest.h>

#include <Eigen/Dense>
#ifdef QMOTION_WITH_CGAL
#include <qmotion/kernel/cgal_scalar.hpp>
#endif
#include <qmotion/kernel/coefficient.hpp>
#include <random>
#include <vector>

namespace qmotion::test {

#ifdef QMOTION_WITH_CGAL
using kernel::Rational;
/// The scalars every typed kernel test runs on: double, and exact rationals when built with
/// CGAL (QMOTION_WITH_CGAL).
using Scalars = ::testing::Types<double, Rational>;
#else
using Scalars = ::testing::Types<double>;
#endif

/// A random scalar: uniform in [-1, 1] for double, p/q with |p| <= 20, 1 <= q <= 9 for
/// rationals (small enough that exact products of degree 12 stay fast).
template <typename S>
S rand_scalar(std::mt19937& g) {
  if constexpr (kernel::is_exact_v<S>) {
    std::uniform_int_distribution<int> p(-20, 20), q(1, 9);
    return S(p(g)) / S(q(g));
  } else {
    return std::uniform_real_distribution<S>(-1, 1)(g);
  }
}

/// A random scalar in [0, 1] (for rationals k/q with 0 <= k <= q <= 9).
template <typename S>
S rand_unit(std::mt19937& g) {
  if constexpr (kernel::is_exact_v<S>) {
    std::uniform_int_distribution<int> q(1, 9);
    const int d = q(g);
    return S(std::uniform_int_distribution<int>(0, d)(g)) / S(d);
  } else {
    return std::uniform_real_distribution<S>(0, 1)(g);
  }
}

/// A random coefficient of ring C.
template <typename C>
C rand_coef(std::mt19937& g) {
  using S = kernel::coef_scalar_t<C>;
  C c = kernel::coef_zero<C>();
  if constexpr (kernel::is_scalar_coef_v<C>) {
    c = rand_scalar<S>(g);
  } else if constexpr (kernel::is_eigen_v<C>) {
    for (Eigen::Index j = 0; j < c.cols(); ++j)
      for (Eigen::Index i = 0; i < c.rows(); ++i) c(i, j) = rand_scalar<S>(g);
  } else if constexpr (std::is_same_v<C, kernel::Quaternion<S>>) {
    c = C(rand_scalar<S>(g), rand_scalar<S>(g), rand_scalar<S>(g), rand_scalar<S>(g));
  } else {
    for (int i = 0; i < 8; ++i) c[i] = rand_scalar<S>(g);
  }
  return c;
}

/// Equality for exact types; for double, max component difference <= tol * max(1, |a|).
template <typename C>
::testing::AssertionResult coef_near(const C& a, const C& b, double tol = 1e-12) {
  using S = kernel::coef_scalar_t<C>;
  const C d = C(a - b);
  if constexpr (kernel::is_exact_v<S>) {
    if (kernel::is_exact_zero(d)) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "exact values differ by " << kernel::max_abs(d);
  } else {
    const double err = kernel::max_abs(d), ref = std::max(1.0, kernel::max_abs(a));
    if (err <= tol * ref) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "difference " << err << " exceeds " << tol << " * " << ref;
  }
}

/// Tolerance for double, 0 for exact types.
template <typename S>
double tol_for(double t) {
  return kernel::is_exact_v<S> ? 0.0 : t;
}

}  // namespace qmotion::test
