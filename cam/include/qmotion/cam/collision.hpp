// <qmotion/cam/collision.hpp>: the first instant of a move at which a body carried by the
// tool (the holder) enters the stock as the program has left it so far, or the part,
// certified by branch and bound over time and the body (docs/guide/verify.md,
// "Collisions").
#pragma once
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <qmotion/cam/program.hpp>
#include <qmotion/cam/stock.hpp>
#include <qmotion/kernel/outward.hpp>
#include <utility>
#include <vector>

namespace qmotion::cam {

/// A body's first contact over one move. A contact is a point of the body strictly inside
/// the target: inside the stock and outside all that was cut up to that instant, or inside
/// the part. tol is the resolution: a time interval is halved until the tool moves at most
/// tol / 4 in it, and cells smaller than tol / 8 that are neither proven clear nor hold a
/// contact leave the interval undecided. A contact that starts by grazing shows a witness
/// only a little later, so the search passes up to kUndecidedRun undecided intervals.
struct Contact {
  enum class Kind { clear, contact, undecided };
  Kind kind = Kind::clear;
  /// contact: the first lies in [t_lo, t_hi] (none before t_lo, one at t_hi); undecided:
  /// none before t_lo, and no interval up to t_hi proven clear or holding a contact.
  double t_lo = 0, t_hi = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< contact: the body's point at t_hi
  double depth = 0;                                 ///< contact: its depth, at least
  std::size_t cells = 0;
};

/// Cells one time interval may split the body into.
inline constexpr std::size_t kContactCells = std::size_t(1) << 14;
/// Undecided intervals at the finest resolution a search passes, looking for a witness.
inline constexpr int kUndecidedRun = 64;

namespace detail {

/// The distance between the boxes [lo, hi] and r in the plane.
inline double box_rect_distance(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                const Eigen::AlignedBox2d& r) {
  const Eigen::Vector2d gap = (r.min() - hi).cwiseMax(lo - r.max()).cwiseMax(0.0);
  return gap.norm();
}

/// The distance between the segment ab and the box r in the plane: 0 where they meet, else
/// reached at an end of the segment or at a corner of the box.
inline double segment_rect_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                    const Eigen::AlignedBox2d& r) {
  // Clip ab to the box's slabs (Liang and Barsky).
  double t0 = 0, t1 = 1;
  const Eigen::Vector2d d = b - a;
  for (int k = 0; k < 2 && t0 <= t1; ++k) {
    if (d(k) == 0) {
      if (a(k) < r.min()(k) || a(k) > r.max()(k)) t1 = -1;
      continue;
    }
    const double u = (r.min()(k) - a(k)) / d(k), v = (r.max()(k) - a(k)) / d(k);
    t0 = std::max(t0, std::min(u, v));
    t1 = std::min(t1, std::max(u, v));
  }
  if (t0 <= t1) return 0;
  double best = std::min(box_rect_distance(a, a, r), box_rect_distance(b, b, r));
  const double dd = d.squaredNorm();
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d c = r.corner(static_cast<Eigen::AlignedBox2d::CornerType>(k));
    const double t = dd > 0 ? std::clamp((c - a).dot(d) / dd, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * d - c).norm());
  }
  return best;
}

class ContactSearch {
 public:
  /// `cut`: what the program removes (the moves before `index`, and this one up to the
  /// instant); none for a target that is never cut (the part).
  ContactSearch(const Move& m, std::size_t index, const std::vector<Core>& body,
                const Stock& target, const CutIndex* cut, double tol, bool retract, double covered)
      : m_(m),
        arc_(m.kind == Move::Kind::arc ? arc_shape(m) : ArcShape{}),
        speed_(speed_bound(m)),
        index_(index),
        body_(body),
        target_(target),
        cut_(cut),
        tol_(tol) {
    box_ = cores_box(body);
    top_ = HUGE_VAL;
    for (const Core& c : body) {
      top_ = std::min(top_, c.z1);
      cylinders_ = cylinders_ && c.r_in == 0 && c.rc == 0 && !c.solid;
    }
    // A straight move up the tool's axis after another move: the body is the cutter, and the
    // instance where the move starts was cut (the move before ended there).
    is_cutter_ = retract;
    covered_ = covered;
    retract_ = retract && cut && index > 0 && m.kind != Move::Kind::arc && m.from.x() == m.to.x() &&
               m.from.y() == m.to.y() && m.to.z() >= m.from.z();
  }

