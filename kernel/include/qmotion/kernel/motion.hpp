// <qmotion/kernel/motion.hpp>
#pragma once
#include <algorithm>
#include <cmath>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/kernel/dual_quaternion.hpp>
#include <qmotion/kernel/error.hpp>
#include <string>
#include <utility>
#include <vector>

namespace qmotion::kernel {

/// How a Q-motion was given: one Bezier polynomial (13) or a B-spline (section 6).
enum class Basis { bezier, bspline };

/// A Q-motion: a dual-quaternion polynomial or spline Q(t) on [a, b]. A Bezier motion is
/// stored as the B-spline on the knot vector a^(n+1) b^(n+1), so every algorithm has one
/// representation; `basis` records how it is written.
/// @see Juettler 1994, eq. (13) and section 6
template <typename Scalar>
struct QMotion {
  Basis basis;
  BSpline<DualQuaternion<Scalar>> curve;

  int degree() const { return curve.degree(); }
  const Scalar& a() const { return curve.a(); }
  const Scalar& b() const { return curve.b(); }
  /// Number of polynomial segments (non-empty knot spans).
  int segments() const { return static_cast<int>(curve.breakpoints().size()) - 1; }
};

/// Polar forms (symmetric bilinear maps) of the quadratic maps of a dual quaternion used
/// below; product(Q, Q, polar) gives the composite polynomial exactly.
namespace polar {
/// |Q0|^2: the weight (homogenising coordinate) of every trajectory.
struct Weight {
  template <typename S>
  S operator()(const DualQuaternion<S>& a, const DualQuaternion<S>& b) const {
    return a.real().dot(b.real());
  }
};
/// The Plucker form (8).
struct Plucker {
  template <typename S>
  S operator()(const DualQuaternion<S>& a, const DualQuaternion<S>& b) const {
    return S((a.real().dot(b.dual()) + b.real().dot(a.dual())) / S(2));
  }
};
/// The 4x4 matrix (10) of kernel/dual_quaternion.hpp's to_matrix4.
struct Matrix4 {
  template <typename S>
  Eigen::Matrix<S, 4, 4> operator()(const DualQuaternion<S>& a, const DualQuaternion<S>& b) const {
    const Eigen::Matrix<S, 4, 4> m =
        to_matrix4(DualQuaternion<S>(a + b)) - to_matrix4(a) - to_matrix4(b);
    return (m / S(2)).eval();
  }
};
/// The image (12) of a fixed homogeneous point x.
template <typename S>
struct PointImage {
  Eigen::Matrix<S, 4, 1> x;
  Eigen::Matrix<S, 4, 1> operator()(const DualQuaternion<S>& a, const DualQuaternion<S>& b) const {
    const Eigen::Matrix<S, 4, 1> y = apply(DualQuaternion<S>(a + b), x) - apply(a, x) - apply(b, x);
    return (y / S(2)).eval();
  }
};
}  // namespace polar

/// Q(t).
template <typename Scalar>
DualQuaternion<Scalar> evaluate(const QMotion<Scalar>& m, const Scalar& t) {
  return evaluate(m.curve, t);
}

/// The scalar spline |Q0(t)|^2 (degree 2n).
template <typename Scalar>
BSpline<Scalar> weight_spline(const QMotion<Scalar>& m) {
  return product(m.curve, m.curve, polar::Weight{});
}

/// The scalar spline of the Plucker form (8) along the motion (degree 2n).
template <typename Scalar>
BSpline<Scalar> plucker_spline(const QMotion<Scalar>& m) {
  return product(m.curve, m.curve, polar::Plucker{});
}

/// The 4x4 matrix spline M(t) of (10) (degree 2n): y(t) = M(t) x for every point x.
template <typename Scalar>
BSpline<Eigen::Matrix<Scalar, 4, 4>> matrix_spline(const QMotion<Scalar>& m) {
  return product(m.curve, m.curve, polar::Matrix4{});
}

/// The homogeneous trajectory (y0, y) of the homogeneous point x (degree 2n before
/// reduction).
template <typename Scalar>
BSpline<Eigen::Matrix<Scalar, 4, 1>> homogeneous_trajectory(const QMotion<Scalar>& m,
                                                            const Eigen::Matrix<Scalar, 4, 1>& x) {
  return product(m.curve, m.curve, polar::PointImage<Scalar>{x});
}

/// Largest real-part and dual-part coefficient magnitude of a motion (as double).
template <typename Scalar>
std::pair<double, double> coefficient_scales(const QMotion<Scalar>& m) {
  double r = 0, d = 0;
  for (const auto& c : m.curve.ctrl()) {
    r = std::max(r, max_abs(c.real()));
    d = std::max(d, max_abs(c.dual()));
  }
  return {r, d};
}

/// Plucker residual of the whole motion, normwise: max |Plucker coefficient| of the
/// degree-2n spline Du(Q Q~)/2 (its Bernstein coefficients on each span, O(n) from the
/// motion's pieces) divided by (largest real coefficient) x (largest dual
/// coefficient), or by the largest real coefficient squared for a pure rotation. Scale
/// free in both parts (positions in mm make the dual part large) and the natural measure
/// of floating-point error; exactly zero for an exact Q-motion in exact arithmetic.
template <typename Scalar>
Scalar plucker_residual(const QMotion<Scalar>& m) {
  Scalar num(0);
  for (const auto& piece : bezier_pieces(m.curve)) {
    const auto pl = product(piece, piece, polar::Plucker{});
    for (const auto& c : pl.coeffs()) num = std::max(num, abs_value(c));
  }
  if (num == Scalar(0)) return num;
  const auto [r, d] = coefficient_scales(m);
  if (r == 0.0)
    throw Error(Errc::numerical_failure, "motion with identically zero rotational part");
  return Scalar(num / Scalar(r * (d > 0.0 ? d : r)));
}

/// Zeros of the rotational part Q0(t) on [a, b] (poles of the motion: the trajectories
/// run to infinity there). Q0 vanishes exactly where the weight |Q0|^2 >= 0 does; the
/// weight's Bernstein pieces are subdivided where their convex hull reaches below
/// rel_tol times the weight's scale, pruning every piece whose coefficients stay above.
/// Errc::numerical_failure, naming `label` (the motion) and where, when 200 000 subdivisions
/// do not isolate the zeros (the weight stays near zero over a stretch, as on a span whose
/// rotational control points vanish).
/// @return parameters of the poles found, ascending
template <typename Scalar>
std::vector<double> find_poles(const QMotion<Scalar>& m, const std::string& label = "motion",
                               double rel_tol = 1e-16) {
  // The weight's Bezier pieces, each the product of the motion's piece with itself: O(n)
  // without assembling the degree-2n spline and taking it apart again.
  std::vector<Bernstein<double>> stack;
  double scale = 0.0;
  for (const auto& piece : bezier_pieces(m.curve)) {
    const auto w = product(piece, piece, polar::Weight{});
    std::vector<double> c;
    c.reserve(w.coeffs().size());
    for (const auto& v : w.coeffs()) {
      c.push_back(to_double(v));
      scale = std::max(scale, std::abs(c.back()));
    }
    stack.emplace_back(std::move(c), to_double(w.a()), to_double(w.b()));
  }
  std::reverse(stack.begin(), stack.end());  // popped from the back: left to right
  const double thr = rel_tol * scale;
  // A double zero of |Q0|^2 is located to about sqrt(eps) in double precision: leaves
  // narrower than that add nothing, and neighbouring leaves are one pole.
  const double range = to_double(m.b()) - to_double(m.a());
  const double width_min = 1e-10 * range;
  std::vector<std::pair<double, double>> leaves;  // (t, weight)
  std::size_t budget = 200000;
  while (!stack.empty()) {
    if (budget-- == 0)
      throw Error(Errc::numerical_failure,
                  label +
                      ": the zeros of the rotational part could not be isolated within 200000 "
                      "subdivisions: the weight |Q0|^2 stays near zero over a stretch from t = " +
                      std::to_string(stack.back().a()) +
                      " (a span whose rotational part vanishes?)");
    Bernstein<double> p = std::move(stack.back());
    stack.pop_back();
    double lo = p[0];
    for (double c : p.coeffs()) lo = std::min(lo, c);
    if (lo > thr) continue;
    const double mid = 0.5 * (p.a() + p.b());
    if (p.b() - p.a() <= width_min) {
      const double v = evaluate(p, mid);
      if (v <= thr) leaves.emplace_back(mid, v);
      continue;
    }
    auto halves = subdivide(p, mid);
    stack.push_back(std::move(halves.second));
    stack.push_back(std::move(halves.first));
  }
  std::sort(leaves.begin(), leaves.end());
  std::vector<double> poles;
  double last_t = 0.0, best_v = 0.0;
  for (const auto& [t, v] : leaves) {
    if (poles.empty() || t - last_t > 1e-7 * range) {
      poles.push_back(t);
      best_v = v;
    } else if (v < best_v) {
      poles.back() = t;
      best_v = v;
    }
    last_t = t;
  }
  return poles;
}

}  // namespace qmotion::kernel
