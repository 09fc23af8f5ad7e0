// <qmotion/sweep/pipe.hpp>: the exact surface a sphere sweeps along a rational path: the
// pipe (tubular) surface around the centre's trajectory and its two half-sphere caps, as
// rational tensor-product faces (docs/geometry.md, "Exact pipe surfaces").
#pragma once
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <qmotion/kernel/bernstein.hpp>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/pipe_poly.hpp>
#include <qmotion/sweep/shell.hpp>
#include <qmotion/sweep/solid.hpp>
#include <string>
#include <type_traits>
#include <vector>

namespace qmotion::sweep {

/// The pipe of radius r around a path, closed by its end caps: every face point lies at
/// distance r from the path's point at the face's u = t (pipe faces) or from its end point
/// (caps), up to rounding.
struct PipeShell {
  NurbsShell<double> shell;     ///< pipe faces first (by piece, then arc), then the caps
  std::size_t pipe_faces = 0;   ///< the rest are caps: 4 at the start, then 4 at the end
  int degree_t = 0;             ///< the highest degree of the pipe faces along t
  std::size_t pieces = 0;       ///< parameter pieces of the path (its spans, subdivided)
  double orthogonality = 0;     ///< largest |(n . c')| / |c'| at the sampled points: rounding
  double radius_deviation = 0;  ///< largest ||X - c(t)| - r| / r at the sampled face points
  double volume = 0;            ///< enclosed, by Gauss-Legendre on every face (measured)
  /// Set by pipe_overlap_free (pipe_reach.hpp): the proof that the pipe does not overlap
  /// itself. pieces == 0: not proven.
  struct Reach {
    std::size_t pieces = 0, pairs = 0;
    double curvature_radius = 0, sampled_min_radius = 0;
  } reach;
};

namespace pipe_detail {

/// A parameter piece of the path: its homogeneous Bezier form on [t0, t1] and the pipe's
/// ingredients there. The stereographic pole moves: q(u) = (1 - u) + u q1 turns the frame
/// G (whose third axis is the unit tangent at t0) about one axis onto the frame whose third
/// axis is the unit tangent at t1, so both ends project from the tangent itself.
struct Piece {
  double t0 = 0, t1 = 1;
  std::vector<Eigen::Vector4d> H;  // (w, w x, w y, w z), Bernstein on [0, 1]
  Poly w;
  std::array<Poly, 3> P;
  std::array<Poly, 3> v;                 // direction of c': P' w - P w', global axes
  Eigen::Matrix3d G;                     // frame at t0: columns e1, e2, unit tangent
  Eigen::Quaterniond q1;                 // the turn from the frame at t0 to the frame at t1
  std::array<std::array<Poly, 3>, 3> R;  // |q|^2 times q's rotation (degree 2)
  Poly qq;                               // |q(u)|^2
  std::array<Poly, 3> vl;                // R^T G^T v: v in the moving frame (times |q|^2)
  Poly V, W2;                            // |vl|^2 = |q|^4 |v|^2, vl1^2 + vl2^2
  Poly Vv;                               // |v|^2
  CPoly h;                               // |h|^2 = V
};

inline void split_H(Piece& p) {
  p.w.clear();
  for (auto& c : p.P) c.clear();
  for (const auto& c : p.H) {
    p.w.push_back(c(0));
    for (int k = 0; k < 3; ++k) p.P[static_cast<std::size_t>(k)].push_back(c(k + 1));
  }
}

inline Eigen::Vector3d eval3(const std::array<Poly, 3>& a, double u) {
  return {evaluate(a[0], u), evaluate(a[1], u), evaluate(a[2], u)};
}

/// The polynomial e . v.
inline Poly along(const std::array<Poly, 3>& v, const Eigen::Vector3d& e) {
  Poly r(v[0].size(), 0.0);
  for (std::size_t k = 0; k < 3; ++k) r = add(r, v[k], e(static_cast<Eigen::Index>(k)));
  return r;
}

/// c' numerator of the piece: P' w - P w', at its true degree.
inline void prepare(Piece& p) {
  split_H(p);
  for (int k = 0; k < 3; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    p.v[kk] = add(mul(derivative(p.P[kk]), p.w), mul(p.P[kk], derivative(p.w)), -1);
  }
  // deg w = deg P: the top terms of P' w and P w' cancel (exactly, up to rounding).
  const bool cancel = p.w.size() > 1;
  std::size_t deg = 0;
  for (auto& c : p.v) {
    if (cancel && c.size() > 1) {
      kernel::Bernstein<double> red;
      if (kernel::detail::reduce_once(kernel::Bernstein<double>(c), 1e-7, red)) c = red.coeffs();
    }
    c = true_degree(c);
    deg = std::max(deg, c.size() - 1);
  }
  for (auto& c : p.v) c = elevate_to(c, deg);
}

/// The moving frame of the piece from its frame G at t0 (third axis the unit tangent there).
/// False when the tangent leaves the 30-degree cone around the moving pole (certified on the
/// Bernstein coefficients of vl3 and of vl3^2 - cos^2(30 deg) |vl|^2): subdivide.
inline bool frame(Piece& p, const Eigen::Matrix3d& G) {
  p.G = G;
  const Eigen::Vector3d a = G.transpose() * eval3(p.v, 1).normalized();
  p.q1 = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), a);
  const std::array<double, 4> q0{1, 0, 0, 0}, qe{p.q1.w(), p.q1.x(), p.q1.y(), p.q1.z()};
  std::array<Poly, 4> q;
  for (std::size_t i = 0; i < 4; ++i) q[i] = {q0[i], qe[i]};
  const auto& [qw, qx, qy, qz] = q;
  auto sq = [](const Poly& x) { return mul(x, x); };
  auto two = [](const Poly& x, const Poly& y) { return add(mul(x, y), mul(x, y)); };
  p.qq = add(add(sq(qw), sq(qx)), add(sq(qy), sq(qz)));
  p.R[0] = {add(add(sq(qw), sq(qx)), add(sq(qy), sq(qz)), -1), add(two(qx, qy), two(qw, qz), -1),
            add(two(qx, qz), two(qw, qy))};
  p.R[1] = {add(two(qx, qy), two(qw, qz)), add(add(sq(qw), sq(qy)), add(sq(qx), sq(qz)), -1),
            add(two(qy, qz), two(qw, qx), -1)};
  p.R[2] = {add(two(qx, qz), two(qw, qy), -1), add(two(qy, qz), two(qw, qx)),
            add(add(sq(qw), sq(qz)), add(sq(qx), sq(qy)), -1)};
  std::array<Poly, 3> vg;  // G^T v
  for (std::size_t i = 0; i < 3; ++i) vg[i] = along(p.v, G.col(static_cast<Eigen::Index>(i)));
  for (std::size_t i = 0; i < 3; ++i) {  // (R^T vg)_i = sum_j R_ji vg_j
    Poly s = mul(p.R[0][i], vg[0]);
    s = add(s, mul(p.R[1][i], vg[1]));
    p.vl[i] = add(s, mul(p.R[2][i], vg[2]));
  }
  p.Vv = add(add(mul(p.v[0], p.v[0]), mul(p.v[1], p.v[1])), mul(p.v[2], p.v[2]));
  p.W2 = add(mul(p.vl[0], p.vl[0]), mul(p.vl[1], p.vl[1]));
  p.V = add(p.W2, mul(p.vl[2], p.vl[2]));
  for (double c : p.vl[2])
    if (!(c > 0)) return false;
  const double c2 = std::pow(std::cos(30.0 * M_PI / 180), 2);
  for (double c : add(mul(p.vl[2], p.vl[2]), p.V, -c2))
    if (!(c > 0)) return false;
  return true;
}

