// kernel/banded.hpp
#pragma once
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

}  // namespace qmotion::kernel
