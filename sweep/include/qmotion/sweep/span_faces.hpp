// <qmotion/sweep/span_faces.hpp>
#pragma once
// A surface cut into one face per span along u: the face layout of the solids qmotion writes
// to STEP and IGES (docs/geometry.md, "Why FreeCAD's volume of a fitted tube is off").
#include <Eigen/Core>
#include <cstddef>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/sweep/nurbs.hpp>
#include <qmotion/sweep/shell.hpp>
#include <utility>
#include <vector>

namespace qmotion::sweep {

/// The surface with every interior u knot raised to multiplicity degree_u by Boehm's
/// insertion, in homogeneous coordinates (w x, w), column by column: the same surface up to
/// rounding, each u span's poles its own (the new weights are convex combinations of the old,
/// so they stay positive).
template <typename Scalar>
NurbsSurface<Scalar> with_full_u_knots(const NurbsSurface<Scalar>& s) {
  using V4 = Eigen::Matrix<Scalar, 4, 1>;
  const int p = s.degree_u;
  const std::vector<Scalar>& T = s.knots_u;
  const std::size_t n = s.points.size();      // poles along u
  std::vector<std::pair<Scalar, int>> raise;  // knot, insertions
  for (std::size_t r = static_cast<std::size_t>(p) + 1; r < n;) {
    std::size_t m = 1;
    while (r + m < n && T[r + m] == T[r]) ++m;
    if (static_cast<int>(m) < p) raise.emplace_back(T[r], p - static_cast<int>(m));
    r += m;
  }
  if (raise.empty()) return s;
  const std::size_t cols = s.points.front().size();
  NurbsSurface<Scalar> out{s.degree_u, s.degree_v, {}, s.knots_v, {}, {}};
  for (std::size_t j = 0; j < cols; ++j) {
    std::vector<V4> P(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Scalar w = s.weights[i][j];
      P[i] << s.points[i][j] * w, w;
    }
    auto c = kernel::BSpline<V4>::make(p, T, std::move(P));
    for (const auto& [knot, times] : raise) c = kernel::insert_knot(c, knot, times);
    if (j == 0) {
      out.knots_u = c.knots();
      out.points.resize(c.ctrl().size());
      out.weights.resize(c.ctrl().size());
    }
    for (std::size_t i = 0; i < c.ctrl().size(); ++i) {
      const V4& q = c.ctrl()[i];
      out.points[i].push_back((q.template head<3>() / q(3)).eval());
      out.weights[i].push_back(q(3));
    }
  }
  return out;
}

/// The surface cut into one face per u span (and at its C0 knots in v), every face keeping
/// the parametrisation (u is still t). OpenCASCADE's fixed-order volume rule, which is
/// FreeCAD's Shape.Volume, sizes its Gauss rule along u from v alone; with one u span a face
/// it integrates each face's polynomial piece in u well (docs/geometry.md).
template <typename Scalar>
std::vector<NurbsSurface<Scalar>> split_u_spans(const NurbsSurface<Scalar>& s) {
  return split_c0(with_full_u_knots(s));
}

}  // namespace qmotion::sweep
