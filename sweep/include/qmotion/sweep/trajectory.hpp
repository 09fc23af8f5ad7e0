// <qmotion/sweep/trajectory.hpp>
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <optional>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/sweep/factors.hpp>
#include <sstream>
#include <utility>
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

namespace detail {

/// The Bezier pieces of matrix_from_factors' spline, span by span on the factors' common
/// breakpoints: start(d, knots) is told the spline's degree and knot vector first, then each
/// piece is handed to visit(piece) as it is made (an lvalue visit may move from; its storage
/// is otherwise reused for the next piece; kernel::BezierJoiner assembles the spline).
template <typename Scalar, typename Start, typename Visit>
void matrix_pieces(const MotionFactors<Scalar>& f, Start&& start, Visit&& visit) {
  using V3 = Eigen::Matrix<Scalar, 3, 1>;
  using M3 = Eigen::Matrix<Scalar, 3, 3>;
  using M4 = Eigen::Matrix<Scalar, 4, 4>;
  using Q = kernel::Quaternion<Scalar>;
  using kernel::Bernstein;
  const auto method = f.method;
  // Every factor taken apart once on the common breakpoints; each span's matrix is then
  // built from Bezier products alone and the spline assembled once (no intermediate
  // spline products, each of which would take its factors apart and reassemble them).
  std::vector<Scalar> x = f.rotation.breakpoints();
  for (const auto& v : f.translation.breakpoints()) x.push_back(v);
  if (f.translation2)
    for (const auto& v : f.translation2->breakpoints()) x.push_back(v);
  std::sort(x.begin(), x.end());
  x.erase(std::unique(x.begin(), x.end()), x.end());
  const auto rot = kernel::bezier_pieces(f.rotation, x);
  const auto tr1 = kernel::bezier_pieces(f.translation, x);
  std::vector<Bernstein<V3>> tr2;
  if (method == kernel::TranslationMethod::trt) tr2 = kernel::bezier_pieces(*f.translation2, x);
  const auto times = [](const M3& u, const V3& v) { return V3(u * v); };
  // The polar form of q -> [[|q|^2, 0], [0, U(q)]] is symmetric and bilinear:
  // polar(p, q) = [[p.q, 0], [0, (U(p + q) - U(p) - U(q)) / 2]], polar(q, q) = the form at q.
  // A rotation piece's Bezier product with itself under it (the piece's |Q_rot|^2 and U,
  // degree 2k) takes each unordered pair of coefficients once, with each U(q_i) made once.
  const int kr = f.rotation.degree(), k2 = 2 * kr;
  std::vector<Scalar> pair_weight;  // C(k,i) C(k,j) / C(2k,i+j), doubled off the diagonal
  for (int i = 0; i <= kr; ++i)
    for (int j = i; j <= kr; ++j)
      pair_weight.push_back(
          Scalar(kernel::binomial<Scalar>(kr, i) * kernel::binomial<Scalar>(kr, j) /
                 kernel::binomial<Scalar>(k2, i + j) * Scalar(i == j ? 1 : 2)));
  // Every span's piece is made in buffers reused from span to span (no allocation in the
  // loop for TR and minimal order: a few hundred spans of a B-spline motion spent a third of
  // their time in malloc and free), by the very operations kernel::product and
  // kernel::elevate perform, in their order: the pieces are theirs bit for bit.
  std::vector<M3> u_of;
  std::vector<M4> nu;  // |Q_rot|^2 and U of the span, degree 2k
  const auto square = [&](const Bernstein<Q>& r) {
    const auto& q = r.coeffs();
    u_of.clear();
    for (const Q& qi : q) u_of.push_back(kernel::rotation_matrix_unnormalized(qi));
    nu.assign(static_cast<std::size_t>(k2 + 1), M4::Zero());
    std::size_t w = 0;
    for (std::size_t i = 0; i < q.size(); ++i)
      for (std::size_t j = i; j < q.size(); ++j, ++w) {
        M4 m = M4::Zero();
        m(0, 0) = q[i].dot(q[j]);
        if (i == j)
          m.template block<3, 3>(1, 1) = u_of[i];
        else
          m.template block<3, 3>(1, 1) =
              ((kernel::rotation_matrix_unnormalized(Q(q[i] + q[j])) - u_of[i] - u_of[j]) /
               Scalar(2))
                  .eval();
        nu[i + j] += kernel::scale(pair_weight[w], m);
      }
  };
  // Degree: 2k for |Q_rot|^2 and U; the translation column 2k + l (TR), 2k + max(l1, l2)
  // (TRT), l (minimal order).
  const int l1 = f.translation.degree();
  int d = std::max(k2, l1 + (method == kernel::TranslationMethod::minimal ? 0 : k2));
  if (method == kernel::TranslationMethod::trt) d = std::max(d, k2 + f.translation2->degree());
  // At a breakpoint the matrix is as smooth as the least smooth factor there.
  std::vector<Scalar> knots(static_cast<std::size_t>(d + 1), x.front());
  for (std::size_t k = 1; k + 1 < x.size(); ++k) {
    int cont = std::min(kernel::continuity_at(f.rotation, x[k]),
                        kernel::continuity_at(f.translation, x[k]));
    if (method == kernel::TranslationMethod::trt)
      cont = std::min(cont, kernel::continuity_at(*f.translation2, x[k]));
    knots.insert(knots.end(), static_cast<std::size_t>(std::clamp(d - cont, 0, d + 1)), x[k]);
  }
  knots.insert(knots.end(), static_cast<std::size_t>(d + 1), x.back());
  start(d, knots);
  // kernel::product's weights for |Q_rot|^2 (degree 2k) times p (l1).
  const std::vector<Scalar> product_weight = kernel::product_weights<Scalar>(k2, l1);
  std::vector<V3> a;  // column 0 below the weight
  std::vector<M4> c;  // the piece's coefficients, handed to visit and taken back
  for (std::size_t k = 0; k < rot.size(); ++k) {
    square(rot[k]);
    // Column 0 below the weight: a = |Q_rot|^2 p (TR), |Q_rot|^2 p1 + U p2 (TRT), w (minimal).
    const auto& p = tr1[k].coeffs();
    if (method == kernel::TranslationMethod::minimal) {
      a.assign(p.begin(), p.end());
    } else {
      a.assign(static_cast<std::size_t>(k2 + l1 + 1), V3::Zero());
      std::size_t w = 0;
      for (int i = 0; i <= k2; ++i)
        for (int j = 0; j <= l1; ++j, ++w)
          a[static_cast<std::size_t>(i + j)] += kernel::scale(
              product_weight[w], V3(kernel::RingMul{}(nu[static_cast<std::size_t>(i)](0, 0),
                                                      p[static_cast<std::size_t>(j)])));
    }
    kernel::elevate_coeffs(a, d - (static_cast<int>(a.size()) - 1));
    if (method == kernel::TranslationMethod::trt) {
      std::vector<M3> u;
      for (const auto& m : nu) u.push_back(m.template block<3, 3>(1, 1));
      auto b = kernel::product(Bernstein<M3>(std::move(u), rot[k].a(), rot[k].b()), tr2[k], times);
      b = kernel::elevate(b, d - b.degree());
      for (int i = 0; i <= d; ++i)
        a[static_cast<std::size_t>(i)] = V3(a[static_cast<std::size_t>(i)] + b[i]);
    }
    c.assign(nu.begin(), nu.end());
    kernel::elevate_coeffs(c, d - k2);
    for (int i = 0; i <= d; ++i)
      c[static_cast<std::size_t>(i)].template block<3, 1>(1, 0) = a[static_cast<std::size_t>(i)];
    Bernstein<M4> piece(std::move(c), rot[k].a(), rot[k].b());
    visit(piece);  // may move the piece away (matrix_from_factors keeps it)
    c = std::move(piece).take_coeffs();
  }
}

}  // namespace detail

