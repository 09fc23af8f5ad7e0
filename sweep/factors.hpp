// sweep/factors.hpp
#pragma once
#include <Eigen/Core>
#include <optional>

#include "kernel/interpolation.hpp"

namespace qmotion::sweep {

/// The factors a Q-motion was built as the product of (Juettler 1994, (30), (32), (36)):
/// the rotational part Q_rot and the translational coefficient spline(s). They give every
/// trajectory at its minimal degree exactly, with the structurally known common factor
/// |Q_rot|^2 (TR, TRT) or |Q_rot|^4 (minimal order) never formed.
template <typename Scalar>
struct MotionFactors {
  using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
  kernel::TranslationMethod method = kernel::TranslationMethod::tr;
  kernel::BSpline<kernel::Quaternion<Scalar>> rotation;  ///< Q_rot
  kernel::BSpline<Vec3> translation;                     ///< p (TR), w (minimal), p1 (TRT)
  std::optional<kernel::BSpline<Vec3>> translation2;     ///< p2 (TRT)

  /// The motion the factors multiply to, up to a constant factor:
  /// TR (2 + eps p) Q_rot; TRT (2 + eps p1) Q_rot (2 + eps p2);
  /// minimal (2 |Q_rot|^2 + eps w) Q_rot.
  kernel::DualQuaternion<Scalar> evaluate(const Scalar& t) const {
    using DQ = kernel::DualQuaternion<Scalar>;
    const kernel::Quaternion<Scalar> r = kernel::evaluate(rotation, t);
    const Vec3 p = kernel::evaluate(translation, t);
    switch (method) {
      case kernel::TranslationMethod::tr:
        return DQ::translation(p) * r;
      case kernel::TranslationMethod::trt:
        return DQ::translation(p) * r * DQ::translation(kernel::evaluate(*translation2, t));
      case kernel::TranslationMethod::minimal:
        return DQ(r * Scalar(Scalar(2) * r.norm2()), kernel::Quaternion<Scalar>::pure(p) * r);
    }
    return DQ();
  }
};

/// The factors of an interpolation result (Bezier factors on the motion's interval).
template <typename Scalar>
MotionFactors<Scalar> factors_of(const kernel::Interpolation<Scalar>& r,
                                 kernel::TranslationMethod method) {
  using V3 = Eigen::Matrix<Scalar, 3, 1>;
  auto rows = [&](const kernel::MatX<Scalar>& P) {
    std::vector<V3> c;
    for (Eigen::Index j = 0; j < P.rows(); ++j) c.emplace_back(P(j, 0), P(j, 1), P(j, 2));
    return kernel::BSpline<V3>::from_bezier(
        kernel::Bernstein<V3>(std::move(c), r.rotation.a(), r.rotation.b()));
  };
  MotionFactors<Scalar> f{method,
                          kernel::BSpline<kernel::Quaternion<Scalar>>::from_bezier(r.rotation),
                          rows(r.translation), std::nullopt};
  if (method == kernel::TranslationMethod::trt) f.translation2 = rows(r.translation2);
  return f;
}

/// True when the factors reproduce the motion (proportional at 17 parameters, relative
/// tolerance `tol`; exactly for exact Scalar): a file whose recorded factors were edited
/// apart from its control points must not be trusted.
template <typename Scalar>
bool factors_match(const MotionFactors<Scalar>& f, const kernel::QMotion<Scalar>& m,
                   double tol = 1e-9) {
  if (f.rotation.a() != m.a() || f.rotation.b() != m.b()) return false;
  for (int i = 0; i <= 16; ++i) {
    const Scalar t = Scalar(m.a() + (m.b() - m.a()) * Scalar(i) / Scalar(16));
    const auto q = kernel::evaluate(m, t), g = f.evaluate(t);
    if constexpr (kernel::is_exact_v<Scalar>) {
      for (int c = 0; c < 8; ++c)
        for (int d = c + 1; d < 8; ++d)
          if (q[c] * g[d] != q[d] * g[c]) return false;
    } else {
      kernel::DualQuaternion<double> qd, gd;
      for (int c = 0; c < 8; ++c) {
        qd[c] = kernel::to_double(q[c]);
        gd[c] = kernel::to_double(g[c]);
      }
      if (!(kernel::pose_residual(qd, gd) <= tol)) return false;
    }
  }
  return true;
}

}  // namespace qmotion::sweep
