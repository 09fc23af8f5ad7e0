// <qmotion/kernel/qspline_bounds.hpp>: proven bounds of a quaternion spline's second
// derivatives on a parameter interval (docs/geometry.md, "The fit's proof"): what the
// certificate of a fitted frame needs between its samples. Every step rounds outward
// (<qmotion/kernel/outward.hpp>), so the bounds hold including rounding.
#pragma once
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/outward.hpp>
#include <qmotion/kernel/qspline.hpp>

namespace qmotion::kernel {

/// Upper bounds on [u0, u1] of |p''(u)| (the position's second derivative) and of the
/// operator norm of R''(u) (the rotation matrix's), both per unit of u squared.
struct FrameSecondDerivativeBound {
  double position = 0;
  double rotation = 0;
};

namespace detail {

/// Bernstein coefficients of degree 4 on [0, 1], each an interval that holds the exact one.
using Bernstein4 = std::array<Interval, 5>;

/// The coefficients of the polynomial sum_k a_k t^k (degree <= 4, a_k exact doubles) in the
/// Bernstein basis of degree 4: b_i = sum_{k <= i} C(i, k) / C(4, k) a_k.
inline Bernstein4 from_power(const std::array<double, 5>& a) {
  static constexpr double kBinom[5][5] = {
      {1, 0, 0, 0, 0}, {1, 1, 0, 0, 0}, {1, 2, 1, 0, 0}, {1, 3, 3, 1, 0}, {1, 4, 6, 4, 1}};
  Bernstein4 b;
  for (int i = 0; i <= 4; ++i) {
    Interval sum(0.0);
    for (int k = 0; k <= i; ++k)
      sum += Interval(kBinom[i][k]) / Interval(kBinom[4][k]) * Interval(a[k]);
    b[static_cast<std::size_t>(i)] = sum;
  }
  return b;
}

/// The derivatives d_0..d_3 of segment seg's blending functions, in t, as Bernstein
/// coefficients of degree 4 on [0, 1] that hold the exact ones: the uniform constructions'
/// fixed polynomials (as QuaternionSpline::blend_derivative writes them), or for the quintic
/// 5 (V_{i+1} - V_i) of its Bezier points, computed in intervals from the tensions.
inline std::array<Bernstein4, 4> blend_derivatives(const QuaternionSpline& s, int seg) {
  std::array<Bernstein4, 4> d;
  if (s.scheme == QSplineScheme::quintic) {
    const Interval al(s.tension[static_cast<std::size_t>(seg)]);
    const Interval be(s.tension[static_cast<std::size_t>(seg + 1)]);
    const Interval one(1.0), zero(0.0);
    // QuaternionSpline::quintic_points, each fraction of a tension enclosed.
    const std::array<std::array<Interval, 4>, 6> V{{
        {zero, one, zero, zero},
        {-al / Interval(5.0), one, al / Interval(5.0), zero},
        {-(Interval(7.0) * al / Interval(20.0)), one - al / Interval(10.0),
         Interval(9.0) * al / Interval(20.0), zero},
        {zero, Interval(9.0) * be / Interval(20.0), one - be / Interval(10.0),
         -(Interval(7.0) * be / Interval(20.0))},
        {zero, be / Interval(5.0), one, -be / Interval(5.0)},
        {zero, zero, one, zero},
    }};
    for (std::size_t j = 0; j < 4; ++j)
      for (std::size_t i = 0; i < 5; ++i) d[j][i] = Interval(5.0) * (V[i + 1][j] - V[i][j]);
    return d;
  }
  if (s.scheme == QSplineScheme::kks) {  // the uniform cubic B-spline basis, differentiated
    d[0] = from_power({-0.5, 1, -0.5, 0, 0});
    d[1] = from_power({0, -2, 1.5, 0, 0});
    d[2] = from_power({0.5, 1, -1.5, 0, 0});
    d[3] = from_power({0, 0, 0.5, 0, 0});
    return d;
  }
  d[0] = from_power({-0.5, 3, -4.5, 2, 0});  // (4) of seed 003, differentiated
  d[1] = from_power({0, -6, 7.5, -2, 0});
  d[2] = from_power({0.5, 3, -1.5, -2, 0});
  d[3] = from_power({0, 0, -1.5, 2, 0});
  return d;
}

/// The coefficients of a Bernstein polynomial of degree N on [0, 1] restricted to [x0, x1]
/// (exact doubles in [0, 1]): coefficient i is its blossom at (x1 i times, x0 N - i times),
/// evaluated by de Casteljau's steps in intervals.
template <std::size_t M>
std::array<Interval, M> restrict_to(const std::array<Interval, M>& b, double x0, double x1) {
  std::array<Interval, M> out;
  for (std::size_t i = 0; i < M; ++i) {
    std::array<Interval, M> w = b;
    for (std::size_t level = 1; level < M; ++level) {
      const Interval x(level <= i ? x1 : x0), rest = Interval(1.0) - x;
      for (std::size_t k = 0; k + level < M; ++k) w[k] = rest * w[k] + x * w[k + 1];
    }
    out[i] = w[0];
  }
  return out;
}

/// The derivative's coefficients: 4 (b_{i+1} - b_i), degree 3.
inline std::array<Interval, 4> derivative(const Bernstein4& b) {
  std::array<Interval, 4> d;
  for (std::size_t i = 0; i < 4; ++i) d[i] = Interval(4.0) * (b[i + 1] - b[i]);
  return d;
}

/// An upper bound of |f| over the interval, f given by Bernstein coefficients (convex hull).
template <std::size_t M>
double hull_up(const std::array<Interval, M>& c) {
  double m = 0;
  for (const auto& x : c) m = std::max(m, abs(x).hi);
  return m;
}

/// The local parameter of u in segment seg, enclosed: (u - u_seg) / (u_{seg+1} - u_seg).
inline Interval local_parameter(const QuaternionSpline& s, int seg, double u) {
  if (s.scheme == QSplineScheme::quintic) {
    const Interval k0(s.knots[static_cast<std::size_t>(seg)]);
    return (Interval(u) - k0) / (Interval(s.knots[static_cast<std::size_t>(seg + 1)]) - k0);
  }
  const Interval a(s.a());
  return (Interval(u) - a) / (Interval(s.b()) - a) * Interval(static_cast<double>(s.segments())) -
         Interval(static_cast<double>(seg));
}

/// dt/du in segment seg, enclosed.
inline Interval local_rate(const QuaternionSpline& s, int seg) {
  if (s.scheme == QSplineScheme::quintic)
    return Interval(1.0) / (Interval(s.knots[static_cast<std::size_t>(seg + 1)]) -
                            Interval(s.knots[static_cast<std::size_t>(seg)]));
  return Interval(static_cast<double>(s.segments())) / (Interval(s.b()) - Interval(s.a()));
}

}  // namespace detail

/// The bounds on the local parameters [t0, t1] (exact doubles, 0 <= t0 <= t1 <= 1) of
/// segment seg. On a segment,
/// q(t) = E exp(w1 c1(t)) exp(w2 c2(t)) exp(w3 c3(t)) with polynomial cumulative blends c_j,
/// so the angular velocity is 2 sum_j P_j w_j P_j^-1 c_j' (P_j the product before factor j):
/// |omega| <= 2 sum |w_j| |c_j'|, |omega'| <= 2 sum |w_j| (|c_j''| + 2 |c_j'| sum_{i<j}
/// |w_i||c_i'|), and R'' = ([omega']x + [omega]x^2) R gives |R''| <= |omega'| + |omega|^2. The
/// position is sum C_j(t) P_j. Every |c_j'|, |c_j''| and |p''| is bounded by the convex hull
/// of its Bernstein coefficients on [t0, t1] (detail::restrict_to), and dt/du converts to u;
/// every step rounds outward, so the bounds hold including rounding.
inline FrameSecondDerivativeBound segment_second_derivative_bound(const QuaternionSpline& s,
                                                                  int seg, double t0, double t1) {
  const auto d = detail::blend_derivatives(s, seg);
  // The cumulative blends' derivatives c_j' = d_j + ... + d_3 (j = 1, 2, 3), on [0, 1].
  std::array<detail::Bernstein4, 3> c;
  c[2] = d[3];
  for (std::size_t i = 0; i < 5; ++i) {
    c[1][i] = d[2][i] + c[2][i];
    c[0][i] = d[1][i] + c[1][i];
  }
  std::array<Interval, 3> c1, c2, w;  // bounds of |c_j'|, |c_j''| on [t0, t1], and |w_j|
  for (std::size_t j = 0; j < 3; ++j) {
    c1[j] = Interval(0.0, detail::hull_up(detail::restrict_to(c[j], t0, t1)));
    c2[j] = Interval(0.0, detail::hull_up(detail::restrict_to(detail::derivative(c[j]), t0, t1)));
    const Eigen::Vector3d v = s.omega[static_cast<std::size_t>(seg) + j].vec();
    w[j] = Interval(0.0, norm_up(difference(v, Eigen::Vector3d::Zero())));
  }
  Interval omega(0.0), domega(0.0), before(0.0);  // before: sum_{i<j} |w_i| |c_i'|
  for (std::size_t j = 0; j < 3; ++j) {
    omega += Interval(2.0) * w[j] * c1[j];
    domega += Interval(2.0) * w[j] * (c2[j] + Interval(2.0) * c1[j] * before);
    before += w[j] * c1[j];
  }
  // p'' = sum_j d_j' P_j: its coefficients on [t0, t1], component by component.
  std::array<std::array<Interval, 4>, 4> dd;
  for (std::size_t j = 0; j < 4; ++j) dd[j] = detail::restrict_to(detail::derivative(d[j]), t0, t1);
  double p2 = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    Interval3 v{Interval(0.0), Interval(0.0), Interval(0.0)};
    for (std::size_t j = 0; j < 4; ++j) {
      const Eigen::Vector3d& P = s.pctrl[static_cast<std::size_t>(seg) + j];
      for (int k = 0; k < 3; ++k) v[static_cast<std::size_t>(k)] += dd[j][i] * Interval(P(k));
    }
    p2 = std::max(p2, norm_up(v));
  }
  const Interval rate2 = square(detail::local_rate(s, seg));
  FrameSecondDerivativeBound b;
  b.rotation = (rate2 * (domega + omega * omega)).hi;
  b.position = (rate2 * Interval(0.0, p2)).hi;
  return b;
}

