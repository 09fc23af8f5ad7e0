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
/// the part. tol is the resolution: the first contact's time interval is at most as long as
/// the tool takes to move tol / 4, and cells smaller than tol / 8 that are neither proven
/// clear nor hold a contact make the interval undecided.
struct Contact {
  enum class Kind { clear, contact, undecided };
  Kind kind = Kind::clear;
  /// contact: the first lies in [t_lo, t_hi] (none before t_lo, one at t_hi); undecided:
  /// the first interval neither proven clear nor holding a contact.
  double t_lo = 0, t_hi = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< contact: the body's point at t_hi
  double depth = 0;                                 ///< contact: its depth, at least
  std::size_t cells = 0;
};

/// Cells one time interval may split the body into.
inline constexpr std::size_t kContactCells = std::size_t(1) << 14;

namespace detail {

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
    for (const Core& c : body) top_ = std::min(top_, c.z1);
    // A straight move up the tool's axis after another move: the body is the cutter, and the
    // instance where the move starts was cut (the move before ended there).
    is_cutter_ = retract;
    covered_ = covered;
    retract_ = retract && cut && index > 0 && m.kind != Move::Kind::arc && m.from.x() == m.to.x() &&
               m.from.y() == m.to.y() && m.to.z() >= m.from.z();
  }

  /// Time intervals, earliest first: a proven one is passed, another halved until the
  /// tool moves at most tol / 4 in it.
  Contact run() {
    Contact out;
    std::vector<std::pair<double, double>> todo{{0.0, 1.0}};
    while (!todo.empty()) {
      const auto [t0, t1] = todo.back();
      todo.pop_back();
      const Contact::Kind v = classify(t0, t1, out);
      if (v == Contact::Kind::clear) continue;
      if (speed_ * (t1 - t0) <= tol_ / 4 || t1 - t0 < 1e-12) {
        out.kind = v;
        out.t_lo = t0;
        out.t_hi = t1;
        return out;
      }
      const double tm = 0.5 * (t0 + t1);
      todo.emplace_back(tm, t1);
      todo.emplace_back(t0, tm);
    }
    out.kind = Contact::Kind::clear;
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
      // Every point of the cell over [t0, t1] lies in [lo, hi] (a segment's points: the box
      // of its ends; an arc's: within its reach of the middle).
      Eigen::Vector3d lo = b.min() + p0.cwiseMin(p1), hi = b.max() + p0.cwiseMax(p1);
      if (!straight) {
        lo = (b.min() + pm).array() - grow;
        hi = (b.max() + pm).array() + grow;
      }
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

  /// A point of the body among the cell's centre and corners (a contact first shows at a
  /// face or an edge of the body) that is, at t1, inside the target and outside what was cut
  /// up to t1.
  bool witness(const Eigen::AlignedBox3d& b, double t1, Contact& out) const {
    const Eigen::Vector3d p = position(m_, arc_, t1);
    for (int k = -1; k < 8; ++k) {
      const Eigen::Vector3d y =
          k < 0 ? b.center() : b.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k));
      if (cutter_distance(body_, y) > 0) continue;
      const Eigen::Vector3d x = p + y;
      double depth = target_.depth(x) - margin(x);
      if (!(depth > 0)) continue;
      if (cut_) {
        const CutIndex::Near n =
            cut_->distance(x, std::min(tol_ / 4, depth / 2), depth, false, index_, own(t1), 0);
        depth = std::min(depth, n.lower);
        if (!(depth > 0)) continue;
      }
      out.point = x;
      out.depth = depth;
      return true;
    }
    return false;
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
  double covered_ = 0;      ///< how far up the axis the move before swept the cutter
};

}  // namespace detail

/// The holder `cylinder:r,h` as a body of the tool: radius r from the cutter's length L up
/// to L + h.
inline std::vector<detail::Core> holder_cores(double r, double h, double cutter_length) {
  return {detail::Core{0, r, 0, cutter_length, cutter_length + h}};
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
