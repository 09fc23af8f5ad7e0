// sweep/trajectory.hpp
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <optional>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/sweep/factors.hpp>
#include <vector>

namespace qmotion::sweep {

template <typename Scalar>
using Vec4 = Eigen::Matrix<Scalar, 4, 1>;

namespace detail {

using kernel::combine;

/// The homogeneous spline (y0, y).
template <typename Scalar>
kernel::BSpline<Vec4<Scalar>> homogeneous(const kernel::BSpline<Scalar>& y0,
                                          const kernel::BSpline<Eigen::Matrix<Scalar, 3, 1>>& y) {
  return combine(y0, y,
                 [](const kernel::Bernstein<Scalar>& p,
                    const kernel::Bernstein<Eigen::Matrix<Scalar, 3, 1>>& q) {
                   std::vector<Vec4<Scalar>> c;
                   for (int i = 0; i <= p.degree(); ++i) {
                     Vec4<Scalar> v;
                     v << p[i], q[i];
                     c.push_back(v);
                   }
                   return kernel::Bernstein<Vec4<Scalar>>(std::move(c), p.a(), p.b());
                 });
}

template <typename Scalar>
kernel::BSpline<kernel::Quaternion<Scalar>> pure(
    const kernel::BSpline<Eigen::Matrix<Scalar, 3, 1>>& v) {
  return kernel::map_coeffs(
      v, [](const Eigen::Matrix<Scalar, 3, 1>& x) { return kernel::Quaternion<Scalar>::pure(x); });
}

template <typename Scalar>
kernel::BSpline<Eigen::Matrix<Scalar, 3, 1>> vec(
    const kernel::BSpline<kernel::Quaternion<Scalar>>& q) {
  return kernel::map_coeffs(q, [](const kernel::Quaternion<Scalar>& x) { return x.vec(); });
}

template <typename Scalar>
kernel::BSpline<Eigen::Matrix<Scalar, 3, 1>> constant_vector(const Eigen::Matrix<Scalar, 3, 1>& v,
                                                             const Scalar& a, const Scalar& b) {
  return kernel::BSpline<Eigen::Matrix<Scalar, 3, 1>>::make(0, {a, b}, {v});
}

/// U(Q_rot) v = Vec(Q_rot v Q_rot~) for a vector spline v (degree 2k + deg v).
template <typename Scalar>
kernel::BSpline<Eigen::Matrix<Scalar, 3, 1>> rotate(
    const kernel::BSpline<kernel::Quaternion<Scalar>>& r,
    const kernel::BSpline<Eigen::Matrix<Scalar, 3, 1>>& v) {
  const auto rc =
      kernel::map_coeffs(r, [](const kernel::Quaternion<Scalar>& x) { return x.conj(); });
  return vec(kernel::product(kernel::product(r, pure(v)), rc));
}

template <typename Scalar>
kernel::BSpline<Eigen::Matrix<Scalar, 3, 1>> add(
    const kernel::BSpline<Eigen::Matrix<Scalar, 3, 1>>& a,
    const kernel::BSpline<Eigen::Matrix<Scalar, 3, 1>>& b) {
  return combine(a, b, [](const auto& p, const auto& q) { return p + q; });
}

}  // namespace detail

/// The motion's matrix spline at the minimal degree its factors allow (the form (35) of
/// Theorem 6): y(t) = M(t) X for every homogeneous point X = (x0, x), with
///   M = [[|Q_rot|^2, 0], [a(t), U(t)]],  U v = Vec(Q_rot v Q_rot~),
/// a = |Q_rot|^2 p (TR), |Q_rot|^2 p1 + U p2 (TRT), w (minimal order). Degree 2k + l (TR),
/// 2k + max(l1, l2) (TRT), max(2k, l) (minimal). Built once; every trajectory and every
/// column of a kinematic surface is then a linear map of its poles. Exact for exact Scalar.
template <typename Scalar>
kernel::BSpline<Eigen::Matrix<Scalar, 4, 4>> matrix_from_factors(const MotionFactors<Scalar>& f) {
  using V3 = Eigen::Matrix<Scalar, 3, 1>;
  using M4 = Eigen::Matrix<Scalar, 4, 4>;
  using Q = kernel::Quaternion<Scalar>;
  const Scalar a = f.rotation.a(), b = f.rotation.b();
  const auto rc = kernel::map_coeffs(f.rotation, [](const Q& q) { return q.conj(); });
  const auto n2 =
      kernel::map_coeffs(kernel::product(f.rotation, rc), [](const Q& q) { return Scalar(q.w()); });
  kernel::BSpline<V3> transl = f.translation;
  switch (f.method) {
    case kernel::TranslationMethod::tr:
      transl = kernel::product(n2, f.translation);
      break;
    case kernel::TranslationMethod::trt:
      transl = detail::add(kernel::product(n2, f.translation),
                           detail::rotate(f.rotation, *f.translation2));
      break;
    case kernel::TranslationMethod::minimal:
      break;
  }
  // Column 0: (|Q_rot|^2, a); columns 1-3: (0, U e_c).
  auto M = kernel::combine(n2, transl,
                           [](const kernel::Bernstein<Scalar>& w, const kernel::Bernstein<V3>& v) {
                             std::vector<M4> c;
                             for (int i = 0; i <= w.degree(); ++i) {
                               M4 m = M4::Zero();
                               m(0, 0) = w[i];
                               m.template block<3, 1>(1, 0) = v[i];
                               c.push_back(m);
                             }
                             return kernel::Bernstein<M4>(std::move(c), w.a(), w.b());
                           });
  for (int col = 1; col <= 3; ++col) {
    const auto u = detail::rotate(f.rotation, detail::constant_vector(V3(V3::Unit(col - 1)), a, b));
    M = kernel::combine(M, u,
                        [col](const kernel::Bernstein<M4>& m, const kernel::Bernstein<V3>& v) {
                          std::vector<M4> c = m.coeffs();
                          for (int i = 0; i <= m.degree(); ++i)
                            c[static_cast<std::size_t>(i)].template block<3, 1>(1, col) = v[i];
                          return kernel::Bernstein<M4>(std::move(c), m.a(), m.b());
                        });
  }
  return M;
}

/// y = M X for a matrix spline M.
template <typename Scalar>
kernel::BSpline<Vec4<Scalar>> apply(const kernel::BSpline<Eigen::Matrix<Scalar, 4, 4>>& M,
                                    const Vec4<Scalar>& X) {
  return kernel::map_coeffs(
      M, [&](const Eigen::Matrix<Scalar, 4, 4>& m) { return Vec4<Scalar>(m * X); });
}

/// Homogeneous trajectory (y0, y) of the homogeneous point X = (x0, x) of the moving space,
/// parametrised by t, from the motion's factors at the minimal degree the construction
/// allows (SPEC §2.6): M(t) X with matrix_from_factors, except that under TR the origin
/// (x = 0) gives (x0, x0 p) of degree l (Proposition 4) unless `uniform_degree`.
template <typename Scalar>
kernel::BSpline<Vec4<Scalar>> trajectory_from_factors(const MotionFactors<Scalar>& f,
                                                      const Vec4<Scalar>& X,
                                                      bool uniform_degree = false) {
  using V3 = Eigen::Matrix<Scalar, 3, 1>;
  if (f.method == kernel::TranslationMethod::tr && X.template tail<3>() == V3::Zero() &&
      !uniform_degree) {
    const Scalar x0 = X(0);
    const auto one = kernel::BSpline<Scalar>::make(0, {f.rotation.a(), f.rotation.b()}, {x0});
    return detail::homogeneous(
        one, kernel::map_coeffs(f.translation, [&](const V3& v) { return V3(v * x0); }));
  }
  return apply(matrix_from_factors(f), X);
}

/// Homogeneous trajectory of X from the motion alone (y = M(t) X, degree 2n), with the
/// degree elevation a Bezier representation carries stripped (exactly for exact Scalar,
/// within 1e-12 otherwise). Used for motions without recorded factors.
template <typename Scalar>
kernel::BSpline<Vec4<Scalar>> trajectory_from_motion(const kernel::QMotion<Scalar>& m,
                                                     const Vec4<Scalar>& X) {
  auto y = kernel::homogeneous_trajectory(m, X);
  if (m.segments() == 1) {
    const auto red = kernel::reduce_degree(kernel::bezier_pieces(y)[0]);
    y = kernel::BSpline<Vec4<Scalar>>::from_bezier(red);
  }
  return y;
}

}  // namespace qmotion::sweep