/// The frame at the piece's end (the next piece's G).
inline Eigen::Matrix3d end_frame(const Piece& p) { return p.G * p.q1.toRotationMatrix(); }

inline Eigen::Matrix3d rotation_at(const Piece& p, double u) {
  Eigen::Matrix3d M;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      M(i, j) = evaluate(p.R[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)], u);
  return p.G * M / evaluate(p.qq, u);
}

/// The unit normal at (u, z) of the pipe's circle: the inverse stereographic image, from the
/// moving pole, of the plane circle h z^2 / |z|^2 (docs/geometry.md).
inline Eigen::Vector3d normal_at(const Piece& p, double u, Cx z) {
  const Eigen::Vector3d v = eval3(p.vl, u);
  const Cx xi = evaluate(p.h, u) * z * z / std::norm(z);
  const double x = (xi.real() - v(0)) / v(2), y = (xi.imag() - v(1)) / v(2), q = x * x + y * y;
  return rotation_at(p, u) * Eigen::Vector3d(2 * x, 2 * y, q - 1) / (q + 1);
}

/// Homogeneous tensor-product Bezier patch: c[i][j] = (weight, weighted point), i along t.
using Patch = std::vector<std::vector<Eigen::Vector4d>>;

/// The circle's homogeneous pieces along s for arc j: the s-factors of the normal.
struct ArcFactors {
  Poly re, im, norm;  // Re z^2, Im z^2, |z|^2 (degree 2 in s)
};

