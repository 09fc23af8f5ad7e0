// <qmotion/sweep/swept_volume.hpp>: how far a point is from the space a moving body sweeps,
// { M(t) x : t in [a, b], x in the body }, with certified lower and upper bounds
// (docs/geometry.md, "Swept volumes").
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <qmotion/kernel/error.hpp>
#include <qmotion/motion.hpp>
#include <qmotion/sweep/body.hpp>
#include <qmotion/sweep/keyframes.hpp>
#include <string>
#include <utility>
#include <vector>

namespace qmotion::sweep {

/// What a query learns of the distance f(q) from a point q to the swept volume V:
/// lower <= f(q) (certified: V lies in the union of sets the query measured against), and,
/// from the body placed by the exact motion at the parameter t, signed = the signed distance
/// from q to M(t) K, so f(q) <= max(signed, 0), and q lies in V with a ball of radius
/// -signed about it when signed < 0.
struct VolumeDistance {
  double lower = 0;
  double signed_upper = HUGE_VAL;
  double t = 0;           ///< where signed_upper was found
  double t0 = 0, t1 = 0;  ///< the finest interval of t searched there
  int node = -1;          ///< the tree's node whose placement gave signed_upper
};

/// A convex lower bound of a closed mesh body's signed distance, for the plane bounds of the
/// tree's leaves: the polytope P = { x : n_i . x <= b_i } about the mesh (n_i the 26
/// directions to the faces, edges and corners of a cube, b_i the mesh's largest n_i . v,
/// raised by 1e-12 of its radius for rounding). L(x) = max_i (n_i . x - b_i) is convex, with
/// the maximising n_i as a subgradient, and L <= sd_P <= sd_body: outside P every point p of P
/// has |x - p| >= n_i . (x - p) >= n_i . x - b_i; inside, L is minus the distance to P's
/// nearest face plane; and P holds the body, so sd_P <= sd_body everywhere.
class Dop {
 public:
  Dop() = default;
  explicit Dop(const TriangleMesh& m) {
    double rho = 0;
    for (const auto& v : m.vertices) rho = std::max(rho, v.norm());
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b)
        for (int c = -1; c <= 1; ++c) {
          if (a == 0 && b == 0 && c == 0) continue;
          const Eigen::Vector3d n = Eigen::Vector3d(a, b, c).normalized();
          double most = -HUGE_VAL;
          for (const auto& v : m.vertices) most = std::max(most, n.dot(v));
          n_.push_back(n);
          b_.push_back(most + 1e-12 * rho);
        }
  }
  /// L(x), and g its subgradient there.
  double lower(const Eigen::Vector3d& x, Eigen::Vector3d& g) const {
    g.setZero();
    double best = -HUGE_VAL;
    for (std::size_t i = 0; i < n_.size(); ++i) {
      const double v = n_[i].dot(x) - b_[i];
      if (v > best) {
        best = v;
        g = n_[i];
      }
    }
    return best;
  }

 private:
  std::vector<Eigen::Vector3d> n_;
  std::vector<double> b_;
};

/// A binary tree over the motion's parameter: every node is an interval [t0, t1] of one
/// segment, with the body placed at its middle, M(tm) K, and a radius Delta such that every
/// point of the body stays within Delta of where M(tm) puts it over the interval:
/// |M(t) x - M(tm) x| <= Delta for t in [t0, t1], |x| <= rho (rho: sweep::radius). So the
/// piece of V swept over the node lies in M(tm) K grown by Delta, and the distance from q to
/// it is at least sd_K(M(tm)^-1 q) - Delta.
///
/// Delta comes from KeyframeBound between the exact poses at t0 and t1 (the certified
/// deviation delta of the motion from the player's blend S: translation linear, rotation
/// spherical): |M(t) x - M(tm) x| <= |M(t) x - S(t) x| + |S(t) x - S(tm) x| + |S(tm) x -
/// M(tm) x| <= 2 delta + |p1 - p0| / 2 + rho |q1 - q0|, since the blend turns by at most
/// half the angle phi between the ends from its middle, and |q1 - q0| = 2 sin(phi / 4).
/// Leaves are split until Delta <= the requested leaf size.
class SweptVolumeTree {
 public:
  struct Node {
    double t0 = 0, t1 = 0, tm = 0;
    Eigen::Matrix3d Rt = Eigen::Matrix3d::Identity();  ///< M(tm)'s rotation, transposed
    Eigen::Vector3d p = Eigen::Vector3d::Zero();       ///< M(tm)'s translation
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< of the placed body's bounding ball
    double delta = HUGE_VAL;
    int child[2] = {-1, -1};
  };

