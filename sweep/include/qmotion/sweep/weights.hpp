// <qmotion/sweep/weights.hpp>
#pragma once
#include <algorithm>
#include <qmotion/kernel/bspline.hpp>
#include <vector>

namespace qmotion::sweep {

/// Knots to insert so that every pole of the homogeneous spline h has a positive weight
/// (first component), when the weight function is positive on the interval (docs/formats.md).
/// Knot insertion keeps the function and its parametrisation (u stays t); as spans shrink
/// the weights converge to the weight function's values, so a positive function ends with
/// positive poles. Rounds insert the midpoint of the widest span under each non-positive
/// pole. Throws Errc::numerical_failure when 40 rounds do not succeed (a zero of the weight
/// function: a pole of the motion).
template <typename Scalar>
std::vector<Scalar> knots_for_positive_weights(
    const kernel::BSpline<Eigen::Matrix<Scalar, 4, 1>>& h) {
  kernel::BSpline<Eigen::Matrix<Scalar, 4, 1>> cur = h;
  std::vector<Scalar> inserted;
  for (int round = 0; round < 40; ++round) {
    double wmax = 0;
    for (const auto& p : cur.ctrl()) wmax = std::max(wmax, std::abs(kernel::to_double(p(0))));
    const auto& T = cur.knots();
    const int deg = cur.degree();
    std::vector<Scalar> mids;
    for (std::size_t i = 0; i < cur.ctrl().size(); ++i) {
      if (kernel::to_double(cur.ctrl()[i](0)) > 1e-12 * wmax) continue;
      std::size_t best = i;
      Scalar width(-1);
      for (std::size_t j = i; j < i + static_cast<std::size_t>(deg) + 1 && j + 1 < T.size(); ++j)
        if (Scalar(T[j + 1] - T[j]) > width) {
          width = Scalar(T[j + 1] - T[j]);
          best = j;
        }
      mids.push_back(Scalar((T[best] + T[best + 1]) / Scalar(2)));
    }
    if (mids.empty()) return inserted;
    std::sort(mids.begin(), mids.end());
    mids.erase(std::unique(mids.begin(), mids.end()), mids.end());
    for (const auto& m : mids) {
      cur = kernel::insert_knot(cur, m);
      inserted.push_back(m);
    }
  }
  throw Error(Errc::numerical_failure,
              "weights stay non-positive after refinement: the weight function vanishes on the "
              "interval (a pole of the motion)");
}

/// Inserts the given knots (each once) into h.
template <typename Coef>
kernel::BSpline<Coef> insert_knots(kernel::BSpline<Coef> h,
                                   const std::vector<kernel::coef_scalar_t<Coef>>& knots) {
  for (const auto& k : knots) h = kernel::insert_knot(h, k);
  return h;
}

}  // namespace qmotion::sweep
