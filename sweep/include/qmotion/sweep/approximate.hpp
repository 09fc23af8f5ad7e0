// <qmotion/sweep/approximate.hpp>
#pragma once
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>
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

namespace detail {

/// A breakpoint of a fit's knot vector: its multiplicity in the fit and the most it may take
/// (the degree less the approximated curves' continuity there; 1 for a knot of the fit's own).
struct Break {
  double x;
  int mult, most;
};

/// One least-squares fit on the knots `br` (ends first and last) with its deviation per span.
struct SpanFit {
  Approximation approx;
  std::vector<double> dev;
  int poles = 0;
};

/// Fits the homogeneous curves h at 2 (D + 1) points a span (both ends included, so each span
/// pins its own poles) by banded least squares, and measures the Cartesian deviation of every
/// span at 6 (D + 1) + 1 points (HUGE_VAL where a weight is not positive).
inline SpanFit fit_on_breaks(const std::vector<kernel::BSpline<Eigen::Vector4d>>& h, int D,
                             const std::vector<Break>& br) {
  const auto cart = [](const Eigen::Vector4d& y) { return Eigen::Vector3d(y.tail<3>() / y(0)); };
  const int per_span = 2 * (D + 1), checks = 6 * (D + 1);
  std::vector<double> T(static_cast<std::size_t>(D + 1), br.front().x);
  std::vector<int> span_index{D};  // T[span_index[s]] <= t < T[span_index[s] + 1] in span s
  for (std::size_t s = 1; s + 1 < br.size(); ++s) {
    T.insert(T.end(), static_cast<std::size_t>(br[s].mult), br[s].x);
    span_index.push_back(static_cast<int>(T.size()) - 1);
  }
  T.insert(T.end(), static_cast<std::size_t>(D + 1), br.back().x);
  const std::size_t spans = br.size() - 1;
  SpanFit out;
  out.poles = static_cast<int>(T.size()) - D - 1;
  const Eigen::Index samples = static_cast<Eigen::Index>(spans) * per_span;
  Eigen::MatrixXd A(samples, D + 1), Y(samples, 4 * static_cast<Eigen::Index>(h.size()));
  std::vector<int> first(static_cast<std::size_t>(samples));
  Eigen::Index row = 0;
  for (std::size_t s = 0; s < spans; ++s) {
    const int j = span_index[s];
    for (int i = 0; i < per_span; ++i, ++row) {
      const double t = br[s].x + (br[s + 1].x - br[s].x) * i / (per_span - 1);
      const auto N = basis_functions(T, j, D, t);
      first[static_cast<std::size_t>(row)] = j - D;
      for (int k = 0; k <= D; ++k) A(row, k) = N[static_cast<std::size_t>(k)];
      for (std::size_t c = 0; c < h.size(); ++c)
        Y.block<1, 4>(row, static_cast<Eigen::Index>(4 * c)) =
            kernel::evaluate(h[c], t).transpose();
    }
  }
  const Eigen::MatrixXd P =
      kernel::least_squares_banded(out.poles, D, first, A, Y, "degree-capped approximation");
  out.approx.spans = static_cast<int>(spans);
  for (std::size_t c = 0; c < h.size(); ++c) {
    std::vector<Eigen::Vector4d> poles;
    poles.reserve(static_cast<std::size_t>(out.poles));
    for (int i = 0; i < out.poles; ++i)
      poles.push_back(P.block<1, 4>(i, static_cast<Eigen::Index>(4 * c)).transpose());
    out.approx.curves.push_back(kernel::BSpline<Eigen::Vector4d>::make(D, T, poles));
  }
  out.dev.assign(spans, 0.0);
  for (std::size_t s = 0; s < spans; ++s)
    for (int i = 0; i <= checks; ++i) {
      const double t = br[s].x + (br[s + 1].x - br[s].x) * i / checks;
      for (std::size_t c = 0; c < h.size(); ++c) {
        const Eigen::Vector4d y = kernel::evaluate(out.approx.curves[c], t);
        out.dev[s] = y(0) > 0
                         ? std::max(out.dev[s], (cart(y) - cart(kernel::evaluate(h[c], t))).norm())
                         : HUGE_VAL;
      }
    }
  out.approx.max_deviation = *std::max_element(out.dev.begin(), out.dev.end());
  return out;
}

/// The next knots: in every span above `target`, a joint at its end where the fit is smoother
/// than the curves loses one order of continuity (once a round: a kink in a derivative is what
/// a smooth fit cannot follow), else the span is split into as many equal parts as its error
/// predicts (it falls as h^(D + 1)), 2 to 8.
inline std::vector<Break> refine(const std::vector<Break>& br, const std::vector<double>& dev,
                                 int D, double target) {
  std::vector<Break> next{br.front()};
  bool raised_left = false;
  for (std::size_t s = 0; s + 1 < br.size(); ++s) {
    Break& left = next.back();
    Break right = br[s + 1];
    bool raised_right = false;
    if (dev[s] > target) {
      const bool kink_left = left.mult < left.most || raised_left,
                 kink_right = right.mult < right.most;
      if (kink_left || kink_right) {
        if (kink_left && !raised_left) ++left.mult;
        if (kink_right) ++right.mult, raised_right = true;
      } else {
        const double ratio = std::isfinite(dev[s]) ? dev[s] / target : 1e9;
        const int parts =
            std::min(8, std::max(2, static_cast<int>(std::ceil(std::pow(ratio, 1.0 / (D + 1))))));
        for (int k = 1; k < parts; ++k)
          next.push_back({br[s].x + (br[s + 1].x - br[s].x) * k / parts, 1, 1});
      }
    }
    next.push_back(right);
    raised_left = raised_right;
  }
  return next;
}

}  // namespace detail