/// The bounds on [u0, u1]: the larger of segment_second_derivative_bound over the segments
/// the interval meets. Each segment takes the local parameters that enclose the exact ones of
/// u0 and u1 (and its neighbours too, for a u within rounding of a knot).
inline FrameSecondDerivativeBound second_derivative_bound(const QuaternionSpline& s, double u0,
                                                          double u1) {
  if (!(u0 <= u1) || !(u0 >= s.a()) || !(u1 <= s.b()))
    throw Error(Errc::invalid_input, "second_derivative_bound: expected a <= u0 <= u1 <= b");
  const int first = std::max(0, s.locate(u0).first - 1);
  const int last = std::min(s.segments() - 1, s.locate(u1).first + 1);
  FrameSecondDerivativeBound b;
  for (int seg = first; seg <= last; ++seg) {
    const double x0 = std::max(0.0, detail::local_parameter(s, seg, u0).lo);
    const double x1 = std::min(1.0, detail::local_parameter(s, seg, u1).hi);
    if (!(x0 <= x1)) continue;  // the interval does not meet the segment
    const auto g = segment_second_derivative_bound(s, seg, x0, x1);
    b.position = std::max(b.position, g.position);
    b.rotation = std::max(b.rotation, g.rotation);
  }
  return b;
}

}  // namespace qmotion::kernel
