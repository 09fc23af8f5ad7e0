// <qmotion/kernel/quaternion.hpp>
#pragma once
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/scalar_traits.hpp>
#include <type_traits>

namespace qmotion::kernel {

/// Quaternion q = w + x i + y j + z k, components ordered (w, x, y, z) (docs/formats.md).
/// Not normalised: every operation here is polynomial, so it is exact for exact Scalar.
/// @tparam Scalar double or an exact field type (CGAL::Exact_rational)
/// @see Juettler 1994, eq. (2) for the product
template <typename Scalar_>
class Quaternion {
 public:
  using Scalar = Scalar_;
  using Vec3 = Eigen::Matrix<Scalar, 3, 1>;

  Quaternion() : c_{Scalar(0), Scalar(0), Scalar(0), Scalar(0)} {}
  Quaternion(const Scalar& w, const Scalar& x, const Scalar& y, const Scalar& z) : c_{w, x, y, z} {}
  /// Quaternion with scalar part s and vector part v.
  Quaternion(const Scalar& s, const Vec3& v) : c_{s, v(0), v(1), v(2)} {}
  /// The real number s as a quaternion.
  static Quaternion real(const Scalar& s) { return Quaternion(s, Scalar(0), Scalar(0), Scalar(0)); }
  /// The pure quaternion with vector part v.
  static Quaternion pure(const Vec3& v) { return Quaternion(Scalar(0), v); }

  const Scalar& w() const { return c_[0]; }
  const Scalar& x() const { return c_[1]; }
  const Scalar& y() const { return c_[2]; }
  const Scalar& z() const { return c_[3]; }
  Scalar& w() { return c_[0]; }
  Scalar& x() { return c_[1]; }
  Scalar& y() { return c_[2]; }
  Scalar& z() { return c_[3]; }
  const Scalar& operator[](int i) const { return c_[static_cast<std::size_t>(i)]; }
  Scalar& operator[](int i) { return c_[static_cast<std::size_t>(i)]; }

  /// Scal Q.
  const Scalar& scal() const { return c_[0]; }
  /// Vec Q.
  Vec3 vec() const { return Vec3(c_[1], c_[2], c_[3]); }

  Quaternion conj() const {
    return Quaternion(c_[0], Scalar(-c_[1]), Scalar(-c_[2]), Scalar(-c_[3]));
  }
  /// Q * conj(Q) = w^2 + x^2 + y^2 + z^2.
  Scalar norm2() const {
    Scalar s = c_[0] * c_[0];
    for (std::size_t i = 1; i < 4; ++i) s += c_[i] * c_[i];
    return s;
  }
  Scalar dot(const Quaternion& o) const {
    Scalar s = c_[0] * o.c_[0];
    for (std::size_t i = 1; i < 4; ++i) s += c_[i] * o.c_[i];
    return s;
  }

  Quaternion& operator+=(const Quaternion& o) {
    for (std::size_t i = 0; i < 4; ++i) c_[i] += o.c_[i];
    return *this;
  }
  Quaternion& operator-=(const Quaternion& o) {
    for (std::size_t i = 0; i < 4; ++i) c_[i] -= o.c_[i];
    return *this;
  }
  Quaternion& operator*=(const Scalar& s) {
    for (auto& c : c_) c *= s;
    return *this;
  }
  Quaternion operator-() const {
    return Quaternion(Scalar(-c_[0]), Scalar(-c_[1]), Scalar(-c_[2]), Scalar(-c_[3]));
  }
  friend Quaternion operator+(Quaternion a, const Quaternion& b) { return a += b; }
  friend Quaternion operator-(Quaternion a, const Quaternion& b) { return a -= b; }
  friend Quaternion operator*(Quaternion a, const Scalar& s) { return a *= s; }
  friend Quaternion operator*(const Scalar& s, Quaternion a) { return a *= s; }
  friend Quaternion operator/(Quaternion a, const Scalar& s) {
    for (auto& c : a.c_) c /= s;
    return a;
  }
  /// Hamilton product (2).
  friend Quaternion operator*(const Quaternion& a, const Quaternion& b) {
    const auto& p = a.c_;
    const auto& q = b.c_;
    return Quaternion(Scalar(p[0] * q[0] - p[1] * q[1] - p[2] * q[2] - p[3] * q[3]),
                      Scalar(p[0] * q[1] + p[1] * q[0] + p[2] * q[3] - p[3] * q[2]),
                      Scalar(p[0] * q[2] - p[1] * q[3] + p[2] * q[0] + p[3] * q[1]),
                      Scalar(p[0] * q[3] + p[1] * q[2] - p[2] * q[1] + p[3] * q[0]));
  }
  friend bool operator==(const Quaternion& a, const Quaternion& b) { return a.c_ == b.c_; }
  friend bool operator!=(const Quaternion& a, const Quaternion& b) { return !(a == b); }