  /// Errc::numerical_failure for a rational motion with a pole on its interval, or when a
  /// node narrower than 1e-12 of the interval cannot reach the leaf size.
  SweptVolumeTree(const qmotion::Motion& m, const Body& body, double leaf_delta)
      : motion_(m),
        body_(body),
        convex_(is_convex(body)),
        rho_(radius(body)),
        bound_(m, radius(body), 4),
        leaf_(leaf_delta) {
    if (!convex_) dop_ = Dop(body.mesh);
    ball_centre_ = ball_centre(body);
    ball_radius_ = 0;
    for (const auto& v : triangulate(body, 1e-3 * rho_).vertices)
      ball_radius_ = std::max(ball_radius_, (v - ball_centre_).norm());
    // The triangulation's vertices lie on the body; its curved parts bulge out by at most
    // 1e-3 rho between them.
    ball_radius_ += 1e-3 * rho_ + 1e-12 * rho_;
    const auto x = m.breakpoints();
    for (std::size_t i = 0; i + 1 < x.size(); ++i) roots_.push_back(build(x[i], x[i + 1], 0));
  }

  const std::vector<Node>& nodes() const { return nodes_; }
  const std::vector<int>& roots() const { return roots_; }
  std::size_t leaves() const { return leaves_; }
  double leaf_delta() const { return leaf_; }
  double largest_leaf_delta() const { return largest_leaf_; }
  const Body& body() const { return body_; }
  double body_ball_radius() const { return ball_radius_; }

  /// An axis-aligned box holding V: the leaves' bounding balls grown by their Delta.
  Eigen::AlignedBox3d bounds() const {
    Eigen::AlignedBox3d box;
    for (const auto& n : nodes_)
      if (n.child[0] < 0) {
        const double r = ball_radius_ + n.delta;
        box.extend(n.centre - Eigen::Vector3d::Constant(r));
        box.extend(n.centre + Eigen::Vector3d::Constant(r));
      }
    return box;
  }

  /// Bounds of the distance from q to V by branch and bound over the tree on the signed
  /// distance to the placed body: a node is not opened when its lower bound is no better than
  /// the best placement's. Once a placement holds q, lower = 0 is exact and the search goes
  /// on for the deepest placement. It ends at the first placement whose signed distance is
  /// below stop_below (<= 0: q lies in V that deep).
  VolumeDistance query(const Eigen::Vector3d& q, double stop_below = 0) const {
    VolumeDistance out;
    out.lower = HUGE_VAL;
    thread_local std::vector<std::pair<int, double>> stack;  // node, its parent's bound
    stack.clear();
    double best = HUGE_VAL;  // the smallest upper bound so far (signed)
    for (auto r = roots_.rbegin(); r != roots_.rend(); ++r) stack.emplace_back(*r, -HUGE_VAL);
    while (!stack.empty()) {
      const auto [i, parent_lb] = stack.back();
      stack.pop_back();
      const Node& n = nodes_[i];
      if (parent_lb >= best) {  // the parent's bound already says no
        out.lower = std::min(out.lower, parent_lb);
        continue;
      }
      // A cheap bound from the bounding ball, then the body itself.
      const double ball = (q - n.centre).norm() - ball_radius_ - n.delta;
      if (ball >= best) {
        out.lower = std::min(out.lower, ball);
        continue;
      }
      const double sd = signed_distance(body_, n.Rt * (q - n.p));
      const double lb = std::max(ball, sd - n.delta);
      if (sd < best) {
        best = sd;
        out.signed_upper = sd;
        found_at(out, i);
      }
      if (best < stop_below) {
        out.lower = 0;
        return out;
      }
      if (n.child[0] < 0 || lb >= best) {
        out.lower = std::min(out.lower, lb);
        continue;
      }
      // Children: the nearer one last, so it is opened first.
      const Node &c0 = nodes_[n.child[0]], &c1 = nodes_[n.child[1]];
      const bool first0 = (q - c0.centre).squaredNorm() < (q - c1.centre).squaredNorm();
      stack.emplace_back(first0 ? n.child[1] : n.child[0], lb);
      stack.emplace_back(first0 ? n.child[0] : n.child[1], lb);
    }
    out.lower = std::max(0.0, std::min(out.lower, std::max(best, 0.0)));
    return out;
  }

