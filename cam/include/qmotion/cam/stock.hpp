// <qmotion/cam/stock.hpp>: what a program leaves of the stock: the distance from a point to
// the volume the cutter sweeps over the whole program, certified by branch and bound over
// the moves and over time, and how deep the point lies in the raw stock
// (docs/guide/verify.md, "Stock left").
#pragma once
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <qmotion/cam/gouge.hpp>
#include <qmotion/cam/program.hpp>
#include <qmotion/kernel/outward.hpp>
#include <qmotion/sweep/body.hpp>
#include <queue>
#include <utility>
#include <vector>

namespace qmotion::cam {

/// The raw stock: a box in the program's frame, or a closed body (a mesh) when `body` is set.
struct Stock {
  Eigen::AlignedBox3d box;
  std::shared_ptr<const sweep::Body> body;

  /// How deep x lies in the stock: its distance to the stock's outside where positive, and
  /// at most 0 outside. 1-Lipschitz (a box: the least distance to its six planes).
  double depth(const Eigen::Vector3d& x) const {
    if (body) return -sweep::signed_distance(*body, x);
    return std::min((x - box.min()).minCoeff(), (box.max() - x).minCoeff());
  }
  /// A bound of depth over the triangle abc, for a box: the depth is the least of six
  /// linear functions, each at most its largest value at a corner. HUGE_VAL for a body.
  double depth_max(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                   const Eigen::Vector3d& c) const {
    return depth_max(a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c));
  }
  /// The same over the box [lo, hi].
  double depth_max(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
    if (body) return HUGE_VAL;
    return std::min((hi - box.min()).minCoeff(), (box.max() - lo).minCoeff());
  }
};

/// The signed distance from y (the cutter's frame: tip at the origin, axis +z) to the
/// cutter, as the union of its cores grown by rc (detail::cores_of, the body the gouge
/// search bounds): the distance outside, at most 0 inside; 1-Lipschitz.
inline double cutter_distance(const std::vector<detail::Core>& cores, const Eigen::Vector3d& y) {
  const double rho = std::hypot(y.x(), y.y());
  double best = HUGE_VAL;
  for (const detail::Core& c : cores) {
    const double dr = std::max({c.r_in - rho, rho - c.r_out, 0.0});
    const double dz = std::max({c.z0 - y.z(), y.z() - c.z1, 0.0});
    double d = std::hypot(dr, dz);
    if (d == 0) {  // inside the core: minus the distance to its nearest side
      d = std::min({c.r_out - rho, y.z() - c.z0, c.z1 - y.z()});
      if (c.r_in > 0) d = std::min(d, rho - c.r_in);
      d = -d;
    }
    best = std::min(best, d - c.rc);
  }
  return best;
}

/// The volume a cutter sweeps over a program's moves (every move: a rapid through the stock
/// removes it as surely as a feed), indexed by a tree of the moves' boxes.
class CutIndex {
 public:
  CutIndex(const Program& program, const sweep::Body& cutter);

  /// The distance from x to the swept volume, min(distance, limit), enclosed: lower <= it
  /// <= upper, upper - lower <= eps unless `settled` is false. Negative inside the volume.
  /// `move` and `t` give where the cutter comes nearest (upper is reached there).
  struct Near {
    double lower = 0, upper = 0;
    std::size_t move = 0;
    double t = 0;
    bool settled = true;
    std::size_t queries = 0;
    /// The search stops as soon as upper is below it (lower is then not within eps).
    double stop_below = -HUGE_VAL;
  };
  /// `clipped`: the distance clipped at 0 (0 inside), found faster on straight moves, where
  /// it is convex in t (golden-section search; docs/guide/verify.md, "Stock left").
  /// `stop_below`: stop once upper is below it (all a caller asking "inside?" needs).
  /// `before`, `t_end`: only the moves before that one, and that one over [0, t_end] (the
  /// stock cut so far: docs/guide/verify.md, "Collisions").
  Near distance(const Eigen::Vector3d& x, double eps, double limit, bool clipped = false,
                std::size_t before = SIZE_MAX, double t_end = 1,
                double stop_below = -HUGE_VAL) const;