inline ArcFactors arc_factors(double a, double b) {
  const CPoly z{std::polar(1.0, a), std::polar(1.0, b)};
  const CPoly z2 = mul(z, z);
  const CPoly zz = mul(z, conj(z));
  return {real(z2), imag(z2), real(zz)};
}

/// t-factor x s-factor sums: out[i][j] += T[i] S[j] (T elevated to `dt`).
inline void accumulate(std::vector<std::vector<double>>& out, const Poly& T, const Poly& S,
                       double f) {
  const Poly Te = elevate_to(T, out.size() - 1);
  for (std::size_t i = 0; i < out.size(); ++i)
    for (std::size_t j = 0; j < S.size(); ++j) out[i][j] += f * Te[i] * S[j];
}

/// The pipe patch of arc [a, b] over the piece: with the s-factors of z and the t-factors
/// of the piece, n = G R (v3 A, v3 B, W2 |z|^2 - Re(g z^2)) / (|q|^2 (V |z|^2 - Re(g z^2))),
/// A + i B = h z^2 - (v1 + i v2) |z|^2, g = h (v1 - i v2).
inline Patch pipe_patch(const Piece& p, double a, double b, double r) {
  const ArcFactors s = arc_factors(a, b);
  const Poly &v1 = p.vl[0], &v2 = p.vl[1], &v3 = p.vl[2];
  const CPoly v3h = mul(to_complex(v3), p.h);
  CPoly om(v1.size());
  for (std::size_t i = 0; i < om.size(); ++i) om[i] = Cx(v1[i], -v2[i]);
  const CPoly g = mul(p.h, om);
  const Poly v3v1 = mul(v3, v1), v3v2 = mul(v3, v2);
  const std::size_t dn = p.V.size() - 1;
  auto grid = [&] { return std::vector<std::vector<double>>(dn + 1, std::vector<double>(3, 0.0)); };
  auto N1 = grid(), N2 = grid(), N3 = grid(), D = grid();
  accumulate(N1, real(v3h), s.re, 1);
  accumulate(N1, imag(v3h), s.im, -1);
  accumulate(N1, v3v1, s.norm, -1);
  accumulate(N2, real(v3h), s.im, 1);
  accumulate(N2, imag(v3h), s.re, 1);
  accumulate(N2, v3v2, s.norm, -1);
  // With |h|^2 in place of V where the identity |h|^2 = V was used, |n| = 1 holds for
  // any h; only n . c' = 0 rests on the factorisation (and its error enters the distance
  // to the path squared).
  const Poly hh = real(mul(p.h, conj(p.h)));
  accumulate(N3, add(hh, add(p.W2, mul(v3, v3), -1)), s.norm, 0.5);
  accumulate(N3, real(g), s.re, -1);
  accumulate(N3, imag(g), s.im, 1);
  accumulate(D, add(hh, p.V), s.norm, 0.5);
  accumulate(D, real(g), s.re, -1);
  accumulate(D, imag(g), s.im, 1);
  // M = G R (degree 2); weight w |q|^2 D, numerator P |q|^2 D + r w M N.
  std::array<std::array<Poly, 3>, 3> M;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) {
      Poly e(3, 0.0);
      for (std::size_t k = 0; k < 3; ++k)
        e = add(e, p.R[k][j], p.G(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)));
      M[i][j] = e;
    }
  const Poly wq = mul(p.w, p.qq);
  const std::size_t dt = p.w.size() - 1 + 2 + dn;
  Patch out(dt + 1, std::vector<Eigen::Vector4d>(3, Eigen::Vector4d::Zero()));
  for (std::size_t j = 0; j < 3; ++j) {
    std::array<Poly, 3> n;
    Poly Dj;
    for (std::size_t i = 0; i <= dn; ++i) {
      Dj.push_back(D[i][j]);
      n[0].push_back(N1[i][j]);
      n[1].push_back(N2[i][j]);
      n[2].push_back(N3[i][j]);
    }
    const Poly W = mul(wq, Dj);
    std::array<Poly, 3> X;
    for (std::size_t k = 0; k < 3; ++k) {
      Poly Mn = mul(M[k][0], n[0]);
      Mn = add(add(Mn, mul(M[k][1], n[1])), mul(M[k][2], n[2]));
      X[k] = add(mul(p.P[k], mul(p.qq, Dj)), mul(p.w, Mn), r);
    }
    for (std::size_t i = 0; i <= dt; ++i)
      out[i][j] = Eigen::Vector4d(W[i], X[0][i], X[1][i], X[2][i]);
  }
  return out;
}

