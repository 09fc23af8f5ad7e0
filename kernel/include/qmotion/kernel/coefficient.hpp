// <qmotion/kernel/coefficient.hpp>
#pragma once
// What the polynomial and spline modules need of a coefficient ring: its scalar type, a
// zero, products that return plain values, an inverse where one exists, and a view of its
// components for norms and zero tests. Covered: scalars (double, Rational), fixed-size
// Eigen vectors and matrices, Quaternion and DualQuaternion.
#include <Eigen/Core>
#include <algorithm>
#include <qmotion/kernel/dual_quaternion.hpp>
#include <qmotion/kernel/scalar_traits.hpp>
#include <type_traits>

namespace qmotion::kernel {

namespace detail {
template <typename C, typename = void>
struct CoefScalar {
  using type = C;
};
template <typename C>
struct CoefScalar<C, std::void_t<typename C::Scalar>> {
  using type = typename C::Scalar;
};
}  // namespace detail

/// Scalar field of a coefficient ring (C itself for scalars).
template <typename C>
using coef_scalar_t = typename detail::CoefScalar<C>::type;

template <typename C>
inline constexpr bool is_eigen_v = std::is_base_of_v<Eigen::EigenBase<C>, C>;

/// True when C is its own scalar field.
template <typename C>
inline constexpr bool is_scalar_coef_v = std::is_same_v<coef_scalar_t<C>, C>;

/// The zero of C (fixed-size Eigen types are zero-filled).
template <typename C>
C coef_zero() {
  if constexpr (is_eigen_v<C>) {
    return C::Zero();
  } else {
    return C{};
  }
}

/// a * b as a plain value (no Eigen or Boost expression templates escape).
template <typename A, typename B>
auto ring_mul(const A& a, const B& b) {
  if constexpr (is_eigen_v<A> || is_eigen_v<B>) {
    return (a * b).eval();
  } else if constexpr (is_scalar_coef_v<A> && is_scalar_coef_v<B>) {
    return A(a * b);
  } else {
    return a * b;
  }
}

/// Scales c by the scalar s.
template <typename C>
C scale(const coef_scalar_t<C>& s, const C& c) {
  if constexpr (is_scalar_coef_v<C>) {
    return C(s * c);
  } else if constexpr (is_eigen_v<C>) {
    return (c * s).eval();
  } else {
    return c * s;
  }
}

/// Calls f(component) for every scalar component of c.
template <typename C, typename F>
void for_each_component(const C& c, F&& f) {
  if constexpr (is_scalar_coef_v<C>) {
    f(c);
  } else if constexpr (is_eigen_v<C>) {
    for (Eigen::Index j = 0; j < c.cols(); ++j)
      for (Eigen::Index i = 0; i < c.rows(); ++i) f(c(i, j));
  } else {
    c.for_each_component(f);
  }
}

/// Largest absolute component, as double (for relative tolerances and diagnostics).
template <typename C>
double max_abs(const C& c) {
  double m = 0.0;
  for_each_component(c, [&](const auto& x) { m = std::max(m, std::abs(to_double(x))); });
  return m;
}

/// Exactly zero (every component == 0).
template <typename C>
bool is_exact_zero(const C& c) {
  bool z = true;
  using S = coef_scalar_t<C>;
  for_each_component(c, [&](const auto& x) { z = z && (x == S(0)); });
  return z;
}

/// Multiplicative inverse where C has one (scalars, quaternions). Throws when c == 0.
template <typename C>
C coef_inverse(const C& c) {
  if constexpr (is_scalar_coef_v<C>) {
    if (c == C(0)) throw Error(Errc::numerical_failure, "division by zero coefficient");
    return C(C(1) / c);
  } else {
    return inverse(c);
  }
}

/// Tolerance-aware zero test for a coefficient measured against a scale: exact types
/// compare with zero; floating point compares max_abs(c) <= rel_tol * scale.
template <typename C>
bool coef_negligible(const C& c, double scale, double rel_tol) {
  if constexpr (is_exact_v<coef_scalar_t<C>>) {
    (void)scale;
    (void)rel_tol;
    return is_exact_zero(c);
  } else {
    return max_abs(c) <= rel_tol * scale;
  }
}

}  // namespace qmotion::kernel
