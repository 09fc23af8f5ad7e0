// <qmotion/sweep/solid.hpp>: what a swept solid needs besides its faces: the profile's planar
// region, the test that the region never sweeps back over itself, and an independent volume.
#pragma once
#include <Eigen/Dense>
#include <cmath>
#include <optional>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <qmotion/sweep/surface.hpp>
#include <string>
#include <vector>

namespace qmotion::sweep {

/// The planar region a closed planar profile bounds: unit normal (the boundary runs
/// counter-clockwise about it), area and centroid, in the moving space.
struct PlanarRegion {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double area = 0;
};

namespace detail {

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n from Chebyshev guesses).
inline const std::vector<std::pair<double, double>>& gauss_legendre() {
  static const std::vector<std::pair<double, double>> rule = [] {
    constexpr int n = 24;
    std::vector<std::pair<double, double>> r;
    for (int i = 1; i <= n; ++i) {
      double x = std::cos(M_PI * (i - 0.25) / (n + 0.5)), dp = 1;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1, p1 = x;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (x * p1 - p0) / (x * x - 1);
        const double dx = p1 / dp;
        x -= dx;
        if (std::abs(dx) < 1e-16) break;
      }
      r.emplace_back(x, 2 / ((1 - x * x) * dp * dp));
    }
    return r;
  }();
  return rule;
}

/// Integral of f over [a, b] split at the breakpoints x (and each span into `sub` parts),
/// by 24-point Gauss-Legendre per part: near machine precision for the smooth rational
/// integrands of sweeps.
template <typename F>
double integrate(const std::vector<double>& x, F&& f, int sub = 8) {
  double sum = 0;
  for (std::size_t k = 0; k + 1 < x.size(); ++k)
    for (int s = 0; s < sub; ++s) {
      const double a = x[k] + (x[k + 1] - x[k]) * s / sub,
                   b = x[k] + (x[k + 1] - x[k]) * (s + 1) / sub;
      for (const auto& [node, w] : gauss_legendre())
        sum += w * (b - a) / 2 * f((a + b) / 2 + (b - a) / 2 * node);
    }
  return sum;
}

/// Point and derivative of a homogeneous spline's Cartesian curve at t.
inline std::pair<Eigen::Vector3d, Eigen::Vector3d> point_and_tangent(
    const kernel::BSpline<Eigen::Vector4d>& h, const kernel::BSpline<Eigen::Vector4d>& dh,
    double t) {
  const Eigen::Vector4d y = kernel::evaluate(h, t), dy = kernel::evaluate(dh, t);
  const Eigen::Vector3d p = y.tail<3>() / y(0);
  return {p, (dy.tail<3>() * y(0) - y.tail<3>() * dy(0)) / (y(0) * y(0))};
}

}  // namespace detail