/// The patch as NURBS faces on t in [t0, t1], s in [s0, s0 + 1], split along t until every
/// weight is positive (exact: de Casteljau).
inline void emit(const Patch& c, double t0, double t1, double s0,
                 std::vector<NurbsSurface<double>>& out, const std::string& where, int depth = 0) {
  double wmax = 0, wmin = HUGE_VAL;
  for (const auto& row : c)
    for (const auto& x : row) {
      wmax = std::max(wmax, x(0));
      wmin = std::min(wmin, x(0));
    }
  if (!(wmin > 1e-12 * wmax)) {
    if (depth >= 8)
      throw Error(
          Errc::numerical_failure,
          where + ": a pipe face's weights stay non-positive near t = " + std::to_string(t0));
    const std::size_t n = c.size() - 1;
    Patch left = c, right = c;
    for (std::size_t j = 0; j < c.front().size(); ++j) {
      std::vector<Eigen::Vector4d> col;
      for (const auto& row : c) col.push_back(row[j]);
      for (std::size_t r = 1; r <= n; ++r) {
        for (std::size_t i = 0; i + r <= n; ++i) col[i] = 0.5 * (col[i] + col[i + 1]);
        left[r][j] = col[0];
        right[n - r][j] = col[n - r];
      }
      left[0][j] = c[0][j];
      right[n][j] = c[n][j];
    }
    const double tm = 0.5 * (t0 + t1);
    emit(left, t0, tm, s0, out, where, depth + 1);
    emit(right, tm, t1, s0, out, where, depth + 1);
    return;
  }
  NurbsSurface<double> f;
  f.degree_u = static_cast<int>(c.size()) - 1;
  f.degree_v = static_cast<int>(c.front().size()) - 1;
  f.knots_u.assign(c.size(), t0);
  f.knots_u.insert(f.knots_u.end(), c.size(), t1);
  f.knots_v.assign(c.front().size(), s0);
  f.knots_v.insert(f.knots_v.end(), c.front().size(), s0 + 1);
  for (const auto& row : c) {
    std::vector<Eigen::Vector3d> pts;
    std::vector<double> ws;
    for (const auto& x : row) {
      pts.push_back(x.tail<3>() / x(0));
      ws.push_back(x(0) / wmax);
    }
    f.points.push_back(std::move(pts));
    f.weights.push_back(std::move(ws));
  }
  out.push_back(std::move(f));
}

