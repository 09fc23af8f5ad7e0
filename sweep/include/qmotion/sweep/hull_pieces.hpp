// <qmotion/sweep/hull_pieces.hpp>: the space a body's boundary sweeps, covered by convex
// pieces of second order (the hull of a convex part at two times, grown by the motion's
// certified deviation from the linear blend), and a certificate that a triangle stays clear
// of all of them (docs/guide/volume.md, "The adaptive mesh").
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <qmotion/kernel/error.hpp>
#include <qmotion/motion.hpp>
#include <qmotion/sweep/body.hpp>
#include <qmotion/sweep/keyframes.hpp>
#include <vector>

namespace qmotion::sweep {

/// The point of a convex body (is_convex) farthest along u, in the moving space: its support
/// point, so that h(u) = u . support_point(u) is the body's support function. The revolved
/// bodies are the hull of their top disk and of their bottom disk of radius R - rc at height
/// rc grown by a ball of radius rc (the flat cutter and the cylinder: rc = 0; the ball
/// cutter: rc = R).
inline Eigen::Vector3d support_point(const Body& body, const Eigen::Vector3d& u) {
  using K = Body::Kind;
  const double n = u.norm();
  switch (body.kind) {
    case K::sphere:
      return n > 0 ? Eigen::Vector3d(body.r * u / n) : Eigen::Vector3d(body.r, 0, 0);
    case K::box:
      return 0.5 * Eigen::Vector3d(u.x() < 0 ? -body.a : body.a, u.y() < 0 ? -body.b : body.b,
                                   u.z() < 0 ? -body.c : body.c);
    case K::mesh:
      break;
    default: {
      const bool cyl = body.kind == K::cylinder;
      const double R = cyl ? body.r : body.D / 2, L = cyl ? body.h : body.L;
      const double rc = cyl || body.kind == K::flat_cutter ? 0.0
                        : body.kind == K::ball_cutter      ? R
                                                           : body.rc;
      const double m = std::sqrt(u.x() * u.x() + u.y() * u.y());
      const Eigen::Vector3d ex =
          m > 0 ? Eigen::Vector3d(u.x() / m, u.y() / m, 0.0) : Eigen::Vector3d::Zero();
      const Eigen::Vector3d top = R * ex + Eigen::Vector3d(0, 0, L);
      Eigen::Vector3d bottom = (R - rc) * ex + Eigen::Vector3d(0, 0, rc);
      if (n > 0) bottom += rc * u / n;
      return u.dot(top) >= u.dot(bottom) ? top : bottom;
    }
  }
  throw Error(Errc::invalid_input, "support_point: a mesh body is not taken as convex");
}

/// V = { M(t) x : t in [a, b], x in K } for a convex body K, covered by pieces: between two
/// consecutive keys k0, k1 of the motion (sweep::place_keyframes, exact poses), every point
/// M(t) x lies within delta = KeyframeBound::linear(k0, k1) of the linear blend
/// (1 - s) M0 x + s M1 x, a point of C = conv(M0 K u M1 K). So V lies in the union of the sets
/// C grown by delta. Their distance to a triangle is bounded below by a separating
/// direction n: every point y of C has n . y <= max(h0(n), h1(n)), hi(n) = n . pi +
/// h_K(Ri^T n), so the triangle is farther than delta + m from C's growth when
/// min over its corners of n . x - max(h0(n), h1(n)) > delta + m. The direction is the
/// triangle's normal first, then GJK's (Gilbert, Johnson, Keerthi 1988) on the triangle and
/// C, whose support point is the placed body's of the larger hi.
///
/// A closed mesh body B is not convex: the pieces then cover what its boundary sweeps, part
/// by part, each part a convex patch of its triangles or one of them (under a tree of
/// them, `Part`; build_parts). A
/// triangle clear of that is outside V = U M(t) B when one of its points lies outside
/// M(t0) B for one t0: a point that never meets M(t) dB is inside
/// M(t) B for every t or for none (docs/geometry.md, "The adaptive mesh").
///
/// The pieces sit under a binary tree over the keys: a node over keys lo..hi holds the
/// placement of its middle key Mm and a reach, max delta + max_j lever_norm(Mj - Mm, rho)
/// (detail::lever_norm: |(Mj - Mm)(1, x)| for |x| <= rho), so the pieces of a part P lie in
/// Mm P grown by the reach, and in a ball about Mm's placement of P's ball. A test walks
/// the pairs (key node, part), halving the wider of the two.
class HullPieces {
 public:
  struct Stats {
    std::size_t node_tests = 0, piece_tests = 0, gjk = 0;
  };