  /// Time intervals, earliest first: a proven one is passed, another halved until the
  /// tool moves at most tol / 4 in it.
  /// An interval that stays undecided at the finest resolution is passed too, up to
  /// kUndecidedRun of them: a contact that starts by grazing deepens, and a later interval's
  /// witness bounds the first contact from above, the undecided one's start from below.
  Contact run() {
    Contact out;
    std::vector<std::pair<double, double>> todo{{0.0, 1.0}};
    int undecided = 0;
    while (!todo.empty()) {
      const auto [t0, t1] = todo.back();
      todo.pop_back();
      const Contact::Kind v = classify(t0, t1, out);
      if (v == Contact::Kind::clear) continue;
      if (speed_ * (t1 - t0) <= tol_ / 4 || t1 - t0 < 1e-12) {
        if (undecided == 0) out.t_lo = t0;
        out.kind = v;
        out.t_hi = t1;
        if (v == Contact::Kind::contact || ++undecided > kUndecidedRun) return out;
        continue;
      }
      const double tm = 0.5 * (t0 + t1);
      todo.emplace_back(tm, t1);
      todo.emplace_back(t0, tm);
    }
    if (undecided == 0) out.kind = Contact::Kind::clear;
    return out;
  }

 private:
  /// Over [t0, t1]: clear when every cell of the body is proven outside the target; contact
  /// when a point of the body is strictly inside it at t1.
  Contact::Kind classify(double t0, double t1, Contact& out) const {
    using kernel::up;
    const Eigen::Vector3d p0 = position(m_, arc_, t0), p1 = position(m_, arc_, t1);
    const Eigen::Vector3d pm = position(m_, arc_, 0.5 * (t0 + t1));
    const bool straight = m_.kind != Move::Kind::arc;
    // Back up the column the move before came down: every instance is one of that move's.
    if (retract_ && p1.z() - m_.from.z() <= covered_) return Contact::Kind::clear;
    const double grow = straight ? 0.0 : up(speed_ * up(0.5 * (t1 - t0)));
    // Where the tool's tip is over [t0, t1] (a segment's points: the box of its ends; an
    // arc's: within its reach of the middle).
    const Eigen::Vector3d tip_lo = straight ? p0.cwiseMin(p1) : Eigen::Vector3d(pm.array() - grow);
    const Eigen::Vector3d tip_hi = straight ? p0.cwiseMax(p1) : Eigen::Vector3d(pm.array() + grow);
    const Eigen::Vector2d seg[2] = {p0.head<2>(), p1.head<2>()};
    const Eigen::Vector2d* segment = straight ? seg : nullptr;
    if (round_clear(tip_lo, tip_hi, segment, -HUGE_VAL, HUGE_VAL)) return Contact::Kind::clear;
    if (round_witness(p1, t1, out)) return Contact::Kind::contact;
    // Upright cylinders and a box never cut: the two tests above are exact but for the
    // tip's reach over [t0, t1], so time is halved instead of the body.
    if (cylinders_ && !target_.body && !cut_) return Contact::Kind::undecided;
    std::vector<Eigen::AlignedBox3d> cells{box_};
    bool undecided = false;
    std::size_t used = 0;
    while (!cells.empty()) {
      const Eigen::AlignedBox3d b = cells.back();
      cells.pop_back();
      if (++used > kContactCells) return Contact::Kind::undecided;
      ++out.cells;
      const Eigen::Vector3d cb = b.center();
      const double hb = up(0.5 * b.diagonal().norm());
      if (cutter_distance(body_, cb) > hb) continue;  // no point of the body in it
      // Moving the cutter up its axis by d keeps a point of it below top - d inside the
      // instance it started from: every cutter's cross-section widens (or stays) upwards
      // up to its cores' top.
      if (retract_ && b.max().z() + (p1.z() - m_.from.z()) <= top_) continue;
      if (round_clear(tip_lo, tip_hi, segment, b.min().z(), b.max().z())) continue;
      // Every point of the cell over [t0, t1] lies in [lo, hi].
      const Eigen::Vector3d lo = b.min() + tip_lo, hi = b.max() + tip_hi;
      const Eigen::Vector3d c = 0.5 * (lo + hi);
      const double r = up(0.5 * (hi - lo).norm()) + margin(c);
      const double depth = target_.body ? up(target_.depth(c) + r) : target_.depth_max(lo, hi);
      if (depth <= 0) continue;
      if (cut_) {  // cut away by t0: deeper than r in what was cut
        const CutIndex::Near n =
            cut_->distance(c, std::max(tol_ / 4, r / 4), -r, false, index_, own(t0), -r);
        if (n.upper + r < 0) continue;
      }
      if (witness(b, t1, out)) return Contact::Kind::contact;
      if (hb < tol_ / 8) {
        undecided = true;
        continue;
      }
      int axis = 0;
      b.sizes().maxCoeff(&axis);
      Eigen::AlignedBox3d lower = b, upper = b;
      lower.max()(axis) = upper.min()(axis) = cb(axis);
      cells.push_back(lower);
      cells.push_back(upper);
    }
    return undecided ? Contact::Kind::undecided : Contact::Kind::clear;
  }