/// A half-sphere cap over one arc of the piece's circle at u (0: start, 1: end): the circle's
/// row (`ring`, as the pipe face has it) swept by a rational quarter circle to the pole
/// c -/+ r t (t the unit tangent), u along the meridian, v along the arc.
inline NurbsSurface<double> cap(const Piece& p, const std::vector<Eigen::Vector4d>& ring, double u,
                                double r, double s0) {
  const Eigen::Vector4d H = evaluate(p.H, u);
  const Eigen::Vector3d c = H.tail<3>() / H(0);
  const Eigen::Vector3d t = eval3(p.v, u).normalized() * (u == 0 ? -1.0 : 1.0);
  const double q = std::sqrt(0.5);
  const double om[3] = {1, q, 1}, al[3] = {1, q, 0}, be[3] = {0, q, 1};
  NurbsSurface<double> f;
  f.degree_u = 2;
  f.degree_v = 2;
  f.knots_u = {0, 0, 0, 1, 1, 1};
  f.knots_v = {s0, s0, s0, s0 + 1, s0 + 1, s0 + 1};
  double wmax = 0;
  for (const auto& x : ring) wmax = std::max(wmax, x(0));
  for (int k = 0; k < 3; ++k) {
    std::vector<Eigen::Vector3d> pts;
    std::vector<double> ws;
    for (const auto& x : ring) {
      const double Dj = x(0);
      const Eigen::Vector3d Nj = (x.tail<3>() - Dj * c) / r;  // = D n, |Nj| = Dj
      const double W = Dj * om[k];
      const Eigen::Vector3d X = W * c + r * (al[k] * Nj + be[k] * Dj * t);
      pts.push_back(X / W);
      ws.push_back(W / wmax);
    }
    f.points.push_back(std::move(pts));
    f.weights.push_back(std::move(ws));
  }
  return f;
}

/// Point and first partial derivatives of a single-span (Bezier) NURBS face at (u, v) in
/// its own knot ranges.
inline void face_derivs(const NurbsSurface<double>& f, double u, double v, Eigen::Vector3d& X,
                        Eigen::Vector3d& Xu, Eigen::Vector3d& Xv) {
  const double u0 = f.knots_u.front(), u1 = f.knots_u.back(), v0 = f.knots_v.front(),
               v1 = f.knots_v.back();
  const double a = (u - u0) / (u1 - u0), b = (v - v0) / (v1 - v0);
  // Bernstein values of degree n and n - 1 from tables of powers and binomials (std::pow
  // here took most of the shell's time).
  auto basis = [](int n, double x, std::vector<double>& B, std::vector<double>& dB) {
    const auto m = static_cast<std::size_t>(n);
    std::vector<double> xp(m + 1, 1.0), yp(m + 1, 1.0), C(m + 1, 1.0), Cm(m + 1, 1.0);
    for (std::size_t k = 1; k <= m; ++k) {
      xp[k] = xp[k - 1] * x;
      yp[k] = yp[k - 1] * (1 - x);
    }
    for (std::size_t k = 1; k <= m; ++k) {  // C(n, k) and C(n - 1, k)
      C[k] = C[k - 1] * static_cast<double>(m + 1 - k) / static_cast<double>(k);
      Cm[k] = k < m ? Cm[k - 1] * static_cast<double>(m - k) / static_cast<double>(k) : 0.0;
    }
    B.assign(m + 1, 0.0);
    dB.assign(m + 1, 0.0);
    for (std::size_t i = 0; i <= m; ++i) B[i] = C[i] * xp[i] * yp[m - i];
    for (std::size_t i = 0; i <= m; ++i) {
      const double lo = i > 0 ? Cm[i - 1] * xp[i - 1] * yp[m - i] : 0.0;
      const double hi = i < m ? Cm[i] * xp[i] * yp[m - 1 - i] : 0.0;
      dB[i] = n * (lo - hi);
    }
  };
  std::vector<double> Bu, dBu, Bv, dBv;
  basis(f.degree_u, a, Bu, dBu);
  basis(f.degree_v, b, Bv, dBv);
  Eigen::Vector4d H = Eigen::Vector4d::Zero(), Hu = H, Hv = H;
  for (std::size_t i = 0; i < f.points.size(); ++i)
    for (std::size_t j = 0; j < f.points[i].size(); ++j) {
      const double w = f.weights[i][j];
      const Eigen::Vector4d c(w, w * f.points[i][j](0), w * f.points[i][j](1),
                              w * f.points[i][j](2));
      H += Bu[i] * Bv[j] * c;
      Hu += dBu[i] * Bv[j] * c;
      Hv += Bu[i] * dBv[j] * c;
    }
  X = H.tail<3>() / H(0);
  Xu = (Hu.tail<3>() - X * Hu(0)) / H(0) / (u1 - u0);
  Xv = (Hv.tail<3>() - X * Hv(0)) / H(0) / (v1 - v0);
}

