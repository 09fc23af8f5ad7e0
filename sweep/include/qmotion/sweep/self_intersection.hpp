// <qmotion/sweep/self_intersection.hpp>: a proof that a sweep's exact surfaces (and a solid's
// caps) do not meet themselves, by Bezier subdivision with no sampling (docs/geometry.md,
// "Self-intersection").
#pragma once
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/sweep/bezier_patch.hpp>
#include <qmotion/sweep/nurbs.hpp>
#include <qmotion/sweep/self_intersection_proof.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace qmotion::sweep {

namespace detail_si {

using bezier::boxes_apart;
using bezier::Injectivity;
using bezier::Net;
using bezier::restrict_net;
using bezier::restrict_side;
using bezier::V3;
using bezier::V4;

/// A patch of one face: its parameter box, its place in the common parameters (T = t, V the
/// profile's edges laid end to end, each as long as its control polygon), its net.
struct Piece {
  std::size_t face = 0;
  double t0 = 0, t1 = 0, v0 = 0, v1 = 0;
  double V0 = 0, V1 = 0;
  Net net;
};

/// A part of a piece: [s0, s1] x [r0, r1] of its [0, 1]^2, with its net and box.
struct Cell {
  std::size_t piece = 0;
  double s0 = 0, s1 = 1, r0 = 0, r1 = 1;
  double T0 = 0, T1 = 0, V0 = 0, V1 = 0;
  Net net;
  std::vector<V3> pts;  ///< Cartesian control points
  V3 lo, hi;
  double diam = 0;
  int depth = 0;
  std::array<std::ptrdiff_t, 4> kids{-1, -1, -1, -1};
};

/// An end cap: the plane n.x = c through the faces' boundary at the first or last t, and
/// the box of that boundary's control points (which holds the planar region it bounds).
struct Cap {
  V3 n = V3::Zero();
  double c = 0;
  V3 lo, hi;
  std::vector<V4> boundary;
};

class Prover {
 public:
  Prover(const std::vector<NurbsSurface<double>>& faces, bool closed, bool caps,
         std::size_t max_pairs)
      : closed_(closed), max_pairs_(max_pairs) {
    make_pieces(faces);
    if (out_.status == SelfIntersectionProof::Status::undecided && !out_.reason.empty()) return;
    if (caps) make_caps(faces);
  }

  SelfIntersectionProof run() {
    if (!out_.reason.empty()) return out_;
    for (std::size_t i = 0; i < pieces_.size(); ++i) {
      Cell c;
      c.piece = i;
      c.net = pieces_[i].net;
      finish_cell(c);
      cells_.push_back(std::move(c));
    }
    // Caps first: they can fail without subdivision (two caps that may meet).
    if (caps_.size() == 2 && !caps_apart()) return undecided("the end caps may meet");
    for (std::size_t i = 0; i < cells_.size(); ++i) {
      stack_.push_back({i, i, -1});
      for (int k = 0; k < static_cast<int>(caps_.size()); ++k) stack_.push_back({i, i, k});
    }
    overlapping_pairs();
    while (!stack_.empty()) {
      const Job job = stack_.back();
      stack_.pop_back();
      if (++out_.pairs > max_pairs_) {
        out_.first = place(cells_[job.a]);  // the pair it could not decide
        if (job.cap < 0) out_.second = place(cells_[job.b]);
        return undecided(
            "the budget of " + std::to_string(max_pairs_) + " pairs ran out, undecided between " +
            out_.where(out_.first) +
            (job.cap >= 0 ? std::string(" and an end cap") : " and " + out_.where(out_.second)));
      }
      const bool done = job.cap >= 0     ? cell_cap(job.a, job.cap)
                        : job.a == job.b ? self(job.a)
                                         : pair(job.a, job.b);
      if (done && out_.status != SelfIntersectionProof::Status::undecided) break;
    }
    if (out_.status == SelfIntersectionProof::Status::undecided && out_.reason.empty())
      out_.status = SelfIntersectionProof::Status::none;
    out_.cells = cells_.size();
    return out_;
  }