  std::size_t size() const { return moves_.size(); }

  /// A value of the distance from x to the volume the cutter sweeps over one move (program
  /// index), clipped at 0: reached at a t found by golden-section search, so at least the
  /// least one. For a straight move that distance is convex in x (the cutter is convex and
  /// the move a segment), so over a triangle it is at most its largest value at a corner.
  double move_upper(std::size_t move, const Eigen::Vector3d& x) const;

 private:
  struct Leaf {
    const Move* move;
    std::size_t index;
    detail::ArcShape arc;
    double speed;
    Eigen::AlignedBox3d box;  ///< every cutter point over the move
  };
  struct Node {
    Eigen::AlignedBox3d box;
    int left = -1, right = -1;
    std::size_t first = 0, count = 0;
  };
  int build(std::size_t first, std::size_t count);
  void move_distance(const Leaf& leaf, const Eigen::Vector3d& x, double eps, bool clipped,
                     double t_end, Near& near, double& lower) const;
  void convex_distance(const Leaf& leaf, const Eigen::Vector3d& x, double eps, double t_end,
                       Near& near, double& lower) const;

  std::vector<detail::Core> cores_;
  std::vector<Leaf> moves_;
  std::vector<std::size_t> leaf_of_;  ///< by the moves' index in the program
  double depth_bound_ = 0;            ///< no point lies deeper in the cutter
  std::vector<Node> nodes_;
};

namespace detail {

/// A box holding the cores grown by their rc (the body's points about the tool tip).
inline Eigen::AlignedBox3d cores_box(const std::vector<Core>& cores) {
  Eigen::AlignedBox3d b;
  for (const Core& c : cores) {
    const double r = c.r_out + c.rc;
    b.extend(Eigen::Vector3d(-r, -r, c.z0 - c.rc));
    b.extend(Eigen::Vector3d(r, r, c.z1 + c.rc));
  }
  return b;
}

}  // namespace detail

/// The least distance from x to the box (0 inside), rounded down.
inline double box_distance(const Eigen::Vector3d& x, const Eigen::AlignedBox3d& b) {
  const Eigen::Vector3d d = (b.min() - x).cwiseMax(x - b.max()).cwiseMax(Eigen::Vector3d::Zero());
  return kernel::down(kernel::down(d.norm()) * (1 - 1e-15));
}

inline CutIndex::CutIndex(const Program& program, const sweep::Body& cutter)
    : cores_(detail::cores_of(cutter)) {
  // The bull's flat core up to the side core's top: the body is then convex (no dent
  // between the side's rounded top and the core's flat one), as move_upper needs.
  if (cutter.kind == sweep::Body::Kind::bull_cutter) cores_[0].z1 += cutter.rc;
  const Eigen::AlignedBox3d reach = detail::cores_box(cores_);  // about the tip
  for (const detail::Core& c : cores_) depth_bound_ = std::max(depth_bound_, c.r_out + c.rc);
  moves_.reserve(program.moves.size());
  for (std::size_t i = 0; i < program.moves.size(); ++i) {
    const Move& m = program.moves[i];
    Leaf leaf{&m,
              i,
              m.kind == Move::Kind::arc ? detail::arc_shape(m) : detail::ArcShape{},
              speed_bound(m),
              {}};
    leaf.box.extend(m.from);
    leaf.box.extend(m.to);
    if (m.kind == Move::Kind::arc) {  // the circle's square in its plane
      const auto [u, v, w] = plane_axes(m.plane);
      (void)w;
      const double r = std::max(leaf.arc.r0, leaf.arc.r1);
      Eigen::Vector3d lo = leaf.box.min(), hi = leaf.box.max();
      lo(u) = m.centre(u) - r;
      hi(u) = m.centre(u) + r;
      lo(v) = m.centre(v) - r;
      hi(v) = m.centre(v) + r;
      leaf.box = Eigen::AlignedBox3d(lo, hi);
    }
    const Eigen::Vector3d pad =
        1e-9 * (Eigen::Vector3d::Ones() + leaf.box.max().cwiseAbs() + leaf.box.min().cwiseAbs());
    leaf.box =
        Eigen::AlignedBox3d(leaf.box.min() + reach.min() - pad, leaf.box.max() + reach.max() + pad);
    moves_.push_back(leaf);
  }
  if (!moves_.empty()) build(0, moves_.size());
  leaf_of_.resize(moves_.size());
  for (std::size_t i = 0; i < moves_.size(); ++i) leaf_of_[moves_[i].index] = i;
}