  /// Errc::numerical_failure from place_keyframes. A mesh body must be closed and oriented
  /// (sweep::validate).
  HullPieces(const qmotion::Motion& m, const Body& body, double delta_max)
      : body_(body), rho_(radius(body)) {
    if (is_convex(body))
      parts_.push_back(convex_ball(body));
    else
      build_parts(body.mesh, delta_max);
    KeyframeOptions opt;
    opt.tol = delta_max;
    opt.radius = rho_;
    const auto placed = place_keyframes(m, opt).keys;
    // A piece's hull is wider than what the body sweeps where it turns: a point
    // (1 - s) M0 x + s M1 y of the hull is s (1 - s) (R0 - R1)(x - y) from the blend of
    // (1 - s) x + s y, so the excess is up to |R0 - R1| diam / 4, first order in the turn.
    // Pieces are halved until that estimate (for a revolved body, the turn of its axis;
    // none for a sphere) is below 2 delta_max. It decides only how tight the cover is: every
    // piece's hull holds what the body sweeps over it whatever its length.
    std::vector<Keyframe> keys{placed.front()};
    for (std::size_t k = 0; k + 1 < placed.size(); ++k)
      refine(m, keys, placed[k + 1], 2 * delta_max, 0);
    const KeyframeBound bound(m, rho_, opt.subdivisions);
    double far = rho_;
    for (const auto& k : keys) {
      keys_.push_back(detail::key_matrix(k));
      far = std::max(far, k.translation.norm() + rho_);
    }
    for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
      delta_.push_back(bound.linear(keys[k], keys[k + 1]));
      largest_ = std::max(largest_, delta_.back());
    }
    if (delta_.empty()) {  // a motion of one pose
      keys_.push_back(keys_.back());
      delta_.push_back(0);
    }
    // The rounding of a support value and of the products: relative 1e-12 of the scene.
    rounding_ = 1e-12 * far;
    build(0, static_cast<int>(delta_.size()));
  }

  std::size_t size() const { return delta_.size(); }
  /// The body's parts: 1 for a convex body, leaves of the triangles' tree for a mesh.
  std::size_t parts() const {
    return static_cast<std::size_t>(
        std::count_if(parts_.begin(), parts_.end(), [](const Part& p) { return p.child < 0; }));
  }
  /// How much wider a piece's hull may be than the body's sweep over it (see the
  /// constructor): a turn's measure times the body's diameter / 4.
  double turn_excess(const Keyframe& k0, const Keyframe& k1) const {
    using K = Body::Kind;
    if (body_.kind == K::sphere) return 0;
    const Eigen::Matrix3d R0 = k0.rotation.normalized().toRotationMatrix(),
                          R1 = k1.rotation.normalized().toRotationMatrix();
    const bool revolved = body_.kind != K::box && body_.kind != K::mesh;
    const double turn = revolved ? (R1.col(2) - R0.col(2)).norm() : (R1 - R0).norm();
    return turn * 2 * parts_.front().radius / 4;
  }
  double largest_delta() const { return largest_; }

  /// Whether the triangle (a, b, c) is certainly farther than margin from what the body
  /// sweeps (a convex body), or from what its boundary sweeps (a mesh). `dirs`, unit
  /// vectors, are the directions tried first (the surface's normal about the triangle, the
  /// triangle's own); GJK's after them.
  bool clear(const std::array<Eigen::Vector3d, 3>& tri, const std::array<Eigen::Vector3d, 2>& dirs,
             double margin, Stats* stats = nullptr) const {
    return walk(tri.data(), 3, dirs, margin, stats, nullptr, nullptr);
  }

  /// Pairs of a piece's node of the tree over the keys and a part of the body.
  using Pairs = std::vector<std::pair<int, int>>;
  /// The pieces (with the parts) that the convex hull of `pts` could not be cleared of, as
  /// clear() tries: every other piece is clear of the hull, so of every triangle in it. A
  /// patch of the surface is asked once, and then each of its triangles only of these
  /// (clear_of), which are few where the patch lies near V and none elsewhere.
  Pairs unclear(const std::vector<Eigen::Vector3d>& pts, const std::array<Eigen::Vector3d, 2>& dirs,
                double margin, Stats* stats = nullptr) const {
    Pairs left;
    if (!pts.empty()) walk(pts.data(), pts.size(), dirs, margin, stats, &left, nullptr);
    return left;
  }
  /// clear() of the triangle, asked only of `pairs` (from unclear() of points whose hull holds
  /// the triangle).
  bool clear_of(const std::array<Eigen::Vector3d, 3>& tri,
                const std::array<Eigen::Vector3d, 2>& dirs, double margin, const Pairs& pairs,
                Stats* stats = nullptr) const {
    return pairs.empty() || walk(tri.data(), 3, dirs, margin, stats, nullptr, &pairs);
  }

