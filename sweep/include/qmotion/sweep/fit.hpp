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
#include <qmotion/kernel/qspline_bounds.hpp>
#include <qmotion/motion.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace qmotion::sweep {

struct FrameFitOptions {
  int degree = 5;                   ///< of the fitted splines (>= 1)
  double tol = 1e-6;                ///< absolute, in the motion's length unit
  std::size_t max_spans = 1 << 16;  ///< refuse (numerical failure) beyond this many spans
  int check_density = 64;           ///< final check: samples per span, at least
};

/// Bounds of a motion's second derivatives on a parameter interval inside one of its
/// segments (kernel::second_derivative_bound for a quaternion spline).
using FrameBoundFn = std::function<kernel::FrameSecondDerivativeBound(double, double)>;

/// The fitted motion: M(t) acts on homogeneous points as the rigid maps do,
/// M(t) (x0, x) = (x0, R~(t) x + x0 p~(t)), so the trajectory of every point is M(t) (1, x)
/// on one knot vector, and a rational profile's surface takes the columns' poles
/// (docs/geometry.md).
struct FrameFit {
  kernel::BSpline<Eigen::Matrix4d> matrix =  // (the identity on [0, 1] until fitted)
      kernel::BSpline<Eigen::Matrix4d>::make(0, {0.0, 1.0}, {Eigen::Matrix4d::Identity()});
  double max_deviation = 0;  ///< largest |M~(t)(1,x) - M(t)(1,x)| over the points, final grid
  double worst_t = 0;        ///< where it is reached
  /// Proven: no point of the convex hull of the points deviates more, at any t (at most tol).
  double max_deviation_bound = 0;
  int spans = 0;                  ///< non-empty knot spans
  int rounds = 0;                 ///< fit-and-measure rounds (each bisects the spans still out)
  std::size_t check_samples = 0;  ///< parameters of the final check grid
};

/// The share of the tolerance the certificate's second-derivative term may take: the final
/// grid of each span is made fine enough for that (docs/geometry.md, "The fit's proof").
inline constexpr double kFitRemainderShare = 0.05;
/// Most samples the certificate takes on one span; a span that would need more is halved.
inline constexpr int kFitMaxSamplesPerSpan = 1 << 14;

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

/// The certificate of a fit on the spans between the breakpoints x.
struct Certificate {
  double bound = 0, measured = 0, worst_t = 0;
  std::size_t samples = 0;
  std::vector<double> span_bound;  ///< per span
};

/// Certifies the fitted matrix spline f against frame on every span [x_k, x_{k+1}] (see
/// fit_frames): the largest sampled deviation plus M h^2 / 8, M bounding the deviation's
/// second derivative (|D (1, x)| over the active poles D of f'' plus the motion's |p''| and
/// |R''| |x|). Linear interpolation of the samples errs by at most M h^2 / 8 (its Peano kernel)
/// and is never larger than its ends.
inline Certificate certify(const kernel::BSpline<Eigen::Matrix4d>& f,
                           const std::function<Eigen::Matrix4d(double)>& frame,
                           const FrameBoundFn& bound, const std::vector<double>& x,
                           const std::vector<Eigen::Vector3d>& points, const FrameFitOptions& opt) {
  const int d = f.degree();
  const auto& T = f.knots();
  const int n = static_cast<int>(f.ctrl().size());
  // Poles of f'' (none below degree 2: f'' = 0 in a span): R_i from P_i, P_{i+1}, P_{i+2},
  // those of span j being R_{j-d} .. R_{j-2}. (Not kernel::derivative twice: at a C0 knot the
  // second derivative's knot vector is not a valid B-spline's; its poles still are these.)
  std::vector<Eigen::Matrix4d> d2;
  if (d >= 2) {
    const auto& P = f.ctrl();
    auto slope = [&](std::size_t i) -> Eigen::Matrix4d {  // pole i of f'
      const double den = T[i + static_cast<std::size_t>(d) + 1] - T[i + 1];
      return den > 0 ? Eigen::Matrix4d(d * (P[i + 1] - P[i]) / den) : Eigen::Matrix4d::Zero();
    };
    for (std::size_t i = 0; i + 2 < P.size(); ++i) {
      const double den = T[i + static_cast<std::size_t>(d) + 1] - T[i + 2];
      d2.push_back(den > 0 ? Eigen::Matrix4d((d - 1) * (slope(i + 1) - slope(i)) / den)
                           : Eigen::Matrix4d::Zero());
    }
  }
  Certificate c;
  c.span_bound.assign(x.size() - 1, 0.0);
  c.samples = 1;
  auto deviation = [&](double t) {
    const int j = kernel::knot_span(T, d, n, t);
    const auto B = kernel::basis_functions(T, j, d, t);
    Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
    for (int i = 0; i <= d; ++i)
      m += B[static_cast<std::size_t>(i)] * f.ctrl()[static_cast<std::size_t>(j - d + i)];
    const double e = frame_distance(m, frame(t), points);
    return std::isnan(e) ? HUGE_VAL : e;
  };
  for (std::size_t k = 0; k + 1 < x.size(); ++k) {
    const double a = x[k], b = x[k + 1], L = b - a;
    const int j = kernel::knot_span(T, d, n, 0.5 * (a + b));
    const auto mb = bound(a, b);
    double M = 0;
    for (const auto& p : points) {
      const Eigen::Vector4d h(1, p(0), p(1), p(2));
      double fit = 0;
      for (int i = j - d; i <= j - 2 && d >= 2; ++i)
        fit = std::max(fit, (d2[static_cast<std::size_t>(i)] * h).tail<3>().norm());
      M = std::max(M, fit + mb.position + mb.rotation * p.norm());
    }
    if (!std::isfinite(M)) M = HUGE_VAL;
    const double wanted = std::ceil(L * std::sqrt(M / (8 * kFitRemainderShare * opt.tol)));
    if (!(wanted <= kFitMaxSamplesPerSpan)) {  // too fine a grid: the span is halved
      c.span_bound[k] = HUGE_VAL;
      c.bound = HUGE_VAL;
      continue;
    }
    const int m = std::max(opt.check_density, static_cast<int>(wanted));
    double top = 0;
    for (int s = 0; s <= m; ++s) {
      const double t = s == m ? b : a + L * s / m;
      const double e = deviation(t);
      if (!(e <= top)) top = e;
      if (!(e <= c.measured)) {
        c.measured = e;
        c.worst_t = t;
      }
    }
    c.samples += static_cast<std::size_t>(m);
    const double h = L / m;
    c.span_bound[k] = top + M * h * h / 8;
    c.bound = std::max(c.bound, c.span_bound[k]);
  }
  return c;
}

}  // namespace detail

