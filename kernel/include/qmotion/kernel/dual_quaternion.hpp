// <qmotion/kernel/dual_quaternion.hpp>
#pragma once
#include <Eigen/Core>
#include <qmotion/kernel/quaternion.hpp>

namespace qmotion::kernel {

/// Dual quaternion Q = Q0 + eps Qe with eps^2 = 0 (docs/formats.md, Juettler 1994 eq. (3)).
/// Kept unnormalised: proportional dual quaternions describe the same displacement, and
/// every map below is homogeneous and polynomial, so it is exact for exact Scalar.
template <typename Scalar_>
class DualQuaternion {
 public:
  using Scalar = Scalar_;
  using Quat = Quaternion<Scalar>;
  using Vec3 = Eigen::Matrix<Scalar, 3, 1>;

  DualQuaternion() = default;
  DualQuaternion(const Quat& real, const Quat& dual) : real_(real), dual_(dual) {}
  /// The quaternion q as a dual quaternion with zero dual part.
  static DualQuaternion from_real(const Quat& q) { return DualQuaternion(q, Quat()); }
  /// The translation (5) 2 + eps v: displacement by the vector v.
  static DualQuaternion translation(const Vec3& v) {
    return DualQuaternion(Quat::real(Scalar(2)), Quat::pure(v));
  }
  /// Pose (14): P = (2 + eps s) * r, rotation r (any non-zero quaternion) then translation s.
  static DualQuaternion pose(const Vec3& s, const Quat& r) { return translation(s) * from_real(r); }

  const Quat& real() const { return real_; }
  const Quat& dual() const { return dual_; }
  Quat& real() { return real_; }
  Quat& dual() { return dual_; }
  /// Component i of (w, x, y, z, eps w, eps x, eps y, eps z).
  const Scalar& operator[](int i) const { return i < 4 ? real_[i] : dual_[i - 4]; }
  Scalar& operator[](int i) { return i < 4 ? real_[i] : dual_[i - 4]; }

  /// The conjugate (4): quaternion conjugate of both parts.
  DualQuaternion conj() const { return DualQuaternion(real_.conj(), dual_.conj()); }

  DualQuaternion& operator+=(const DualQuaternion& o) {
    real_ += o.real_;
    dual_ += o.dual_;
    return *this;
  }
  DualQuaternion& operator-=(const DualQuaternion& o) {
    real_ -= o.real_;
    dual_ -= o.dual_;
    return *this;
  }
  DualQuaternion& operator*=(const Scalar& s) {
    real_ *= s;
    dual_ *= s;
    return *this;
  }
  DualQuaternion operator-() const { return DualQuaternion(-real_, -dual_); }
  friend DualQuaternion operator+(DualQuaternion a, const DualQuaternion& b) { return a += b; }
  friend DualQuaternion operator-(DualQuaternion a, const DualQuaternion& b) { return a -= b; }
  friend DualQuaternion operator*(DualQuaternion a, const Scalar& s) { return a *= s; }
  friend DualQuaternion operator*(const Scalar& s, DualQuaternion a) { return a *= s; }
  friend DualQuaternion operator/(const DualQuaternion& a, const Scalar& s) {
    return DualQuaternion(a.real_ / s, a.dual_ / s);
  }
  friend DualQuaternion operator*(const DualQuaternion& a, const DualQuaternion& b) {
    return DualQuaternion(a.real_ * b.real_, a.real_ * b.dual_ + a.dual_ * b.real_);
  }
  /// Product with a quaternion (a dual quaternion with zero dual part) on either side.
  friend DualQuaternion operator*(const DualQuaternion& a, const Quat& q) {
    return DualQuaternion(a.real_ * q, a.dual_ * q);
  }
  friend DualQuaternion operator*(const Quat& q, const DualQuaternion& b) {
    return DualQuaternion(q * b.real_, q * b.dual_);
  }
  friend bool operator==(const DualQuaternion& a, const DualQuaternion& b) {
    return a.real_ == b.real_ && a.dual_ == b.dual_;
  }
  friend bool operator!=(const DualQuaternion& a, const DualQuaternion& b) { return !(a == b); }

  template <typename F>
  void for_each_component(F&& f) const {
    real_.for_each_component(f);
    dual_.for_each_component(f);
  }

