// <qmotion/sweep/profiles.hpp>
#pragma once
#include <cmath>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/nurbs.hpp>
#include <string>
#include <vector>

namespace qmotion::sweep {

/// The straight segment from p to q, v in [0, 1] (degree 1).
template <typename Scalar>
NurbsCurve<Scalar> segment(const Eigen::Matrix<Scalar, 3, 1>& p,
                           const Eigen::Matrix<Scalar, 3, 1>& q) {
  return NurbsCurve<Scalar>{
      1, {Scalar(0), Scalar(0), Scalar(1), Scalar(1)}, {p, q}, {Scalar(1), Scalar(1)}};
}

/// The full circle of radius r about the origin in the x-y plane, from (r, 0, 0)
/// counter-clockwise about +z, v in [0, 1], as an exact rational quadratic NURBS with
/// rational data only: four arcs whose half-angles a and 90 deg - a have cos a = 4/5,
/// sin a = 3/5 (a Pythagorean angle), so every pole and weight is a rational multiple of r
/// (the usual quarter arcs need the irrational weight sqrt(2)/2).
/// @see Piegl & Tiller, The NURBS Book, 7.5 (circle as rational quadratic arcs)
template <typename Scalar>
NurbsCurve<Scalar> circle(const Scalar& r) {
  if (!(r > Scalar(0))) throw Error(Errc::invalid_input, "circle radius must be positive");
  using V = Eigen::Matrix<Scalar, 3, 1>;
  auto pt = [&](int num_x, int den_x, int num_y, int den_y) {
    return V(Scalar(r * Scalar(num_x) / Scalar(den_x)), Scalar(r * Scalar(num_y) / Scalar(den_y)),
             Scalar(0));
  };
  NurbsCurve<Scalar> c;
  c.degree = 2;
  const Scalar k1 = Scalar(1) / Scalar(5), h = Scalar(1) / Scalar(2);
  c.knots = {Scalar(0), Scalar(0),      Scalar(0),      k1,        k1,        h,
             h,         Scalar(h + k1), Scalar(h + k1), Scalar(1), Scalar(1), Scalar(1)};
  c.points = {pt(1, 1, 0, 1),      pt(1, 1, 3, 4),  pt(7, 25, 24, 25),
              pt(-1, 1, 4, 3),     pt(-1, 1, 0, 1), pt(-1, 1, -3, 4),
              pt(-7, 25, -24, 25), pt(1, 1, -4, 3), pt(1, 1, 0, 1)};
  const Scalar w4 = Scalar(4) / Scalar(5), w3 = Scalar(3) / Scalar(5);
  c.weights = {Scalar(1), w4, Scalar(1), w3, Scalar(1), w4, Scalar(1), w3, Scalar(1)};
  return c;
}

/// The arc of the circle above from angle a0 to a1 (degrees; a1 < a0 runs clockwise),
/// v in [0, 1]: rational quadratic arcs of at most 90 degrees each, with the middle
/// weight cos(half-angle) (exact up to rounding of the trigonometric values).
inline NurbsCurve<double> arc(double r, double a0_deg, double a1_deg) {
  if (!(r > 0)) throw Error(Errc::invalid_input, "arc radius must be positive");
  const double sweep = a1_deg - a0_deg;
  if (!(std::abs(sweep) > 0) || std::abs(sweep) > 360.0)
    throw Error(Errc::invalid_input,
                "arc angles must differ by more than 0 and at most 360 degrees");
  const int n = static_cast<int>(std::ceil(std::abs(sweep) / 90.0 - 1e-12));
  const double d = sweep / n * M_PI / 180.0, a0 = a0_deg * M_PI / 180.0;
  NurbsCurve<double> c;
  c.degree = 2;
  c.knots = {0, 0, 0};
  for (int i = 1; i < n; ++i) c.knots.insert(c.knots.end(), 2, static_cast<double>(i) / n);
  c.knots.insert(c.knots.end(), 3, 1.0);
  for (int i = 0; i < n; ++i) {
    const double t0 = a0 + i * d, tm = t0 + d / 2;
    if (i == 0) {
      c.points.emplace_back(r * std::cos(t0), r * std::sin(t0), 0.0);
      c.weights.push_back(1.0);
    }
    const double w = std::cos(d / 2);
    c.points.emplace_back(r / w * std::cos(tm), r / w * std::sin(tm), 0.0);
    c.weights.push_back(w);
    c.points.emplace_back(r * std::cos(t0 + d), r * std::sin(t0 + d), 0.0);
    c.weights.push_back(1.0);
  }
  return c;
}

/// A profile of the moving space: one or more edges in order, each a NURBS curve with its
/// own parameter (docs/formats.md). `closed` when the last edge ends where the first starts.
template <typename Scalar>
struct Profile {
  std::vector<NurbsCurve<Scalar>> edges;
  bool closed = false;
};

/// The profile of one curve (closed when its end points coincide).
template <typename Scalar>
Profile<Scalar> single_edge(NurbsCurve<Scalar> c) {
  const bool closed = c.points.front() == c.points.back();
  return Profile<Scalar>{{std::move(c)}, closed};
}

/// The polyline through the points, one segment edge (v in [0, 1]) per pair; closed when
/// the last point equals the first. Throws Errc::invalid_input on fewer than two points or
/// a repeated consecutive point.
template <typename Scalar>
Profile<Scalar> polyline(const std::vector<Eigen::Matrix<Scalar, 3, 1>>& pts) {
  if (pts.size() < 2) throw Error(Errc::invalid_input, "a polyline needs at least two points");
  Profile<Scalar> p;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    if (pts[i] == pts[i + 1])
      throw Error(Errc::invalid_input, "polyline points " + std::to_string(i + 1) + " and " +
                                           std::to_string(i + 2) + " coincide");
    p.edges.push_back(segment(pts[i], pts[i + 1]));
  }
  p.closed = pts.size() > 3 && pts.front() == pts.back();
  return p;
}

/// The closed w x h rectangle centred at the origin in the x-y plane, counter-clockwise
/// about +z from (w/2, -h/2): four segment edges.
template <typename Scalar>
Profile<Scalar> rect(const Scalar& w, const Scalar& h) {
  if (!(w > Scalar(0)) || !(h > Scalar(0)))
    throw Error(Errc::invalid_input, "rectangle sides must be positive");
  using V = Eigen::Matrix<Scalar, 3, 1>;
  const Scalar x = Scalar(w / Scalar(2)), y = Scalar(h / Scalar(2));
  return polyline<Scalar>({V(x, Scalar(-y), Scalar(0)), V(x, y, Scalar(0)),
                           V(Scalar(-x), y, Scalar(0)), V(Scalar(-x), Scalar(-y), Scalar(0)),
                           V(x, Scalar(-y), Scalar(0))});
}

}  // namespace qmotion::sweep