 private:
  struct Job {
    std::size_t a, b;
    int cap;  ///< >= 0: cell a against that cap
  };

  bool closed_;
  std::size_t max_pairs_;
  std::vector<Piece> pieces_;
  std::vector<Cell> cells_;
  std::vector<Cap> caps_;
  std::vector<Job> stack_;
  std::vector<double> edge_v0_;  ///< V where each face starts
  double vtotal_ = 0, tmin_ = 0, tmax_ = 0, scale_ = 0;
  SelfIntersectionProof out_;

  /// The pairs of patches whose boxes overlap, found by sorting them along the widest axis
  /// (O(n log n) and the overlaps, not O(n^2)): every other pair is apart along an axis.
  void overlapping_pairs() {
    V3 lo = cells_.front().lo, hi = cells_.front().hi;
    for (const auto& c : cells_) {
      lo = lo.cwiseMin(c.lo);
      hi = hi.cwiseMax(c.hi);
    }
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    std::vector<std::size_t> order(cells_.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return cells_[a].lo(axis) < cells_[b].lo(axis);
    });
    const double gap = 1e-12 * scale_;
    for (std::size_t a = 0; a < order.size(); ++a) {
      const Cell& ca = cells_[order[a]];
      for (std::size_t b = a + 1;
           b < order.size() && cells_[order[b]].lo(axis) <= ca.hi(axis) + gap; ++b) {
        const Cell& cb = cells_[order[b]];
        if (!boxes_apart(ca.lo, ca.hi, cb.lo, cb.hi, gap))
          stack_.push_back({std::min(order[a], order[b]), std::max(order[a], order[b]), -1});
      }
    }
  }

  SelfIntersectionProof undecided(const std::string& why) {
    out_.status = SelfIntersectionProof::Status::undecided;
    out_.reason = why;
    out_.cells = cells_.size();
    return out_;
  }