  template <typename F>
  void for_each_component(F&& f) const {
    for (const auto& c : c_) f(c);
  }

 private:
  std::array<Scalar, 4> c_;
};

/// Multiplicative inverse conj(q)/|q|^2. @pre q != 0
template <typename Scalar>
Quaternion<Scalar> inverse(const Quaternion<Scalar>& q) {
  const Scalar n = q.norm2();
  if (n == Scalar(0)) throw Error(Errc::numerical_failure, "inverse of the zero quaternion");
  return q.conj() / n;
}

/// The matrix U of (11): |q|^2 times the rotation matrix of q. Polynomial in q (exact).
template <typename Scalar>
Eigen::Matrix<Scalar, 3, 3> rotation_matrix_unnormalized(const Quaternion<Scalar>& q) {
  const Scalar &d0 = q.w(), &d1 = q.x(), &d2 = q.y(), &d3 = q.z();
  const Scalar two(2);
  Eigen::Matrix<Scalar, 3, 3> u;
  u(0, 0) = d0 * d0 + d1 * d1 - d2 * d2 - d3 * d3;
  u(0, 1) = two * (d1 * d2 - d0 * d3);
  u(0, 2) = two * (d0 * d2 + d1 * d3);
  u(1, 0) = two * (d0 * d3 + d1 * d2);
  u(1, 1) = d0 * d0 + d2 * d2 - d1 * d1 - d3 * d3;
  u(1, 2) = two * (d2 * d3 - d0 * d1);
  u(2, 0) = two * (d1 * d3 - d0 * d2);
  u(2, 1) = two * (d0 * d1 + d2 * d3);
  u(2, 2) = d0 * d0 + d3 * d3 - d1 * d1 - d2 * d2;
  return u;
}

/// Rotation matrix of a non-zero quaternion: U/|q|^2 (exact for exact Scalar).
template <typename Scalar>
Eigen::Matrix<Scalar, 3, 3> rotation_matrix(const Quaternion<Scalar>& q) {
  const Scalar n = q.norm2();
  if (n == Scalar(0)) throw Error(Errc::invalid_input, "rotation of the zero quaternion");
  Eigen::Matrix<Scalar, 3, 3> u = rotation_matrix_unnormalized(q);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) u(i, j) = Scalar(u(i, j) / n);
  return u;
}

/// Rotates the vector v by the quaternion q (not necessarily unit): q v conj(q) / |q|^2.
template <typename Scalar>
Eigen::Matrix<Scalar, 3, 1> rotate(const Quaternion<Scalar>& q,
                                   const Eigen::Matrix<Scalar, 3, 1>& v) {
  const Quaternion<Scalar> r = q * Quaternion<Scalar>::pure(v) * q.conj();
  return r.vec() / q.norm2();
}

// ----- floating point only (sqrt, trig) ---------------------------------------------------

template <typename S>
using EnableIfFloat = std::enable_if_t<std::is_floating_point_v<S>, int>;

/// Unit quaternion of the rotation by `angle` radians about `axis` (right-hand rule).
/// @pre axis != 0
template <typename Scalar, EnableIfFloat<Scalar> = 0>
Quaternion<Scalar> from_axis_angle(const Eigen::Matrix<Scalar, 3, 1>& axis, Scalar angle) {
  const Scalar n = axis.norm();
  if (!(n > Scalar(0))) throw Error(Errc::invalid_input, "rotation axis is the zero vector");
  return Quaternion<Scalar>(std::cos(angle / 2), axis * (std::sin(angle / 2) / n));
}

