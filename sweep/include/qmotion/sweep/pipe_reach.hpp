// <qmotion/sweep/pipe_reach.hpp>: a proof that a sphere's pipe does not overlap itself, so
// that its faces bound the swept volume (docs/geometry.md, "When a pipe bounds the sweep").
//
// The pipe of radius r around a regular C^1 path c, closed by its two half-sphere caps, is
// the boundary of the sweep { x : dist(x, c) <= r } exactly when r is below the path's
// reach: every point within r of the path then has one nearest point on it. The reach of a
// curve is the smaller of (Federer 1959; for curves, the thickness of Gonzalez and Maddocks
// 1999):
// - its least radius of curvature;
// - half the length of its shortest "critical" chord: a local minimum of
//   D(s1, s2) = |c(s2) - c(s1)|^2 over s1 < s2 that is not on the diagonal.
// So the proof has two parts, both on Bernstein coefficients of the rational path's pieces:
// - curvature: kappa = w^2 |v x v'| / |v|^3, with c = P / w and v = P' w - P w' (so that
//   c' = v / w^2), is bounded on a piece by the coefficients' extremes; r kappa < 1;
// - chords: every pair of pieces (I before J) is cleared by one of
//   - distance: the balls holding their control points are more than 2 r apart;
//   - monotony: D has no local minimum over I x J, because g1 = (c(s2) - c(s1)) . c'(s1) or
//     g2 = (c(s2) - c(s1)) . c'(s2) keeps a sign there that lets s1 or s2 move on while D
//     decreases (g1 > 0 or g2 > 0 always; g1 < 0 unless I holds the path's start, g2 < 0
//     unless J holds its end). Within a run of pieces whose tangents all lie within 45
//     degrees of the first's, and for two neighbouring pieces whose tangents are pairwise
//     within 90 degrees, g1 > 0: the chord is an integral of tangents at acute angles to
//     c'(s1).
//   Pairs that neither clears are halved, down to a limit; what is left is refused.
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <qmotion/kernel/bernstein.hpp>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/sweep/pipe.hpp>
#include <string>
#include <utility>
#include <vector>