 private:
  using Map = Eigen::Matrix<double, 3, 4>;
  static constexpr int kStack = 160;  ///< more than two trees of 2^64 leaves need

  /// The walk of clear() over the pairs (key node, part) from the roots, or from `seeds`,
  /// for the hull of pts[0, n) (a triangle when n is 3). A pair of a piece and a part that is
  /// not cleared ends the walk (false) or, with `left`, is appended there.
  bool walk(const Eigen::Vector3d* pts, std::size_t n, const std::array<Eigen::Vector3d, 2>& dirs,
            double margin, Stats* stats, Pairs* left, const Pairs* seeds) const {
    // The directions tried: the two given, and the last that GJK found (consecutive pieces
    // are apart along much the same direction).
    Directions d;
    for (int i = 0; i < 2; ++i) d.add(dirs[static_cast<std::size_t>(i)], pts, n);
    const double slack = margin + rounding_;
    // A ball about the points: pairs whose ball lies beyond it need no nearest point.
    Eigen::Vector3d tc = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < n; ++i) tc += pts[i];
    tc /= static_cast<double>(n);
    double tr = 0;
    for (std::size_t i = 0; i < n; ++i) tr = std::max(tr, (pts[i] - tc).squaredNorm());
    tr = std::sqrt(tr) * (1 + 1e-12);
    const std::size_t runs = seeds ? seeds->size() : 1;
    for (std::size_t s = 0; s < runs; ++s) {
      // Each pair popped pushes two whose depths add one more: the stack holds at most the
      // two trees' depths added (build() and split_part() halve, so each is a log2 of its
      // size).
      std::pair<int, int> stack[kStack];
      int top = 0;
      stack[top++] = seeds ? (*seeds)[s] : std::pair<int, int>{0, 0};
      while (top > 0) {
        const auto [ki, pi] = stack[--top];
        const Node& nd = nodes_[static_cast<std::size_t>(ki)];
        const Part& P = parts_[static_cast<std::size_t>(pi)];
        if (stats) ++stats->node_tests;
        const Map& Mm = keys_[static_cast<std::size_t>(nd.key)];
        const Eigen::Vector3d c =
            pi == 0 ? nd.centre : Eigen::Vector3d(Mm.col(0) + Mm.rightCols<3>() * P.centre);
        const double ball = P.radius + nd.reach + slack;
        if ((c - tc).norm() > ball + tr) continue;
        if (n == 3 && (detail::closest_on_triangle(c, pts[0], pts[1], pts[2]) - c).norm() > ball)
          continue;
        const bool leaf_part = P.child < 0, leaf_node = nd.child[0] < 0;
        if (leaf_part) {
          bool apart = false;
          for (int i = 0; i < d.n && !apart; ++i)
            apart = d.low[i] - support(nd.key, P, d.n_[i]) > nd.reach + slack;
          if (apart) continue;
        }
        if (leaf_part && leaf_node) {
          if (stats) ++stats->piece_tests;
          if (piece_clear(nd.lo, P, pts, n, d, margin, stats)) continue;
          if (!left) return false;
          left->push_back({ki, pi});
          continue;
        }
        if (!leaf_part && (leaf_node || P.radius >= nd.reach)) {
          stack[top++] = {ki, P.child};
          stack[top++] = {ki, P.child + 1};
        } else {
          stack[top++] = {nd.child[0], pi};
          stack[top++] = {nd.child[1], pi};
        }
      }
    }
    return true;
  }
  struct Node {
    int lo = 0, hi = 0, key = 0;  ///< pieces lo..hi-1, keys lo..hi; key: the middle one
    double reach = 0;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< the placed centre of the root part
    int child[2] = {-1, -1};
  };
  /// A part of the body, in the moving space: a ball about it, and its children (child,
  /// child + 1) or, a leaf, its points points_[first, first + count), whose hull it is (count
  /// 0: the whole convex body, through support_point; -1: an inner node).
  struct Part {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double radius = 0;
    int child = -1, first = 0, count = 0;
  };

  /// A ball about a convex body: the sphere's and the box's own; about the middle of a
  /// revolved body's axis, the farther of its top rim and of its bottom torus (or disk).
  static Part convex_ball(const Body& body) {
    using K = Body::Kind;
    Part p;
    if (body.kind == K::sphere) {
      p.radius = body.r;
    } else if (body.kind == K::box) {
      p.radius = radius(body);
    } else {
      const bool cyl = body.kind == K::cylinder;
      const double R = cyl ? body.r : body.D / 2, L = cyl ? body.h : body.L;
      const double rc = cyl || body.kind == K::flat_cutter ? 0.0
                        : body.kind == K::ball_cutter      ? R
                                                           : body.rc;
      p.centre = Eigen::Vector3d(0, 0, L / 2);
      p.radius = std::max(std::hypot(R, L / 2), std::hypot(R - rc, L / 2 - rc) + rc);
    }
    p.radius *= 1 + 1e-12;
    return p;
  }

  /// The parts of a mesh: its triangles halved at the median of their centroids along the
  /// longest axis, down to a patch of at most kPatch triangles that is convex within eps
  /// (every corner of the patch at most eps outside every triangle's plane), else to one; a
  /// leaf holds its patch's corners, and covers the patch whatever it is. (A patch about a
  /// concave edge would cover space outside the body, which the surface must not enter; a
  /// convex one stays in the body, and one leaf for many thin triangles keeps the walk short.)
  void build_parts(const TriangleMesh& mesh, double eps) {
    std::vector<int> order(mesh.triangles.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    parts_.emplace_back();
    split_part(mesh, order, 0, 0, order.size(), eps);
  }
  static constexpr std::size_t kPatch = 16;
  /// Corner k of the triangle order[i] of the mesh.
  static const Eigen::Vector3d& corner_of(const TriangleMesh& mesh, const std::vector<int>& order,
                                          std::size_t i, int k) {
    return mesh.vertices[static_cast<std::size_t>(
        mesh.triangles[static_cast<std::size_t>(order[i])][static_cast<std::size_t>(k)])];
  }
  /// Whether the triangles order[a, b) are convex within eps (see build_parts).
  static bool convex_patch(const TriangleMesh& mesh, const std::vector<int>& order, std::size_t a,
                           std::size_t b, double eps) {
    auto at = [&](std::size_t i, int k) -> const Eigen::Vector3d& {
      return corner_of(mesh, order, i, k);
    };
    for (std::size_t i = a; i < b; ++i) {
      const Eigen::Vector3d n = (at(i, 1) - at(i, 0)).cross(at(i, 2) - at(i, 0)).normalized();
      if (!n.allFinite()) return false;
      for (std::size_t j = a; j < b; ++j)
        for (int k = 0; k < 3; ++k)
          if (!(n.dot(at(j, k) - at(i, 0)) <= eps)) return false;
    }
    return true;
  }
  void split_part(const TriangleMesh& mesh, std::vector<int>& order, std::size_t at, std::size_t a,
                  std::size_t b, double eps) {
    auto corner = [&](std::size_t i, int k) -> const Eigen::Vector3d& {
      return corner_of(mesh, order, i, k);
    };
    Eigen::AlignedBox3d box;
    for (std::size_t i = a; i < b; ++i)
      for (int k = 0; k < 3; ++k) box.extend(corner(i, k));
    Part p;
    p.count = -1;
    p.centre = box.center();
    for (std::size_t i = a; i < b; ++i)
      for (int k = 0; k < 3; ++k) p.radius = std::max(p.radius, (corner(i, k) - p.centre).norm());
    p.radius *= 1 + 1e-12;
    if (b - a <= 1 || (b - a <= kPatch && convex_patch(mesh, order, a, b, eps))) {
      p.first = static_cast<int>(points_.size());
      std::vector<int> corners;
      for (std::size_t i = a; i < b; ++i)
        for (int v : mesh.triangles[static_cast<std::size_t>(order[i])]) corners.push_back(v);
      std::sort(corners.begin(), corners.end());
      corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
      for (int v : corners) points_.push_back(mesh.vertices[static_cast<std::size_t>(v)]);
      p.count = static_cast<int>(corners.size());
      parts_[at] = p;
      return;
    }
    const std::size_t mid = detail::split_at_median(mesh, order, a, b);
    p.child = static_cast<int>(parts_.size());
    parts_[at] = p;
    parts_.emplace_back();
    parts_.emplace_back();
    split_part(mesh, order, static_cast<std::size_t>(p.child), a, mid, eps);
    split_part(mesh, order, static_cast<std::size_t>(p.child) + 1, mid, b, eps);
  }

  /// The part's point farthest along u (a moving-space direction).
  Eigen::Vector3d part_support(const Part& P, const Eigen::Vector3d& u) const {
    if (P.count == 0) return support_point(body_, u);
    const auto* q = points_.data() + P.first;
    int best = 0;
    for (int i = 1; i < P.count; ++i)
      if (u.dot(q[i]) > u.dot(q[best])) best = i;
    return q[best];
  }
  /// hi(n): the support value of the part placed by key k.
  double support(int k, const Part& P, const Eigen::Vector3d& n) const {
    const Map& M = keys_[static_cast<std::size_t>(k)];
    const Eigen::Vector3d u = M.rightCols<3>().transpose() * n;
    return n.dot(M.col(0)) + u.dot(part_support(P, u));
  }
  /// The support point of C = conv(M_k P u M_k+1 P) along d.
  Eigen::Vector3d piece_support(int k, const Part& P, const Eigen::Vector3d& d) const {
    Eigen::Vector3d best = Eigen::Vector3d::Zero();
    double most = -HUGE_VAL;
    for (int j = k; j <= k + 1; ++j) {
      const Map& M = keys_[static_cast<std::size_t>(j)];
      const Eigen::Vector3d y =
          M.col(0) + M.rightCols<3>() * part_support(P, M.rightCols<3>().transpose() * d);
      if (d.dot(y) > most) {
        most = d.dot(y);
        best = y;
      }
    }
    return best;
  }

  /// Directions with the points' least extent along each.
  struct Directions {
    Eigen::Vector3d n_[3];
    double low[3] = {0, 0, 0};
    int n = 0;
    void add(const Eigen::Vector3d& u, const Eigen::Vector3d* pts, std::size_t m) {
      const int i = n < 3 ? n++ : 2;
      n_[i] = u;
      low[i] = HUGE_VAL;
      for (std::size_t j = 0; j < m; ++j) low[i] = std::min(low[i], u.dot(pts[j]));
    }
  };

  /// Whether the hull of pts[0, m) is farther than margin from piece k of part P (grown by
  /// its delta): along one of the directions, else along GJK's.
  bool piece_clear(int k, const Part& P, const Eigen::Vector3d* pts, std::size_t m,
                   Directions& dirs, double margin, Stats* stats) const {
    const double need = delta_[static_cast<std::size_t>(k)] + margin + rounding_;
    for (int i = dirs.n - 1; i >= 0; --i) {
      const Eigen::Vector3d& n = dirs.n_[i];
      if (dirs.low[i] - std::max(support(k, P, n), support(k + 1, P, n)) > need) return true;
    }
    if (stats) ++stats->gjk;
    // GJK on D = H - C, H the hull of the points (a triangle, or a patch): v, the point of the
    // simplex W nearest the origin, is a point of D, so |v| >= dist; w, D's point least along v,
    // gives the plane v . x >= v . w that holds D: dist >= v . w / |v|, which is the separation
    // along v / |v| above.
    Simplex W;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < m; ++i) mean += pts[i];
    Eigen::Vector3d v = mean / static_cast<double>(m) - piece_support(k, P, -dirs.n_[0]);
    for (int it = 0; it < 48; ++it) {
      const double vn = v.norm();
      if (!(vn > need)) return false;
      std::size_t lo = 0;
      for (std::size_t i = 1; i < m; ++i)
        if (v.dot(pts[i]) < v.dot(pts[lo])) lo = i;
      const Eigen::Vector3d w = pts[lo] - piece_support(k, P, v);
      // d . w: the points' least extent along d less C's support value there (the
      // support point above is C's farthest along v, so along d).
      const Eigen::Vector3d d = v / vn;
      const double low = d.dot(w);
      if (low > need) {
        dirs.add(d, pts, m);
        return true;
      }
      if (vn * vn - v.dot(w) <= 1e-12 * vn * vn) return false;  // converged short of need
      W.p[W.n++] = w;
      v = nearest_on_simplex(W);
      if (W.n == 4) return false;  // the origin inside a tetrahedron of D: they meet
    }
    return false;
  }

  struct Simplex {
    Eigen::Vector3d p[4];
    int n = 0;
  };

  /// The point of conv(W) nearest the origin (W: up to four points); W keeps the face it
  /// lies on. Every face's affine nearest point is tried; the nearest one inside its face wins.
  static Eigen::Vector3d nearest_on_simplex(Simplex& W) {
    const int n = W.n;
    double best = HUGE_VAL;
    int best_mask = 1;
    Eigen::Vector3d best_x = W.p[0];
    for (int mask = 1; mask < (1 << n); ++mask) {
      int idx[4] = {0, 0, 0, 0}, k = 0;
      for (int i = 0; i < n; ++i)
        if (mask >> i & 1) idx[k++] = i;
      const Eigen::Vector3d& w0 = W.p[idx[0]];
      Eigen::Vector3d x = w0;
      if (k > 1) {
        // Minimise |w0 + A mu| over mu: (A^T A) mu = -A^T w0, at most 3 x 3.
        Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
        for (int i = 1; i < k; ++i) A.col(i - 1) = W.p[idx[i]] - w0;
        const int m = k - 1;
        const Eigen::Matrix3d G = A.transpose() * A;
        const Eigen::Vector3d r = -A.transpose() * w0;
        Eigen::Vector3d mu = Eigen::Vector3d::Zero();
        if (m == 1) {
          if (!(G(0, 0) > 0)) continue;
          mu(0) = r(0) / G(0, 0);
        } else if (m == 2) {
          const Eigen::Matrix2d g2 = G.topLeftCorner<2, 2>();
          const double det = g2.determinant();
          if (!(std::abs(det) > 1e-24 * g2.squaredNorm())) continue;
          mu.head<2>() = g2.inverse() * r.head<2>();
        } else {
          const double det = G.determinant();
          if (!(std::abs(det) > 1e-24 * std::pow(G.norm(), 3))) continue;
          mu = G.inverse() * r;
        }
        if (!mu.allFinite() || mu.head(m).minCoeff() < 0 || mu.head(m).sum() > 1) continue;
        x = w0 + A * mu;
      }
      if (x.norm() < best) {
        best = x.norm();
        best_mask = mask;
        best_x = x;
      }
    }
    Simplex kept;
    for (int i = 0; i < n; ++i)
      if (best_mask >> i & 1) kept.p[kept.n++] = W.p[i];
    W = kept;
    return best_x;
  }

  /// Appends k1 to keys, with keys between the last one and it while turn_excess is above
  /// target (exact poses at the middles).
  void refine(const qmotion::Motion& m, std::vector<Keyframe>& keys, const Keyframe& k1,
              double target, int depth) const {
    const Keyframe k0 = keys.back();
    if (depth < 40 && turn_excess(k0, k1) > target) {
      const Keyframe mid = exact_key(m, 0.5 * (k0.t + k1.t), &k0);
      if (mid.t > k0.t && mid.t < k1.t) {
        refine(m, keys, mid, target, depth + 1);
        refine(m, keys, k1, target, depth + 1);
        return;
      }
    }
    keys.push_back(k1);
  }

  int build(int lo, int hi) {
    Node nd;
    nd.lo = lo;
    nd.hi = hi;
    nd.key = (lo + hi) / 2;
    const Map& Mm = keys_[static_cast<std::size_t>(nd.key)];
    double lever = 0, delta = 0;
    for (int j = lo; j <= hi; ++j)
      lever = std::max(lever, detail::lever_norm(keys_[static_cast<std::size_t>(j)] - Mm, rho_));
    for (int k = lo; k < hi; ++k) delta = std::max(delta, delta_[static_cast<std::size_t>(k)]);
    nd.reach = (lever + delta) * (1 + 1e-12);
    nd.centre = Mm.col(0) + Mm.rightCols<3>() * parts_.front().centre;
    const int at = static_cast<int>(nodes_.size());
    nodes_.push_back(nd);
    if (hi - lo > 1) {
      const int mid = (lo + hi) / 2;
      const int c0 = build(lo, mid), c1 = build(mid, hi);
      nodes_[static_cast<std::size_t>(at)].child[0] = c0;
      nodes_[static_cast<std::size_t>(at)].child[1] = c1;
    }
    return at;
  }

  const Body& body_;
  double rho_;
  std::vector<Part> parts_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<Map> keys_;
  std::vector<double> delta_;
  double largest_ = 0, rounding_ = 0;
  std::vector<Node> nodes_;
};

}  // namespace qmotion::sweep