  /// For a box target: every core that reaches heights [z0, z1] of the body is proven
  /// outside the box's interior while the tip stays in [lo, hi]. A core's points lie within
  /// r_out + rc of its axis: the box is missed when that disc, moved over [lo, hi], misses
  /// its rectangle, or the core's heights miss its heights. Exact for a round body, where
  /// box cells would need to follow its curvature.
  bool round_clear(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                   const Eigen::Vector2d* segment, double z0, double z1) const {
    using kernel::down;
    using kernel::sum_at_least;
    using kernel::sum_at_most;
    using kernel::up;
    if (target_.body) return false;
    const Eigen::AlignedBox3d& s = target_.box;
    const Eigen::AlignedBox2d rect(s.min().head<2>(), s.max().head<2>());
    // A straight move's tip runs along a segment; an arc's stays in [lo, hi].
    const double d = down(segment ? segment_rect_distance(segment[0], segment[1], rect)
                                  : box_rect_distance(lo.head<2>(), hi.head<2>(), rect));
    for (const Core& c : body_) {
      const double c0 = std::max(c.rc > 0 ? down(c.z0 - c.rc) : c.z0, z0);
      const double c1 = std::min(c.rc > 0 ? up(c.z1 + c.rc) : c.z1, z1);
      if (c0 > c1) continue;  // not at these heights
      if (sum_at_most(hi.z(), c1, s.min().z()) || sum_at_least(lo.z(), c0, s.max().z())) continue;
      if (d >= up(up(c.r_out + c.rc) + margin(s.center()))) continue;
      return false;
    }
    return true;
  }

  /// For a box target: a core's point inside the box with the tip at p, if there is one
  /// at the heights both share: on the way from the axis to the rectangle's nearest point,
  /// half-way between that point and the core's rim (inside the rectangle: beyond its
  /// nearest point, away from the axis), or on the axis when it is over the rectangle.
  bool round_witness(const Eigen::Vector3d& p, double t1, Contact& out) const {
    if (target_.body) return false;
    const Eigen::AlignedBox3d& s = target_.box;
    const Eigen::Vector2d c = p.head<2>();
    const Eigen::Vector2d q = c.cwiseMax(s.min().head<2>()).cwiseMin(s.max().head<2>());
    const double d = (q - c).norm();
    for (const Core& k : body_) {
      const double z0 = std::max(p.z() + k.z0, s.min().z()),
                   z1 = std::min(p.z() + k.z1, s.max().z());
      const double R = k.r_out + k.rc;
      if (!(z0 < z1) || !(d < R)) continue;
      const Eigen::Vector2d w = d > 0 ? Eigen::Vector2d(c + (q - c) * (0.5 * (d + R) / d)) : c;
      if (witness_at(Eigen::Vector3d(w.x(), w.y(), 0.5 * (z0 + z1)), p, t1, out)) return true;
    }
    return false;
  }