namespace qmotion::sweep {

/// What pipe_overlap_free proved: the pieces of the path and the pairs of pieces it used, a
/// certified lower bound of the least radius of curvature, and beside it the least radius
/// of curvature at the pieces' middles (sampled).
using PipeReach = PipeShell::Reach;

namespace reach_detail {

using pipe_detail::Poly;

/// A piece of the path on [t0, t1]: its homogeneous Bezier form, the ball that holds its
/// control points (so the piece), and the cone that holds its tangents.
struct Arc {
  kernel::Bernstein<Eigen::Vector4d> H;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double cone = M_PI;       ///< half-angle of the tangents' cone about axis (pi: none found)
  double kappa = HUGE_VAL;  ///< an upper bound of the curvature on the piece
  double t0() const { return H.a(); }
  double t1() const { return H.b(); }
};

inline std::array<Poly, 3> hodograph(const kernel::Bernstein<Eigen::Vector4d>& H, Poly& w) {
  std::array<Poly, 3> P;
  w.clear();
  for (const auto& c : H.coeffs()) {
    w.push_back(c(0));
    for (int k = 0; k < 3; ++k) P[static_cast<std::size_t>(k)].push_back(c(k + 1));
  }
  std::array<Poly, 3> v;
  for (std::size_t k = 0; k < 3; ++k)
    v[k] = pipe_detail::add(pipe_detail::mul(pipe_detail::derivative(P[k]), w),
                            pipe_detail::mul(P[k], pipe_detail::derivative(w)), -1);
  return v;
}

/// The ball, the tangent cone and the curvature bound of a piece. The curvature bound is
/// w_max^2 max|v x v'| / (min d . v)^3 over the coefficients (d: the cone's axis), HUGE_VAL
/// when a weight or d . v is not positive.
inline Arc make_arc(kernel::Bernstein<Eigen::Vector4d> H) {
  Arc a;
  a.H = std::move(H);
  Eigen::AlignedBox3d box;
  double wmin = HUGE_VAL, wmax = 0;
  for (const auto& c : a.H.coeffs()) {
    wmin = std::min(wmin, c(0));
    wmax = std::max(wmax, c(0));
    if (c(0) > 0) box.extend(Eigen::Vector3d(c.tail<3>() / c(0)));
  }
  if (!(wmin > 0)) return a;  // radius 0, cone pi: the caller subdivides
  a.centre = box.center();
  for (const auto& c : a.H.coeffs())
    a.radius = std::max(a.radius, (Eigen::Vector3d(c.tail<3>() / c(0)) - a.centre).norm());
  a.radius *= 1 + 1e-12;
  Poly w;
  const auto v = hodograph(a.H, w);
  const Eigen::Vector3d mid = pipe_detail::eval3(v, 0.5);
  if (!(mid.norm() > 0)) return a;
  a.axis = mid.normalized();
  double cone = 0, vmin = HUGE_VAL;
  for (std::size_t i = 0; i < v[0].size(); ++i) {
    const Eigen::Vector3d vi(v[0][i], v[1][i], v[2][i]);
    const double along = a.axis.dot(vi);
    if (!(along > 0)) return a;
    vmin = std::min(vmin, along);
    cone = std::max(cone, std::acos(std::clamp(along / vi.norm(), -1.0, 1.0)));
  }
  a.cone = cone * (1 + 1e-9) + 1e-12;
  std::array<Poly, 3> dv;
  for (std::size_t k = 0; k < 3; ++k) dv[k] = pipe_detail::derivative(v[k]);
  std::array<Poly, 3> X;  // v x v'
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t i = (k + 1) % 3, j = (k + 2) % 3;
    X[k] = pipe_detail::add(pipe_detail::mul(v[i], dv[j]), pipe_detail::mul(v[j], dv[i]), -1);
  }
  double xmax = 0;
  for (std::size_t i = 0; i < X[0].size(); ++i)
    xmax = std::max(xmax, Eigen::Vector3d(X[0][i], X[1][i], X[2][i]).norm());
  a.kappa = wmax * wmax * xmax / (vmin * vmin * vmin) * (1 + 1e-9);
  return a;
}

/// The curvature at the piece's middle (a sample, for the messages and the report).
inline double kappa_at_middle(const Arc& a) {
  Poly w;
  const auto v = hodograph(a.H, w);
  std::array<Poly, 3> dv;
  for (std::size_t k = 0; k < 3; ++k) dv[k] = pipe_detail::derivative(v[k]);
  const Eigen::Vector3d x = pipe_detail::eval3(v, 0.5), y = pipe_detail::eval3(dv, 0.5);
  const double ww = pipe_detail::evaluate(w, 0.5);
  return ww * ww * x.cross(y).norm() / std::pow(x.norm(), 3);
}

inline std::pair<Arc, Arc> halves(const Arc& a) {
  auto [l, r] = kernel::subdivide(a.H, 0.5 * (a.t0() + a.t1()));
  return {make_arc(std::move(l)), make_arc(std::move(r))};
}

/// Whether D = |c(s2) - c(s1)|^2 has no local minimum with s1 in I, s2 in J (I before J):
/// see the file's comment. The chords lie in the ball about J's centre less I's, of
/// radius the sum of theirs; a tangent of I lies within I's cone of its axis.
inline bool monotone(const Arc& I, const Arc& J, bool I_has_start, bool J_has_end) {
  const Eigen::Vector3d m = J.centre - I.centre;
  const double rho = I.radius + J.radius, len = m.norm();
  if (!(len > rho)) return false;
  const double spread = std::asin(std::min(1.0, rho / len));
  // The sign of chord . tangent over the box: +1, -1, or 0 when it may vanish.
  auto sign = [&](const Arc& A) {
    const double angle = std::acos(std::clamp(m.dot(A.axis) / len, -1.0, 1.0));
    const double margin = 1e-9;
    if (angle + spread + A.cone < M_PI / 2 - margin) return 1;
    if (angle - spread - A.cone > M_PI / 2 + margin) return -1;
    return 0;
  };
  const int g1 = sign(I), g2 = sign(J);
  return g1 > 0 || g2 > 0 || (g1 < 0 && !I_has_start) || (g2 < 0 && !J_has_end);
}

}  // namespace reach_detail