/// Approximates homogeneous curves h_j (one parameter interval, sharing their knots) by
/// B-splines of degree `degree` on one common knot vector (u stays t), by least squares on the
/// homogeneous coordinates (detail::fit_on_breaks), until every span's measured Cartesian
/// deviation is within 0.9 `tol`. Two knot vectors are tried and the one with fewer poles kept:
/// - adaptive: the curves' joints as simple knots, then refined where the fit is poor
///   (detail::refine): a joint whose continuity the fit exceeds gets one more knot, up to the
///   curves' own continuity there (C^k stays C^k, no more), and smooth spans are split;
/// - uniform, smooth everywhere (C^(degree - 1)), its span count doubling from the curves' own
///   while it has fewer poles than the adaptive one: at loose tolerances a smooth fit across
///   the joints can be the smaller.
/// Weights are made positive afterwards by knot insertion. Throws Errc::numerical_failure when
/// 40 rounds or 2^16 spans do not reach the tolerance.
inline Approximation approximate_homogeneous(const std::vector<kernel::BSpline<Eigen::Vector4d>>& h,
                                             int degree, double tol) {
  using detail::Break;
  const int D = degree;
  const double a = h.front().a(), b = h.front().b(), target = 0.9 * tol;
  std::vector<Break> br{{a, 0, 0}};
  for (const double x : h.front().breakpoints())
    if (x > a && x < b)
      br.push_back({x, 1, std::clamp(D - kernel::continuity_at(h.front(), x), 1, D)});
  br.push_back({b, 0, 0});
  const std::size_t input_spans = br.size() - 1;
  std::optional<detail::SpanFit> best;
  for (int round = 0; round < 40 && br.size() <= (std::size_t{1} << 16); ++round) {
    auto fit = detail::fit_on_breaks(h, D, br);
    if (fit.approx.max_deviation <= target) {
      best = std::move(fit);
      break;
    }
    br = detail::refine(br, fit.dev, D, target);
  }
  std::size_t spans = 1;
  while (spans < input_spans) spans *= 2;
  for (; !best || static_cast<int>(spans) + D < best->poles; spans *= 2) {
    if (spans > (std::size_t{1} << 16)) break;
    std::vector<Break> uniform{{a, 0, 0}};
    for (std::size_t i = 1; i < spans; ++i)
      uniform.push_back({a + (b - a) * static_cast<double>(i) / static_cast<double>(spans), 1, 1});
    uniform.push_back({b, 0, 0});
    auto fit = detail::fit_on_breaks(h, D, uniform);
    if (fit.approx.max_deviation <= target) {
      best = std::move(fit);
      break;
    }
  }
  if (!best)
    throw Error(Errc::numerical_failure, "no approximation of degree " + std::to_string(D) +
                                             " within the tolerance with up to 65536 spans");
  Approximation out = std::move(best->approx);
  const auto extra = knots_for_positive_weights(out.curves.front());
  for (auto& c : out.curves) c = insert_knots(c, extra);
  return out;
}

}  // namespace qmotion::sweep