  /// A point of the body among the cell's centre and corners (a contact first shows at a
  /// face or an edge of the body) that is, at t1, inside the target and outside what was cut
  /// up to t1.
  bool witness(const Eigen::AlignedBox3d& b, double t1, Contact& out) const {
    const Eigen::Vector3d p = position(m_, arc_, t1);
    for (int k = -1; k < 8; ++k) {
      const Eigen::Vector3d y =
          k < 0 ? b.center() : b.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k));
      if (witness_at(p + y, p, t1, out)) return true;
    }
    return false;
  }

  /// x (the tip at p at t1) is a point of the body inside the target and outside what was cut.
  bool witness_at(const Eigen::Vector3d& x, const Eigen::Vector3d& p, double t1,
                  Contact& out) const {
    if (cutter_distance(body_, x - p) > 0) return false;
    double depth = target_.depth(x) - margin(x);
    if (!(depth > 0)) return false;
    if (cut_) {
      const CutIndex::Near n =
          cut_->distance(x, std::min(tol_ / 4, depth / 2), depth, false, index_, own(t1), 0);
      depth = std::min(depth, n.lower);
      if (!(depth > 0)) return false;
    }
    out.point = x;
    out.depth = depth;
    return true;
  }

  /// How much of this move counts as cut by t: up to t for a body the cutter carries, none
  /// for the cutter itself (its instance at t would hold every point of it).
  double own(double t) const { return is_cutter_ ? 0.0 : t; }

  const Move& m_;
  ArcShape arc_;
  double speed_;
  std::size_t index_;
  const std::vector<Core>& body_;
  const Stock& target_;
  const CutIndex* cut_;
  double tol_;
  Eigen::AlignedBox3d box_;
  double top_ = 0;
  bool retract_ = false;
  bool is_cutter_ = false;  ///< the body is the cutter
  bool cylinders_ = true;   ///< every core a solid upright cylinder
  double covered_ = 0;      ///< how far up the axis the move before swept the cutter
};

}  // namespace detail

/// A stepped holder (a collet nut, then the chuck's body, ...): sections (r, h) stacked
/// upwards from the cutter's length, each a cylinder of radius r and length h.
inline std::vector<detail::Core> holder_cores(
    const std::vector<std::pair<double, double>>& sections, double cutter_length) {
  std::vector<detail::Core> cores;
  double z = cutter_length;
  for (const auto& [r, h] : sections) {
    cores.push_back(detail::Core{0, r, 0, z, z + h});
    z += h;
  }
  return cores;
}

/// The holder `cylinder:r,h` as a body of the tool: radius r from the cutter's length L up
/// to L + h.
inline std::vector<detail::Core> holder_cores(double r, double h, double cutter_length) {
  return holder_cores({{r, h}}, cutter_length);
}

/// The first contact of `body` (in the tool's frame) with `target` over move `index` of the
/// program; `cut` (none for the part) removes what the program has cut up to each instant.
/// `is_cutter`: the body is the cutter cut's index sweeps (a rapid move's), whose instance
/// at the move's start was cut by the move before; `covered`: how far up the tool's axis
/// from the start that move swept it (a plunge straight down: its length; else 0).
inline Contact first_contact(const Move& m, std::size_t index,
                             const std::vector<detail::Core>& body, const Stock& target,
                             const CutIndex* cut, double tol, bool is_cutter = false,
                             double covered = 0) {
  return detail::ContactSearch(m, index, body, target, cut, tol, is_cutter, covered).run();
}

}  // namespace qmotion::cam