  /// Records node i as where d's upper bound was found: its parameters and interval.
  void found_at(VolumeDistance& d, int i) const {
    const Node& n = nodes_[static_cast<std::size_t>(i)];
    d.node = i;
    d.t = n.tm;
    d.t0 = n.t0;
    d.t1 = n.t1;
  }

  /// The signed distance from q to the body as node i places it, M(tm) K: an upper bound of
  /// the distance from q to V.
  double node_distance(const Eigen::Vector3d& q, int i) const {
    const Node& n = nodes_[static_cast<std::size_t>(i)];
    return signed_distance(body_, n.Rt * (q - n.p));
  }

  /// The leaves that can hold the nearest placement for some point within r of c, for a
  /// batch of queries about c (see candidates()), and what bounds them for such a point.
  struct Candidates {
    /// The smallest lb - r of the nodes left out: a lower bound, for every x within r of c,
    /// of its distance to the part of V they sweep.
    double rest = HUGE_VAL;
    /// narrow(): the signed distance from c to the body placed by best_node (-1: none), an
    /// upper bound of f(c), and the least lower bound for the ball, lower.
    double best = HUGE_VAL, lower = HUGE_VAL;
    int best_node = -1;
    std::vector<int> node;
    std::vector<double> bound;  ///< the leaf's bound at c less r: a lower bound for every x
    /// The leaf's plane bound: base + g . x <= sd_K(M(tm)^-1 x) - Delta for every x, with g
    /// the subgradient at c of the signed distance (a convex body: see signed_distance with
    /// g) or of its polytope bound (a mesh: Dop).
    std::vector<double> base, gx, gy, gz;
    void clear() {
      node.clear();
      bound.clear();
      base.clear();
      gx.clear();
      gy.clear();
      gz.clear();
    }
  };

  /// The leaves that can hold the nearest placement for some point within r of c, for a
  /// batch of queries about c. A node whose bound at c, lb, is at least best + 2 r (best: the
  /// smallest signed distance from c to a placement seen) is left out: for x within r of c
  /// its bound is at least lb - r >= best + r, and best + r bounds x's distance from above.
  /// Each leaf also gets a plane: for a convex body through its signed distance at c along a
  /// subgradient there, a lower bound of the signed distance everywhere, exact to first order
  /// about c; for a mesh the same of its polytope bound (Dop), exact to first order where the
  /// mesh's nearest point lies on that polytope's boundary.
  void candidates(const Eigen::Vector3d& c, double r, Candidates& out) const {
    out.clear();
    thread_local std::vector<std::pair<int, double>> stack;  // node, its bound at c
    struct Found {
      int node;
      double lb, pv;  // the leaf's bound at c; its plane's value at c
      Eigen::Vector3d g;
    };
    thread_local std::vector<Found> found;
    stack.clear();
    found.clear();
    double best = HUGE_VAL, left_out = HUGE_VAL;
    for (auto it = roots_.rbegin(); it != roots_.rend(); ++it) stack.emplace_back(*it, -HUGE_VAL);
    while (!stack.empty()) {
      const auto [i, parent_lb] = stack.back();
      stack.pop_back();
      if (parent_lb >= best + 2 * r) {
        left_out = std::min(left_out, parent_lb);
        continue;
      }
      const Node& n = nodes_[static_cast<std::size_t>(i)];
      const double ball = (c - n.centre).norm() - ball_radius_ - n.delta;
      if (ball >= best + 2 * r) {
        left_out = std::min(left_out, ball);
        continue;
      }
      const bool leaf = n.child[0] < 0;
      Eigen::Vector3d g = Eigen::Vector3d::Zero();
      const Eigen::Vector3d local = n.Rt * (c - n.p);
      const double sd =
          leaf && convex_ ? signed_distance(body_, local, g) : signed_distance(body_, local);
      // The plane's value at c: the signed distance itself for a convex body, else the
      // polytope bound (Dop), whose subgradient is g.
      const double pv = leaf && !convex_ ? dop_.lower(local, g) : sd;
      best = std::min(best, sd);
      const double lb = std::max(ball, sd - n.delta);
      if (lb >= best + 2 * r) {
        left_out = std::min(left_out, lb);
        continue;
      }
      if (leaf) {
        found.push_back({i, lb, pv, n.Rt.transpose() * g});
        continue;
      }
      const Node &c0 = nodes_[static_cast<std::size_t>(n.child[0])],
                 &c1 = nodes_[static_cast<std::size_t>(n.child[1])];
      const bool first0 = (c - c0.centre).squaredNorm() < (c - c1.centre).squaredNorm();
      stack.emplace_back(first0 ? n.child[1] : n.child[0], lb);
      stack.emplace_back(first0 ? n.child[0] : n.child[1], lb);
    }
    // Leaves found before best fell far enough are left out now.
    for (const auto& f : found) {
      if (f.lb >= best + 2 * r) {
        left_out = std::min(left_out, f.lb);
        continue;
      }
      out.node.push_back(f.node);
      out.bound.push_back(f.lb - r);
      // Rounding: the plane is lowered by 1e-12 of the sizes it sums.
      const double delta = nodes_[static_cast<std::size_t>(f.node)].delta;
      const double gc = f.g.dot(c);
      out.base.push_back(f.pv - delta - gc -
                         1e-12 * (std::abs(f.pv) + std::abs(gc) + delta + r + rho_));
      out.gx.push_back(f.g.x());
      out.gy.push_back(f.g.y());
      out.gz.push_back(f.g.z());
    }
    out.rest = left_out - r;
  }

