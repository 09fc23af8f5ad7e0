// <qmotion/kernel/motion_factors.hpp>
#pragma once
#include <Eigen/Core>
#include <optional>
#include <qmotion/kernel/methods.hpp>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/kernel/pose.hpp>

namespace qmotion::kernel {

/// The factors a Q-motion was built as the product of (Juettler 1994, (30), (32), (36)):
/// the rotational part Q_rot and the translational coefficient spline(s). They give every
/// trajectory at its minimal degree exactly, with the structurally known common factor
/// |Q_rot|^2 (TR, TRT) or |Q_rot|^4 (minimal order) never formed.
template <typename Scalar>
struct MotionFactors {
  using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
  TranslationMethod method = TranslationMethod::tr;
  BSpline<Quaternion<Scalar>> rotation;       ///< Q_rot
  BSpline<Vec3> translation;                  ///< p (TR), w (minimal), p1 (TRT)
  std::optional<BSpline<Vec3>> translation2;  ///< p2 (TRT)

  /// The motion the factors multiply to, up to a constant factor:
  /// TR (2 + eps p) Q_rot; TRT (2 + eps p1) Q_rot (2 + eps p2);
  /// minimal (2 |Q_rot|^2 + eps w) Q_rot.
  DualQuaternion<Scalar> evaluate(const Scalar& t) const {
    using DQ = DualQuaternion<Scalar>;
    const Quaternion<Scalar> r = kernel::evaluate(rotation, t);
    const Vec3 p = kernel::evaluate(translation, t);
    switch (method) {
      case TranslationMethod::tr:
        return DQ::translation(p) * r;
      case TranslationMethod::trt:
        return DQ::translation(p) * r * DQ::translation(kernel::evaluate(*translation2, t));
      case TranslationMethod::minimal:
        return DQ(r * Scalar(Scalar(2) * r.norm2()), Quaternion<Scalar>::pure(p) * r);
    }
    return DQ();
  }
};

/// True when the factors reproduce the motion (proportional at 17 parameters, relative
/// tolerance `tol`; exactly for exact Scalar): a file whose recorded factors were edited
/// apart from its control points must not be trusted.
template <typename Scalar>
bool factors_match(const MotionFactors<Scalar>& f, const QMotion<Scalar>& m, double tol = 1e-9) {
  if (f.rotation.a() != m.a() || f.rotation.b() != m.b()) return false;
  for (int i = 0; i <= 16; ++i) {
    const Scalar t = Scalar(m.a() + (m.b() - m.a()) * Scalar(i) / Scalar(16));
    const auto q = evaluate(m, t), g = f.evaluate(t);
    if constexpr (is_exact_v<Scalar>) {
      for (int c = 0; c < 8; ++c)
        for (int d = c + 1; d < 8; ++d)
          if (q[c] * g[d] != q[d] * g[c]) return false;
    } else {
      DualQuaternion<double> qd, gd;
      for (int c = 0; c < 8; ++c) {
        qd[c] = to_double(q[c]);
        gd[c] = to_double(g[c]);
      }
      if (!(pose_residual(qd, gd) <= tol)) return false;
    }
  }
  return true;
}

}  // namespace qmotion::kernel
