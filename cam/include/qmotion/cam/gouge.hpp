// <qmotion/cam/gouge.hpp>: how deep a cutter moving along one canonical move enters a part,
// certified by branch and bound over time and the cutter's cores (docs/guide/verify.md,
// "Gouges").
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <qmotion/cam/program.hpp>
#include <qmotion/kernel/outward.hpp>
#include <qmotion/sweep/body.hpp>
#include <queue>
#include <vector>

namespace qmotion::cam {

/// The gouge of one move: the largest depth -sd_part(x) over the points x of the cutter at
/// every t of the move, 0 when it never enters. lower is reached (by `point`, a point of the
/// cutter at `t`); no point of the cutter lies deeper than upper; upper - lower <= the
/// tolerance unless `settled` is false (the cell budget ran out; the interval is what was
/// proven). When the move clears the part by more than the tolerance, upper is 0 and the
/// clearance is proven: `clear`.
struct Gouge {
  double lower = 0, upper = 0;
  /// The deepest point found, of either sign: below 0, its clearance from the part.
  double found = -HUGE_VAL;
  double t = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  std::size_t queries = 0;
  bool settled = true;
  bool clear = false;  ///< no point of the cutter touches the part (proven)
};

/// Cells one core of a move may split into before the search turns to the cutter's solid
/// (move_gouge), and cells that search may split into before the interval is reported as
/// it stands.
inline constexpr std::size_t kGougeCoreCells = std::size_t(1) << 16;
inline constexpr std::size_t kGougeCells = std::size_t(1) << 20;

namespace detail {

/// A core of the cutter: the points of the annulus r_in <= rho <= r_out, z0 <= z <= z1
/// (cutter frame), grown by a ball of radius rc. A cutter is the union of its cores' points
/// within rc of them (up to points above its top, which only loosen the bound).
struct Core {
  double r_in = 0, r_out = 0, rc = 0, z0 = 0, z1 = 0;
  /// The cutter's solid itself (rc = 0): a box is kept while the cutter may meet it.
  const sweep::Body* solid = nullptr;
};

/// Flat: the cutter itself. Ball: the axis from the ball's centre up, grown by the radius.
/// Bull: the flat cutter of radius R - rc, and the cylinder rho = R - rc from z = rc up
/// grown by rc (the corner's torus and the side).
inline std::vector<Core> cores_of(const sweep::Body& cutter) {
  using K = sweep::Body::Kind;
  const double R = cutter.D / 2, L = cutter.L;
  if (cutter.kind == K::ball_cutter) return {Core{0, 0, R, R, std::max(R, L)}};
  if (cutter.kind == K::bull_cutter)
    return {Core{0, R - cutter.rc, 0, 0, L},
            Core{R - cutter.rc, R - cutter.rc, cutter.rc, cutter.rc, std::max(cutter.rc, L)}};
  return {Core{0, R, 0, 0, L}};
}

/// Whether a search whose deepest point found is `lower` may stop at `upper`: within tol of
/// it; proven clear when that point clears the part by more than tol; and proven within
/// tol of the part (no gouge at tol) when that point is less than tol/2 deep.
inline bool settled(double upper, double lower, double tol) {
  return upper <= std::max(lower, 0.0) + tol && (upper <= 0 || lower >= -tol) &&
         (upper <= tol || lower > tol / 2);
}

/// A cell of the search: a time interval and a box of a core, with the bound of -sd_part
/// over the cutter's points it holds.
struct GougeCell {
  double t0, t1;
  Eigen::Vector3d lo, hi;
  double upper;
  /// The normal of the plane whose bound is the cell's (convex_bound), or zero.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  bool operator<(const GougeCell& o) const { return upper < o.upper; }
};

/// The rounding of one distance query at x: a few ulps of the coordinates' size
/// (docs/guide/verify.md, "Rounding").
inline double margin(const Eigen::Vector3d& x) { return 1e-12 * (1 + x.cwiseAbs().maxCoeff()); }

/// Whether the box [lo, hi] meets the annulus r_in <= rho <= r_out (in x, y).
inline bool meets_annulus(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const Core& c) {
  const double nx = std::max({lo.x(), -hi.x(), 0.0}), ny = std::max({lo.y(), -hi.y(), 0.0});
  const double fx = std::max(std::abs(lo.x()), std::abs(hi.x()));
  const double fy = std::max(std::abs(lo.y()), std::abs(hi.y()));
  return std::hypot(nx, ny) <= c.r_out && std::hypot(fx, fy) >= c.r_in;
}

/// The search over one core; g gathers the deepest point found across cores.
class GougeSearch {
 public:
  GougeSearch(const Move& m, const Core& core, const sweep::Body& part, double tol, Gouge& g,
              std::size_t budget)
      : m_(m),
        core_(core),
        part_(part),
        tol_(tol),
        g_(g),
        speed_(speed_bound(m)),
        budget_(budget) {}