/// The region bounded by a closed planar profile. Throws Errc::invalid_input when the
/// profile is open (an edge does not start where the previous one ends, or the last does
/// not end where the first starts, beyond rel_tol of its size), not planar (a control
/// point off the best plane by more than rel_tol of its size), or bounds no area.
inline PlanarRegion planar_region(const Profile<double>& p, double rel_tol = 1e-9) {
  std::vector<Eigen::Vector3d> pts;
  for (const auto& e : p.edges) pts.insert(pts.end(), e.points.begin(), e.points.end());
  Eigen::Vector3d lo = pts.front(), hi = pts.front(), mean = Eigen::Vector3d::Zero();
  for (const auto& x : pts) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
    mean += x;
  }
  mean /= static_cast<double>(pts.size());
  const double size = (hi - lo).norm(), tol = rel_tol * size;
  for (std::size_t k = 0; k < p.edges.size(); ++k) {
    const auto& next = p.edges[(k + 1) % p.edges.size()];
    const double gap = (p.edges[k].points.back() - next.points.front()).norm();
    if (!(gap <= tol))
      throw Error(Errc::invalid_input,
                  "--solid needs a closed profile: edge " + std::to_string(k + 1) + " ends " +
                      std::to_string(gap) + " away from where " +
                      (k + 1 == p.edges.size() ? std::string("the first edge starts")
                                               : "edge " + std::to_string(k + 2) + " starts"));
  }
  Eigen::MatrixXd A(static_cast<Eigen::Index>(pts.size()), 3);
  for (std::size_t i = 0; i < pts.size(); ++i)
    A.row(static_cast<Eigen::Index>(i)) = (pts[i] - mean).transpose();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  PlanarRegion r;
  r.normal = svd.matrixV().col(2);
  const Eigen::Vector3d e1 = svd.matrixV().col(0), e2 = r.normal.cross(e1);
  for (const auto& x : pts) {
    const double off = std::abs((x - mean).dot(r.normal));
    if (!(off <= tol))
      throw Error(Errc::invalid_input, "--solid needs a planar profile: a control point lies " +
                                           std::to_string(off) + " off the profile's plane");
  }
  // Green's theorem in plane coordinates (x, y) = ((P - mean).e1, (P - mean).e2):
  // area = 1/2 closed-integral (x dy - y dx), integral of x dA = 1/2 closed-integral x^2 dy,
  // integral of y dA = -1/2 closed-integral y^2 dx.
  double area = 0, mx = 0, my = 0;
  for (const auto& e : p.edges) {
    const auto h = to_homogeneous(e);
    const auto dh = kernel::derivative(h);
    const auto x = h.breakpoints();
    auto f = [&](double v, int which) {
      const auto [pt, d] = detail::point_and_tangent(h, dh, v);
      const double X = (pt - mean).dot(e1), Y = (pt - mean).dot(e2), dX = d.dot(e1), dY = d.dot(e2);
      return which == 0   ? 0.5 * (X * dY - Y * dX)
             : which == 1 ? 0.5 * X * X * dY
                          : -0.5 * Y * Y * dX;
    };
    area += detail::integrate(x, [&](double v) { return f(v, 0); });
    mx += detail::integrate(x, [&](double v) { return f(v, 1); });
    my += detail::integrate(x, [&](double v) { return f(v, 2); });
  }
  if (!(std::abs(area) > 1e-12 * size * size))
    throw Error(Errc::invalid_input, "--solid: the profile bounds no area");
  r.centroid = mean + e1 * (mx / area) + e2 * (my / area);
  if (area < 0) r.normal = -r.normal;  // the boundary runs counter-clockwise about it
  r.area = std::abs(area);
  return r;
}

/// Where the region sweeps back over itself, if anywhere: the first parameter t at which
/// some point of the region has normal velocity v(x, t).n(t) of the wrong sign or zero.
/// The normal velocity is affine in x and the region lies in the convex hull of the
/// profile's control points (positive weights), so their trajectories decide it. For each
/// control point the numerator n_h . (y' y0 - y y0') of the normal velocity, a polynomial
/// on every span, is proved positive by its Bernstein coefficients, subdividing where they
/// do not yet show it (no sampling). The sign that counts is the one the first control point
/// has at the middle of the interval (a region may move against its normal: then `flip`).
struct BacksweepResult {
  std::optional<double> t;  ///< the parameter where the normal velocity vanishes or turns
  bool flip = false;        ///< the region moves against its normal
};

/// The homogeneous control points (w, w x) of every edge of the profile, in order.
inline std::vector<Eigen::Vector4d> homogeneous_points(const Profile<double>& p) {
  std::vector<Eigen::Vector4d> X;
  for (const auto& e : p.edges)
    for (std::size_t j = 0; j < e.points.size(); ++j)
      X.emplace_back(e.weights[j], e.weights[j] * e.points[j](0), e.weights[j] * e.points[j](1),
                     e.weights[j] * e.points[j](2));
  return X;
}

