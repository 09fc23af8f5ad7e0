// <qmotion/kernel/cgal_scalar.hpp>
#pragma once
// Exact rational scalars: CGAL::Exact_rational. Through the CGAL::CGAL CMake target
// (which defines CGAL_USE_GMPXX on Debian) it is gmpxx's mpq_class; without it, Boost's
// gmp_rational. Both are exact fields with expression templates: name the type of every
// intermediate (Scalar x = a * b), never `auto`.
#include <CGAL/Exact_rational.h>

#include <Eigen/Core>
#include <qmotion/kernel/scalar_traits.hpp>

namespace qmotion::kernel {

using Rational = CGAL::Exact_rational;

template <>
struct ScalarTraits<Rational> {
  static constexpr bool is_exact = true;
  static Rational tolerance() { return Rational(0); }
  static double to_double(const Rational& x) { return CGAL::to_double(x); }
};

}  // namespace qmotion::kernel
