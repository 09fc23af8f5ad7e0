// <qmotion/kernel/linear_solve.hpp>
#pragma once
#include <Eigen/Dense>
#include <qmotion/kernel/bernstein.hpp>
#include <qmotion/kernel/error.hpp>
#include <string>
#include <vector>

namespace qmotion::kernel {

template <typename Scalar>
using MatX = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

/// Collocation matrix B(i, j) = b_j^k(t_i) of the Bernstein basis of degree k on [a, b]
/// (the matrix of (21), (25), (31), (39)). Exact for exact Scalar.
template <typename Scalar>
MatX<Scalar> bernstein_collocation(const std::vector<Scalar>& t, int k, const Scalar& a,
                                   const Scalar& b) {
  MatX<Scalar> B = MatX<Scalar>::Zero(static_cast<Eigen::Index>(t.size()), k + 1);
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Scalar s = Scalar((t[i] - a) / (b - a)), s1 = Scalar(Scalar(1) - s);
    std::vector<Scalar> v(static_cast<std::size_t>(k + 1), Scalar(0));
    v[0] = Scalar(1);
    for (int d = 1; d <= k; ++d)
      for (int j = d; j >= 0; --j) {
        const std::size_t uj = static_cast<std::size_t>(j);
        Scalar next = Scalar(s1 * v[uj]);
        if (j > 0) next += s * v[uj - 1];
        v[uj] = next;
      }
    for (int j = 0; j <= k; ++j)
      B(static_cast<Eigen::Index>(i), j) = v[static_cast<std::size_t>(j)];
  }
  return B;
}

/// Solves the square system A X = B. Exact Scalar: full-pivot LU, exact; refuses a
/// singular A. Double: full-pivot LU, refusing A when its estimated reciprocal condition
/// number (1-norm) is below 1e-14 (numerically singular). Throws Errc::numerical_failure
/// naming `what`.
template <typename Scalar>
MatX<Scalar> solve_square(const MatX<Scalar>& A, const MatX<Scalar>& B, const std::string& what) {
  const Eigen::FullPivLU<MatX<Scalar>> lu(A);
  if constexpr (is_exact_v<Scalar>) {
    if (lu.rank() < A.rows())
      throw Error(Errc::numerical_failure, what + " is singular (rank " +
                                               std::to_string(lu.rank()) + " of " +
                                               std::to_string(A.rows()) + ")");
  } else {
    if (!(lu.rcond() > 1e-14))
      throw Error(Errc::numerical_failure, what + " is singular (numerically rank-deficient)");
  }
  return lu.solve(B);
}

/// A basis of the null space of E (columns). Exact Scalar: exact kernel of the LU.
/// Double: right singular vectors whose singular values are below rel_tol * sigma_max.
template <typename Scalar>
MatX<Scalar> null_space(const MatX<Scalar>& E, double rel_tol = 1e-10) {
  if constexpr (is_exact_v<Scalar>) {
    (void)rel_tol;
    const Eigen::FullPivLU<MatX<Scalar>> lu(E);
    if (lu.rank() == E.cols()) return MatX<Scalar>(E.cols(), 0);
    return lu.kernel();
  } else {
    // Column-pivoting QR of E^T: E^T P = Q R; the columns of Q past the rank span null(E).
    Eigen::ColPivHouseholderQR<MatX<double>> qr(E.transpose());
    qr.setThreshold(rel_tol);
    const Eigen::Index rank = qr.rank();
    const MatX<double> Q = qr.householderQ() * MatX<double>::Identity(E.cols(), E.cols());
    return Q.rightCols(E.cols() - rank);
  }
}

}  // namespace qmotion::kernel
