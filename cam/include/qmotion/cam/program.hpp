// <qmotion/cam/program.hpp>: a machining program as the moves a controller's interpreter
// makes of it (LinuxCNC calls them canonical moves): straight traverses, straight feeds and
// helical arcs of the tool tip, in millimetres, with the rotary axes in degrees
// (docs/guide/verify.md). io::read_gcode makes one from G-code.
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace qmotion::cam {

/// One canonical move of the tool tip, from `from` to `to`.
struct Move {
  enum class Kind { traverse, feed, arc };
  Kind kind = Kind::feed;
  int line = 0;  ///< the source line (1-based) of the block that made it
  Eigen::Vector3d from = Eigen::Vector3d::Zero(), to = Eigen::Vector3d::Zero();  ///< mm
  std::array<double, 3> abc_from{}, abc_to{};  ///< A, B, C in degrees
  /// Arcs: the plane (17: XY, 18: ZX, 19: YZ, as G17 to G19 name them), the centre (its
  /// coordinate along the plane's normal is the start's), and the turns: > 0 counterclockwise
  /// about the plane's normal (+Z, +Y, +X: G3), < 0 clockwise (G2); |turns| - 1 full circles
  /// come before the last, partial one.
  int plane = 17;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  int turns = 0;
  double feed = 0;            ///< mm/min, or 1/min under inverse time (G93); 0 for traverses
  bool inverse_time = false;  ///< G93
};

/// A program's moves, in order, and the file they came from.
struct Program {
  std::string source;
  std::vector<Move> moves;
};

/// The indices (u, v, w) of the coordinates of an arc's plane: G17 (x, y, z), G18 (z, x, y),
/// G19 (y, z, x); an arc turns counterclockwise from u towards v about w.
inline std::array<int, 3> plane_axes(int plane) {
  if (plane == 18) return {2, 0, 1};
  if (plane == 19) return {1, 2, 0};
  return {0, 1, 2};
}

namespace detail {

/// An arc's start radius, end radius, start angle and signed sweep (radians), as an
/// interpreter runs it: the radius changes linearly with the angle when the end does not
/// lie on the start's circle, and a start equal to the end is a full turn.
struct ArcShape {
  double r0 = 0, r1 = 0, a0 = 0, sweep = 0;
};

inline ArcShape arc_shape(const Move& m) {
  const auto [u, v, w] = plane_axes(m.plane);
  (void)w;
  const double pi = 3.14159265358979323846;
  ArcShape s;
  const double su = m.from(u) - m.centre(u), sv = m.from(v) - m.centre(v);
  const double eu = m.to(u) - m.centre(u), ev = m.to(v) - m.centre(v);
  s.r0 = std::hypot(su, sv);
  s.r1 = std::hypot(eu, ev);
  s.a0 = std::atan2(sv, su);
  double d = std::atan2(ev, eu) - s.a0;  // in (-2 pi, 2 pi)
  const int n = std::max(1, std::abs(m.turns));
  if (m.turns >= 0) {
    while (d <= 1e-12) d += 2 * pi;
    s.sweep = d + 2 * pi * (n - 1);
  } else {
    while (d >= -1e-12) d -= 2 * pi;
    s.sweep = d - 2 * pi * (n - 1);
  }
  return s;
}

}  // namespace detail

/// The tool tip at t in [0, 1] along the move, s its arc_shape for arcs: linear for traverses and
/// feeds (every axis together, as an interpreter's straight moves are), and for arcs linear in the
/// angle, the radius and the coordinate along the plane's normal.
inline Eigen::Vector3d position(const Move& m, const detail::ArcShape& s, double t) {
  if (m.kind != Move::Kind::arc) return m.from + t * (m.to - m.from);
  const auto [u, v, w] = plane_axes(m.plane);
  const double a = s.a0 + t * s.sweep, r = s.r0 + t * (s.r1 - s.r0);
  Eigen::Vector3d p;
  p(u) = m.centre(u) + r * std::cos(a);
  p(v) = m.centre(v) + r * std::sin(a);
  p(w) = m.from(w) + t * (m.to(w) - m.from(w));
  return p;
}

/// The same, the arc's shape worked out here (arc_shape; pass it in where t varies).
inline Eigen::Vector3d position(const Move& m, double t) {
  return position(m, m.kind == Move::Kind::arc ? detail::arc_shape(m) : detail::ArcShape{}, t);
}

/// A bound on |d position / dt| over the whole move: |p(t) - p(s)| <= speed_bound * |t - s|.
/// Straight: the chord. Arc: the derivative's parts are r'(t) (radial), r(t) * sweep
/// (tangential) and the normal's rise, orthogonal, with r(t) <= max(r0, r1).
inline double speed_bound(const Move& m) {
  if (m.kind != Move::Kind::arc) return (m.to - m.from).norm();
  const int w = plane_axes(m.plane)[2];
  const detail::ArcShape s = detail::arc_shape(m);
  const double dr = s.r1 - s.r0, tang = std::max(s.r0, s.r1) * std::abs(s.sweep);
  const double dw = m.to(w) - m.from(w);
  return std::sqrt(dr * dr + tang * tang + dw * dw) * (1 + 1e-12);
}

}  // namespace qmotion::cam
