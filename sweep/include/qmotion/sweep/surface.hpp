// <qmotion/sweep/surface.hpp>
#pragma once
#include <optional>
#include <qmotion/sweep/factors.hpp>
#include <qmotion/sweep/nurbs.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <qmotion/sweep/trajectory.hpp>
#include <qmotion/sweep/weights.hpp>
#include <vector>

namespace qmotion::sweep {

/// A rational tensor-product surface in homogeneous form: poles[i][j] = (w, w x, w y, w z),
/// i along u (the motion parameter), j along v (the profile parameter).
template <typename Scalar>
struct HomogeneousSurface {
  int degree_u = 0, degree_v = 0;
  std::vector<Scalar> knots_u, knots_v;
  std::vector<std::vector<Vec4<Scalar>>> poles;
};

/// Homogeneous trajectories of the homogeneous points X_j, all with one degree and knot
/// vector: from the factors when given, else from the motion with the elevation common to
/// all of them stripped.
template <typename Scalar>
std::vector<kernel::BSpline<Vec4<Scalar>>> trajectories(const Motion<Scalar>& motion,
                                                        const std::vector<Vec4<Scalar>>& X) {
  if (motion.factors) return trajectories_from_factors(*motion.factors, X);
  const kernel::QMotion<Scalar>& m = motion.curve;
  std::vector<kernel::BSpline<Vec4<Scalar>>> cols;
  for (const auto& x : X) cols.push_back(kernel::homogeneous_trajectory(m, x));
  if (m.segments() == 1) {
    int d = 0;
    for (const auto& c : cols) d = std::max(d, kernel::exact_degree(kernel::bezier_pieces(c)[0]));
    for (auto& c : cols) {
      const auto r = kernel::reduce_degree(kernel::bezier_pieces(c)[0]);
      c = kernel::BSpline<Vec4<Scalar>>::from_bezier(kernel::elevate(r, d - r.degree()));
    }
  }
  return cols;
}

namespace detail {

/// The homogeneous poles of the kinematic surface y(t, v) = M(t) x(v) (see
/// kinematic_surface), handed to out(degree_u, knots_u, rows, pole) with pole(i, j) the pole
/// of row i (along u) and column j (the profile's pole j); returns what out returns.
template <typename Scalar, typename Out>
auto kinematic_poles(const Motion<Scalar>& m, const NurbsCurve<Scalar>& profile, Out&& out) {
  std::vector<Vec4<Scalar>> X;
  X.reserve(profile.points.size());
  for (std::size_t j = 0; j < profile.points.size(); ++j) {
    Vec4<Scalar> x;
    x << profile.weights[j], profile.points[j] * profile.weights[j];
    X.push_back(x);
  }
  if (m.factors && X.size() >= 4) {
    auto M = matrix_from_factors(*m.factors);
    // Every column's weight function is w_j |Q_rot|^2, M's first row: one refinement
    // serves all, found on the trajectory of (1, 0, 0, 0).
    Vec4<Scalar> e0 = Vec4<Scalar>::Zero();
    e0(0) = Scalar(1);
    const auto extra = knots_for_positive_weights(apply(M, e0));  // before M is moved from
    M = insert_knots(std::move(M), extra);
    std::vector<Vec4<Scalar>> P;  // row by row, each product made once
    P.reserve(M.ctrl().size() * X.size());
    for (const auto& Mi : M.ctrl())
      for (const auto& x : X) P.push_back(Vec4<Scalar>(Mi * x));
    return out(
        M.degree(), M.knots(), M.ctrl().size(),
        [&](std::size_t i, std::size_t j) -> const Vec4<Scalar>& { return P[i * X.size() + j]; });
  }
  auto cols = trajectories(m, X);
  // Every column's weight function is w_j times the motion's: one refinement serves all.
  const auto extra = knots_for_positive_weights(cols.front());
  for (auto& c : cols) c = insert_knots(std::move(c), extra);
  return out(
      cols.front().degree(), cols.front().knots(), cols.front().ctrl().size(),
      [&](std::size_t i, std::size_t j) -> const Vec4<Scalar>& { return cols[j].ctrl()[i]; });
}

/// The NURBS surface of the homogeneous poles pole(i, j) (rows x cols), weights scaled so
/// that the largest is 1. Throws Errc::numerical_failure at a weight that is not positive.
template <typename Scalar, typename Pole>
NurbsSurface<Scalar> nurbs_from_poles(int degree_u, int degree_v, std::vector<Scalar> knots_u,
                                      std::vector<Scalar> knots_v, std::size_t rows,
                                      std::size_t cols, Pole&& pole) {
  Scalar wmax(0);
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t j = 0; j < cols; ++j) wmax = std::max(wmax, Scalar(pole(i, j)(0)));
  NurbsSurface<Scalar> s;
  s.degree_u = degree_u;
  s.degree_v = degree_v;
  s.knots_u = std::move(knots_u);
  s.knots_v = std::move(knots_v);
  s.points.reserve(rows);
  s.weights.reserve(rows);
  for (std::size_t i = 0; i < rows; ++i) {
    auto& points = s.points.emplace_back();
    auto& weights = s.weights.emplace_back();
    points.reserve(cols);  // one allocation a row, not one a doubling
    weights.reserve(cols);
    for (std::size_t j = 0; j < cols; ++j) {
      const auto& p = pole(i, j);
      if (!(p(0) > Scalar(0)))
        throw Error(Errc::numerical_failure, "a surface weight is not positive");
      points.push_back((p.template tail<3>() / p(0)).eval());
      weights.push_back(Scalar(p(0) / wmax));
    }
  }
  return s;
}

}  // namespace detail

