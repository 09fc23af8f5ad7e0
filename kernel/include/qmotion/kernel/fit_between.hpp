// <qmotion/kernel/fit_between.hpp>: how far a fitted motion strays between the poses of its
// stream (`fit --between`, docs/fitting.md): the moving origin from the polyline through the
// positions, the rotation from the geodesic between neighbouring rotations. The bounds are
// proven on Bernstein coefficients (convex hull), refined by subdivision; a sampled check
// stands beside them.
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/kernel/segment.hpp>
#include <utility>
#include <vector>

namespace qmotion::kernel::between {

/// Bernstein coefficients of one piece (rows; 3 or 4 columns), held without the heap.
using Piece = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 26, 4>;

/// The Bernstein coefficients (rows) on [u0, u1] of the piece on span j (T[j] <= u < T[j + 1])
/// of the degree-p B-spline with control points P (rows): its blossom at (u0^(p-k), u1^k).
inline Piece bezier_piece(const std::vector<double>& T, int p, const Eigen::MatrixXd& P, int j,
                          double u0, double u1) {
  Piece B(p + 1, P.cols()), d(p + 1, P.cols());
  for (int k = 0; k <= p; ++k) {
    d = P.middleRows(j - p, p + 1);
    for (int r = 1; r <= p; ++r) {
      const double x = r <= p - k ? u0 : u1;  // the blossom is symmetric: any order
      for (int i = p; i >= r; --i) {
        const double lo = T[static_cast<std::size_t>(j - p + i)];
        const double hi = T[static_cast<std::size_t>(j + 1 + i - r)];
        const double a = hi > lo ? (x - lo) / (hi - lo) : 0.0;
        d.row(i) = (1 - a) * d.row(i - 1) + a * d.row(i);
      }
    }
    B.row(k) = d.row(p);
  }
  return B;
}

/// The largest of per-interval values and the interval where it is (0 for none).
inline std::pair<double, std::size_t> largest(const std::vector<double>& v) {
  const auto it = std::max_element(v.begin(), v.end());
  return it == v.end()
             ? std::pair<double, std::size_t>{0.0, 0}
             : std::pair<double, std::size_t>{*it, static_cast<std::size_t>(it - v.begin())};
}

/// de Casteljau at 1/2: the coefficients of the two halves.
inline std::pair<Piece, Piece> halves(const Piece& B) {
  const Eigen::Index n = B.rows();
  Piece left(n, B.cols()), right(n, B.cols()), w = B;
  for (Eigen::Index r = 0; r < n; ++r) {
    left.row(r) = w.row(0);
    right.row(n - 1 - r) = w.row(n - 1 - r);
    for (Eigen::Index i = 0; i + 1 < n - r; ++i) w.row(i) = 0.5 * (w.row(i) + w.row(i + 1));
  }
  return {left, right};
}

using kernel::point_segment_distance;

/// A bound of the distance of a curve piece (Bernstein coefficients B, rows in R^3) from the
/// segment [a, b]: the distance to a convex set is convex, so the largest at the
/// coefficients bounds it on the whole piece.
inline double position_bound(const Piece& B, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  double worst = 0;
  for (Eigen::Index k = 0; k < B.rows(); ++k)
    worst = std::max(worst, point_segment_distance(B.row(k).transpose(), a, b));
  return worst;
}

/// The great-circle arc from unit quaternion r0 to r1 (sign-consistent: r0 . r1 > 0), in the
/// frame e1 = r0, e2 across it in their plane; theta is the arc's length on S^3.
struct Arc {
  Eigen::Vector4d e1, e2, mid;
  double theta = 0;

