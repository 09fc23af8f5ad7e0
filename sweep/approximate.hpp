// sweep/approximate.hpp
#pragma once
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <qmotion/kernel/banded.hpp>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/sweep/weights.hpp>
#include <vector>

namespace qmotion::sweep {

using kernel::basis_functions;

/// Result of approximate_homogeneous.
struct Approximation {
  std::vector<kernel::BSpline<Eigen::Vector4d>> curves;  ///< same degree and knots for all
  double max_deviation = 0;                              ///< measured, Cartesian
  int spans = 0;
};

/// Approximates homogeneous curves h_j (one parameter interval) by B-splines of degree
/// `degree` on one common uniform knot vector (u stays t), fitting the homogeneous
/// coordinates by least squares at dense samples (banded QR: O(samples) per fit). The span count
/// doubles until the largest Cartesian deviation measured at 8x denser points is within `tol`.
/// Weights are made positive afterwards by knot insertion. Throws Errc::numerical_failure when 4096
/// spans do not reach the tolerance.
inline Approximation approximate_homogeneous(const std::vector<kernel::BSpline<Eigen::Vector4d>>& h,
                                             int degree, double tol) {
  const double a = h.front().a(), b = h.front().b();
  auto cart = [](const Eigen::Vector4d& y) { return Eigen::Vector3d(y.tail<3>() / y(0)); };
  for (int spans = 1; spans <= 4096; spans *= 2) {
    std::vector<double> T(static_cast<std::size_t>(degree + 1), a);
    for (int i = 1; i < spans; ++i) T.push_back(a + (b - a) * i / spans);
    T.insert(T.end(), static_cast<std::size_t>(degree + 1), b);
    const int n = spans + degree;  // poles
    const int samples = 4 * n + 1;
    // Row s of the collocation matrix: degree + 1 basis values from column span - degree.
    Eigen::MatrixXd A(samples, degree + 1), Y(samples, 4 * static_cast<Eigen::Index>(h.size()));
    std::vector<int> first(static_cast<std::size_t>(samples));
    const auto span_of = [&](double t) {
      int j =
          static_cast<int>(std::upper_bound(T.begin() + degree, T.begin() + n, t) - T.begin()) - 1;
      return std::min(std::max(j, degree), n - 1);
    };
    for (int s = 0; s < samples; ++s) {
      const double t = a + (b - a) * s / (samples - 1);
      const int j = span_of(t);
      const auto N = basis_functions(T, j, degree, t);
      first[static_cast<std::size_t>(s)] = j - degree;
      for (int k = 0; k <= degree; ++k) A(s, k) = N[static_cast<std::size_t>(k)];
      for (std::size_t c = 0; c < h.size(); ++c)
        Y.block<1, 4>(s, static_cast<Eigen::Index>(4 * c)) = kernel::evaluate(h[c], t).transpose();
    }
    const Eigen::MatrixXd P =
        kernel::least_squares_banded(n, degree, first, A, Y, "degree-capped approximation");
    Approximation out;
    out.spans = spans;
    for (std::size_t c = 0; c < h.size(); ++c) {
      std::vector<Eigen::Vector4d> poles;
      for (int i = 0; i < n; ++i)
        poles.push_back(P.block<1, 4>(i, static_cast<Eigen::Index>(4 * c)).transpose());
      out.curves.push_back(kernel::BSpline<Eigen::Vector4d>::make(degree, T, poles));
    }
    double dev = 0;
    for (int s = 0; s <= 8 * samples; ++s) {
      const double t = a + (b - a) * s / (8.0 * samples);
      for (std::size_t c = 0; c < h.size(); ++c) {
        const Eigen::Vector4d y = kernel::evaluate(out.curves[c], t);
        dev =
            y(0) > 0 ? std::max(dev, (cart(y) - cart(kernel::evaluate(h[c], t))).norm()) : HUGE_VAL;
      }
    }
    out.max_deviation = dev;
    if (dev <= tol) {
      const auto extra = knots_for_positive_weights(out.curves.front());
      for (auto& c : out.curves) c = insert_knots(c, extra);
      return out;
    }
  }
  throw Error(Errc::numerical_failure,
              "no approximation within the tolerance with up to 4096 spans");
}

}  // namespace qmotion::sweep
