// <qmotion/cam/cam_nurbs.hpp>: a trajectory as a NURBS of degree <= 3 (what NURBS G-code accepts),
// exact where the trajectory allows it, else a cubic fit, with a certified bound on its
// deviation from the trajectory.
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <qmotion/kernel/bernstein.hpp>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/fit.hpp>
#include <vector>

namespace qmotion::cam {

/// A certified bound on the deviation of the homogeneous curve c (w, w x) from h, span by
/// span: span k of c (its k-th non-empty knot span) stands for span k of `t_knots` (the
/// knots c had before they were rounded for writing, with the same multiplicities), so c is
/// compared with h under the piecewise-affine map between the two knot vectors. On every
/// part (the spans cut at h's breakpoints, and each into `parts` equal parts) the numerator
/// h0 c - c0 h is a polynomial whose Bernstein coefficients bound its norm (convex hull),
/// and each weight is at least its smallest Bernstein coefficient. Infinite where a weight
/// coefficient is not positive (no bound from this split).
inline double rational_deviation_bound(const kernel::BSpline<Eigen::Vector4d>& c,
                                       const std::vector<double>& t_knots,
                                       const kernel::BSpline<Eigen::Vector4d>& h, int parts) {
  const std::vector<double> xc = c.breakpoints();
  std::vector<double> xt = t_knots;
  xt.erase(std::unique(xt.begin(), xt.end()), xt.end());
  if (xt.size() != xc.size() || xt.front() != h.a() || xt.back() != h.b())
    throw Error(Errc::internal, "rational_deviation_bound: the knot vectors do not match");
  std::vector<double> xh = h.breakpoints();
  const auto cross_weights = [](const Eigen::Vector4d& hi, const Eigen::Vector4d& cj) {
    return Eigen::Vector3d(hi(0) * cj.tail<3>() - cj(0) * hi.tail<3>());
  };
  double bound = 0;
  for (std::size_t k = 0; k + 1 < xc.size(); ++k) {
    const auto own = kernel::bezier_piece(c, xc[k], xc[k + 1]);
    const kernel::Bernstein<Eigen::Vector4d> piece(own.coeffs(), xt[k], xt[k + 1]);
    std::vector<double> cuts{xt[k]};
    for (double v : xh)
      if (v > xt[k] && v < xt[k + 1]) cuts.push_back(v);
    cuts.push_back(xt[k + 1]);
    for (std::size_t j = 0; j + 1 < cuts.size(); ++j)
      for (int s = 0; s < parts; ++s) {
        const double u0 = cuts[j] + (cuts[j + 1] - cuts[j]) * s / parts;
        const double u1 =
            s + 1 == parts ? cuts[j + 1] : cuts[j] + (cuts[j + 1] - cuts[j]) * (s + 1) / parts;
        if (!(u1 > u0)) continue;
        const auto hp = kernel::bezier_piece(h, u0, u1);
        const auto cp = kernel::restrict_to(piece, u0, u1);
        double hw = HUGE_VAL, cw = HUGE_VAL, num = 0;
        for (const auto& v : hp.coeffs()) hw = std::min(hw, v(0));
        for (const auto& v : cp.coeffs()) cw = std::min(cw, v(0));
        if (!(hw > 0) || !(cw > 0)) return HUGE_VAL;
        const auto numerator = kernel::product(hp, cp, cross_weights);
        for (const auto& v : numerator.coeffs()) num = std::max(num, v.norm());
        bound = std::max(bound, num / (hw * cw));
      }
  }
  return bound;
}

/// The knots mapped to [0, 1] and rounded to `decimals` places, more (up to 15) while
/// rounding would merge distinct knots; the ends are exactly 0 and 1.
inline std::vector<double> rounded_unit_knots(const std::vector<double>& T, int decimals) {
  const double a = T.front(), b = T.back();
  for (int d = decimals;; ++d) {
    const double q = std::pow(10.0, d);
    std::vector<double> K;
    bool merged = false;
    for (std::size_t i = 0; i < T.size(); ++i) {
      K.push_back(T[i] == a ? 0.0 : T[i] == b ? 1.0 : std::round((T[i] - a) / (b - a) * q) / q);
      if (i > 0 && (T[i] > T[i - 1]) != (K[i] > K[i - 1])) merged = true;
    }
    if (!merged || d >= 15) return K;
  }
}

struct CamNurbsOptions {
  double tol = 1e-3;  ///< the deviation the curve as written may have from h (length unit)
  int max_degree = 3;
  /// Controllers take weights in [min_weight, max_weight]; the exact curve is used only when
  /// its weights, scaled by one factor, fit.
  double min_weight = 1e-4, max_weight = 99.9999;
  std::size_t max_spans = 1 << 16;
  /// Decimal places of the written knots (on [0, 1]; more where needed to keep them apart).
  int knot_decimals = 9;
  /// The pole (w, w x) as it will be written (rounded); the bound is certified for that.
  std::function<Eigen::Vector4d(const Eigen::Vector4d&)> written = [](const Eigen::Vector4d& v) {
    return v;
  };
};

struct CamNurbs {
  /// As written: homogeneous poles (w, w x) and knots on [0, 1], both rounded.
  kernel::BSpline<Eigen::Vector4d> curve =
      kernel::BSpline<Eigen::Vector4d>::make(0, {0.0, 1.0}, {Eigen::Vector4d(1, 0, 0, 0)});
  std::vector<double> t_knots;  ///< the knots in the motion's parameter t
  bool exact = false;           ///< the trajectory itself (degree <= max_degree), only rounded
  double bound = 0;             ///< certified max |curve(t) - h(t)| (parametric, so also geometric)
  int spans = 0;
  int fits = 0;  ///< least-squares fits tried (0 when exact)
};

/// The trajectory h (homogeneous, positive weight) as a NURBS of degree <= opt.max_degree
/// within opt.tol, certified by rational_deviation_bound after rounding the poles by
/// opt.written and the knots (mapped to [0, 1]) to opt.knot_decimals places:
/// - exact when h has that degree and its pole weights are positive and fit the weight
///   range after one common scale (the curve is unchanged by it);
/// - else a polynomial (weights 1) B-spline of opt.max_degree fitted to `point` (the exact
///   trajectory; h itself for a rational motion) by sweep::fit_frames on the breakpoints
///   `breaks` with their `continuity`, refined where the certificate needs it.
/// Throws Errc::numerical_failure when no fit within opt.max_spans spans is certified.
inline CamNurbs cam_nurbs(const kernel::BSpline<Eigen::Vector4d>& h,
                          const std::function<Eigen::Vector3d(double)>& point,
                          const std::vector<double>& breaks, const std::vector<int>& continuity,
                          const CamNurbsOptions& opt) {
  CamNurbs out;
  // The curve as written (rounded poles, rounded unit knots) and its certified bound.
  const auto written = [&](int degree, const std::vector<double>& T,
                           const std::vector<Eigen::Vector4d>& poles, double& bound) {
    std::vector<Eigen::Vector4d> w;
    for (const auto& v : poles) w.push_back(opt.written(v));
    auto c = kernel::BSpline<Eigen::Vector4d>::make(
        degree, rounded_unit_knots(T, opt.knot_decimals), std::move(w));
    for (int parts : {4, 16}) {
      bound = rational_deviation_bound(c, T, h, parts);
      if (bound <= opt.tol) break;
    }
    return c;
  };
  if (h.degree() <= opt.max_degree) {
    double lo = HUGE_VAL, hi = 0;
    for (const auto& v : h.ctrl()) {
      lo = std::min(lo, v(0));
      hi = std::max(hi, v(0));
    }
    if (lo > 0 && hi / lo <= opt.max_weight / opt.min_weight) {
      // The smallest weight 1 where the range allows it, else the range's middle (in ratio).
      const double scale = hi / lo <= opt.max_weight
                               ? 1 / lo
                               : std::sqrt(opt.min_weight * opt.max_weight / (lo * hi));
      std::vector<Eigen::Vector4d> poles;
      for (const auto& v : h.ctrl()) poles.push_back(scale * v);
      double b = HUGE_VAL;
      auto c = written(h.degree(), h.knots(), poles, b);
      if (b <= opt.tol) {
        out.curve = std::move(c);
        out.t_knots = h.knots();
        out.exact = true;
        out.bound = b;
        out.spans = static_cast<int>(h.breakpoints().size()) - 1;
        return out;
      }
    }
  }
  // A polynomial fit: the translation part of frames [I | p(t)] (sweep::fit_frames keeps the
  // identity exactly), fitted at a tolerance the certificate then confirms, or tightened (so
  // the fit is given no bound of its own).
  sweep::FrameFitOptions fo;
  fo.degree = opt.max_degree;
  fo.max_spans = opt.max_spans;
  fo.tol = 1.8 * opt.tol;  // the fit's measured deviation ends at most half of this
  // Knots only where the trajectory is less than C2 (a kink or a jump in curvature, which a
  // C2 cubic must follow); a jump in a higher derivative the fit smooths over, with knots
  // where the error needs them (the fewest spans).
  std::vector<double> fit_breaks{breaks.front()};
  std::vector<int> fit_continuity;
  for (std::size_t k = 1; k + 1 < breaks.size(); ++k)
    if (continuity[k - 1] < std::min(2, opt.max_degree)) {
      fit_breaks.push_back(breaks[k]);
      fit_continuity.push_back(continuity[k - 1]);
    }
  fit_breaks.push_back(breaks.back());
  for (int round = 1; round <= 8; ++round) {
    const sweep::FrameFit fit = sweep::fit_frames(
        [&](double t) {
          Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
          m.block<3, 1>(1, 0) = point(t);
          return m;
        },
        sweep::FrameBoundFn(), fit_breaks, fit_continuity, {Eigen::Vector3d::Zero()}, fo);
    std::vector<Eigen::Vector4d> poles;
    for (const auto& m : fit.matrix.ctrl()) poles.push_back(m.col(0));
    double b = HUGE_VAL;
    auto c = written(fit.matrix.degree(), fit.matrix.knots(), poles, b);
    out.fits = round;
    if (b <= opt.tol) {
      out.curve = std::move(c);
      out.t_knots = fit.matrix.knots();
      out.bound = b;
      out.spans = fit.spans;
      return out;
    }
    fo.tol *= 0.6;
  }
  throw Error(Errc::numerical_failure,
              "no NURBS of degree " + std::to_string(opt.max_degree) +
                  " with a certified deviation within the tolerance was found (the tolerance "
                  "may be below the rounding of the written coordinates)");
}

}  // namespace qmotion::cam