  Arc(const Eigen::Vector4d& r0, const Eigen::Vector4d& r1) : e1(r0) {
    Eigen::Vector4d c = r1 - r0.dot(r1) * r0;
    if (c.norm() < 1e-300) {  // one rotation: any great circle through r0 serves
      c = Eigen::Vector4d::Unit(0);
      for (int i = 1; i < 4; ++i)
        if (std::abs(r0(i)) < std::abs(r0.dot(c))) c = Eigen::Vector4d::Unit(i);
      c -= r0.dot(c) * r0;
    }
    e2 = c.normalized();
    theta = std::atan2(std::max(0.0, r1.dot(e2)), r1.dot(e1));
    mid = std::cos(theta / 2) * e1 + std::sin(theta / 2) * e2;
  }
};

/// A bound, in degrees, of the rotation angle between the frames of a quaternion piece
/// (Bernstein coefficients B, rows w, x, y, z, not unit) and the nearest frame on the arc.
/// On S^3, the point q/|q| lies within asin(h / |q|) of the great circle (h: the part of q
/// across the arc's plane), at the circle's angle psi from e1; and the arc is within
/// max(0, -psi, psi - theta) of that along the circle. h <= the largest at the coefficients
/// (convexity), |q| >= the least q . mid at them (a linear bound), psi within the
/// coefficients' range when every coefficient lies in the half-plane about mid. The rotation
/// angle is twice the distance on S^3. Infinity when the piece is too wide to bound.
inline double angle_bound_deg(const Piece& B, const Arc& arc) {
  double h = 0, least = INFINITY, psi_lo = INFINITY, psi_hi = -INFINITY;
  for (Eigen::Index k = 0; k < B.rows(); ++k) {
    const Eigen::Vector4d c = B.row(k).transpose();
    const double x1 = c.dot(arc.e1), x2 = c.dot(arc.e2);
    h = std::max(h, (c - x1 * arc.e1 - x2 * arc.e2).norm());
    least = std::min(least, c.dot(arc.mid));
    const double psi = std::atan2(x2, x1);
    psi_lo = std::min(psi_lo, psi);
    psi_hi = std::max(psi_hi, psi);
  }
  if (!(least > 0) || !(h < least) || psi_hi - psi_lo > M_PI / 2) return INFINITY;
  const double along = std::max({0.0, -psi_lo, psi_hi - arc.theta});
  return 2 * (std::asin(h / least) + along) * 180 / M_PI;
}

/// Bounds on one piece, halved up to `depth` times while above `tol`; the largest over the
/// pieces that remain.
template <typename Bound>
double refined(const Piece& B, double tol, int depth, const Bound& bound) {
  const double b = bound(B);
  if (b <= tol || depth == 0) return b;
  const auto [l, r] = halves(B);
  return std::max(refined(l, tol, depth - 1, bound), refined(r, tol, depth - 1, bound));
}

/// The value at s in [0, 1] of the Bernstein coefficients B (de Casteljau).
inline Eigen::VectorXd bezier_value(const Piece& B, double s) {
  Piece w = B;
  for (Eigen::Index r = 1; r < B.rows(); ++r)
    for (Eigen::Index i = 0; i + r < B.rows(); ++i)
      w.row(i) = (1 - s) * w.row(i) + s * w.row(i + 1);
  return w.row(0).transpose();
}

/// The rotation angle, in degrees, between the frame of q (not unit) and the nearest frame on
/// the arc: twice the distance on S^3 from q / |q| to the arc.
inline double arc_angle_deg(const Eigen::Vector4d& q, const Arc& arc) {
  Eigen::Vector4d u = q.normalized();
  if (u.dot(arc.mid) < 0) u = -u;  // the same frame, on the arc's side
  const double x1 = u.dot(arc.e1), x2 = u.dot(arc.e2);
  const double psi = std::atan2(x2, x1);
  double d;
  if (psi >= 0 && psi <= arc.theta)
    d = std::asin(std::min(1.0, (u - x1 * arc.e1 - x2 * arc.e2).norm()));
  else
    d = std::acos(std::clamp(
        std::max(u.dot(arc.e1), std::cos(arc.theta) * x1 + std::sin(arc.theta) * x2), -1.0, 1.0));
  return 2 * d * 180 / M_PI;
}

/// The proven bounds of fit_between.hpp on every interval between neighbouring poses: the
/// origin's distance from the nearest of the segments i - 1, i, i + 1 of the polyline, the
/// rotation's angle from the nearest of the arcs i - 1, i, i + 1; each piece between knots
/// halved up to four times while above the tolerance. With `sampled`, also the largest
/// distances at 16 times per interval.
struct Bounds {
  std::vector<double> position, angle_deg;  ///< per interval
  double sampled_position = 0, sampled_angle_deg = 0;
};

/// The stream a fit follows: parameters, positions (n x 3), sign-consistent unit rotations
/// (n x 4, w x y z) and the tolerances.
struct Stream {
  const std::vector<double>& t;
  const Eigen::MatrixXd& S;
  const Eigen::MatrixXd& R;
  double tol, angle_tol_deg;
};

/// A fit's factors: Q_rot of degree k on knots Tr, the translation of degree l on Tt (control
/// points as rows), with the same interior knots.
struct Factors {
  const std::vector<double>& Tr;
  int k;
  const Eigen::MatrixXd& rot;
  const std::vector<double>& Tt;
  int l;
  const Eigen::MatrixXd& trans;
};

inline Bounds bounds(const Stream& d, const Factors& f, bool sampled = false) {
  const std::size_t n = d.t.size();
  Bounds out{std::vector<double>(n - 1, 0.0), std::vector<double>(n - 1, 0.0), 0, 0};
  auto point = [&](std::size_t i) -> Eigen::Vector3d {
    return d.S.row(static_cast<Eigen::Index>(i)).transpose();
  };
  auto unit = [&](std::size_t i) -> Eigen::Vector4d {
    return d.R.row(static_cast<Eigen::Index>(i)).transpose();
  };
  std::vector<Arc> arcs;
  for (std::size_t i = 0; i + 1 < n; ++i) arcs.emplace_back(unit(i), unit(i + 1));
  const auto& Tr = f.Tr;
  const auto& Tt = f.Tt;
  const int k = f.k, l = f.l;
  const int nr = static_cast<int>(Tr.size()) - k - 1, nt = static_cast<int>(Tt.size()) - l - 1;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const std::size_t j0 = i > 0 ? i - 1 : i, j1 = std::min(i + 1, n - 2);
    auto position = [&](const Piece& B) {
      double b = INFINITY;
      for (std::size_t j = j0; j <= j1; ++j)
        b = std::min(b, position_bound(B, point(j), point(j + 1)));
      return b;
    };
    auto angle = [&](const Piece& B) {
      double b = INFINITY;
      for (std::size_t j = j0; j <= j1; ++j) b = std::min(b, angle_bound_deg(B, arcs[j]));
      return b;
    };
    // The pieces of [t_i, t_i+1] between the knots (both factors share the interior knots).
    std::vector<double> cuts{d.t[i]};
    for (std::size_t q = static_cast<std::size_t>(k) + 1;
         q + static_cast<std::size_t>(k) + 1 < Tr.size(); ++q)
      if (Tr[q] > d.t[i] && Tr[q] < d.t[i + 1]) cuts.push_back(Tr[q]);
    cuts.push_back(d.t[i + 1]);
    for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
      const double u0 = cuts[c], u1 = cuts[c + 1], um = 0.5 * (u0 + u1);
      const auto P = bezier_piece(Tt, l, f.trans, knot_span(Tt, l, nt, um), u0, u1);
      const auto Q = bezier_piece(Tr, k, f.rot, knot_span(Tr, k, nr, um), u0, u1);
      out.position[i] = std::max(out.position[i], refined(P, d.tol, 4, position));
      out.angle_deg[i] = std::max(out.angle_deg[i], refined(Q, d.angle_tol_deg, 4, angle));
      if (!sampled) continue;
      for (int s = 0; s <= 16; ++s) {
        const double u = u0 + (u1 - u0) * s / 16.0;
        const Eigen::Vector3d x = bezier_value(P, (u - u0) / (u1 - u0));
        const Eigen::Vector4d q = bezier_value(Q, (u - u0) / (u1 - u0));
        double dp = INFINITY, da = INFINITY;
        for (std::size_t j = j0; j <= j1; ++j) {
          dp = std::min(dp, point_segment_distance(x, point(j), point(j + 1)));
          da = std::min(da, arc_angle_deg(q, arcs[j]));
        }
        out.sampled_position = std::max(out.sampled_position, dp);
        out.sampled_angle_deg = std::max(out.sampled_angle_deg, da);
      }
    }
  }
  return out;
}

}  // namespace qmotion::kernel::between
