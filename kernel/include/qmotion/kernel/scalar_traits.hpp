// <qmotion/kernel/scalar_traits.hpp>
#pragma once
#include <cmath>
#include <limits>
#include <type_traits>

namespace qmotion::kernel {

/// Properties of a scalar field type. The default covers floating point; exact types
/// specialise it (kernel/cgal_scalar.hpp).
template <typename Scalar, typename = void>
struct ScalarTraits {
  static constexpr bool is_exact = false;
  /// Absolute tolerance for "zero" of a quantity of unit size.
  static Scalar tolerance() { return Scalar(64) * std::numeric_limits<Scalar>::epsilon(); }
  static double to_double(const Scalar& x) { return static_cast<double>(x); }
};

template <typename Scalar>
inline constexpr bool is_exact_v = ScalarTraits<Scalar>::is_exact;

/// |x| for any ordered field type, returned as Scalar (no expression templates escape).
template <typename Scalar>
Scalar abs_value(const Scalar& x) {
  if (x < Scalar(0)) return Scalar(-x);
  return x;
}

/// Zero test: exact comparison for exact types, tolerance() otherwise.
template <typename Scalar>
bool is_zero(const Scalar& x) {
  if constexpr (is_exact_v<Scalar>) {
    return x == Scalar(0);
  } else {
    return abs_value(x) <= ScalarTraits<Scalar>::tolerance();
  }
}

/// The one conversion to double (io/CLI boundary, diagnostics).
template <typename Scalar>
double to_double(const Scalar& x) {
  return ScalarTraits<Scalar>::to_double(x);
}

}  // namespace qmotion::kernel
