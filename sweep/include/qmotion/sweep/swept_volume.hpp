// <qmotion/sweep/swept_volume.hpp>: how far a point is from the space a moving body sweeps,
// { M(t) x : t in [a, b], x in the body }, with certified lower and upper bounds
// (docs/geometry.md, "Swept volumes").
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
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

  /// Runs f(0), ..., f(n - 1), in any order and on any threads: each span's tree is built
  /// by one call (api passes TBB's parallel_for; the default runs them in turn).
  using ForEach = std::function<void(std::size_t n, const std::function<void(std::size_t)>& f)>;

  /// Errc::numerical_failure for a rational motion with a pole on its interval, or when a
  /// node narrower than 1e-12 of the interval cannot reach the leaf size.
  SweptVolumeTree(const qmotion::Motion& m, const Body& body, double leaf_delta,
                  const ForEach& for_each = {})
      : motion_(m), body_(body), rho_(radius(body)), bound_(m, radius(body), 4), leaf_(leaf_delta) {
    ball_centre_ = ball_centre(body);
    for (const auto& v : body.mesh.vertices) mesh_box_.extend(v);
    ball_radius_ = 0;
    for (const auto& v : triangulate(body, 1e-3 * rho_).vertices)
      ball_radius_ = std::max(ball_radius_, (v - ball_centre_).norm());
    // The triangulation's vertices lie on the body; its curved parts bulge out by at most
    // 1e-3 rho between them.
    ball_radius_ += 1e-3 * rho_ + 1e-12 * rho_;
    const auto x = m.breakpoints();
    // A tree per span, numbered from 0 in it, then one list of nodes.
    std::vector<Built> spans(x.size() > 0 ? x.size() - 1 : 0);
    const auto one = [&](std::size_t i) { build(spans[i], x[i], x[i + 1], 0); };
    if (for_each)
      for_each(spans.size(), one);
    else
      for (std::size_t i = 0; i < spans.size(); ++i) one(i);
    for (auto& b : spans) {
      const int base = static_cast<int>(nodes_.size());
      roots_.push_back(base);
      for (Node n : b.nodes) {
        for (int& c : n.child)
          if (c >= 0) c += base;
        nodes_.push_back(n);
      }
      leaves_ += b.leaves;
      largest_leaf_ = std::max(largest_leaf_, b.largest);
    }
    if (nodes_.size() > max_nodes) too_many();
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
  /// below stop_below (<= 0: q lies in V that deep). `hint`, a node whose placement is
  /// likely near the best (a neighbouring point's), is measured first: the search is
  /// shorter, its best placement the same (every node that could do better is still
  /// opened; with stop_below, the first found below it), and `lower` still a lower bound.
  /// With stop_above, nodes whose lower bound reaches it are not opened either, and a mesh
  /// body's distances are searched only that far: unless signed_upper < stop_above, it is
  /// only known that f(q) >= lower >= stop_above - largest_leaf_delta() (a leaf is closed
  /// at its distance less its Delta; signed_upper is a placement's or HUGE_VAL). That is
  /// all a caller needs that asks whether f(q) is below a level well under stop_above.
  VolumeDistance query(const Eigen::Vector3d& q, double stop_below = 0, int hint = -1,
                       double stop_above = HUGE_VAL) const {
    VolumeDistance out;
    out.lower = HUGE_VAL;
    thread_local std::vector<std::pair<int, double>> stack;  // node, its parent's bound
    stack.clear();
    double best = HUGE_VAL;   // the smallest upper bound so far (signed)
    double bar = stop_above;  // min(best, stop_above): what a node must beat to be opened
    if (hint >= 0 && static_cast<std::size_t>(hint) < nodes_.size()) {
      best = node_distance(q, hint);
      out.signed_upper = best;
      found_at(out, hint);
      bar = std::min(best, stop_above);
      if (best < stop_below) {
        out.lower = 0;
        return out;
      }
    }
    for (auto r = roots_.rbegin(); r != roots_.rend(); ++r) stack.emplace_back(*r, -HUGE_VAL);
    while (!stack.empty()) {
      const auto [i, parent_lb] = stack.back();
      stack.pop_back();
      const Node& n = nodes_[i];
      if (parent_lb >= bar) {  // the parent's bound already says no
        out.lower = std::min(out.lower, parent_lb);
        continue;
      }
      // A cheap bound from the bounding ball, then the body itself.
      const double ball = (q - n.centre).norm() - ball_radius_ - n.delta;
      if (ball >= bar) {
        out.lower = std::min(out.lower, ball);
        continue;
      }
      bool capped = false;
      const double sd = capped_distance(n.Rt * (q - n.p), bar + n.delta, &capped);
      const double lb = std::max(ball, sd - n.delta);
      if (!capped && sd < best) {
        best = sd;
        bar = std::min(best, stop_above);
        out.signed_upper = sd;
        found_at(out, i);
      }
      if (best < stop_below) {
        out.lower = 0;
        return out;
      }
      if (n.child[0] < 0 || lb >= bar) {
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

  /// The signed distance from q to the body placed by the exact motion at t.
  double placed_distance(const Eigen::Vector3d& q, double t) const {
    const Eigen::Matrix4d f = motion_.frame(t);
    return signed_distance(body_, f.block<3, 3>(1, 1).transpose() * (q - f.block<3, 1>(1, 0)));
  }

 private:
  /// The body's signed distance at a local point, or, for a mesh, cap when it is certainly
  /// at least cap (> 0): no triangle lies nearer than cap and the point is outside the
  /// mesh's box. A query needs no more of a node whose distance reaches best + Delta.
  double capped_distance(const Eigen::Vector3d& local, double cap, bool* capped) const {
    if (!body_.index || !(cap > 0) || !(cap < HUGE_VAL)) return signed_distance(body_, local);
    const double d = body_.index->signed_distance(local, nullptr, cap);
    if (d < HUGE_VAL) return d;
    if (mesh_box_.exteriorDistance(local) > 0) {
      *capped = true;  // a lower bound, not a placement's distance
      return cap;
    }
    return signed_distance(body_, local);
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

  /// One span's tree, its nodes numbered from 0.
  struct Built {
    std::vector<Node> nodes;
    std::size_t leaves = 0;
    double largest = 0;
  };

  [[noreturn]] void too_many() const {
    throw Error(Errc::numerical_failure,
                motion_.label() + ": more than " + std::to_string(max_nodes) +
                    " parameter intervals to bound the swept volume within " +
                    kernel::detail::format_double(leaf_) + ": the tolerance is too fine");
  }

  int build(Built& out, double t0, double t1, int depth) const {
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
    const int index = static_cast<int>(out.nodes.size());
    out.nodes.push_back(n);
    if (n.delta <= leaf_) {
      ++out.leaves;
      out.largest = std::max(out.largest, n.delta);
      return index;
    }
    if (t1 - t0 < 1e-12 * range || depth > 60)
      throw Error(Errc::numerical_failure,
                  motion_.label() + ": cannot bound the swept volume within " +
                      kernel::detail::format_double(leaf_) + " near t = " +
                      kernel::detail::format_double(n.tm) + " (a pole, or a tolerance too fine)");
    if (out.nodes.size() > max_nodes) too_many();
    const int c0 = build(out, t0, n.tm, depth + 1);
    const int c1 = build(out, n.tm, t1, depth + 1);
    out.nodes[static_cast<std::size_t>(index)].child[0] = c0;
    out.nodes[static_cast<std::size_t>(index)].child[1] = c1;
    return index;
  }

  static constexpr std::size_t max_nodes = 1 << 22;
  const qmotion::Motion& motion_;
  const Body& body_;
  double rho_;
  KeyframeBound bound_;
  double leaf_;
  Eigen::Vector3d ball_centre_ = Eigen::Vector3d::Zero();
  double ball_radius_ = 0;
  Eigen::AlignedBox3d mesh_box_;  ///< a mesh body's vertices' box (empty for the others)
  std::vector<Node> nodes_;
  std::vector<int> roots_;
  std::size_t leaves_ = 0;
  double largest_leaf_ = 0;
};

}  // namespace qmotion::sweep