/// find_backsweep from the homogeneous trajectories `cols` of the profile's control points
/// and `nh` of the region's normal (a direction, weight 0), as any motion (rational, or a
/// fitted matrix spline) gives them.
inline BacksweepResult find_backsweep(const std::vector<kernel::BSpline<Eigen::Vector4d>>& cols,
                                      const kernel::BSpline<Eigen::Vector4d>& nh) {
  using V4 = Eigen::Vector4d;
  using V3 = Eigen::Vector3d;
  std::vector<double> x = cols.front().breakpoints();
  for (double v : nh.breakpoints()) x.push_back(v);
  std::sort(x.begin(), x.end());
  x.erase(std::unique(x.begin(), x.end()), x.end());
  std::vector<kernel::Bernstein<double>> numerators;  // per span and control point
  double scale = 0;
  for (std::size_t k = 0; k + 1 < x.size(); ++k) {
    const auto np = kernel::bezier_piece(nh, x[k], x[k + 1]);
    for (const auto& c : cols) {
      const auto yp = kernel::bezier_piece(c, x[k], x[k + 1]);
      const auto vel = kernel::product(kernel::derivative(yp), yp, [](const V4& d, const V4& y) {
        return V3(d.tail<3>() * y(0) - y.tail<3>() * d(0));
      });
      numerators.push_back(
          kernel::product(np, vel, [](const V4& n, const V3& v) { return n.tail<3>().dot(v); }));
      for (double c0 : numerators.back().coeffs()) scale = std::max(scale, std::abs(c0));
    }
  }
  BacksweepResult r;
  const double mid = (x.front() + x.back()) / 2;
  for (const auto& n : numerators)
    if (n.a() <= mid && mid <= n.b()) {
      r.flip = kernel::evaluate(n, mid) < 0;
      break;
    }
  const double eps = 1e-12 * scale, s = r.flip ? -1.0 : 1.0;
  std::optional<double> first;
  // Depth-first: a piece whose coefficients are all positive is done; one whose end value is
  // not positive names its parameter; others are halved (to 2^-40 of the span).
  std::vector<std::pair<kernel::Bernstein<double>, int>> stack;
  for (auto it = numerators.rbegin(); it != numerators.rend(); ++it) stack.emplace_back(*it, 0);
  while (!stack.empty()) {
    auto [n, depth] = stack.back();
    stack.pop_back();
    if (first && n.a() >= *first) continue;
    double lo = s * n[0];
    for (double c : n.coeffs()) lo = std::min(lo, s * c);
    if (lo > eps) continue;
    std::optional<double> at;  // found, or unresolved at 2^-40 of a span: touching zero
    if (s * n[0] <= eps)
      at = n.a();
    else if (s * n[n.degree()] <= eps)
      at = n.b();
    else if (depth >= 40)
      at = (n.a() + n.b()) / 2;
    if (at) {
      first = first ? std::min(*first, *at) : *at;
      continue;
    }
    auto [left, right] = kernel::subdivide(n, (n.a() + n.b()) / 2);
    stack.emplace_back(std::move(right), depth + 1);
    stack.emplace_back(std::move(left), depth + 1);
  }
  r.t = first;
  return r;
}

inline BacksweepResult find_backsweep(const Motion<double>& m, const Profile<double>& p,
                                      const PlanarRegion& region) {
  const Eigen::Vector4d n(0, region.normal(0), region.normal(1), region.normal(2));
  return find_backsweep(trajectories(m, homogeneous_points(p)), trajectories(m, {n}).front());
}

/// The volume a planar region sweeps when it never sweeps back over itself:
/// V = A * integral of n(t).c'(t) dt, with n(t) the region's unit normal carried by the
/// motion and c(t) the trajectory of its centroid (the rotational part of the velocity
/// integrates to zero over the region about its centroid). Computed from the motion alone,
/// independently of the exported faces.
inline double swept_volume(const Motion<double>& motion, const PlanarRegion& region) {
  const kernel::QMotion<double>& m = motion.curve;
  Eigen::Vector4d C;
  C << 1, region.centroid;
  const auto h = kernel::homogeneous_trajectory(m, C);
  const auto dh = kernel::derivative(h);
  const double integral = detail::integrate(h.breakpoints(), [&](double t) {
    const auto q = kernel::evaluate(m, t);
    const Eigen::Vector3d n = kernel::rotate(q.real(), region.normal);
    return n.dot(detail::point_and_tangent(h, dh, t).second);
  });
  return region.area * std::abs(integral);
}

}  // namespace qmotion::sweep
