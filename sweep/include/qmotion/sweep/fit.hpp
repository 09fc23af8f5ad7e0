// <qmotion/sweep/fit.hpp>: geometry of a motion known only by evaluation (the non-rational mode,
// docs/geometry.md): its rigid maps fitted by one matrix B-spline on a common knot vector, refined
// until the trajectories of given points are within a tolerance on a dense grid.
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <qmotion/kernel/banded.hpp>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/motion.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace qmotion::sweep {

struct FrameFitOptions {
  int degree = 5;                   ///< of the fitted splines (>= 1)
  double tol = 1e-6;                ///< absolute, in the motion's length unit
  std::size_t max_spans = 1 << 16;  ///< refuse (numerical failure) beyond this many spans
  int check_density = 64;           ///< final check: samples per span
};

/// The fitted motion: M(t) acts on homogeneous points as the rigid maps do,
/// M(t) (x0, x) = (x0, R~(t) x + x0 p~(t)), so the trajectory of every point is M(t) (1, x)
/// on one knot vector, and a rational profile's surface takes the columns' poles
/// (docs/geometry.md).
struct FrameFit {
  kernel::BSpline<Eigen::Matrix4d> matrix =  // (the identity on [0, 1] until fitted)
      kernel::BSpline<Eigen::Matrix4d>::make(0, {0.0, 1.0}, {Eigen::Matrix4d::Identity()});
  double max_deviation = 0;       ///< largest |M~(t)(1,x) - M(t)(1,x)| over the points, final grid
  double worst_t = 0;             ///< where it is reached
  int spans = 0;                  ///< non-empty knot spans
  int rounds = 0;                 ///< fit-and-measure rounds (each bisects the spans still out)
  std::size_t check_samples = 0;  ///< parameters of the final check grid
};

/// The final check's grid can miss the peak of the error between its points, by about 1%
/// for 64 points per span (the error oscillates a few times per span): the fit keeps 5% in
/// hand, measuring at most tol / kFitMargin.
inline constexpr double kFitMargin = 1.05;

namespace detail {

/// The 12 numbers of rows 1..3 of a frame, row by row.
inline Eigen::Matrix<double, 1, 12> frame_row(const Eigen::Matrix4d& m) {
  Eigen::Matrix<double, 1, 12> r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) r(4 * i + j) = m(i + 1, j);
  return r;
}

inline Eigen::Matrix4d frame_of_row(const Eigen::Matrix<double, 1, 12>& r) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 0) = 1;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) m(i + 1, j) = r(4 * i + j);
  return m;
}

/// The largest distance between the images of the points under two frames.
inline double frame_distance(const Eigen::Matrix4d& f, const Eigen::Matrix4d& g,
                             const std::vector<Eigen::Vector3d>& points) {
  const Eigen::Matrix4d e = f - g;
  const Eigen::Vector3d e0 = e.block<3, 1>(1, 0);
  const Eigen::Matrix3d E = e.block<3, 3>(1, 1);
  double d = 0;
  for (const auto& x : points) d = std::max(d, (e0 + E * x).norm());
  return d;
}

}  // namespace detail

