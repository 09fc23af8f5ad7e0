// <qmotion/sweep/shell.hpp>
#pragma once
#include <algorithm>
#include <qmotion/sweep/nurbs.hpp>
#include <utility>
#include <vector>

namespace qmotion::sweep {

/// Several NURBS faces that belong together: the sweeps of a profile's edges, each split at
/// its C0 knots (docs/formats.md). `closed` marks a solid's faces: lateral faces whose caps
/// `cap_start`/`cap_end` are the planar regions bounded by the profile's images at both
/// ends of the interval (the curves in profile order), or, with no cap curves, faces that
/// close by themselves (a pipe and its half-sphere caps, sweep/pipe.hpp).
template <typename Scalar>
struct NurbsShell {
  std::vector<NurbsSurface<Scalar>> faces;
  std::vector<NurbsCurve<Scalar>> cap_start, cap_end;
  bool closed = false;
};

/// The diagonal of the box around every face's poles: the size of the shell.
template <typename Scalar>
Scalar diagonal(const NurbsShell<Scalar>& s) {
  Eigen::Matrix<Scalar, 3, 1> lo = s.faces.front().points.front().front(), hi = lo;
  for (const auto& f : s.faces)
    for (const auto& row : f.points)
      for (const auto& p : row) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
  return (hi - lo).norm();
}

/// Index ranges of the C1 pieces of a clamped knot vector of degree p: the interior knots
/// of multiplicity >= p (continuity C0 or a break) split it. Each piece is (first pole, pole
/// count, its clamped knot vector); the poles are shared, unchanged, with the whole (a knot
/// of multiplicity p is a pole of the curve).
template <typename Scalar>
struct KnotPiece {
  std::size_t first = 0, count = 0;
  std::vector<Scalar> knots;
};

template <typename Scalar>
std::vector<KnotPiece<Scalar>> c0_pieces(const std::vector<Scalar>& T, int degree) {
  const std::size_t p = static_cast<std::size_t>(degree);
  const std::size_t n = T.size() - p - 1;  // poles
  std::vector<KnotPiece<Scalar>> pieces;
  // The current piece starts at pole `start`; T[start + p] is its first knot value.
  std::size_t start = 0;
  std::size_t r = p + 1;
  while (r < n) {  // interior knots T[p+1 .. n-1]
    std::size_t m = 1;
    while (r + m < n && T[r + m] == T[r]) ++m;
    if (m >= p && p > 0) {
      KnotPiece<Scalar> piece;
      piece.first = start;
      piece.count = r - start;  // poles before the split
      piece.knots.assign(p + 1, T[start + p]);
      piece.knots.insert(piece.knots.end(), T.begin() + static_cast<std::ptrdiff_t>(start + p + 1),
                         T.begin() + static_cast<std::ptrdiff_t>(r));
      piece.knots.insert(piece.knots.end(), p + 1, T[r]);
      pieces.push_back(std::move(piece));
      start = r + m - p - 1;
    }
    r += m;
  }
  KnotPiece<Scalar> last;
  last.first = start;
  last.count = n - start;
  last.knots.assign(p + 1, T[start + p]);
  last.knots.insert(last.knots.end(), T.begin() + static_cast<std::ptrdiff_t>(start + p + 1),
                    T.end());
  pieces.push_back(std::move(last));
  return pieces;
}

/// The surface split at its C0 knots in u and in v into C1 patches (row-major: u outer).
/// Every patch keeps the parametrisation: u is still t, v the profile's parameter.
template <typename Scalar>
std::vector<NurbsSurface<Scalar>> split_c0(const NurbsSurface<Scalar>& s) {
  const auto pu = c0_pieces(s.knots_u, s.degree_u);
  const auto pv = c0_pieces(s.knots_v, s.degree_v);
  std::vector<NurbsSurface<Scalar>> out;
  for (const auto& a : pu)
    for (const auto& b : pv) {
      NurbsSurface<Scalar> f{s.degree_u, s.degree_v, a.knots, b.knots, {}, {}};
      for (std::size_t i = a.first; i < a.first + a.count; ++i) {
        f.points.emplace_back(s.points[i].begin() + static_cast<std::ptrdiff_t>(b.first),
                              s.points[i].begin() + static_cast<std::ptrdiff_t>(b.first + b.count));
        f.weights.emplace_back(
            s.weights[i].begin() + static_cast<std::ptrdiff_t>(b.first),
            s.weights[i].begin() + static_cast<std::ptrdiff_t>(b.first + b.count));
      }
      out.push_back(std::move(f));
    }
  return out;
}

/// The curve split at its C0 knots into C1 pieces on the same parameter.
template <typename Scalar>
std::vector<NurbsCurve<Scalar>> split_c0(const NurbsCurve<Scalar>& c) {
  std::vector<NurbsCurve<Scalar>> out;
  for (const auto& piece : c0_pieces(c.knots, c.degree)) {
    NurbsCurve<Scalar> e{c.degree, piece.knots, {}, {}};
    const auto b = static_cast<std::ptrdiff_t>(piece.first),
               e_ = static_cast<std::ptrdiff_t>(piece.first + piece.count);
    e.points.assign(c.points.begin() + b, c.points.begin() + e_);
    e.weights.assign(c.weights.begin() + b, c.weights.begin() + e_);
    out.push_back(std::move(e));
  }
  return out;
}

/// The iso-curve v -> S(u0, v) at an end of the u interval (first or last row of poles:
/// exact, the knot vector is clamped).
template <typename Scalar>
NurbsCurve<Scalar> boundary_v_curve(const NurbsSurface<Scalar>& s, bool at_end) {
  const std::size_t i = at_end ? s.points.size() - 1 : 0;
  return NurbsCurve<Scalar>{s.degree_v, s.knots_v, s.points[i], s.weights[i]};
}

/// Lowest continuity declared by an interior knot of a clamped vector (degree - the
/// largest interior multiplicity; the degree itself, as "C^degree at least", when there is
/// no interior knot).
template <typename Scalar>
int min_continuity(const std::vector<Scalar>& T, int degree) {
  int worst = degree;
  const std::size_t p = static_cast<std::size_t>(degree), n = T.size() - p - 1;
  for (std::size_t r = p + 1; r < n;) {
    std::size_t m = 1;
    while (r + m < n && T[r + m] == T[r]) ++m;
    worst = std::min(worst, degree - static_cast<int>(m));
    r += m;
  }
  return worst;
}

}  // namespace qmotion::sweep