/// Fits the rigid maps `frame(t)` (4x4, row 0 = (1, 0, 0, 0)) of a motion on
/// [breaks.front(), breaks.back()] by a B-spline of opt.degree. The knot vector starts with
/// the motion's own breakpoints; interior break k has multiplicity degree - continuity[k-1]
/// (at least 1), so the fit may bend where the motion does. The poles are the least-squares
/// solution at degree + 2 points per span with the end poles fixed to the end frames (the
/// ends are exact: a planar profile stays planar there), from banded normal equations.
/// The deviation is measured for every point of `points` at 16 points per span; spans above
/// half the tolerance are halved and the fit repeated until the measurement is within it. Then
/// each span is certified: with M a bound of the deviation's second derivative there (the
/// fit's from the convex hull of its second-derivative poles, the motion's from `bound`),
/// the deviation between samples h apart exceeds the larger sampled end by at most M h^2 / 8;
/// the grid is made fine enough for that term to be kFitRemainderShare of opt.tol at most
/// (opt.check_density samples at least), and a span whose sum exceeds opt.tol is halved. A
/// frame of any point in the convex hull of `points` is then within the proven bound too (the
/// error is affine in x). With no `bound` (a caller that certifies the result itself, such as
/// cam::cam_nurbs) the last step is a measurement at opt.check_density points per span and
/// max_deviation_bound is NaN. Throws Errc::numerical_failure beyond opt.max_spans, naming
/// the deviation reached.
inline FrameFit fit_frames(const std::function<Eigen::Matrix4d(double)>& frame,
                           const FrameBoundFn& bound, const std::vector<double>& breaks,
                           const std::vector<int>& continuity,
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
    double cut = 0.5 * opt.tol;    // spans above this are halved
    if (worst <= cut && !bound) {  // the caller certifies: the check grid's measurement
      dev = measure(opt.check_density, worst, worst_t);
      out.max_deviation = worst;
      out.worst_t = worst_t;
      out.max_deviation_bound = std::nan("");
      out.check_samples = (x.size() - 1) * static_cast<std::size_t>(opt.check_density) + 1;
      if (worst <= opt.tol) return out;
    } else if (worst <= cut) {
      const auto cert = detail::certify(out.matrix, frame, bound, x, points, opt);
      out.max_deviation = cert.measured;
      out.worst_t = cert.worst_t;
      out.max_deviation_bound = cert.bound;
      out.check_samples = cert.samples;
      worst = cert.measured;
      worst_t = cert.worst_t;
      if (cert.bound <= opt.tol) return out;
      dev = cert.span_bound;
      cut = opt.tol;
    }
    std::vector<double> nx{x.front()};
    std::vector<int> nm{mult.front()};
    for (std::size_t k = 0; k + 1 < x.size(); ++k) {
      if (!(dev[k] <= cut)) {
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

/// fit_frames for a quaternion spline: its rigid maps on its knots with its continuity there,
/// certified with kernel::second_derivative_bound.
inline FrameFit fit_frames(const kernel::QuaternionSpline& s,
                           const std::vector<Eigen::Vector3d>& points, const FrameFitOptions& opt) {
  return fit_frames([&s](double t) { return s.frame(t); },
                    [&s](double a, double b) { return kernel::second_derivative_bound(s, a, b); },
                    s.knots, s.interior_continuity(), points, opt);
}

/// fit_frames for a motion: a quaternion spline's geometry (a rational motion's is exact and
/// needs none: refused). Refusals name the motion.
inline FrameFit fit_frames(const qmotion::Motion& motion,
                           const std::vector<Eigen::Vector3d>& points, const FrameFitOptions& opt) {
  if (motion.is_rational())
    throw Error(Errc::invalid_input,
                motion.label() + ": a rational motion's geometry is exact; it needs no fit");
  try {
    return fit_frames(motion.spline(), points, opt);
  } catch (const Error& e) {
    throw Error(e.code(), motion.label() + ": " + e.what());
  }
}

}  // namespace qmotion::sweep