inline double CutIndex::move_upper(std::size_t move, const Eigen::Vector3d& x) const {
  const Leaf& leaf = moves_[leaf_of_[move]];
  auto f = [&](double t) {
    return std::max(cutter_distance(cores_, x - position(*leaf.move, leaf.arc, t)), 0.0);
  };
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double a = 0, b = 1, c = b - g * (b - a), d = a + g * (b - a), fc = f(c), fd = f(d);
  double best = std::min({f(0), f(1), fc, fd});
  for (int k = 0; k < 48 && b - a > 1e-12; ++k) {
    if (fc <= fd) {
      b = d, d = c, fd = fc, c = b - g * (b - a), fc = f(c);
      best = std::min(best, fc);
    } else {
      a = c, c = d, fc = fd, d = a + g * (b - a), fd = f(d);
      best = std::min(best, fd);
    }
  }
  return kernel::up(best + detail::margin(x));
}

inline int CutIndex::build(std::size_t first, std::size_t count) {
  const int at = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::AlignedBox3d box, centres;
  for (std::size_t i = first; i < first + count; ++i) {
    box.extend(moves_[i].box);
    centres.extend(moves_[i].box.center());
  }
  nodes_[static_cast<std::size_t>(at)].box = box;
  if (count <= 4) {
    nodes_[static_cast<std::size_t>(at)].first = first;
    nodes_[static_cast<std::size_t>(at)].count = count;
    return at;
  }
  int axis = 0;
  centres.sizes().maxCoeff(&axis);
  const auto begin = moves_.begin() + static_cast<std::ptrdiff_t>(first);
  std::nth_element(
      begin, begin + static_cast<std::ptrdiff_t>(count / 2),
      begin + static_cast<std::ptrdiff_t>(count),
      [axis](const Leaf& a, const Leaf& b) { return a.box.center()(axis) < b.box.center()(axis); });
  const int left = build(first, count / 2);
  const int right = build(first + count / 2, count - count / 2);
  nodes_[static_cast<std::size_t>(at)].left = left;
  nodes_[static_cast<std::size_t>(at)].right = right;
  return at;
}

/// Branch and bound over the move's time: on [t0, t1] the distance is at least its value at
/// the middle less speed (t1 - t0) / 2 (the cutter's distance is 1-Lipschitz, the tip moves
/// at most speed). Intervals are split, least bound first, until that bound is within eps of
/// the best value found (near.upper, shared across moves) or the budget runs out.
inline void CutIndex::move_distance(const Leaf& leaf, const Eigen::Vector3d& x, double eps,
                                    bool clipped, double t_end, Near& near, double& lower) const {
  using kernel::down;
  using kernel::up;
  struct Span {
    double bound, t0, t1;
    bool operator<(const Span& o) const { return bound > o.bound; }
  };
  const double slack = detail::margin(x);
  auto eval = [&](double t0, double t1) {
    const double t = 0.5 * (t0 + t1);
    double d = cutter_distance(cores_, x - position(*leaf.move, leaf.arc, t));
    if (clipped) d = std::max(d, 0.0);
    ++near.queries;
    if (d + slack < near.upper) {
      near.upper = d + slack;
      near.move = leaf.index;
      near.t = t;
    }
    return Span{down(down(d - up(leaf.speed * up(0.5 * (t1 - t0)))) - slack), t0, t1};
  };
  std::priority_queue<Span> spans;
  spans.push(eval(0, t_end));
  std::size_t budget = 1 << 12;
  while (!spans.empty() && spans.top().bound < near.upper - eps && near.upper >= near.stop_below) {
    if (--budget == 0) {
      near.settled = false;
      break;
    }
    const Span s = spans.top();
    spans.pop();
    const double tm = 0.5 * (s.t0 + s.t1);
    spans.push(eval(s.t0, tm));
    spans.push(eval(tm, s.t1));
  }
  if (!spans.empty()) lower = std::min(lower, spans.top().bound);
}

