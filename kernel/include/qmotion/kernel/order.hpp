// <qmotion/kernel/order.hpp>
#pragma once
#include <qmotion/kernel/linear_solve.hpp>
#include <qmotion/kernel/motion.hpp>
#include <vector>

namespace qmotion::kernel {

/// Degree of the common factor of f and g, both of degree n in Bernstein form, counted
/// homogeneously: a representation elevated from degree d counts as the true polynomial
/// times (s + (1 - s))^(n - d), so common elevation counts as common factor too and
/// n - result is the degree of the reduced pair. It is the rank deficiency of the
/// Bernstein Sylvester matrix of (u, v) -> u f + v g, deg u, deg v < n.
/// Exact for exact Scalar; double uses singular values below rel_tol * sigma_max.
/// @see Winkler, "Polynomial computations in the Bernstein basis" (Sylvester resultant)
template <typename Scalar>
int common_factor_degree(const Bernstein<Scalar>& f, const Bernstein<Scalar>& g,
                         double rel_tol = 1e-12) {
  const int n = f.degree();
  QMOTION_EXPECTS(g.degree() == n, "common_factor_degree needs equal degrees");
  if (n == 0) return 0;
  MatX<Scalar> S = MatX<Scalar>::Zero(2 * n, 2 * n);
  for (int i = 0; i < n; ++i)  // u = b_i^{n-1}
    for (int j = 0; j <= n; ++j) {
      const Scalar w = Scalar(binomial<Scalar>(n - 1, i) * binomial<Scalar>(n, j) /
                              binomial<Scalar>(2 * n - 1, i + j));
      S(i + j, i) = Scalar(w * f[j]);
      S(i + j, n + i) = Scalar(w * g[j]);
    }
  if constexpr (is_exact_v<Scalar>) {
    (void)rel_tol;
    return static_cast<int>(2 * n - Eigen::FullPivLU<MatX<Scalar>>(S).rank());
  } else {
    const Eigen::JacobiSVD<MatX<double>> svd(S);
    const auto& s = svd.singularValues();
    int rank = 0;
    while (rank < s.size() && s(rank) > rel_tol * s(0)) ++rank;
    return 2 * n - rank;
  }
}

/// Degree of the trajectory of the homogeneous point x on the Bezier piece p of a motion's
/// homogeneous trajectory (4 components), after removing every common factor.
template <typename Scalar>
int reduced_degree(const Bernstein<Eigen::Matrix<Scalar, 4, 1>>& y, double rel_tol = 1e-12) {
  // gcd(y0, y1, y2, y3) = gcd(y0, a1 y1 + a2 y2 + a3 y3) for all but a few (a1, a2, a3).
  const Scalar a1(1), a2 = Scalar(Scalar(3) / Scalar(7)), a3 = Scalar(Scalar(-5) / Scalar(11));
  const auto f = map_coeffs(y, [](const Eigen::Matrix<Scalar, 4, 1>& v) { return Scalar(v(0)); });
  const auto g = map_coeffs(y, [&](const Eigen::Matrix<Scalar, 4, 1>& v) {
    return Scalar(a1 * v(1) + a2 * v(2) + a3 * v(3));
  });
  return y.degree() - common_factor_degree(f, g, rel_tol);
}

/// Order of a motion (section 5): the degree of the trajectory of a general point after
/// common factors are removed; for a spline motion, the largest over its pieces.
/// Exact for exact Scalar. In double it is a numerical rank and only as good as the data:
/// smooth data interpolated at high degree has nearly vanishing top coefficients, which a
/// tolerance cannot tell from zero, so prefer construction_order for motions qmotion built.
template <typename Scalar>
int motion_order(const QMotion<Scalar>& m, double rel_tol = 1e-12) {
  Eigen::Matrix<Scalar, 4, 1> x;  // a point in general position
  x << Scalar(1), Scalar(Scalar(37) / Scalar(100)), Scalar(Scalar(-58) / Scalar(100)),
      Scalar(Scalar(72) / Scalar(100));
  int order = 0;
  for (const auto& piece : bezier_pieces(homogeneous_trajectory(m, x)))
    order = std::max(order, reduced_degree(piece, rel_tol));
  return order;
}

}  // namespace qmotion::kernel
