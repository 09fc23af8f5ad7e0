// <qmotion/kernel/banded.hpp>
#pragma once
#include <cmath>
#include <qmotion/kernel/linear_solve.hpp>
#include <string>
#include <vector>

namespace qmotion::kernel {

/// A square band matrix: entries (i, j) with |i - j| <= w stored densely by row.
template <typename Scalar>
class BandMatrix {
 public:
  BandMatrix(Eigen::Index n, int w)
      : n_(n),
        w_(w),
        a_(static_cast<std::size_t>(n) * static_cast<std::size_t>(2 * w + 1), Scalar(0)) {}
  Eigen::Index size() const { return n_; }
  int bandwidth() const { return w_; }
  Scalar& operator()(Eigen::Index i, Eigen::Index j) { return a_[index(i, j)]; }
  const Scalar& operator()(Eigen::Index i, Eigen::Index j) const { return a_[index(i, j)]; }

 private:
  std::size_t index(Eigen::Index i, Eigen::Index j) const {
    QMOTION_EXPECTS(i - j <= w_ && j - i <= w_, "entry outside the band");
    return static_cast<std::size_t>(i) * static_cast<std::size_t>(2 * w_ + 1) +
           static_cast<std::size_t>(j - i + w_);
  }
  Eigen::Index n_;
  int w_;
  std::vector<Scalar> a_;
};

/// Solves A X = B for a band matrix A by Gaussian elimination without pivoting, in
/// O(n w^2) time: linear in n. Without pivoting it is stable for totally positive
/// matrices such as B-spline collocation matrices at Schoenberg-Whitney points.
/// Throws Errc::numerical_failure naming `what` on a zero (or, in double, tiny) pivot.
/// @see de Boor, A Practical Guide to Splines, ch. XIII (banded collocation systems)
template <typename Scalar>
MatX<Scalar> solve_banded(BandMatrix<Scalar> A, MatX<Scalar> B, const std::string& what) {
  const Eigen::Index n = A.size();
  const int w = A.bandwidth();
  double scale = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = std::max<Eigen::Index>(0, i - w);
         j <= std::min<Eigen::Index>(n - 1, i + w); ++j)
      scale = std::max(scale, std::abs(to_double(A(i, j))));
  for (Eigen::Index k = 0; k < n; ++k) {
    const Scalar piv = A(k, k);
    const bool zero =
        is_exact_v<Scalar> ? piv == Scalar(0) : !(std::abs(to_double(piv)) > 1e-14 * scale);
    if (zero)
      throw Error(Errc::numerical_failure,
                  what + " is singular (zero pivot in row " + std::to_string(k) + ")");
    for (Eigen::Index i = k + 1; i <= std::min<Eigen::Index>(n - 1, k + w); ++i) {
      if (A(i, k) == Scalar(0)) continue;
      const Scalar f = Scalar(A(i, k) / piv);
      for (Eigen::Index j = k; j <= std::min<Eigen::Index>(n - 1, k + w); ++j)
        A(i, j) -= Scalar(f * A(k, j));
      for (Eigen::Index c = 0; c < B.cols(); ++c) B(i, c) -= Scalar(f * B(k, c));
    }
  }
  for (Eigen::Index k = n - 1; k >= 0; --k) {
    for (Eigen::Index j = k + 1; j <= std::min<Eigen::Index>(n - 1, k + w); ++j)
      for (Eigen::Index c = 0; c < B.cols(); ++c) B(k, c) -= Scalar(A(k, j) * B(j, c));
    for (Eigen::Index c = 0; c < B.cols(); ++c) B(k, c) = Scalar(B(k, c) / A(k, k));
  }
  return B;
}

/// Least squares: min |A X - B| (Frobenius) for an m x n matrix A whose row r holds its
/// w + 1 entries rows(r, 0..w) in the consecutive columns first[r] .. first[r] + w (columns
/// past n - 1 are ignored). Givens rotations fold the rows one by one into a banded upper
/// triangle R (n x (w + 1)), then back substitution: O(m w (w + k)) time, O(n (w + k))
/// memory, as stable as a dense QR. Throws Errc::numerical_failure naming `what` when A has
/// a zero column in R (rank deficient).
/// @see Lawson & Hanson, Solving Least Squares Problems, ch. 27 (sequential banded QR)
inline Eigen::MatrixXd least_squares_banded(Eigen::Index n, int w, const std::vector<int>& first,
                                            const Eigen::MatrixXd& rows, const Eigen::MatrixXd& B,
                                            const std::string& what) {
  const Eigen::Index m = rows.rows(), k = B.cols();
  QMOTION_EXPECTS(
      rows.cols() == w + 1 && B.rows() == m && first.size() == static_cast<std::size_t>(m),
      "least_squares_banded: sizes");
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(n, w + 1), Z = Eigen::MatrixXd::Zero(n, k);
  std::vector<char> filled(static_cast<std::size_t>(n), 0);
  Eigen::VectorXd a(w + 1);
  Eigen::RowVectorXd b(k);
  for (Eigen::Index r = 0; r < m; ++r) {
    a = rows.row(r).transpose();
    b = B.row(r);
    const Eigen::Index c0 = first[static_cast<std::size_t>(r)];
    for (int j = 0; j <= w && c0 + j < n; ++j) {
      const Eigen::Index col = c0 + j;
      const double x = a(j);
      if (x == 0) continue;
      const int len = w - j + 1;
      if (!filled[static_cast<std::size_t>(col)]) {  // an empty row of R takes the rest
        R.row(col).head(len) = a.segment(j, len).transpose();
        Z.row(col) = b;
        filled[static_cast<std::size_t>(col)] = 1;
        break;
      }
      const double y = R(col, 0), h = std::hypot(y, x), c = y / h, s = x / h;
      for (int d = 0; d < len; ++d) {
        const double rv = R(col, d), av = a(j + d);
        R(col, d) = c * rv + s * av;
        a(j + d) = c * av - s * rv;
      }
      const Eigen::RowVectorXd z = Z.row(col);
      Z.row(col) = c * z + s * b;
      b = c * b - s * z;
    }
  }
  Eigen::MatrixXd X(n, k);
  const double scale = R.col(0).cwiseAbs().maxCoeff();
  for (Eigen::Index i = n - 1; i >= 0; --i) {
    if (!(std::abs(R(i, 0)) > 1e-14 * scale))
      throw Error(Errc::numerical_failure, what + ": the least-squares system is rank deficient");
    Eigen::RowVectorXd v = Z.row(i);
    for (int d = 1; d <= w && i + d < n; ++d) v -= R(i, d) * X.row(i + d);
    X.row(i) = v / R(i, 0);
  }
  return X;
}

}  // namespace qmotion::kernel