/// The kinematic surface y(t, v) = M(t) x(v) of a rational profile (docs/interpolation.md): its
/// homogeneous poles are the u-poles of the trajectories of the profile's homogeneous
/// poles X_j = (w_j, w_j x_j), since M(t) acts linearly. Exact, no fitting; u is t. Knots
/// are inserted along u until every weight is positive (docs/formats.md). With the motion's factors
/// and four profile poles or more, the matrix spline M is made once and pole i of column j
/// is M_i X_j (the poles of M X are M's poles times X: a linear map commutes with the
/// blossoms that make them): `sweep` with a circle (9 poles) on 10^4 poses, 0.471 -> 0.429 s.
/// With fewer, each column's own trajectory costs no more than M's 16 entries (a segment on
/// the 200-pose helix: 0.32 ms, 0.33-0.34 ms through M) and keeps the poles as before.
template <typename Scalar>
HomogeneousSurface<Scalar> kinematic_surface(const Motion<Scalar>& m,
                                             const NurbsCurve<Scalar>& profile) {
  return detail::kinematic_poles(
      m, profile,
      [&](int degree_u, const std::vector<Scalar>& knots_u, std::size_t rows, auto&& pole) {
        HomogeneousSurface<Scalar> s;
        s.degree_u = degree_u;
        s.degree_v = profile.degree;
        s.knots_u = knots_u;
        s.knots_v = profile.knots;
        s.poles.resize(rows);
        for (std::size_t i = 0; i < rows; ++i) {
          s.poles[i].reserve(profile.points.size());
          for (std::size_t j = 0; j < profile.points.size(); ++j) s.poles[i].push_back(pole(i, j));
        }
        return s;
      });
}

/// to_nurbs(kinematic_surface(m, profile)) without the homogeneous rows in between: the
/// same surface bit for bit, with one allocation a row fewer (what `sweep` and the library's
/// sweeps build).
template <typename Scalar>
NurbsSurface<Scalar> kinematic_nurbs(const Motion<Scalar>& m, const NurbsCurve<Scalar>& profile) {
  return detail::kinematic_poles(
      m, profile,
      [&](int degree_u, const std::vector<Scalar>& knots_u, std::size_t rows, auto&& pole) {
        return detail::nurbs_from_poles(degree_u, profile.degree, knots_u, profile.knots, rows,
                                        profile.points.size(), pole);
      });
}