  /// The candidates of a smaller batch, about c within r, whose ball lies in wide's: wide's
  /// leaves less those that cannot hold the nearest placement for a point of the new ball.
  /// Each leaf's bound for the ball is the larger of wide's and its plane at c less r; the
  /// least is placed at c, best, and a leaf whose bound is at least best + r is left out (a
  /// point of the ball is within best + r of that placement).
  void narrow(const Candidates& wide, const Eigen::Vector3d& c, double r, Candidates& out) const {
    out.clear();
    out.rest = wide.rest;
    const std::size_t n = wide.node.size();
    thread_local std::vector<double> lb;
    const std::size_t first = bounds_at(wide, c, r * (1 + 1e-12), lb);  // |g| <= 1 up to rounding
    const double least = first < n ? lb[first] : HUGE_VAL;
    out.best = HUGE_VAL;
    out.best_node = -1;
    out.lower = std::min(out.rest, least);
    if (first == n) return;
    const double best = node_distance(c, wide.node[first]);
    out.best = best;
    out.best_node = wide.node[first];
    for (std::size_t k = 0; k < n; ++k) {
      if (lb[k] >= best + r) {
        out.rest = std::min(out.rest, lb[k]);
        continue;
      }
      out.node.push_back(wide.node[k]);
      out.bound.push_back(lb[k]);
      out.base.push_back(wide.base[k]);
      out.gx.push_back(wide.gx[k]);
      out.gy.push_back(wide.gy[k]);
      out.gz.push_back(wide.gz[k]);
    }
  }

  /// What query(x) learns from the candidates of a batch about c (candidates(c, r, ...)), for
  /// x within r of c. Every leaf has a lower bound at x without placing the body (its bound
  /// at c less r, and its plane); the leaf with the least is placed first,
  /// then every other whose bound is below what is known less `slack` (so that lower is at
  /// most slack below what placing them all would give). It stops when a placement holds x
  /// deeper than stop_depth.
  VolumeDistance query_among(const Eigen::Vector3d& x, const Candidates& cands, double slack,
                             double stop_depth) const {
    VolumeDistance out;
    const std::size_t n = cands.node.size();
    thread_local std::vector<double> lin;
    const std::size_t first = bounds_at(cands, x, 0, lin);
    double known = cands.rest, skipped = HUGE_VAL, best = HUGE_VAL;
    auto place = [&](std::size_t k) {
      const int i = cands.node[k];
      const double sd = node_distance(x, i);
      known = std::min(known, std::max(lin[k], sd - nodes_[static_cast<std::size_t>(i)].delta));
      if (sd < best) {
        best = sd;
        out.node = i;
      }
    };
    if (first < n) place(first);
    for (std::size_t k = 0; k < n && best > -stop_depth; ++k) {
      if (k == first) continue;
      if (lin[k] >= std::min(known, std::max(best, 0.0)) - slack)
        skipped = std::min(skipped, lin[k]);
      else
        place(k);
    }
    out.signed_upper = best;
    if (out.node >= 0) found_at(out, out.node);
    out.lower = std::max(0.0, std::min({known, skipped, std::max(best, 0.0)}));
    return out;
  }

  /// The signed distance from q to the body placed by the exact motion at t.
  double placed_distance(const Eigen::Vector3d& q, double t) const {
    const Eigen::Matrix4d f = motion_.frame(t);
    return signed_distance(body_, f.block<3, 3>(1, 1).transpose() * (q - f.block<3, 1>(1, 0)));
  }

