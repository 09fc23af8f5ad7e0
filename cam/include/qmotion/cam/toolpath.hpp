// <qmotion/cam/toolpath.hpp>: cutter-location points along a trajectory with certified chord and
// axis-angle bounds (CAM). The bounds come from the Bezier control points of the
// trajectory's pieces (convex hull), not from sampling.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <qmotion/cam/machine.hpp>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/segment.hpp>
#include <string>
#include <vector>

namespace qmotion::cam {

/// A block end as the output states it, in the sampler's unit: the point and the axis that
/// its printed numbers give (read back from them), and the machine axes it prints.
struct WrittenEnd {
  Eigen::Vector3d point = Eigen::Vector3d::Zero(), axis = Eigen::Vector3d::UnitZ();
  MachineAxes machine{};  ///< rotary output only
};

struct ToolpathSample {
  double t = 0;
  Eigen::Vector3d point, axis;  ///< exact; axis: unit
  WrittenEnd written;           ///< as the output states it
};

struct SamplerOptions {
  double chord_tol = 0.01;                                    ///< length units, > 0
  double angle_tol = 0.5 * 3.14159265358979323846 / 180;      ///< radians, > 0
  double max_step = std::numeric_limits<double>::infinity();  ///< chord length cap
  int subdivisions = 4;  ///< parts per piece for the bound (tighter with more)
  /// Called with the share of the interval done after every point (none: not called).
  std::function<void(double)> progress;
  /// How a block end is written, from the exact point and axis at t and the end before it
  /// (null for the first): rounded to the printed decimals, or turned into machine axes and
  /// read back. None: as is. The bounds hold for what it returns. A TravelError refuses the
  /// trial block; it reaches the caller when no block short enough stays within travel.
  std::function<WrittenEnd(double t, const Eigen::Vector3d& p, const Eigen::Vector3d& k,
                           const WrittenEnd* prev)>
      write;
  /// A certified bound on how far what runs between two written ends (a machine's own
  /// interpolation of its axes) leaves their chord (length) and the direction of the blend
  /// of their axes (radians). None: the chord and the blend themselves run.
  std::function<std::pair<double, double>(const WrittenEnd&, const WrittenEnd&)> between;
};

struct SampledToolpath {
  std::vector<ToolpathSample> samples;
  double max_chord_bound = 0;  ///< the largest certified chord deviation of a segment
  double max_angle_bound = 0;  ///< the largest certified axis angle of a segment (rad)
  double max_rounding = 0;     ///< the largest distance of a written point from the exact one
  double max_between = 0;      ///< the largest `between` bounds (length, radians)
  double max_between_angle = 0;
  std::size_t bound_evaluations = 0;
};

namespace detail {

using kernel::point_segment_distance;

inline double angle_between(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

/// The Bernstein coefficients over the local [s0, s1] (0 <= s0 < s1 <= 1) of the polynomial
/// with coefficients c over [0, 1], by two de Casteljau splits (O(n^2), no blossoms).
inline void sub_bezier(const std::vector<Eigen::Vector4d>& c, double s0, double s1,
                       std::vector<Eigen::Vector4d>& out) {
  out = c;
  const std::size_t n = c.size() - 1;
  if (s0 > 0)  // keep [s0, 1]: the right side of the triangle
    for (std::size_t r = 1; r <= n; ++r)
      for (std::size_t i = 0; i + r <= n; ++i) out[i] = out[i] + s0 * (out[i + 1] - out[i]);
  if (s1 < 1) {  // keep [s0, s1] of it: the left side
    const double u = (s1 - s0) / (1 - s0);
    for (std::size_t r = 1; r <= n; ++r)
      for (std::size_t i = n; i >= r; --i) out[i] = out[i - 1] + u * (out[i] - out[i - 1]);
  }
}

}  // namespace detail

/// Cutter-location points along the homogeneous trajectory `h` (w, w x; positive weights)
/// with the tool axis along the spatial part of `d` (a homogeneous direction, weight 0, the
/// image of the moving axis; its length is irrelevant). Consecutive points are as far apart
/// as the bounds allow (a greedy search on t, doubling then bisecting the step). With W0, W1
/// the written ends of [t0, t1] (opt.write), r the larger distance of a written point from
/// the exact one, and (e, ea) the `between` bounds:
/// - chord: on every Bezier part of [t0, t1] (the pieces of h split at their breakpoints
///   and each into opt.subdivisions parts), every Cartesian control point lies within c of
///   the written segment W0 W1. The curve lies in the convex hull of those points and the
///   distance to a segment is convex, so the whole arc does. Conversely every point of the
///   segment P(t0) P(t1) lies within c + r of the arc (its projection onto the segment runs
///   from end to end), so every point of W0 W1 within c + 2r, and what runs between the
///   ends within c + 2r + e. That sum is at most chord_tol.
/// - axis: every control vector of d on those parts and the two written axes lie within g of
///   every other. The axes d(t) and the linear blend of the written axes lie in the cone they
///   span, so each d(t) is within g of the blend (cones narrower than 90 degrees), and
///   within g + ea of what runs. That sum is at most angle_tol.
/// - the written chord is at most max_step long.
/// Throws Errc::numerical_failure when a step below 1e-12 of the interval is needed.
inline SampledToolpath sample_toolpath(const kernel::BSpline<Eigen::Vector4d>& h,
                                       const kernel::BSpline<Eigen::Vector4d>& d,
                                       const SamplerOptions& opt) {
  const double a = h.a(), b = h.b();
  std::vector<double> breaks = h.breakpoints();
  for (double x : d.breakpoints()) breaks.push_back(x);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  auto point = [&](double t) {
    const Eigen::Vector4d y = kernel::evaluate(h, t);
    return Eigen::Vector3d(y.tail<3>() / y(0));
  };
  auto axis = [&](double t) {
    return Eigen::Vector3d(kernel::evaluate(d, t).tail<3>().normalized());
  };
  // The Bezier pieces of h and d on the common spans, computed once; a part of a span is
  // cut from its piece by de Casteljau (detail::sub_bezier).
  std::vector<std::vector<Eigen::Vector4d>> hpieces, dpieces;
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    hpieces.push_back(kernel::bezier_piece(h, breaks[k], breaks[k + 1]).coeffs());
    dpieces.push_back(kernel::bezier_piece(d, breaks[k], breaks[k + 1]).coeffs());
  }
  std::vector<Eigen::Vector4d> part;
  SampledToolpath out;
  // The certified chord and angle bounds of [t0, t1].
  auto bounds = [&](double t0, double t1, const WrittenEnd& w0, const WrittenEnd& w1) {
    ++out.bound_evaluations;
    const Eigen::Vector3d &p0 = w0.point, &p1 = w1.point;
    double chord = 0;
    std::vector<Eigen::Vector3d> gens{w0.axis, w1.axis};
    auto first = std::upper_bound(breaks.begin(), breaks.end(), t0);
    double u = t0;
    while (u < t1) {
      const double next = first != breaks.end() ? std::min(*first, t1) : t1;
      const std::size_t span = static_cast<std::size_t>(first - breaks.begin()) - 1;
      const double xa = breaks[span], len = breaks[span + 1] - xa;
      for (int k = 0; k < opt.subdivisions; ++k) {
        const double u0 = u + (next - u) * k / opt.subdivisions;
        const double u1 =
            k + 1 == opt.subdivisions ? next : u + (next - u) * (k + 1) / opt.subdivisions;
        if (!(u1 > u0)) continue;
        const double s0 = std::clamp((u0 - xa) / len, 0.0, 1.0),
                     s1 = std::clamp((u1 - xa) / len, 0.0, 1.0);
        detail::sub_bezier(hpieces[span], s0, s1, part);
        for (const auto& c : part) {
          if (!(c(0) > 0)) return std::pair<double, double>(HUGE_VAL, HUGE_VAL);
          chord = std::max(chord, detail::point_segment_distance(c.tail<3>() / c(0), p0, p1));
        }
        detail::sub_bezier(dpieces[span], s0, s1, part);
        for (const auto& c : part) gens.push_back(c.tail<3>());
      }
      u = next;
      if (first != breaks.end()) ++first;
    }
    // The widest pair of generators, by the smallest cosine (one acos at the end).
    for (auto& g : gens) g.normalize();
    double min_dot = 1;
    for (std::size_t i = 0; i < gens.size(); ++i)
      for (std::size_t j = i + 1; j < gens.size(); ++j)
        min_dot = std::min(min_dot, gens[i].dot(gens[j]));
    const double angle = std::acos(std::clamp(min_dot, -1.0, 1.0));
    return std::pair<double, double>(chord, angle);
  };
  auto write = [&](double t, const WrittenEnd* prev) {
    ToolpathSample s{t, point(t), axis(t), {}};
    s.written = opt.write ? opt.write(t, s.point, s.axis, prev) : WrittenEnd{s.point, s.axis, {}};
    return s;
  };
  // The block from `s0` to t1 within the tolerances: its end, the chord and angle bounds.
  struct Block {
    ToolpathSample end;
    double chord = 0, angle = 0, rounding = 0, between = 0, between_angle = 0;
  };
  Block trial, good;
  std::optional<TravelError> travel;  // why the last trial block failed, if an axis left travel
  auto ok = [&](const ToolpathSample& s0, double t1) {
    try {
      trial.end = write(t1, &s0.written);
      travel.reset();
    } catch (const TravelError& e) {
      travel = e;  // a shorter block may stay within travel
      return false;
    }
    const WrittenEnd &w0 = s0.written, &w1 = trial.end.written;
    if ((w1.point - w0.point).norm() > opt.max_step) return false;
    const auto [c, g] = bounds(s0.t, t1, w0, w1);
    trial.rounding = std::max((w0.point - s0.point).norm(), (w1.point - trial.end.point).norm());
    const auto [e, ea] = opt.between ? opt.between(w0, w1) : std::pair<double, double>(0, 0);
    trial.between = e;
    trial.between_angle = ea;
    trial.chord = c + 2 * trial.rounding + e;
    trial.angle = g + ea;
    if (!(trial.chord <= opt.chord_tol && trial.angle <= opt.angle_tol)) return false;
    good = trial;
    return true;
  };
  double t0 = a, step = (b - a) / 16;
  out.samples.push_back(write(a, nullptr));
  const double min_step = 1e-12 * (b - a);
  while (t0 < b) {
    double lo = 0, hi = 0;  // largest accepted and smallest refused steps
    double s = std::min(step, b - t0);
    const ToolpathSample s0 = out.samples.back();
    auto at = [&](double step_) { return step_ >= b - t0 ? b : t0 + step_; };
    if (ok(s0, at(s))) {
      lo = s;
      while (lo < b - t0) {  // grow
        s = std::min(2 * lo, b - t0);
        if (!ok(s0, at(s))) {
          hi = s;
          break;
        }
        lo = s;
      }
    } else {
      hi = s;
      while (true) {  // shrink
        s = hi / 2;
        if (s < min_step && travel) throw *travel;
        if (s < min_step)
          throw Error(Errc::numerical_failure,
                      "the toolpath needs a step below 1e-12 of the interval near t = " +
                          std::to_string(t0) + " (the chord or angle tolerance cannot be met)");
        if (ok(s0, at(s))) {
          lo = s;
          break;
        }
        hi = s;
      }
    }
    if (hi > 0)  // bisect between the accepted and the refused step
      for (int it = 0; it < 12 && hi - lo > 1e-3 * lo; ++it) {
        const double m = 0.5 * (lo + hi);
        if (ok(s0, at(m))) {
          lo = m;
        } else {
          hi = m;
        }
      }
    const double t1 = at(lo);
    if (good.end.t != t1) ok(s0, t1);  // the accepted block is the last one tried that held
    out.max_chord_bound = std::max(out.max_chord_bound, good.chord);
    out.max_angle_bound = std::max(out.max_angle_bound, good.angle);
    out.max_rounding = std::max(out.max_rounding, good.rounding);
    out.max_between = std::max(out.max_between, good.between);
    out.max_between_angle = std::max(out.max_between_angle, good.between_angle);
    out.samples.push_back(good.end);
    if (opt.progress) opt.progress((t1 - a) / (b - a));
    step = lo;
    t0 = t1;
  }
  return out;
}

}  // namespace qmotion::cam