/// A straight move, the distance clipped at 0: convex in t (the distance to a convex body
/// along a segment), so golden-section search keeps a least point in its bracket [a, b],
/// and over it the distance is at least its value at an inner point less speed (b - a).
inline void CutIndex::convex_distance(const Leaf& leaf, const Eigen::Vector3d& x, double eps,
                                      double t_end, Near& near, double& lower) const {
  using kernel::down;
  using kernel::up;
  const double slack = detail::margin(x);
  auto f = [&](double t) {
    const double d = std::max(cutter_distance(cores_, x - position(*leaf.move, leaf.arc, t)), 0.0);
    ++near.queries;
    if (d + slack < near.upper) {
      near.upper = d + slack;
      near.move = leaf.index;
      near.t = t;
    }
    return d;
  };
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double a = 0, b = t_end, c = t_end * (1 - g), d = t_end * g, fc = f(c), fd = f(d);
  double bound = -HUGE_VAL;
  for (int k = 0; near.upper >= near.stop_below; ++k) {
    bound = down(down(std::min(fc, fd) - up(leaf.speed * up(b - a))) - slack);
    if (bound >= near.upper - eps || k == 64) break;
    if (fc <= fd) {
      b = d, d = c, fd = fc, c = b - g * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd, d = a + g * (b - a), fd = f(d);
    }
  }
  if (bound < near.upper - eps && near.upper >= near.stop_below) near.settled = false;
  lower = std::min(lower, bound);
}

inline CutIndex::Near CutIndex::distance(const Eigen::Vector3d& x, double eps, double limit,
                                         bool clipped, std::size_t before, double t_end,
                                         double stop_below) const {
  Near near;
  near.upper = limit;
  double lower = limit;  // the least bound of the moves searched
  if (nodes_.empty()) {
    near.lower = limit;
    return near;
  }
  // A bound of the distance to the cutter's points in a box: the box's distance, and inside
  // it (signed) minus the deepest a point can lie in the cutter (within r_out + rc of its
  // axis).
  auto box_bound = [&](const Eigen::AlignedBox3d& b) {
    const double d = box_distance(x, b);
    return clipped || d > 0 ? d : -depth_bound_;
  };
  using Entry = std::pair<double, int>;  // (bound, node), nearest first
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;
  heap.emplace(box_bound(nodes_[0].box), 0);
  near.stop_below = stop_below;
  while (!heap.empty() && heap.top().first < near.upper - eps && near.upper >= stop_below) {
    const Node& n = nodes_[static_cast<std::size_t>(heap.top().second)];
    heap.pop();
    if (n.left >= 0) {
      for (int c : {n.left, n.right})
        heap.emplace(box_bound(nodes_[static_cast<std::size_t>(c)].box), c);
      continue;
    }
    for (std::size_t i = n.first; i < n.first + n.count; ++i) {
      const double te = moves_[i].index < before ? 1.0 : moves_[i].index == before ? t_end : 0.0;
      if (te > 0 && box_bound(moves_[i].box) < near.upper - eps)
        (clipped && moves_[i].move->kind != Move::Kind::arc
             ? convex_distance(moves_[i], x, eps, te, near, lower)
             : move_distance(moves_[i], x, eps, clipped, te, near, lower));
    }
  }
  // A move passed over lies no nearer than near.upper - eps (its box, or its spans).
  near.lower = std::min(lower, kernel::down(near.upper - eps));
  return near;
}

}  // namespace qmotion::cam
