// <qmotion/kernel/outward.hpp>: arithmetic that rounds outward, for certified bounds
// (docs/geometry.md, "Rounding of the certificates").
//
// The floating-point mode is never changed: every operation rounds to nearest, which errs by
// at most half a unit in the last place (IEEE 754: +, -, *, / and sqrt are correctly
// rounded). One step to the next double outward (std::nextafter) therefore encloses the
// exact result of the operation on the operands as they are. An Interval holds the exact
// value of a computation when its operands were exact or enclosed: each operation encloses
// the exact operation on every pair of points of its operands. up() and down() are the same
// step for a single operation whose sign is known.
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>

namespace qmotion::kernel {

/// The next double above x (x itself for +inf; NaN stays NaN).
inline double up(double x) { return std::nextafter(x, HUGE_VAL); }
/// The next double below x.
inline double down(double x) { return std::nextafter(x, -HUGE_VAL); }

/// Whether a + b >= c (at_least) or a + b <= c, decided exactly for finite doubles. Rounding
/// to nearest is monotone, so fl(a + b) > c implies a + b >= c; at fl(a + b) == c, the
/// rounding error of the sum (Knuth's TwoSum, exact) decides.
inline double sum_error(double a, double b, double s) {
  const double bb = s - a;
  return (a - (s - bb)) + (b - bb);
}
inline bool sum_at_least(double a, double b, double c) {
  const double s = a + b;
  return s > c || (s == c && sum_error(a, b, s) >= 0);
}
inline bool sum_at_most(double a, double b, double c) {
  const double s = a + b;
  return s < c || (s == c && sum_error(a, b, s) <= 0);
}

/// A closed interval [lo, hi] of reals that holds an exact value.
struct Interval {
  double lo = 0, hi = 0;

  Interval() = default;
  /// The exact double x.
  Interval(double x) : lo(x), hi(x) {}  // NOLINT: an exact double is an interval
  Interval(double l, double h) : lo(l), hi(h) {}
};

inline Interval operator+(const Interval& a, const Interval& b) {
  return {down(a.lo + b.lo), up(a.hi + b.hi)};
}
inline Interval operator-(const Interval& a, const Interval& b) {
  return {down(a.lo - b.hi), up(a.hi - b.lo)};
}
inline Interval operator-(const Interval& a) { return {-a.hi, -a.lo}; }
inline Interval operator*(const Interval& a, const Interval& b) {
  const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return {down(*std::min_element(p, p + 4)), up(*std::max_element(p, p + 4))};
}
/// a / b for b not containing 0 (else the whole line).
inline Interval operator/(const Interval& a, const Interval& b) {
  if (!(b.lo > 0 || b.hi < 0)) return {-HUGE_VAL, HUGE_VAL};
  const double p[4] = {a.lo / b.lo, a.lo / b.hi, a.hi / b.lo, a.hi / b.hi};
  return {down(*std::min_element(p, p + 4)), up(*std::max_element(p, p + 4))};
}
inline Interval& operator+=(Interval& a, const Interval& b) { return a = a + b; }

/// The square root of the interval's non-negative part.
inline Interval sqrt(const Interval& a) {
  return {a.hi < 0 ? 0.0 : std::max(0.0, down(std::sqrt(std::max(a.lo, 0.0)))),
          up(std::sqrt(std::max(a.hi, 0.0)))};
}
inline Interval abs(const Interval& a) {
  if (a.lo >= 0) return a;
  if (a.hi <= 0) return -a;
  return {0.0, std::max(-a.lo, a.hi)};
}
inline Interval square(const Interval& a) {
  const Interval m = abs(a);
  return {m.lo == 0 ? 0.0 : down(m.lo * m.lo), up(m.hi * m.hi)};
}

/// A vector of three intervals, and the operations on it that the certificates use.
using Interval3 = std::array<Interval, 3>;
/// a - b, exactly held.
inline Interval3 difference(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return {Interval(a.x()) - Interval(b.x()), Interval(a.y()) - Interval(b.y()),
          Interval(a.z()) - Interval(b.z())};
}
inline Interval3 cross(const Interval3& a, const Interval3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline Interval dot(const Interval3& a, const Interval3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
/// An upper bound of the Euclidean norm of every vector in v.
inline double norm_up(const Interval3& v) {
  return sqrt(square(v[0]) + square(v[1]) + square(v[2])).hi;
}

/// A relative margin: x (>= 0) times (1 + r), rounded up, for a bound whose own rounding is
/// covered by r.
inline double grow(double x, double r) { return up(x * up(1 + r)); }

}  // namespace qmotion::kernel