  /// The bound left over this core: at most the deepest point found plus tol when settled.
  double run() {
    std::priority_queue<GougeCell> heap;
    GougeCell root{0, 1, Eigen::Vector3d(-core_.r_out, -core_.r_out, core_.z0),
                   Eigen::Vector3d(core_.r_out, core_.r_out, core_.z1), 0};
    bound(root);
    heap.push(root);
    std::size_t cells = 1;
    while (!heap.empty()) {
      const GougeCell c = heap.top();
      if (settled(c.upper, g_.lower, tol_)) break;
      if (cells >= budget_) {
        g_.settled = false;
        break;
      }
      heap.pop();
      const int axis = split_axis(c);
#ifdef QMOTION_GOUGE_TRACE
      static std::size_t it = 0;
      if ((++it & (it - 1)) == 0)
        std::fprintf(stderr,
                     "cells %zu top %g n %g t [%g %g] lo %g %g %g hi %g %g %g axis %d lower %g\n",
                     cells, c.upper, c.normal.z(), c.t0, c.t1, c.lo.x(), c.lo.y(), c.lo.z(),
                     c.hi.x(), c.hi.y(), c.hi.z(), axis, g_.lower);
#endif
      GougeCell a = c, b = c;
      if (axis < 0)
        a.t1 = b.t0 = 0.5 * (c.t0 + c.t1);
      else
        a.hi(axis) = b.lo(axis) = 0.5 * (c.lo(axis) + c.hi(axis));
      for (GougeCell* h : {&a, &b}) {
        if (!meets(*h)) continue;
        bound(*h);
        heap.push(*h);
        ++cells;
      }
    }
    return heap.empty() ? -HUGE_VAL : heap.top().upper;
  }

 private:
  /// The extent to halve (0 to 2: the box's, -1: time): under a plane's bound, the one
  /// that spans most along the patch's normal; else the longest, time counted by the
  /// distance the tool moves in it.
  int split_axis(const GougeCell& c) const {
    const bool flat = c.normal.squaredNorm() > 0;
    const Eigen::Vector3d n = flat ? Eigen::Vector3d(c.normal.cwiseAbs()) : Eigen::Vector3d::Ones();
    int axis = -1;
    double longest = m_.kind == Move::Kind::arc || !flat
                         ? speed_ * (c.t1 - c.t0)
                         : std::abs(c.normal.dot(position(m_, c.t1) - position(m_, c.t0)));
    for (int k = 0; k < 3; ++k)
      if (n(k) * (c.hi(k) - c.lo(k)) > longest) {
        longest = n(k) * (c.hi(k) - c.lo(k));
        axis = k;
      }
    if (flat && longest < 0.25 * tol_) {
      GougeCell plain = c;
      plain.normal.setZero();
      return split_axis(plain);
    }
    return axis;
  }