  void make_pieces(const std::vector<NurbsSurface<double>>& faces) {
    V3 lo = V3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    double V = 0;
    tmin_ = std::numeric_limits<double>::infinity();
    tmax_ = -tmin_;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const auto& s = faces[f];
      if (s.degree_u < 1 || s.degree_v < 1) {
        out_.reason = "a face has degree 0";
        return;
      }
      double len = 0;  // the control polygon's length along v, at the middle row
      const auto& mid = s.points[s.points.size() / 2];
      for (std::size_t j = 0; j + 1 < mid.size(); ++j) len += (mid[j + 1] - mid[j]).norm();
      if (!(len > 0)) len = 1;
      edge_v0_.push_back(V);
      // Columns along u to Bezier pieces, then each piece's rows along v.
      std::vector<std::vector<kernel::Bernstein<V4>>> cols;  // [j][u-span]
      for (std::size_t j = 0; j < s.points.front().size(); ++j) {
        std::vector<V4> h;
        for (std::size_t i = 0; i < s.points.size(); ++i) {
          const double w = s.weights[i][j];
          if (!(w > 0)) {
            out_.reason = "a weight is not positive";
            return;
          }
          h.emplace_back(w, w * s.points[i][j](0), w * s.points[i][j](1), w * s.points[i][j](2));
          lo = lo.cwiseMin(s.points[i][j]);
          hi = hi.cwiseMax(s.points[i][j]);
        }
        cols.push_back(
            kernel::bezier_pieces(kernel::BSpline<V4>::make(s.degree_u, s.knots_u, std::move(h))));
      }
      const double va = s.knots_v.front(), vb = s.knots_v.back();
      tmin_ = std::min(tmin_, s.knots_u.front());
      tmax_ = std::max(tmax_, s.knots_u.back());
      for (std::size_t k = 0; k < cols.front().size(); ++k) {
        const auto& ref = cols.front()[k];
        std::vector<std::vector<kernel::Bernstein<V4>>> rows;  // [i][v-span]
        for (int i = 0; i <= s.degree_u; ++i) {
          std::vector<V4> h;
          for (const auto& col : cols) h.push_back(col[k][i]);
          rows.push_back(kernel::bezier_pieces(
              kernel::BSpline<V4>::make(s.degree_v, s.knots_v, std::move(h))));
        }
        for (std::size_t l = 0; l < rows.front().size(); ++l) {
          Piece pc;
          pc.face = f;
          pc.t0 = ref.a();
          pc.t1 = ref.b();
          pc.v0 = rows.front()[l].a();
          pc.v1 = rows.front()[l].b();
          pc.V0 = V + len * (pc.v0 - va) / (vb - va);
          pc.V1 = V + len * (pc.v1 - va) / (vb - va);
          pc.net.p = s.degree_u;
          pc.net.q = s.degree_v;
          for (int i = 0; i <= s.degree_u; ++i)
            for (int j = 0; j <= s.degree_v; ++j)
              pc.net.c.push_back(rows[static_cast<std::size_t>(i)][l][j]);
          pieces_.push_back(std::move(pc));
        }
      }
      V += len;
    }
    vtotal_ = V;
    scale_ = (hi - lo).norm();
    out_.patches = pieces_.size();
    out_.eps = 1e-9 * scale_;
    if (pieces_.empty()) out_.reason = "no surface";
  }

  /// The cap at the first (k = 0) or last t: the faces' boundary rows there.
  void make_caps(const std::vector<NurbsSurface<double>>& faces) {
    for (int k = 0; k < 2; ++k) {
      Cap cap;
      std::vector<V3> pts;
      for (const auto& s : faces) {
        const std::size_t i = k == 0 ? 0 : s.points.size() - 1;
        for (std::size_t j = 0; j < s.points[i].size(); ++j) {
          pts.push_back(s.points[i][j]);
          const double w = s.weights[i][j];
          cap.boundary.emplace_back(w, w * pts.back()(0), w * pts.back()(1), w * pts.back()(2));
        }
      }
      // Newell's normal of the closed control polygon.
      for (std::size_t a = 0; a < pts.size(); ++a) {
        const V3& x = pts[a];
        const V3& y = pts[(a + 1) % pts.size()];
        cap.n += V3((x(1) - y(1)) * (x(2) + y(2)), (x(2) - y(2)) * (x(0) + y(0)),
                    (x(0) - y(0)) * (x(1) + y(1)));
      }
      if (!(cap.n.norm() > 0)) {
        out_.reason = "an end cap has no plane";
        return;
      }
      cap.n.normalize();
      V3 centroid = V3::Zero();
      cap.lo = cap.hi = pts.front();
      for (const auto& x : pts) {
        centroid += x;
        cap.lo = cap.lo.cwiseMin(x);
        cap.hi = cap.hi.cwiseMax(x);
      }
      cap.c = cap.n.dot(centroid / static_cast<double>(pts.size()));
      for (const auto& x : pts)
        if (std::abs(cap.n.dot(x) - cap.c) > 1e-9 * scale_) {
          out_.reason = "an end cap's boundary is not planar";
          return;
        }
      caps_.push_back(std::move(cap));
    }
  }

  void finish_cell(Cell& c) {
    const Piece& pc = pieces_[c.piece];
    c.T0 = pc.t0 + c.s0 * (pc.t1 - pc.t0);
    c.T1 = pc.t0 + c.s1 * (pc.t1 - pc.t0);
    c.V0 = pc.V0 + c.r0 * (pc.V1 - pc.V0);
    c.V1 = pc.V0 + c.r1 * (pc.V1 - pc.V0);
    c.pts.clear();
    for (const auto& h : c.net.c) c.pts.push_back(h.tail<3>() / h(0));
    c.lo = c.hi = c.pts.front();
    for (const auto& x : c.pts) {
      c.lo = c.lo.cwiseMin(x);
      c.hi = c.hi.cwiseMax(x);
    }
    c.diam = (c.hi - c.lo).norm();
    out_.depth = std::max(out_.depth, c.depth);
  }

  /// The four quarters of cell i, made once.
  std::array<std::size_t, 4> split(std::size_t i) {
    if (cells_[i].kids[0] < 0) {
      for (int k = 0; k < 4; ++k) {
        const Cell& c = cells_[i];
        Cell d;
        d.piece = c.piece;
        d.depth = c.depth + 1;
        const double sm = (c.s0 + c.s1) / 2, rm = (c.r0 + c.r1) / 2;
        const bool right = k & 1, up = k & 2;
        d.s0 = right ? sm : c.s0;
        d.s1 = right ? c.s1 : sm;
        d.r0 = up ? rm : c.r0;
        d.r1 = up ? c.r1 : rm;
        d.net = restrict_side(c.net, 0.5, true, right);
        d.net = restrict_side(d.net, 0.5, false, up);
        finish_cell(d);
        cells_.push_back(std::move(d));
        cells_[i].kids[static_cast<std::size_t>(k)] =
            static_cast<std::ptrdiff_t>(cells_.size() - 1);
      }
    }
    std::array<std::size_t, 4> k{};
    for (std::size_t j = 0; j < 4; ++j) k[j] = static_cast<std::size_t>(cells_[i].kids[j]);
    return k;
  }

  SelfIntersectionProof::Place place(const Cell& c) const {
    const Piece& p = pieces_[c.piece];
    return {p.t0 + c.s0 * (p.t1 - p.t0), p.t0 + c.s1 * (p.t1 - p.t0), p.face,
            p.v0 + c.r0 * (p.v1 - p.v0), p.v0 + c.r1 * (p.v1 - p.v0)};
  }

  bool self(std::size_t i) {
    Injectivity inj;
    {
      const Cell& c = cells_[i];
      inj.add(c.net, c.T1 - c.T0, c.V1 - c.V0);
    }
    if (inj.injective()) return false;
    if (cells_[i].diam < out_.eps) return singular(cells_[i]);
    const auto k = split(i);
    for (std::size_t a = 0; a < 4; ++a) {
      stack_.push_back({k[a], k[a], -1});
      for (std::size_t b = a + 1; b < 4; ++b) stack_.push_back({k[a], k[b], -1});
    }
    return false;
  }

  bool singular(const Cell& c) {
    out_.status = SelfIntersectionProof::Status::singular;
    out_.first = place(c);
    return true;
  }

  /// The shift of V (0, or +-vtotal_ across a closed profile's seam) that makes the
  /// parameter boxes of a and b touch, if any.
  std::optional<double> touching_shift(const Cell& a, const Cell& b) const {
    const double tol = 1e-12 * (tmax_ - tmin_ + vtotal_);
    if (a.T0 > b.T1 + tol || b.T0 > a.T1 + tol) return std::nullopt;
    for (const double sh : {0.0, vtotal_, -vtotal_}) {
      if (sh != 0 && !closed_) continue;
      if (!(a.V0 > b.V1 + sh + tol || b.V0 + sh > a.V1 + tol)) return sh;
    }
    return std::nullopt;
  }

  /// Injectivity over the parameter box [T0, T1] x [V0, V1] (V unwrapped): every piece part
  /// inside it, each scaled to the common parameters.
  bool injective_over(double T0, double T1, double V0, double V1) const {
    Injectivity inj;
    const double tol = 1e-12 * (tmax_ - tmin_ + vtotal_);
    for (const auto& p : pieces_)
      for (const double sh : {0.0, vtotal_, -vtotal_}) {
        if (sh != 0 && !closed_) continue;
        const double a0 = std::max(T0, p.t0), a1 = std::min(T1, p.t1);
        const double b0 = std::max(V0, p.V0 + sh), b1 = std::min(V1, p.V1 + sh);
        if (a1 - a0 <= tol || b1 - b0 <= tol) continue;
        const double s0 = (a0 - p.t0) / (p.t1 - p.t0), s1 = (a1 - p.t0) / (p.t1 - p.t0);
        const double r0 = (b0 - p.V0 - sh) / (p.V1 - p.V0), r1 = (b1 - p.V0 - sh) / (p.V1 - p.V0);
        inj.add(restrict_net(p.net, std::max(0.0, s0), std::min(1.0, s1), std::max(0.0, r0),
                             std::min(1.0, r1)),
                a1 - a0, b1 - b0);
      }
    return inj.injective();
  }

  /// Separated along one of a few directions (axes, centres, normals), with a margin for
  /// rounding.
  bool apart(const Cell& a, const Cell& b) const {
    const double gap = 1e-12 * scale_;
    if (boxes_apart(a.lo, a.hi, b.lo, b.hi, gap)) return true;
    const V3 ca = (a.lo + a.hi) / 2, cb = (b.lo + b.hi) / 2;
    for (const V3& d : {V3(cb - ca), mean_normal(a), mean_normal(b)}) {
      if (!(d.norm() > 0)) continue;
      const V3 u = d.normalized();
      double amin = std::numeric_limits<double>::infinity(), amax = -amin, bmin = amin,
             bmax = -amin;
      for (const auto& x : a.pts) {
        amin = std::min(amin, u.dot(x));
        amax = std::max(amax, u.dot(x));
      }
      for (const auto& x : b.pts) {
        bmin = std::min(bmin, u.dot(x));
        bmax = std::max(bmax, u.dot(x));
      }
      if (amax + gap < bmin || bmax + gap < amin) return true;
    }
    return false;
  }

  bool pair(std::size_t i, std::size_t j) {
    if (apart(cells_[i], cells_[j])) return false;
    const auto sh = touching_shift(cells_[i], cells_[j]);
    if (sh) {
      const Cell& a = cells_[i];
      const Cell& b = cells_[j];
      if (injective_over(std::min(a.T0, b.T0), std::max(a.T1, b.T1), std::min(a.V0, b.V0 + *sh),
                         std::max(a.V1, b.V1 + *sh)))
        return false;
    }
    const Cell& a = cells_[i];
    const Cell& b = cells_[j];
    if (a.diam < out_.eps && b.diam < out_.eps) {
      if (sh) return singular(a.T1 - a.T0 >= b.T1 - b.T0 ? a : b);
      contact(a, b);
      return true;
    }
    const bool split_a = a.diam >= b.diam;
    const auto k = split(split_a ? i : j);
    for (std::size_t c : k) stack_.push_back(split_a ? Job{c, j, -1} : Job{i, c, -1});
    return false;
  }

  /// The normal of a part's corner quadrilateral (its control net's corners).
  static V3 mean_normal(const Cell& c) {
    const int p = c.net.p, q = c.net.q;
    auto x = [&](int i, int j) { return c.pts[static_cast<std::size_t>(i * (q + 1) + j)]; };
    return (x(p, 0) - x(0, 0) + x(p, q) - x(0, q)).cross(x(0, q) - x(0, 0) + x(p, q) - x(p, 0));
  }

  /// Two tiny parts that meet. The same profile point (their V overlap, within a part's
  /// size) at two t is a still point (the surface is singular there), not a contact.
  void contact(const Cell& a, const Cell& b) {
    const double dv = std::max(a.V1 - a.V0, b.V1 - b.V0);
    if (pieces_[a.piece].face == pieces_[b.piece].face && a.V0 <= b.V1 + dv && b.V0 <= a.V1 + dv) {
      singular(a);
      out_.second = place(b);
      return;
    }
    const V3 na = mean_normal(a), nb = mean_normal(b);
    const double s = na.cross(nb).norm() / std::max(1e-300, na.norm() * nb.norm());
    out_.status = s > 1e-3 ? SelfIntersectionProof::Status::crossing
                           : SelfIntersectionProof::Status::touching;
    out_.first = place(a);
    out_.second = place(b);
  }

  /// Cell i against cap k: off the cap's plane (strictly, by the signs of its homogeneous
  /// distances), or leaving it from the boundary it shares with the cap (distances zero on
  /// that row, of one strict sign on all others), or outside the cap's box.
  bool cell_cap(std::size_t i, int k) {
    const Cap& cap = caps_[static_cast<std::size_t>(k)];
    const Cell& c = cells_[i];
    const double gap = 1e-12 * scale_;
    const int p = c.net.p, q = c.net.q;
    const Piece& pc = pieces_[c.piece];
    const bool on_end = k == 0 ? (c.s0 == 0 && pc.t0 == tmin_) : (c.s1 == 1 && pc.t1 == tmax_);
    int sign = 0;
    bool strict = true, ends_on_plane = on_end;
    for (int a = 0; a <= p; ++a)
      for (int b = 0; b <= q; ++b) {
        const V4& h = c.net.at(a, b);
        const double d = (cap.n.dot(h.tail<3>()) - cap.c * h(0)) / h(0);
        const bool boundary_row = on_end && a == (k == 0 ? 0 : p);
        if (boundary_row) {
          if (std::abs(d) > 1e-9 * scale_) ends_on_plane = false;
          continue;
        }
        if (std::abs(d) <= gap) {
          strict = false;
          continue;
        }
        const int s = d > 0 ? 1 : -1;
        if (sign == 0) sign = s;
        if (s != sign) strict = false;
      }
    if (strict && (!on_end || ends_on_plane)) return false;
    if (boxes_apart(c.lo, c.hi, cap.lo, cap.hi, gap)) return false;
    if (c.diam < out_.eps) {
      out_.status = SelfIntersectionProof::Status::touching;
      out_.first = place(c);
      out_.cap = k;
      const V3 nc = mean_normal(c);
      if (nc.cross(cap.n).norm() > 1e-3 * nc.norm())
        out_.status = SelfIntersectionProof::Status::crossing;
      return true;
    }
    for (std::size_t d : split(i)) stack_.push_back({d, d, k});
    return false;
  }

  /// The caps' boxes are apart, or one cap's boundary control points lie strictly on one
  /// side of the other's plane (its region, in their convex hull, then too).
  bool caps_apart() const {
    const Cap& a = caps_[0];
    const Cap& b = caps_[1];
    const double gap = 1e-12 * scale_;
    if (boxes_apart(a.lo, a.hi, b.lo, b.hi, gap)) return true;
    auto one_side = [gap](const Cap& plane, const Cap& other) {
      int sign = 0;
      for (const auto& h : other.boundary) {
        const double d = (plane.n.dot(h.tail<3>()) - plane.c * h(0)) / h(0);
        if (std::abs(d) <= gap) return false;
        const int s = d > 0 ? 1 : -1;
        if (sign == 0) sign = s;
        if (s != sign) return false;
      }
      return true;
    };
    return one_side(a, b) || one_side(b, a);
  }
};

}  // namespace detail_si

