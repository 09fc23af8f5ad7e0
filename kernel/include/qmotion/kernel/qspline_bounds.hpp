// <qmotion/kernel/qspline_bounds.hpp>: proven bounds of a quaternion spline's second
// derivatives on a parameter interval (docs/geometry.md, "The fit's proof"): what the
// certificate of a fitted frame needs between its samples.
#pragma once
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/qspline.hpp>

namespace qmotion::kernel {

/// Upper bounds on [u0, u1] of |p''(u)| (the position's second derivative) and of the
/// operator norm of R''(u) (the rotation matrix's), both per unit of u squared.
struct FrameSecondDerivativeBound {
  double position = 0;
  double rotation = 0;
};

namespace detail {

/// Bernstein coefficients on [t0, t1] of the polynomial f of degree at most N, from its
/// values at N + 1 evenly spaced points (a 6 x 6 solve at most).
template <int N, typename F>
std::array<Eigen::Vector3d, N + 1> bernstein_on(F f, double t0, double t1) {
  Eigen::Matrix<double, N + 1, N + 1> B;
  Eigen::Matrix<double, N + 1, 3> values;
  for (int k = 0; k <= N; ++k) {
    const double s = static_cast<double>(k) / N;
    for (int i = 0; i <= N; ++i) {
      double b = 1;
      for (int j = 0; j < i; ++j) b *= static_cast<double>(N - j) / (j + 1);  // binomial
      B(k, i) = b * std::pow(s, i) * std::pow(1 - s, N - i);
    }
    values.row(k) = f(t0 + (t1 - t0) * s).transpose();
  }
  const Eigen::Matrix<double, N + 1, 3> c = B.fullPivLu().solve(values);
  std::array<Eigen::Vector3d, N + 1> out;
  for (int i = 0; i <= N; ++i) out[static_cast<std::size_t>(i)] = c.row(i).transpose();
  return out;
}

/// Largest norm of a Bernstein polynomial's coefficients: a bound of its values (convex hull).
template <std::size_t M>
double hull_bound(const std::array<Eigen::Vector3d, M>& c) {
  double m = 0;
  for (const auto& v : c) m = std::max(m, v.norm());
  return m;
}

/// Bound of the derivative of a Bernstein polynomial of degree M - 1 on an interval of
/// length h: its derivative's coefficients are (M - 1)(c_{i+1} - c_i) / h.
template <std::size_t M>
double derivative_hull_bound(const std::array<Eigen::Vector3d, M>& c, double h) {
  double m = 0;
  for (std::size_t i = 0; i + 1 < M; ++i) m = std::max(m, (c[i + 1] - c[i]).norm());
  return static_cast<double>(M - 1) * m / h;
}

}  // namespace detail

/// The bounds on the local parameters [t0, t1] of segment seg. On a segment,
/// q(t) = E exp(w1 c1(t)) exp(w2 c2(t)) exp(w3 c3(t)) with polynomial cumulative blends c_j,
/// so the angular velocity is 2 sum_j P_j w_j P_j^-1 c_j' (P_j the product before factor j):
/// |omega| <= 2 sum |w_j| |c_j'|, |omega'| <= 2 sum |w_j| (|c_j''| + 2 |c_j'| sum_{i<j}
/// |w_i||c_i'|), and R'' = ([omega']x + [omega]x^2) R gives |R''| <= |omega'| + |omega|^2. The
/// position is sum C_j(t) P_j. Every |c_j'|, |c_j''| and |p''| is bounded by the convex hull of
/// Bernstein coefficients on the interval; dt/du converts to u. A relative 1e-9 covers the rounding
/// of the Bernstein solve.
inline FrameSecondDerivativeBound segment_second_derivative_bound(const QuaternionSpline& s,
                                                                  int seg, double t0, double t1) {
  const double rate = s.local_rate(seg);
  const double h = std::max(t1 - t0, 1e-300);
  // c_j' (degree at most 4) for j = 1, 2, 3 in the three components, and p'.
  const auto dc = detail::bernstein_on<4>(
      [&](double t) {
        const auto d = s.blend_derivative(seg, t);
        return Eigen::Vector3d(d[1] + d[2] + d[3], d[2] + d[3], d[3]);
      },
      t0, t1);
  const auto dp = detail::bernstein_on<4>(
      [&](double t) {
        const auto d = s.blend_derivative(seg, t);
        Eigen::Vector3d v = Eigen::Vector3d::Zero();
        for (int j = 0; j < 4; ++j)
          v += d[static_cast<std::size_t>(j)] * s.pctrl[static_cast<std::size_t>(seg + j)];
        return v;
      },
      t0, t1);
  std::array<double, 3> c1{}, c2{}, w{};  // max |c_j'|, max |c_j''|, |w_j|
  for (int j = 0; j < 3; ++j) {
    std::array<Eigen::Vector3d, 5> cj;
    for (std::size_t i = 0; i < 5; ++i) cj[i] = Eigen::Vector3d(dc[i](j), 0, 0);
    c1[static_cast<std::size_t>(j)] = detail::hull_bound(cj);
    c2[static_cast<std::size_t>(j)] = detail::derivative_hull_bound(cj, h);
    w[static_cast<std::size_t>(j)] = s.omega[static_cast<std::size_t>(seg + j)].vec().norm();
  }
  double omega = 0, domega = 0, before = 0;  // before: sum_{i<j} |w_i| |c_i'|
  for (std::size_t j = 0; j < 3; ++j) {
    omega += 2 * w[j] * c1[j];
    domega += 2 * w[j] * (c2[j] + 2 * c1[j] * before);
    before += w[j] * c1[j];
  }
  constexpr double kSlack = 1 + 1e-9;
  FrameSecondDerivativeBound b;
  b.rotation = kSlack * rate * rate * (domega + omega * omega);
  b.position = kSlack * rate * rate * detail::derivative_hull_bound(dp, h);
  return b;
}

/// The bounds on [u0, u1]: the larger of segment_second_derivative_bound over the segments
/// the interval meets.
inline FrameSecondDerivativeBound second_derivative_bound(const QuaternionSpline& s, double u0,
                                                          double u1) {
  if (!(u0 <= u1) || !(u0 >= s.a()) || !(u1 <= s.b()))
    throw Error(Errc::invalid_input, "second_derivative_bound: expected a <= u0 <= u1 <= b");
  const auto [first, t0] = s.locate(u0);
  const auto [last, t1] = s.locate(u1);
  FrameSecondDerivativeBound b;
  for (int seg = first; seg <= last; ++seg) {
    if (seg == last && seg != first && t1 <= 0) break;  // u1 starts the segment: nothing of it
    const auto g =
        segment_second_derivative_bound(s, seg, seg == first ? t0 : 0.0, seg == last ? t1 : 1.0);
    b.position = std::max(b.position, g.position);
    b.rotation = std::max(b.rotation, g.rotation);
  }
  return b;
}

}  // namespace qmotion::kernel