/// Calls fn(u, X, Xu, Xv, w) at the 24 x 24 Gauss-Legendre points of a single-span face: X
/// and its partial derivatives at (u, v), and w the point's weight in the face's parameter
/// area (so that sum w (X - o) . (Xu x Xv) / 3 is the face's part of an enclosed volume).
template <typename F>
void gauss_points(const NurbsSurface<double>& f, F&& fn) {
  const double u0 = f.knots_u.front(), u1 = f.knots_u.back(), v0 = f.knots_v.front(),
               v1 = f.knots_v.back();
  Eigen::Vector3d X, Xu, Xv;
  for (const auto& [x, wx] : detail::gauss_legendre())
    for (const auto& [y, wy] : detail::gauss_legendre()) {
      const double u = 0.5 * (u0 + u1) + 0.5 * (u1 - u0) * x;
      face_derivs(f, u, 0.5 * (v0 + v1) + 0.5 * (v1 - v0) * y, X, Xu, Xv);
      fn(u, X, Xu, Xv, wx * wy * 0.25 * (u1 - u0) * (v1 - v0));
    }
}

}  // namespace pipe_detail

namespace pipe_detail {

/// h for the piece: |h|^2 = |q|^4 |v|^2, so h = c^2 h_v with |c|^2 = |q|^2 (its roots by the
/// quadratic formula) and |h_v|^2 = |v|^2 (V's roots are double at |q|^2's: kept out of the
/// solver). At the ends the pole is the tangent, and n is across it exactly when |h| = |v_l|
/// there: the end coefficients (h's values there) are set to that modulus, so the shared
/// circles and the caps stand square to the path whatever the factorisation's rounding.
inline void factor_h(Piece& p, const std::string& where) {
  const Poly& a = p.qq;  // Bernstein on [0, 1] -> power: a0 + a1 u + a2 u^2
  const double c0 = a[0], c1 = 2 * (a[1] - a[0]), c2 = a[0] - 2 * a[1] + a[2];
  CPoly c{Cx(std::sqrt(c0))};
  if (c2 > 1e-15 * c0) {
    const Cx root = (-c1 + std::sqrt(Cx(c1 * c1 - 4 * c2 * c0))) / (2 * c2);
    const Cx z = root.imag() >= 0 ? root : std::conj(root);
    c = mul(CPoly{Cx(std::sqrt(c2))}, CPoly{-z, Cx(1) - z});
  }
  p.h = mul(mul(c, c), sqrt_sum_of_squares(p.Vv, where));
  p.h.front() *= std::sqrt(p.V.front()) / std::abs(p.h.front());
  p.h.back() *= std::sqrt(p.V.back()) / std::abs(p.h.back());
}

/// Every face of the closed pipe turned outward (X_u x X_v away from the centre of its
/// sphere), its radius deviation sampled, and the enclosed volume (1/3) sum of the integrals
/// of (X - o) . dA (Gauss points).
inline void orient_and_measure(PipeShell& out, const kernel::BSpline<Eigen::Vector4d>& centre,
                               double r) {
  constexpr std::size_t A = 4;  // faces per piece, caps per end
  const Eigen::Vector4d ha = kernel::evaluate(centre, centre.a()),
                        hb = kernel::evaluate(centre, centre.b());
  const Eigen::Vector3d ca = ha.tail<3>() / ha(0), cb = hb.tail<3>() / hb(0);
  auto centre_of = [&](std::size_t k, double u) -> Eigen::Vector3d {
    if (k >= out.pipe_faces) return k < out.pipe_faces + A ? ca : cb;
    const Eigen::Vector4d y = kernel::evaluate(centre, u);
    return y.tail<3>() / y(0);
  };
  for (std::size_t k = 0; k < out.shell.faces.size(); ++k) {
    auto& f = out.shell.faces[k];
    Eigen::Vector3d X, Xu, Xv;
    const double um = 0.5 * (f.knots_u.front() + f.knots_u.back());
    face_derivs(f, um, 0.5 * (f.knots_v.front() + f.knots_v.back()), X, Xu, Xv);
    if (Xu.cross(Xv).dot(X - centre_of(k, um)) < 0) {
      for (auto& row : f.points) std::reverse(row.begin(), row.end());
      for (auto& row : f.weights) std::reverse(row.begin(), row.end());
    }
    gauss_points(f, [&](double u, const Eigen::Vector3d& Y, const Eigen::Vector3d& Yu,
                        const Eigen::Vector3d& Yv, double w) {
      out.volume += w * (Y - ca).dot(Yu.cross(Yv)) / 3;
      out.radius_deviation =
          std::max(out.radius_deviation, std::abs((Y - centre_of(k, u)).norm() - r) / r);
    });
  }
}

}  // namespace pipe_detail