/// Proves that the pipe of radius r around the rational path `centre` (homogeneous control
/// points (w, w x, w y, w z)) does not overlap itself (see the file's comment), or throws
/// Errc::invalid_input naming where on the path it does, or where the proof could not
/// decide: r above the radius of curvature near t, or the path near t = a coming back
/// within 2 r of itself near t = b. `where` names the path in messages. The path must be
/// regular and tangent-continuous (pipe_shell refuses it otherwise).
inline PipeReach pipe_overlap_free(const kernel::BSpline<Eigen::Vector4d>& centre, double r,
                                   const std::string& where) {
  using namespace reach_detail;
  using kernel::detail::format_double;
  PipeReach out;
  const double a0 = centre.a(), b0 = centre.b();
  const double range = b0 - a0;
  // Pieces whose tangents lie in a 20-degree cone and whose curvature is proven below 1/r.
  std::vector<Arc> arcs;
  std::vector<std::pair<Arc, int>> stack;
  const auto spans = kernel::bezier_pieces(centre);
  for (auto it = spans.rbegin(); it != spans.rend(); ++it) stack.emplace_back(make_arc(*it), 0);
  out.sampled_min_radius = HUGE_VAL;
  double kappa = 0;
  while (!stack.empty()) {
    auto [arc, depth] = std::move(stack.back());
    stack.pop_back();
    if (arc.cone <= 20 * M_PI / 180 && arc.kappa * r < 1) {
      kappa = std::max(kappa, arc.kappa);
      out.sampled_min_radius = std::min(out.sampled_min_radius, 1 / kappa_at_middle(arc));
      arcs.push_back(std::move(arc));
      continue;
    }
    const double tm = 0.5 * (arc.t0() + arc.t1());
    const double k = kappa_at_middle(arc);
    if (k * r >= 1)
      throw Error(Errc::invalid_input,
                  where + ": the pipe of radius " + format_double(r) +
                      " overlaps itself: the path's radius of curvature near t = " +
                      format_double(tm) + " is " + format_double(1 / k) +
                      ", below the radius; the faces would not bound the swept volume (write a "
                      "mesh: .stl, .obj, .ply)");
    if (depth >= 30 || arc.t1() - arc.t0() < 1e-12 * range)
      throw Error(Errc::invalid_input,
                  where + ": cannot prove that the pipe of radius " + format_double(r) +
                      " does not overlap itself near t = " + format_double(tm) +
                      " (its radius of curvature there is " + format_double(1 / k) +
                      "); write a mesh: .stl, .obj, .ply");
    auto [l, rr] = halves(arc);
    stack.emplace_back(std::move(rr), depth + 1);
    stack.emplace_back(std::move(l), depth + 1);
  }
  out.curvature_radius = kappa > 0 ? 1 / kappa : HUGE_VAL;
  out.pieces = arcs.size();
  // Chords. run[i]: the last piece j such that every tangent of i..j lies within 45 degrees
  // of i's axis (then g1 > 0 for every pair in i..j).
  const std::size_t n = arcs.size();
  const double two_r = 2 * r * (1 + 1e-12);
  auto angle = [](const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
    return std::acos(std::clamp(x.dot(y), -1.0, 1.0));
  };
  // The balls about two pieces' control points are more than 2 r apart.
  auto apart = [&](const Arc& I, const Arc& J) {
    return (I.centre - J.centre).norm() - I.radius - J.radius > two_r;
  };
  std::vector<std::pair<Arc, Arc>> pairs;
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t j = i + 1;
    while (j < n && angle(arcs[i].axis, arcs[j].axis) + arcs[j].cone < M_PI / 4 - 1e-9) ++j;
    for (; j < n; ++j) {
      if (apart(arcs[i], arcs[j])) {  // most pairs: no copies of the pieces
        ++out.pairs;
        continue;
      }
      pairs.assign(1, {arcs[i], arcs[j]});
      int splits = 0;
      while (!pairs.empty()) {
        auto [I, J] = std::move(pairs.back());
        pairs.pop_back();
        ++out.pairs;
        if (apart(I, J)) continue;
        // Neighbours whose tangents are pairwise within 90 degrees: g1 > 0 (the chord is the
        // integral of tangents that each make an acute angle with c'(s1)).
        if (I.t1() == J.t0() && 2 * I.cone < M_PI / 2 - 1e-9 &&
            angle(I.axis, J.axis) + I.cone + J.cone < M_PI / 2 - 1e-9)
          continue;
        const bool I_start = I.t0() <= a0, J_end = J.t1() >= b0;
        if (monotone(I, J, I_start, J_end)) continue;
        if (++splits > 200000 || std::max(I.radius, J.radius) < 1e-9 * r) {
          const double s1 = 0.5 * (I.t0() + I.t1()), s2 = 0.5 * (J.t0() + J.t1());
          const double d = (I.centre - J.centre).norm();
          throw Error(Errc::invalid_input,
                      where + ": the pipe of radius " + format_double(r) +
                          (d < two_r ? " overlaps itself" : " may overlap itself") +
                          ": the path near t = " + format_double(s1) + " comes back within " +
                          format_double(d) + " of itself near t = " + format_double(s2) +
                          " (twice the radius is " + format_double(2 * r) +
                          "); the faces would not bound the swept volume (write a mesh: .stl, "
                          ".obj, .ply)");
        }
        // Halve the larger piece.
        if (I.radius >= J.radius) {
          auto [l, rr] = halves(I);
          pairs.emplace_back(std::move(l), J);
          pairs.emplace_back(std::move(rr), std::move(J));
        } else {
          auto [l, rr] = halves(J);
          pairs.emplace_back(I, std::move(l));
          pairs.emplace_back(std::move(I), std::move(rr));
        }
      }
    }
  }
  return out;
}

}  // namespace qmotion::sweep