 private:
  Quat real_;
  Quat dual_;
};

/// Plucker form (8): q0 qe + vec(q0).vec(qe) = Scal(Qe * conj(Q0)). Zero iff Q is a
/// displacement (for non-zero real part).
template <typename Scalar>
Scalar plucker(const DualQuaternion<Scalar>& q) {
  return q.real().dot(q.dual());
}

/// Plucker residual of one dual quaternion, scale free in both parts: |q0.qe| / (|Q0| |Qe|)
/// (the cosine between real and dual part as 4-vectors); 0 when either part is zero.
template <typename Scalar>
double plucker_residual(const DualQuaternion<Scalar>& q) {
  const double r = std::sqrt(to_double(q.real().norm2())),
               d = std::sqrt(to_double(q.dual().norm2()));
  if (r == 0.0 || d == 0.0) return 0.0;
  return std::abs(to_double(plucker(q))) / (r * d);
}

/// Trans(Q) = Q * conj(Q0) of (9): a translation 2v0 + eps v (up to a real factor).
template <typename Scalar>
DualQuaternion<Scalar> trans_part(const DualQuaternion<Scalar>& q) {
  return q * q.real().conj();
}

/// Rot(Q) = Q0 / (Q0 conj(Q0)) of (9). @pre Q0 != 0
template <typename Scalar>
Quaternion<Scalar> rot_part(const DualQuaternion<Scalar>& q) {
  const Scalar n = q.real().norm2();
  if (n == Scalar(0)) throw Error(Errc::numerical_failure, "dual quaternion with zero real part");
  return q.real() / n;
}

/// Translation vector of the displacement Q (the image of the moving origin).
/// @pre Q0 != 0
template <typename Scalar>
Eigen::Matrix<Scalar, 3, 1> translation_vector(const DualQuaternion<Scalar>& q) {
  const Scalar n = q.real().norm2();
  if (n == Scalar(0)) throw Error(Errc::numerical_failure, "dual quaternion with zero real part");
  const Quaternion<Scalar> t = q.dual() * q.real().conj();
  return t.vec() * Scalar(Scalar(2) / n);
}

/// Homogeneous 4x4 matrix of (10) for Q = Q0 + eps Qe:
/// [[|Q0|^2, 0], [2 Vec(Qe conj(Q0)), U(Q0)]], acting on (x0, x, y, z).
/// It equals the map (12) and is quadratic in Q (exact for exact Scalar).
template <typename Scalar>
Eigen::Matrix<Scalar, 4, 4> to_matrix4(const DualQuaternion<Scalar>& q) {
  Eigen::Matrix<Scalar, 4, 4> m = Eigen::Matrix<Scalar, 4, 4>::Zero();
  m(0, 0) = q.real().norm2();
  const Quaternion<Scalar> t = q.dual() * q.real().conj();
  for (int i = 0; i < 3; ++i) m(i + 1, 0) = Scalar(2) * t[i + 1];
  m.template block<3, 3>(1, 1) = rotation_matrix_unnormalized(q.real());
  return m;
}

/// The point map (12): homogeneous image (y0, y) of the homogeneous point (x0, x).
template <typename Scalar>
Eigen::Matrix<Scalar, 4, 1> apply(const DualQuaternion<Scalar>& q,
                                  const Eigen::Matrix<Scalar, 4, 1>& x) {
  using Quat = Quaternion<Scalar>;
  const Quat q0c = q.real().conj();
  const DualQuaternion<Scalar> xp(Quat::real(Scalar(2) * x(0)), Quat::pure(x.template tail<3>()));
  const DualQuaternion<Scalar> r = q * xp * q0c;
  Eigen::Matrix<Scalar, 4, 1> y;
  y(0) = q.real().norm2() * x(0);
  y.template tail<3>() = r.dual().vec();
  return y;
}

/// Cartesian image of the Cartesian point p under Q. @pre Q0 != 0
template <typename Scalar>
Eigen::Matrix<Scalar, 3, 1> apply_point(const DualQuaternion<Scalar>& q,
                                        const Eigen::Matrix<Scalar, 3, 1>& p) {
  Eigen::Matrix<Scalar, 4, 1> x;
  x << Scalar(1), p;
  const Eigen::Matrix<Scalar, 4, 1> y = apply(q, x);
  if (y(0) == Scalar(0))
    throw Error(Errc::numerical_failure, "dual quaternion with zero real part");
  return y.template tail<3>() / y(0);
}

}  // namespace qmotion::kernel