/// The exact pipe of radius r around the homogeneous path `centre` (w, w x, w y, w z) with
/// its two half-sphere caps, as a closed shell of rational faces:
/// - each span of the path, subdivided until c' stays within 30 degrees of one direction p,
///   gives 4 faces, one per arc of the circle. The unit normal n(t, z) is the inverse
///   stereographic image, from p, of the circle h(t) z^2 / |z|^2 of the plane, where
///   |h|^2 = |v|^2 for v the numerator of c' (a sum of two squares on the real line):
///   n . c' = 0 and |n| = 1 identically, so c + r n is the envelope of the spheres;
/// - faces meet along shared circles: each piece's arc ends are where the previous piece's
///   were at their common t;
/// - degree along t: m + 2 d_v (m the path's, d_v that of c' 's numerator), 2 along s.
/// Errc::invalid_input for a path with a corner (c' turns at a knot) and r <= 0;
/// Errc::numerical_failure when c' vanishes (a cusp) or the factorisation loses accuracy.
inline PipeShell pipe_shell(const kernel::BSpline<Eigen::Vector4d>& centre, double r,
                            const std::string& where) {
  using namespace pipe_detail;
  if (!(r > 0) || !std::isfinite(r))
    throw Error(Errc::invalid_input, where + ": the pipe's radius must be positive");
  std::vector<Piece> todo;
  for (const auto& b : kernel::bezier_pieces(centre)) {
    const auto red = kernel::reduce_degree(b, 1e-13);
    Piece p;
    p.t0 = red.a();
    p.t1 = red.b();
    p.H = red.coeffs();
    todo.push_back(std::move(p));
  }
  PipeShell out;
  constexpr int A = 4;
  std::vector<double> phi;
  for (int j = 0; j <= A; ++j) phi.push_back(j * M_PI / A);
  // Pieces in order, each subdivided until its tangent stays in the 30-degree cone around
  // the moving pole; the frame and the phase of h carry over from one piece to the next.
  std::vector<std::pair<Piece, int>> stack;
  for (auto it = todo.rbegin(); it != todo.rend(); ++it) stack.emplace_back(std::move(*it), 0);
  Eigen::Matrix3d G;
  Cx phase(0);  // unit h / |h| at the previous piece's end
  Eigen::Vector3d last_tangent = Eigen::Vector3d::Zero();
  Piece first, last;
  std::array<std::vector<Eigen::Vector4d>, A> start_rings, end_rings;
  bool started = false;
  while (!stack.empty()) {
    auto [p, depth] = std::move(stack.back());
    stack.pop_back();
    prepare(p);
    const Eigen::Vector3d t0 = eval3(p.v, 0), t1 = eval3(p.v, 1);
    if (!(t0.norm() > 0) || !(t1.norm() > 0))
      throw Error(Errc::numerical_failure, where + ": the path's speed vanishes at t = " +
                                               std::to_string(t0.norm() > 0 ? p.t1 : p.t0) +
                                               ": no exact pipe around a cusp");
    if (!started) {
      const Eigen::Vector3d z = t0.normalized(), x = z.unitOrthogonal();
      G.col(0) = x;
      G.col(1) = z.cross(x);
      G.col(2) = z;
    } else if (!(last_tangent.dot(t0.normalized()) > 1 - 1e-10)) {
      throw Error(
          Errc::invalid_input,
          where + ": the path has a corner at t = " + std::to_string(p.t0) +
              " (its tangent turns by " +
              std::to_string(std::acos(std::clamp(last_tangent.dot(t0.normalized()), -1.0, 1.0)) *
                             180 / M_PI) +
              " degrees): an exact pipe needs a tangent-continuous path");
    }
    if (!frame(p, G)) {
      if (depth >= 12)
        throw Error(Errc::numerical_failure,
                    where + ": the path's tangent turns too fast near t = " +
                        std::to_string(0.5 * (p.t0 + p.t1)) + ": no exact pipe");
      const kernel::Bernstein<Eigen::Vector4d> whole(p.H);
      auto [l, rr] = kernel::subdivide(whole, 0.5);
      const double tm = 0.5 * (p.t0 + p.t1);
      Piece a, b;
      a.t0 = p.t0;
      a.t1 = tm;
      a.H = l.coeffs();
      b.t0 = tm;
      b.t1 = p.t1;
      b.H = rr.coeffs();
      stack.emplace_back(std::move(b), depth + 1);
      stack.emplace_back(std::move(a), depth + 1);
      continue;
    }
    factor_h(p, where);
    // At t0 the pole is the tangent: the circle's point for z is arg(h) + 2 arg(z) in the
    // frame; matching arg(h) with the previous piece's end makes the arcs meet.
    const Cx h0 = evaluate(p.h, 0.0);
    if (started) {
      const Cx turn = phase / (h0 / std::abs(h0));
      for (auto& c : p.h) c *= turn;
    }
    const Cx h1 = evaluate(p.h, 1.0);
    phase = h1 / std::abs(h1);
    G = end_frame(p);
    last_tangent = t1.normalized();
    for (int j = 0; j < A; ++j) {
      const auto jj = static_cast<std::size_t>(j);
      const Patch patch = pipe_patch(p, phi[jj], phi[jj + 1], r);
      if (!started) start_rings[jj] = patch.front();  // the circles the caps are built on
      end_rings[jj] = patch.back();
      emit(patch, p.t0, p.t1, j, out.shell.faces, where);
    }
    // Orthogonality and unit length, sampled (rounding only: they hold identically).
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; j < 8; ++j) {
        const double u = i / 4.0;
        const Eigen::Vector3d n = normal_at(p, u, std::polar(1.0, j * M_PI / 8));
        out.orthogonality =
            std::max(out.orthogonality,
                     std::max(std::abs(n.dot(eval3(p.v, u).normalized())), std::abs(n.norm() - 1)));
      }
    if (!started) first = p;
    last = std::move(p);
    started = true;
    ++out.pieces;
  }
  for (const auto& f : out.shell.faces) out.degree_t = std::max(out.degree_t, f.degree_u);
  out.pipe_faces = out.shell.faces.size();
  for (int j = 0; j < A; ++j)
    out.shell.faces.push_back(cap(first, start_rings[static_cast<std::size_t>(j)], 0, r, j));
  for (int j = 0; j < A; ++j)
    out.shell.faces.push_back(cap(last, end_rings[static_cast<std::size_t>(j)], 1, r, j));
  out.shell.closed = true;
  orient_and_measure(out, centre, r);
  return out;
}

}  // namespace qmotion::sweep