/// The trajectory of the Cartesian point x as a homogeneous spline with positive weights,
/// at its minimal degree (factors) or with elevation stripped (motion only).
template <typename Scalar>
kernel::BSpline<Vec4<Scalar>> trajectory(const Motion<Scalar>& m,
                                         const Eigen::Matrix<Scalar, 3, 1>& x) {
  Vec4<Scalar> X;
  X << Scalar(1), x;
  auto h = m.factors ? trajectory_from_factors(*m.factors, X) : trajectory_from_motion(m.curve, X);
  return insert_knots(h, knots_for_positive_weights(h));
}

/// Weights scaled so that the largest is 1 (the homogeneous scale is free).
template <typename Scalar>
NurbsSurface<Scalar> to_nurbs(const HomogeneousSurface<Scalar>& h) {
  return detail::nurbs_from_poles(
      h.degree_u, h.degree_v, h.knots_u, h.knots_v, h.poles.size(),
      h.poles.empty() ? std::size_t(0) : h.poles.front().size(),
      [&](std::size_t i, std::size_t j) -> const Vec4<Scalar>& { return h.poles[i][j]; });
}

/// Point of a NURBS surface at (u, v): the (p + 1) x (q + 1) homogeneous poles of the spans
/// of u and v weighted by their basis functions. Exact for exact Scalar.
template <typename Scalar>
Eigen::Matrix<Scalar, 3, 1> evaluate(const NurbsSurface<Scalar>& s, const Scalar& u,
                                     const Scalar& v) {
  const int p = s.degree_u, q = s.degree_v;
  const int ju = kernel::knot_span(s.knots_u, p, static_cast<int>(s.points.size()), u);
  const int jv = kernel::knot_span(s.knots_v, q, static_cast<int>(s.points.front().size()), v);
  const auto Nu = kernel::basis_functions(s.knots_u, ju, p, u);
  const auto Nv = kernel::basis_functions(s.knots_v, jv, q, v);
  Vec4<Scalar> h = Vec4<Scalar>::Zero();
  for (int a = 0; a <= p; ++a) {
    const auto i = static_cast<std::size_t>(ju - p + a);
    Vec4<Scalar> row = Vec4<Scalar>::Zero();
    for (int b = 0; b <= q; ++b) {
      const auto j = static_cast<std::size_t>(jv - q + b);
      const Scalar nw = Scalar(Nv[static_cast<std::size_t>(b)] * s.weights[i][j]);
      row(0) += nw;
      row.template tail<3>() += (s.points[i][j] * nw).eval();
    }
    h += (row * Nu[static_cast<std::size_t>(a)]).eval();
  }
  return (h.template tail<3>() / h(0)).eval();
}

/// The trajectory of the point x under the motion as an exact NURBS curve (u = t), at its
/// minimal degree with positive weights. Throws Errc::numerical_failure through a pole.
template <typename Scalar>
NurbsCurve<Scalar> trajectory_curve(const Motion<Scalar>& m, const Eigen::Matrix<Scalar, 3, 1>& x) {
  return to_nurbs(trajectory(m, x));
}

/// The kinematic surfaces the profile's edges sweep (docs/interpolation.md): one exact NURBS
/// surface per edge, u = t, v the edge's parameter, positive weights.
template <typename Scalar>
std::vector<NurbsSurface<Scalar>> sweep(const Motion<Scalar>& m, const Profile<Scalar>& profile) {
  std::vector<NurbsSurface<Scalar>> out;
  for (const auto& e : profile.edges) out.push_back(kinematic_nurbs(m, e));
  return out;
}

}  // namespace qmotion::sweep
