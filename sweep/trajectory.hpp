// sweep/trajectory.hpp
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <optional>
#include <vector>

#include "kernel/motion.hpp"
#include "sweep/factors.hpp"

namespace qmotion::sweep {

template <typename Scalar>
using Vec4 = Eigen::Matrix<Scalar, 4, 1>;

namespace detail {

/// Combines two splines on the same interval piece by piece over the union of their
/// breakpoints: f(piece_a, piece_b) must return a Bernstein polynomial of degree
/// max(deg a, deg b) on the piece. At each breakpoint the result keeps the continuity of
/// the less smooth input.
template <typename A, typename B, typename F>
auto zip(const kernel::BSpline<A>& a, const kernel::BSpline<B>& b, F f) {
  using S = kernel::coef_scalar_t<A>;
  std::vector<S> x = a.breakpoints();
  for (const auto& v : b.breakpoints()) x.push_back(v);
  std::sort(x.begin(), x.end());
  x.erase(std::unique(x.begin(), x.end()), x.end());
  const int d = std::max(a.degree(), b.degree());
  using R = typename std::decay_t<decltype(f(kernel::bezier_piece(a, x[0], x[1]),
                                             kernel::bezier_piece(b, x[0], x[1])))>;
  std::vector<R> pieces;
  for (std::size_t k = 0; k + 1 < x.size(); ++k) {
    const auto pa = kernel::bezier_piece(a, x[k], x[k + 1]);
    const auto pb = kernel::bezier_piece(b, x[k], x[k + 1]);
    pieces.push_back(f(kernel::elevate(pa, d - pa.degree()), kernel::elevate(pb, d - pb.degree())));
  }
  std::vector<S> knots(static_cast<std::size_t>(d + 1), x.front());
  for (std::size_t k = 1; k + 1 < x.size(); ++k) {
    const int cont = std::min(a.degree() - a.multiplicity(x[k]), b.degree() - b.multiplicity(x[k]));
    knots.insert(knots.end(), static_cast<std::size_t>(std::max(0, d - cont)), x[k]);
  }
  knots.insert(knots.end(), static_cast<std::size_t>(d + 1), x.back());
  return kernel::from_bezier_pieces(pieces, d, std::move(knots));
}

/// The homogeneous spline (y0, y).
template <typename Scalar>
kernel::BSpline<Vec4<Scalar>> homogeneous(const kernel::BSpline<Scalar>& y0,
                                          const kernel::BSpline<Eigen::Matrix<Scalar, 3, 1>>& y) {
  return zip(y0, y,
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
  return zip(a, b, [](const auto& p, const auto& q) { return p + q; });
}

}  // namespace detail

/// Homogeneous trajectory (y0, y) of the homogeneous point X = (x0, x) of the moving space,
/// parametrised by t, built from the motion's factors at the minimal degree the
/// construction allows (SPEC §2.6):
///  - TR:  (x0 |Q_rot|^2, x0 |Q_rot|^2 p + U x), degree 2k + l; for the origin (x = 0)
///    (x0, x0 p), degree l (Proposition 4);
///  - TRT: (x0 |Q_rot|^2, x0 |Q_rot|^2 p1 + U (x0 p2 + x)), degree 2k + max(l1, l2);
///  - minimal order: (x0 |Q_rot|^2, x0 w + U x), degree max(2k, l) (Theorem 6),
/// where U v = Vec(Q_rot v Q_rot~). Exact for exact Scalar.
template <typename Scalar>
kernel::BSpline<Vec4<Scalar>> trajectory_from_factors(const MotionFactors<Scalar>& f,
                                                      const Vec4<Scalar>& X,
                                                      bool uniform_degree = false) {
  using V3 = Eigen::Matrix<Scalar, 3, 1>;
  const Scalar x0 = X(0);
  const V3 x = X.template tail<3>();
  const Scalar a = f.rotation.a(), b = f.rotation.b();
  const auto scaled = [&](const kernel::BSpline<V3>& s) {
    return kernel::map_coeffs(s, [&](const V3& v) { return V3(v * x0); });
  };
  const auto n2 = kernel::product(
      f.rotation,
      kernel::map_coeffs(f.rotation, [](const kernel::Quaternion<Scalar>& q) { return q.conj(); }));
  const auto w0 = kernel::map_coeffs(
      n2, [&](const kernel::Quaternion<Scalar>& q) { return Scalar(q.w() * x0); });
  const bool origin = x == V3::Zero();
  switch (f.method) {
    case kernel::TranslationMethod::tr: {
      if (origin && !uniform_degree) {
        const auto one = kernel::BSpline<Scalar>::make(0, {a, b}, {x0});
        return detail::homogeneous(one, scaled(f.translation));
      }
      const auto n2s =
          kernel::map_coeffs(n2, [](const kernel::Quaternion<Scalar>& q) { return q.w(); });
      const auto y = detail::add(kernel::product(n2s, scaled(f.translation)),
                                 detail::rotate(f.rotation, detail::constant_vector(x, a, b)));
      return detail::homogeneous(w0, y);
    }
    case kernel::TranslationMethod::trt: {
      const auto n2s =
          kernel::map_coeffs(n2, [](const kernel::Quaternion<Scalar>& q) { return q.w(); });
      const auto inner = detail::add(scaled(*f.translation2), detail::constant_vector(x, a, b));
      const auto y = detail::add(kernel::product(n2s, scaled(f.translation)),
                                 detail::rotate(f.rotation, inner));
      return detail::homogeneous(w0, y);
    }
    case kernel::TranslationMethod::minimal: {
      const auto y = detail::add(scaled(f.translation),
                                 detail::rotate(f.rotation, detail::constant_vector(x, a, b)));
      return detail::homogeneous(w0, y);
    }
  }
  throw Error(Errc::internal, "unknown translation method");
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