  /// The cell's bound, and its witness. Every point of the cutter in the cell lies within
  /// e + rc of y = p(tm) + centre, e = speed (t1 - t0) / 2 + |hi - lo| / 2, and -sd_part is
  /// 1-Lipschitz: none lies deeper than -sd_part(y) + e + rc. Where a mesh part is locally
  /// convex, convex_bound's, when smaller.
  void bound(GougeCell& c) {
    using kernel::up;
    const double tm = 0.5 * (c.t0 + c.t1);
    const Eigen::Vector3d pm = position(m_, tm), yc = 0.5 * (c.lo + c.hi), y = pm + yc;
    Eigen::Vector3d grad;
    int tri = -1;
    double s;
    if (part_.index) {
      Eigen::Vector3d near;
      s = part_.index->signed_distance(y, &near, HUGE_VAL, &tri);
      grad = std::abs(s) > 0 ? Eigen::Vector3d((y - near) / s) : Eigen::Vector3d::Zero();
    } else {
      s = sweep::signed_distance(part_, y, grad);
    }
    ++g_.queries;
    const double e = up(up(speed_ * up(0.5 * (c.t1 - c.t0))) + up(0.5 * (c.hi - c.lo).norm()));
    c.upper = up(up(up(-s + e) + core_.rc) + margin(y));
    c.normal.setZero();
    if (tri >= 0) {
      GougeCell flat = c;
      const double by_plane = convex_bound(flat, tri, y, e);
      if (by_plane < c.upper) {
        c.upper = by_plane;
        c.normal = flat.normal;
      }
    }
    witness(tm, pm, yc, grad);
  }

  /// The bound of a cell where the part is locally a convex polyhedron (a face, an edge or a
  /// corner of it; docs/guide/verify.md, "Gouges: the proof"). Let n, a be the plane of the
  /// triangle nearest y and r = 2 (e + rc) + |n.(y - a)|. When the planes of the triangles
  /// within r of y bound a convex Q whose boundary holds each of those triangles, the part
  /// and Q agree within B(y, r), and a point x of the cell lies no deeper than
  /// max(min_j d_j(x), -(r - e - rc)), d_j(x) its depth below plane j: linear, so at most its
  /// largest value over the corners of the cell's points (the box at p(t0) and p(t1); for
  /// arcs at p(tm), grown by the arc's reach), plus rc. HUGE_VAL where the test fails.
  double convex_bound(GougeCell& c, int tri, const Eigen::Vector3d& y, double e) const {
    using kernel::up;
    const auto& mesh = part_.index->mesh();
    auto vertex = [&](int t, int k) -> const Eigen::Vector3d& {
      return mesh.vertices[static_cast<std::size_t>(
          mesh.triangles[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)])];
    };
    auto normal = [&](int t) -> Eigen::Vector3d {
      return (vertex(t, 1) - vertex(t, 0)).cross(vertex(t, 2) - vertex(t, 0)).normalized();
    };
    const Eigen::Vector3d n0 = normal(tri);
    if (!n0.allFinite()) return HUGE_VAL;
    const double r =
        up(up(2 * up(e + core_.rc)) + std::abs(n0.dot(y - vertex(tri, 0)))) + margin(y);
    std::vector<int>& near = near_;
    if (!part_.index->triangles_within(y, r, kLocalTriangles, near)) return HUGE_VAL;
    // The distinct planes, each with a point on it.
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> planes;
    for (int t : near) {
      const Eigen::Vector3d n = normal(t);
      if (!n.allFinite()) return HUGE_VAL;
      const Eigen::Vector3d& a = vertex(t, 0);
      const bool known = std::any_of(planes.begin(), planes.end(), [&](const auto& q) {
        return (q.first - n).norm() < 1e-12 && std::abs(q.first.dot(a - q.second)) <= margin(a);
      });
      if (!known) planes.emplace_back(n, a);
    }
    // Convex: every triangle's corners on the inner side of every plane.
    for (int t : near)
      for (int k = 0; k < 3; ++k)
        for (const auto& [n, a] : planes)
          if (n.dot(vertex(t, k) - a) > 16 * (margin(vertex(t, k)) + margin(a))) return HUGE_VAL;
    const bool straight = m_.kind != Move::Kind::arc;
    const double grow = straight ? 0.0 : up(speed_ * up(0.5 * (c.t1 - c.t0)));
    const double ts[2] = {straight ? c.t0 : 0.5 * (c.t0 + c.t1), c.t1};
    double best = HUGE_VAL;
    for (const auto& [n, a] : planes) {
      double worst = -HUGE_VAL;
      for (int k = 0; k < (straight ? 2 : 1); ++k) {
        const Eigen::Vector3d p = position(m_, ts[k]);
        for (int corner = 0; corner < 8; ++corner) {
          const Eigen::Vector3d v = p + Eigen::Vector3d(corner & 1 ? c.hi.x() : c.lo.x(),
                                                        corner & 2 ? c.hi.y() : c.lo.y(),
                                                        corner & 4 ? c.hi.z() : c.lo.z());
          worst = std::max(worst, up(up(-n.dot(v - a) + margin(v)) + margin(a)));
        }
      }
      worst = up(up(worst + grow) + core_.rc);
      if (worst < best) {
        best = worst;
        c.normal = n;
      }
    }
    return std::max(best, -(r - up(e + core_.rc)));
  }