/// Unit quaternion (w >= 0) of a rotation matrix, by Shepperd's method (stable for every
/// rotation). @pre m orthogonal with det +1
/// @see Shepperd 1978, "Quaternion from rotation matrix"
template <typename Scalar, EnableIfFloat<Scalar> = 0>
Quaternion<Scalar> from_rotation_matrix(const Eigen::Matrix<Scalar, 3, 3>& m) {
  const Scalar tr = m.trace();
  Quaternion<Scalar> q;
  if (tr >= m(0, 0) && tr >= m(1, 1) && tr >= m(2, 2)) {
    const Scalar s = std::sqrt(Scalar(1) + tr) * 2;
    q = Quaternion<Scalar>(s / 4, (m(2, 1) - m(1, 2)) / s, (m(0, 2) - m(2, 0)) / s,
                           (m(1, 0) - m(0, 1)) / s);
  } else if (m(0, 0) >= m(1, 1) && m(0, 0) >= m(2, 2)) {
    const Scalar s = std::sqrt(Scalar(1) + m(0, 0) - m(1, 1) - m(2, 2)) * 2;
    q = Quaternion<Scalar>((m(2, 1) - m(1, 2)) / s, s / 4, (m(0, 1) + m(1, 0)) / s,
                           (m(0, 2) + m(2, 0)) / s);
  } else if (m(1, 1) >= m(2, 2)) {
    const Scalar s = std::sqrt(Scalar(1) + m(1, 1) - m(0, 0) - m(2, 2)) * 2;
    q = Quaternion<Scalar>((m(0, 2) - m(2, 0)) / s, (m(0, 1) + m(1, 0)) / s, s / 4,
                           (m(1, 2) + m(2, 1)) / s);
  } else {
    const Scalar s = std::sqrt(Scalar(1) + m(2, 2) - m(0, 0) - m(1, 1)) * 2;
    q = Quaternion<Scalar>((m(1, 0) - m(0, 1)) / s, (m(0, 2) + m(2, 0)) / s,
                           (m(1, 2) + m(2, 1)) / s, s / 4);
  }
  q = q / std::sqrt(q.norm2());
  return q.w() < 0 ? -q : q;
}

template <typename Scalar, EnableIfFloat<Scalar> = 0>
Scalar norm(const Quaternion<Scalar>& q) {
  return std::sqrt(q.norm2());
}

template <typename Scalar, EnableIfFloat<Scalar> = 0>
Quaternion<Scalar> normalized(const Quaternion<Scalar>& q) {
  const Scalar n = norm(q);
  if (!(n > Scalar(0))) throw Error(Errc::invalid_input, "cannot normalise the zero quaternion");
  return q / n;
}

/// Logarithm of a unit quaternion: the pure quaternion (theta/2) * axis.
template <typename Scalar, EnableIfFloat<Scalar> = 0>
Quaternion<Scalar> log_unit(const Quaternion<Scalar>& q) {
  const Scalar vn = q.vec().norm();
  const Scalar half = std::atan2(vn, q.w());
  if (vn <= std::numeric_limits<Scalar>::min()) return Quaternion<Scalar>();
  return Quaternion<Scalar>::pure(q.vec() * (half / vn));
}

/// Exponential of a pure quaternion v: cos|v| + sin|v| v/|v|.
template <typename Scalar, EnableIfFloat<Scalar> = 0>
Quaternion<Scalar> exp_pure(const Quaternion<Scalar>& v) {
  const Scalar a = v.vec().norm();
  // sin(a)/a by its series near 0 keeps full accuracy.
  const Scalar sinc = a < Scalar(1e-8) ? Scalar(1) - a * a / 6 : std::sin(a) / a;
  return Quaternion<Scalar>(std::cos(a), v.vec() * sinc);
}

/// q^s = exp(s log q) for a unit quaternion q.
template <typename Scalar, EnableIfFloat<Scalar> = 0>
Quaternion<Scalar> pow_unit(const Quaternion<Scalar>& q, Scalar s) {
  return exp_pure(Quaternion<Scalar>::pure(log_unit(q).vec() * s));
}

/// Spherical linear interpolation between unit quaternions along the shorter arc.
/// @see Shoemake 1985
template <typename Scalar, EnableIfFloat<Scalar> = 0>
Quaternion<Scalar> slerp(const Quaternion<Scalar>& a, Quaternion<Scalar> b, Scalar s) {
  if (a.dot(b) < 0) b = -b;
  return a * pow_unit(a.conj() * b, s);
}

}  // namespace qmotion::kernel