/// Proves that the faces (one per profile edge, in order, sharing the boundaries where
/// consecutive edges meet, the last and first too when `closed_profile`) do not meet
/// themselves or each other anywhere else, and with `caps` that the two planar end caps
/// bounded by the faces' boundaries at the first and last t do not meet them either.
///
/// The faces are cut into rational Bezier patches (positive weights) and examined in pairs:
/// - two parts apart along an axis, the line of their centres or a normal (their control
///   points' projections, a convex hull bound) cannot meet;
/// - a part, or two neighbouring parts (their parameter boxes touch, across patches,
///   edges and a closed profile's seam) whose enclosing parameter box passes the
///   injectivity test (detail_si::Injectivity, a bound on the Jacobians' Bezier control
///   points) map no two parameters to one point;
/// - a part against a cap: its homogeneous distances to the cap's plane of one strict sign,
///   except on the boundary row it shares with the cap, or its box apart from the cap's;
/// - anything else is halved in both parameters, until the parts are smaller than 1e-9 of
///   the size (a contact, or a singular point) or `max_pairs` pairs were examined.
/// No sampling: every "apart" comes from convex hulls, with a 1e-12 of the size margin for
/// rounding.
inline SelfIntersectionProof prove_no_self_intersection(
    const std::vector<NurbsSurface<double>>& faces, bool closed_profile, bool caps,
    std::size_t max_pairs = 2'000'000) {
  return detail_si::Prover(faces, closed_profile, caps, max_pairs).run();
}

}  // namespace qmotion::sweep