 private:
  /// Every candidate's lower bound for the points within `reach` of x: the larger of its
  /// bound and its plane at x less reach (a plane's slope |g| is at most
  /// one). The loop runs over plain arrays, so that it vectorises. Returns the index of the
  /// least (the candidates' number when there are none).
  std::size_t bounds_at(const Candidates& cands, const Eigen::Vector3d& x, double reach,
                        std::vector<double>& out) const {
    const std::size_t n = cands.node.size();
    out.resize(n);
    double* const l = out.data();
    const double *bound = cands.bound.data(), *base = cands.base.data(), *gx = cands.gx.data(),
                 *gy = cands.gy.data(), *gz = cands.gz.data();
    const double x0 = x.x(), x1 = x.y(), x2 = x.z();
    for (std::size_t k = 0; k < n; ++k) {
      const double p = base[k] + gx[k] * x0 + gy[k] * x1 + gz[k] * x2 - reach;
      l[k] = bound[k] > p ? bound[k] : p;
    }
    std::size_t first = n;
    double least = HUGE_VAL;
    for (std::size_t k = 0; k < n; ++k)
      if (l[k] < least) {
        least = l[k];
        first = k;
      }
    return first;
  }

  static Eigen::Vector3d ball_centre(const Body& b) {
    using K = Body::Kind;
    switch (b.kind) {
      case K::cylinder:
        return {0, 0, b.h / 2};
      case K::flat_cutter:
      case K::ball_cutter:
      case K::bull_cutter:
        return {0, 0, b.L / 2};
      case K::mesh: {
        Eigen::AlignedBox3d box;
        for (const auto& v : b.mesh.vertices) box.extend(v);
        return box.center();
      }
      default:
        return Eigen::Vector3d::Zero();
    }
  }

  int build(double t0, double t1, int depth) {
    const double range = motion_.b() - motion_.a();
    Node n;
    n.t0 = t0;
    n.t1 = t1;
    n.tm = 0.5 * (t0 + t1);
    const Keyframe k0 = exact_key(motion_, t0, nullptr);
    const Keyframe k1 = exact_key(motion_, t1, &k0);
    const double delta = bound_(k0, k1);
    n.delta = (2 * delta + 0.5 * (k1.translation - k0.translation).norm() +
               rho_ * (k1.rotation.coeffs() - k0.rotation.coeffs()).norm()) *
              (1 + 1e-12);
    if (!std::isfinite(n.delta)) n.delta = HUGE_VAL;
    const Eigen::Matrix4d f = motion_.frame(n.tm);
    n.Rt = f.block<3, 3>(1, 1).transpose();
    n.p = f.block<3, 1>(1, 0);
    n.centre = n.p + f.block<3, 3>(1, 1) * ball_centre_;
    const int index = static_cast<int>(nodes_.size());
    nodes_.push_back(n);
    if (n.delta <= leaf_) {
      ++leaves_;
      largest_leaf_ = std::max(largest_leaf_, n.delta);
      return index;
    }
    if (t1 - t0 < 1e-12 * range || depth > 60)
      throw Error(Errc::numerical_failure,
                  motion_.label() + ": cannot bound the swept volume within " +
                      kernel::detail::format_double(leaf_) + " near t = " +
                      kernel::detail::format_double(n.tm) + " (a pole, or a tolerance too fine)");
    if (nodes_.size() > max_nodes)
      throw Error(Errc::numerical_failure,
                  motion_.label() + ": more than " + std::to_string(max_nodes) +
                      " parameter intervals to bound the swept volume within " +
                      kernel::detail::format_double(leaf_) + ": the tolerance is too fine");
    const int c0 = build(t0, n.tm, depth + 1);
    const int c1 = build(n.tm, t1, depth + 1);
    nodes_[index].child[0] = c0;
    nodes_[index].child[1] = c1;
    return index;
  }

  static constexpr std::size_t max_nodes = 1 << 22;
  const qmotion::Motion& motion_;
  const Body& body_;
  bool convex_;
  Dop dop_;  ///< a non-convex body's polytope bound
  double rho_;
  KeyframeBound bound_;
  double leaf_;
  Eigen::Vector3d ball_centre_ = Eigen::Vector3d::Zero();
  double ball_radius_ = 0;
  std::vector<Node> nodes_;
  std::vector<int> roots_;
  std::size_t leaves_ = 0;
  double largest_leaf_ = 0;
};

}  // namespace qmotion::sweep
