// <qmotion/sweep/nurbs.hpp>
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <qmotion/kernel/bspline.hpp>
#include <vector>

namespace qmotion::sweep {

/// A NURBS curve in the textbook convention (docs/formats.md): full clamped knot vector, Cartesian
/// poles and their weights.
template <typename Scalar>
struct NurbsCurve {
  int degree = 0;
  std::vector<Scalar> knots;
  std::vector<Eigen::Matrix<Scalar, 3, 1>> points;
  std::vector<Scalar> weights;
};

/// A tensor-product NURBS surface: points[i][j] is pole i along u, j along v.
template <typename Scalar>
struct NurbsSurface {
  int degree_u = 0, degree_v = 0;
  std::vector<Scalar> knots_u, knots_v;
  std::vector<std::vector<Eigen::Matrix<Scalar, 3, 1>>> points;
  std::vector<std::vector<Scalar>> weights;
};

/// The NURBS curve of a homogeneous spline (w, w x, w y, w z). Throws
/// Errc::numerical_failure when a weight is zero (a pole at infinity).
template <typename Scalar>
NurbsCurve<Scalar> to_nurbs(const kernel::BSpline<Eigen::Matrix<Scalar, 4, 1>>& h) {
  NurbsCurve<Scalar> c;
  c.degree = h.degree();
  c.knots = h.knots();
  c.weights.reserve(h.ctrl().size());  // no regrowth: a 10^4-span trajectory is 7 x 10^4 poles
  c.points.reserve(h.ctrl().size());
  for (const auto& p : h.ctrl()) {
    if (p(0) == Scalar(0))
      throw Error(Errc::numerical_failure,
                  "a homogeneous pole has weight zero (point at infinity)");
    c.weights.push_back(p(0));
    c.points.push_back((p.template tail<3>() / p(0)).eval());
  }
  return c;
}

/// The homogeneous spline (w, w x, w y, w z) of a NURBS curve.
template <typename Scalar>
kernel::BSpline<Eigen::Matrix<Scalar, 4, 1>> to_homogeneous(const NurbsCurve<Scalar>& c) {
  std::vector<Eigen::Matrix<Scalar, 4, 1>> h;
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    Eigen::Matrix<Scalar, 4, 1> p;
    p << c.weights[i], c.points[i] * c.weights[i];
    h.push_back(p);
  }
  return kernel::BSpline<Eigen::Matrix<Scalar, 4, 1>>::make(c.degree, c.knots, std::move(h));
}

/// Point of the curve at t: the p + 1 homogeneous poles of t's span weighted by their basis
/// functions, then projected. Exact for exact Scalar.
template <typename Scalar>
Eigen::Matrix<Scalar, 3, 1> evaluate(const NurbsCurve<Scalar>& c, const Scalar& t) {
  const int j = kernel::knot_span(c.knots, c.degree, static_cast<int>(c.points.size()), t);
  const auto N = kernel::basis_functions(c.knots, j, c.degree, t);
  Scalar w(0);
  Eigen::Matrix<Scalar, 3, 1> x = Eigen::Matrix<Scalar, 3, 1>::Zero();
  for (int a = 0; a <= c.degree; ++a) {
    const auto i = static_cast<std::size_t>(j - c.degree + a);
    const Scalar nw = Scalar(N[static_cast<std::size_t>(a)] * c.weights[i]);
    w += nw;
    x += (c.points[i] * nw).eval();
  }
  return (x / w).eval();
}

}  // namespace qmotion::sweep