/// Fits the rigid maps `frame(t)` (4x4, row 0 = (1, 0, 0, 0)) of a motion on
/// [breaks.front(), breaks.back()] by a B-spline of opt.degree. The knot vector starts with
/// the motion's own breakpoints; interior break k has multiplicity degree - continuity[k-1]
/// (at least 1), so the fit may bend where the motion does. The poles are the least-squares
/// solution at degree + 2 points per span with the end poles fixed to the end frames (the
/// ends are exact: a planar profile stays planar there), from banded normal equations.
/// The deviation is measured for every point of `points` at 16 points per span; spans above
/// half the tolerance are halved and the fit repeated, until the measurement is, then a
/// check at opt.check_density points per span is, within opt.tol (with kFitMargin in hand). A frame
/// of any point in the convex hull of `points` is then within opt.tol too (the error is affine in
/// x). Throws Errc::numerical_failure beyond opt.max_spans, naming the deviation reached.
inline FrameFit fit_frames(const std::function<Eigen::Matrix4d(double)>& frame,
                           const std::vector<double>& breaks, const std::vector<int>& continuity,
                           const std::vector<Eigen::Vector3d>& points, const FrameFitOptions& opt) {
  using Row = Eigen::Matrix<double, 1, 12>;
  const int d = opt.degree;
  if (d < 1)
    throw Error(Errc::invalid_input,
                "the fitted degree must be at least 1, found " + std::to_string(d));
  if (breaks.size() < 2 || continuity.size() + 2 != breaks.size())
    throw Error(Errc::invalid_input,
                "fit_frames: expected breakpoints and one continuity per "
                "interior breakpoint");
  if (!(opt.tol > 0) || !std::isfinite(opt.tol))
    throw Error(Errc::invalid_input, "the tolerance must be a positive number");
  std::vector<double> x = breaks;  // span ends
  std::vector<int> mult(x.size(), d + 1);
  for (std::size_t k = 1; k + 1 < x.size(); ++k) mult[k] = std::clamp(d - continuity[k - 1], 1, d);
  const Eigen::Matrix4d Fa = frame(x.front()), Fb = frame(x.back());
  for (int round = 1;; ++round) {
    std::vector<double> T;
    for (std::size_t k = 0; k < x.size(); ++k)
      T.insert(T.end(), static_cast<std::size_t>(mult[k]), x[k]);
    const int n = static_cast<int>(T.size()) - d - 1;  // poles
    std::vector<Row> P(static_cast<std::size_t>(n), Row::Zero());
    P.front() = detail::frame_row(Fa);
    P.back() = detail::frame_row(Fb);
    const int unknowns = n - 2;
    if (unknowns > 0) {
      kernel::BandMatrix<double> N(unknowns, d);
      kernel::MatX<double> rhs = kernel::MatX<double>::Zero(unknowns, 12);
      const int S = d + 2;
      for (std::size_t k = 0; k + 1 < x.size(); ++k)
        for (int s = 0; s < S; ++s) {
          const double t = x[k] + (x[k + 1] - x[k]) * (s + 0.5) / S;
          const int j = kernel::knot_span(T, d, n, t);
          const auto B = kernel::basis_functions(T, j, d, t);
          Row y = detail::frame_row(frame(t));
          for (int i = 0; i <= d; ++i) {
            const int p = j - d + i;
            if (p == 0 || p == n - 1)
              y -= B[static_cast<std::size_t>(i)] * P[static_cast<std::size_t>(p)];
          }
          for (int i = 0; i <= d; ++i) {
            const int p = j - d + i;
            if (p == 0 || p == n - 1) continue;
            const double bi = B[static_cast<std::size_t>(i)];
            rhs.row(p - 1) += bi * y;
            for (int l = 0; l <= d; ++l) {
              const int q = j - d + l;
              if (q == 0 || q == n - 1) continue;
              N(p - 1, q - 1) += bi * B[static_cast<std::size_t>(l)];
            }
          }
        }
      const kernel::MatX<double> sol =
          kernel::solve_banded(std::move(N), std::move(rhs), "the fit's normal equations");
      for (int p = 1; p + 1 < n; ++p) P[static_cast<std::size_t>(p)] = sol.row(p - 1);
    }
    std::vector<Eigen::Matrix4d> poles;
    poles.reserve(P.size());
    for (const auto& r : P) poles.push_back(detail::frame_of_row(r));
    FrameFit out{kernel::BSpline<Eigen::Matrix4d>::make(d, T, std::move(poles))};
    out.spans = static_cast<int>(x.size()) - 1;
    out.rounds = round;
    // The deviation per span at `density` points (its left end included; b at the end).
    auto measure = [&](int density, double& worst, double& worst_t) {
      std::vector<double> dev(x.size() - 1, 0.0);
      worst = 0;
      auto at = [&](std::size_t k, double t) {
        const int j = kernel::knot_span(T, d, n, t);
        const auto B = kernel::basis_functions(T, j, d, t);
        Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
        for (int i = 0; i <= d; ++i)
          m += B[static_cast<std::size_t>(i)] *
               out.matrix.ctrl()[static_cast<std::size_t>(j - d + i)];
        const double e = detail::frame_distance(m, frame(t), points);
        dev[k] = std::max(dev[k], std::isnan(e) ? HUGE_VAL : e);
        if (!(e <= worst)) {
          worst = std::isnan(e) ? HUGE_VAL : e;
          worst_t = t;
        }
      };
      for (std::size_t k = 0; k + 1 < x.size(); ++k)
        for (int s = 0; s < density; ++s) at(k, x[k] + (x[k + 1] - x[k]) * s / density);
      at(x.size() - 2, x.back());
      return dev;
    };
    double worst = 0, worst_t = x.front();
    auto dev = measure(16, worst, worst_t);
    if (worst <= 0.5 * opt.tol) {
      dev = measure(opt.check_density, worst, worst_t);
      out.max_deviation = worst;
      out.worst_t = worst_t;
      out.check_samples = (x.size() - 1) * static_cast<std::size_t>(opt.check_density) + 1;
      if (worst <= opt.tol / kFitMargin) return out;
    }
    std::vector<double> nx{x.front()};
    std::vector<int> nm{mult.front()};
    for (std::size_t k = 0; k + 1 < x.size(); ++k) {
      if (dev[k] > 0.5 * opt.tol) {
        nx.push_back(0.5 * (x[k] + x[k + 1]));
        nm.push_back(1);
      }
      nx.push_back(x[k + 1]);
      nm.push_back(mult[k + 1]);
    }
    if (nx.size() - 1 > opt.max_spans || nx.size() == x.size()) {
      std::ostringstream os;
      os.precision(3);
      os << "the fit of the motion reaches a deviation of " << worst << " near t = " << worst_t
         << ", above the tolerance " << opt.tol << ", with " << x.size() - 1 << " spans of degree "
         << d << " (limit " << opt.max_spans << "); ask for a larger tolerance or a higher degree";
      throw Error(Errc::numerical_failure, os.str());
    }
    x = std::move(nx);
    mult = std::move(nm);
  }
}

/// fit_frames for a motion: its rigid maps on its breakpoints with its continuity there (the
/// fit of a quaternion spline's geometry; a rational motion's is exact and needs none).
/// Refusals name the motion.
inline FrameFit fit_frames(const qmotion::Motion& motion,
                           const std::vector<Eigen::Vector3d>& points, const FrameFitOptions& opt) {
  try {
    return fit_frames([&motion](double t) { return motion.frame(t); }, motion.breakpoints(),
                      motion.continuity(), points, opt);
  } catch (const Error& e) {
    throw Error(e.code(), motion.label() + ": " + e.what());
  }
}

}  // namespace qmotion::sweep