/// The motion's matrix spline at the minimal degree its factors allow (the form (35) of
/// Theorem 6): y(t) = M(t) X for every homogeneous point X = (x0, x), with
///   M = [[|Q_rot|^2, 0], [a(t), U(t)]],  U v = Vec(Q_rot v Q_rot~),
/// a = |Q_rot|^2 p (TR), |Q_rot|^2 p1 + U p2 (TRT), w (minimal order). Degree 2k + l (TR),
/// 2k + max(l1, l2) (TRT), max(2k, l) (minimal). Every trajectory and every column of a
/// kinematic surface is a linear map of its poles (trajectories_from_factors makes them
/// without it). Exact for exact Scalar.
template <typename Scalar>
kernel::BSpline<Eigen::Matrix<Scalar, 4, 4>> matrix_from_factors(const MotionFactors<Scalar>& f) {
  std::optional<kernel::BezierJoiner<Eigen::Matrix<Scalar, 4, 4>>> joiner;
  detail::matrix_pieces(
      f, [&](int d, const std::vector<Scalar>& knots) { joiner.emplace(d, knots); },
      [&](auto&& piece) { joiner->add(std::move(piece)); });
  return std::move(*joiner).finish();
}

/// The homogeneous trajectories y_j = M X_j of the points X_j (matrix_from_factors' M), all
/// with M's degree and knots: each span's matrix piece is applied to every X_j as it is made
/// and joined at once (kernel::BezierJoiner), so neither M, its pieces nor the trajectories'
/// pieces are held (a 4 x 4 piece is four times a trajectory's). Exact for exact Scalar.
template <typename Scalar>
std::vector<kernel::BSpline<Vec4<Scalar>>> trajectories_from_factors(
    const MotionFactors<Scalar>& f, const std::vector<Vec4<Scalar>>& X) {
  using M4 = Eigen::Matrix<Scalar, 4, 4>;
  std::vector<kernel::BezierJoiner<Vec4<Scalar>>> joiners;
  detail::matrix_pieces(
      f,
      [&](int d, const std::vector<Scalar>& knots) {
        joiners.reserve(X.size());
        for (std::size_t j = 0; j < X.size(); ++j) joiners.emplace_back(d, knots);
      },
      [&](const kernel::Bernstein<M4>& m) {
        for (std::size_t j = 0; j < X.size(); ++j) {
          std::vector<Vec4<Scalar>> c;
          c.reserve(m.coeffs().size());
          for (const M4& a : m.coeffs()) c.push_back(a * X[j]);
          joiners[j].add(kernel::Bernstein<Vec4<Scalar>>(std::move(c), m.a(), m.b()));
        }
      });
  std::vector<kernel::BSpline<Vec4<Scalar>>> out;
  out.reserve(X.size());
  for (auto& j : joiners) out.push_back(std::move(j).finish());
  return out;
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
/// allows (docs/interpolation.md): M(t) X with matrix_from_factors, except that under TR the origin
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
  return trajectories_from_factors(f, std::vector<Vec4<Scalar>>{X}).front();
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

/// Homogeneous trajectory of the moving point x under the motion, at the minimal degree the
/// construction allows: from the motion's factors when it has them, else from its curve.
template <typename Scalar>
kernel::BSpline<Vec4<Scalar>> point_trajectory(const Motion<Scalar>& m,
                                               const Eigen::Matrix<Scalar, 3, 1>& x) {
  const Vec4<Scalar> X(Scalar(1), x(0), x(1), x(2));
  return m.factors ? trajectory_from_factors(*m.factors, X) : trajectory_from_motion(m.curve, X);
}

/// Refuses (Errc::numerical_failure) a motion whose rotational part vanishes on its interval:
/// its trajectories run to infinity at such a pole.
inline void refuse_poles(const Motion<double>& m) {
  const auto poles = kernel::find_poles(m.curve, m.label());
  if (poles.empty()) return;
  std::ostringstream os;
  os.precision(12);
  for (double p : poles) os << " " << p;
  throw Error(Errc::numerical_failure,
              m.label() + ": the motion has a pole (zero rotational part) at t =" + os.str() +
                  ": its trajectories run to infinity there and cannot be exported");
}

}  // namespace qmotion::sweep
