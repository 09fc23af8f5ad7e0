// sweep/src/volume_tets.cpp: what the adaptive mesh does in one tetrahedron (volume_tets.hpp).
#include "volume_tets.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <qmotion/kernel/outward.hpp>
#include <qmotion/sweep/swept_volume.hpp>

namespace qmotion::sweep::mesher {
namespace {

/// inside_part's two tests of the whole tetrahedron p (all corners inside; `centre`, its
/// circumcentre less p[0]).
bool whole_inside(const Eigen::Vector3d* p, double R, const double* v, const double* at,
                  const sweep::SweptVolumeTree& tree, double scale) {
  bool balls = true;
  for (int i = 0; i < 4; ++i) balls = balls && -v[i] >= R;
  if (balls) return true;
  if (!sweep::is_convex(tree.body())) return false;
  const double margin = 1e-12 * scale;
  for (int j = 0; j < 4; ++j) {
    bool in_one = true;
    for (int i = 0; i < 4 && in_one; ++i)
      in_one = i == j || tree.placed_distance(p[i], at[j]) < -margin;
    if (in_one) return true;
  }
  return false;
}

using kernel::Interval;
using kernel::Interval3;

}  // namespace

void march(const Octree::Tet& t, const OctKey* k, const double* v, double tau,
           std::vector<Tri>& out) {
  int in[4], ot[4], ni = 0, no = 0;
  for (int i = 0; i < 4; ++i) (v[i] < tau ? in[ni++] : ot[no++]) = i;
  if (no == 0 || ni == 0) return;
  auto edge = [&](int i, int o) { return k[i] < k[o] ? EdgeKey{k[i], k[o]} : EdgeKey{k[o], k[i]}; };
  // Orientation from the corners alone (exact, on the lattice): a triangle about corner
  // c of its side, with vertices on c's edges to u0, u1, u2, faces away from c when
  // det(u0 - c, u1 - c, u2 - c) > 0, wherever on those edges the vertices lie.
  const auto det = [&](int c, int a, int b, int d) {
    long m[3][3];
    for (int r = 0; r < 3; ++r) {
      const int to = r == 0 ? a : r == 1 ? b : d;
      for (int x = 0; x < 3; ++x)
        m[r][x] = t[static_cast<std::size_t>(to)][static_cast<std::size_t>(x)] -
                  t[static_cast<std::size_t>(c)][static_cast<std::size_t>(x)];
    }
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  auto emit = [&](bool keep, const EdgeKey& a, const EdgeKey& b, const EdgeKey& c) {
    out.push_back(keep ? Tri{a, b, c} : Tri{a, c, b});
  };
  if (ni == 1) {
    emit(det(in[0], ot[0], ot[1], ot[2]) > 0, edge(in[0], ot[0]), edge(in[0], ot[1]),
         edge(in[0], ot[2]));
  } else if (ni == 3) {  // faces towards the outer corner
    emit(det(ot[0], in[0], in[1], in[2]) < 0, edge(in[0], ot[0]), edge(in[1], ot[0]),
         edge(in[2], ot[0]));
  } else {
    // The quadrilateral i0o0, i0o1, i1o1, i1o0 in turn; at the edges' midpoints it is the
    // parallelogram with sides (o1 - o0)/2 and (i1 - i0)/2, which faces o0 - i0 when
    // det(o0 - i0, o1 - i0, i1 - i0) > 0; moving its vertices along their edges never
    // folds it, so that holds wherever they lie.
    const bool keep = det(in[0], ot[0], ot[1], in[1]) > 0;
    const EdgeKey a = edge(in[0], ot[0]), b = edge(in[0], ot[1]), c = edge(in[1], ot[1]),
                  d = edge(in[1], ot[0]);
    if (keep) {
      emit(true, a, b, c);
      emit(true, a, c, d);
    } else {
      emit(true, a, d, c);
      emit(true, a, c, b);
    }
  }
}

/// A volume of the tetrahedron that certainly lies in V: all of it when its four corners
/// lie in one placement of a convex body, or each in its own deeper than the circumradius
/// (every point of a tetrahedron is within it of a corner); else the parts about its
/// corners in V: a corner deeper than d lies in V with the ball of radius d about it, and
/// the tetrahedron's copy scaled by s about that corner lies within s L of it (L the
/// longest edge from it). Copies about two corners with s at most 1/2 each do not overlap.
double inside_part(const Eigen::Vector3d* p, const double* v, const double* at,
                   const sweep::SweptVolumeTree& tree, double scale) {
  // Rounded outward (kernel/outward.hpp): the volume down, the lengths it is measured
  // against up.
  const Interval3 a[3] = {kernel::difference(p[1], p[0]), kernel::difference(p[2], p[0]),
                          kernel::difference(p[3], p[0])};
  const Interval3 c12 = kernel::cross(a[1], a[2]), c20 = kernel::cross(a[2], a[0]),
                  c01 = kernel::cross(a[0], a[1]);
  const Interval det = kernel::dot(a[0], c12), whole_in = kernel::abs(det) / Interval(6.0);
  const double whole = whole_in.lo;
  if (!(whole > 0)) return 0;
  bool all_in = true;
  for (int i = 0; i < 4; ++i) all_in = all_in && v[i] < 0;
  if (all_in) {
    // The circumcentre less p[0]: (|a0|^2 a1 x a2 + |a1|^2 a2 x a0 + |a2|^2 a0 x a1) / 2 det.
    const Interval twice = det * Interval(2.0);
    Interval3 centre;
    for (int k = 0; k < 3; ++k)
      centre[static_cast<std::size_t>(k)] =
          (kernel::dot(a[0], a[0]) * c12[static_cast<std::size_t>(k)] +
           kernel::dot(a[1], a[1]) * c20[static_cast<std::size_t>(k)] +
           kernel::dot(a[2], a[2]) * c01[static_cast<std::size_t>(k)]) /
          twice;
    if (whole_inside(p, kernel::norm_up(centre), v, at, tree, scale)) return whole;
  }
  double part = 0;
  for (int i = 0; i < 4; ++i) {
    if (!(v[i] < 0)) continue;
    double L = 0;
    for (int j = 0; j < 4; ++j) L = std::max(L, kernel::norm_up(kernel::difference(p[j], p[i])));
    const double s = kernel::down(-v[i] / L);
    if (s >= 1) return whole;
    const double h = std::min(s, 0.5);
    part = kernel::down(part + kernel::down(kernel::down(h * h) * h));
  }
  return kernel::down(whole * part);
}

}  // namespace qmotion::sweep::mesher