  /// The core's point nearest the cell's centre at tm, moved by rc down the distance's
  /// slope while it stays below the cutter's top: a point of the cutter, and its depth.
  void witness(double tm, const Eigen::Vector3d& pm, Eigen::Vector3d w,
               const Eigen::Vector3d& grad) {
    if (core_.solid) {  // the cutter's point nearest the centre (it is convex)
      Eigen::Vector3d g;
      const double d = sweep::signed_distance(*core_.solid, w, g);
      if (d > 0) w -= d * g;
    }
    const double rho = std::hypot(w.x(), w.y());
    if (rho > core_.r_out) w.head<2>() *= core_.r_out / rho;
    if (rho < core_.r_in) {
      if (rho > 0)
        w.head<2>() *= core_.r_in / rho;
      else
        w.x() = core_.r_in;
    }
    Eigen::Vector3d x = pm + w;
    if (core_.rc > 0 && grad.norm() > 0) {
      const Eigen::Vector3d moved = x - core_.rc * grad.normalized();
      if (moved.z() - pm.z() <= core_.z1) x = moved;
    }
    const double depth = -sweep::signed_distance(part_, x);
    ++g_.queries;
    if (depth > g_.lower) {
      g_.lower = depth;
      g_.t = tm;
      g_.point = x;
    }
  }

  /// Whether the cell's box may hold a point of the core (of the solid: the cutter's
  /// distance at its centre is at most its half-diagonal).
  bool meets(const GougeCell& c) const {
    if (!core_.solid) return meets_annulus(c.lo, c.hi, core_);
    return sweep::signed_distance(*core_.solid, 0.5 * (c.lo + c.hi)) <= 0.5 * (c.hi - c.lo).norm();
  }

  static constexpr std::size_t kLocalTriangles = 64;
  const Move& m_;
  Core core_;
  mutable std::vector<int> near_;  ///< convex_bound's triangles, kept between calls
  const sweep::Body& part_;
  double tol_;
  Gouge& g_;
  double speed_;
  std::size_t budget_;
};

}  // namespace detail

/// The gouge of `cutter` (cutter:flat, ball or bull, its tip at the tool tip and its axis
/// along +z: a 3-axis move) moving along m into `part` (a closed body in the program's
/// frame), to within tol: branch and bound over time and each core of the cutter, the
/// deepest cell split first along its longest extent (time counted by the distance the
/// tool moves), until every cell's bound is within tol of the deepest point found.
inline Gouge move_gouge(const Move& m, const sweep::Body& cutter, const sweep::Body& part,
                        double tol) {
  Gouge g;
  g.lower = -HUGE_VAL;
  double upper = -HUGE_VAL;
  for (const detail::Core& core : detail::cores_of(cutter))
    upper = std::max(upper, detail::GougeSearch(m, core, part, tol, g, kGougeCoreCells).run());
  if (!g.settled) {
    // A core grown by rc > 0 can bound no better than rc past its own depth: where the
    // part is neither convex nor far about the cutter, search the cutter's solid itself.
    // Both bounds hold; the smaller is kept.
    g.settled = true;
    detail::Core solid{0, cutter.D / 2, 0, 0, cutter.L, &cutter};
    upper = std::min(upper, detail::GougeSearch(m, solid, part, tol, g, kGougeCells).run());
    g.settled = detail::settled(upper, g.lower, tol);
  }
  g.found = g.lower;
  g.clear = upper < 0;
  g.lower = std::max(g.lower, 0.0);
  g.upper = std::max(upper, g.lower);
  return g;
}

}  // namespace qmotion::cam
