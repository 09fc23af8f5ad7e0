// render/src/plot.cpp: a quantity of one or more motions along t (speed, angular speed,
// curvature, weights), sampled span by span and drawn as a plot.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/io/point_text.hpp>
#include <qmotion/io/profiles.hpp>
#include <qmotion/kernel/dual_quaternion.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/motion_value.hpp>
#include <qmotion/render/render.hpp>
#include <qmotion/sweep/nurbs.hpp>
#include <qmotion/sweep/trajectory.hpp>
#include <qmotion/sweep/weights.hpp>

#include "drawing.hpp"

namespace qmotion::render {
using namespace io;      // NOLINT: the formats this call reads and writes
using namespace detail;  // NOLINT: this module's own drawing helpers

Quantity parse_quantity(const std::string& name) {
  for (Quantity q :
       {Quantity::speed, Quantity::angular_speed, Quantity::curvature, Quantity::weights})
    if (name == to_string(q)) return q;
  throw Error(Errc::invalid_input,
              "--quantity " + name + ": expected speed, angular-speed, curvature or weights");
}

const char* to_string(Quantity q) {
  switch (q) {
    case Quantity::speed:
      return "speed";
    case Quantity::angular_speed:
      return "angular-speed";
    case Quantity::curvature:
      return "curvature";
    case Quantity::weights:
      return "weights";
  }
  return "";
}

namespace {

/// A trajectory's NURBS with its first two derivatives, as homogeneous splines.
struct CurveJet {
  kernel::BSpline<Eigen::Vector4d> h, d1, d2;
  explicit CurveJet(const sweep::NurbsCurve<double>& c)
      : h(sweep::to_homogeneous(c)), d1(kernel::derivative(h)), d2(kernel::derivative(d1)) {}
  /// x, x', x'' at t by the quotient rule.
  std::array<Vector3d, 3> at(double t) const {
    const Eigen::Vector4d y = kernel::evaluate(h, t), y1 = kernel::evaluate(d1, t),
                          y2 = kernel::evaluate(d2, t);
    const Vector3d x = y.tail<3>() / y(0);
    const Vector3d x1 = (y1.tail<3>() - y1(0) * x) / y(0);
    const Vector3d x2 = (y2.tail<3>() - 2 * y1(0) * x1 - y2(0) * x) / y(0);
    return {x, x1, x2};
  }
};

/// The exact trajectory of x as NURBS with positive weights (refused at a pole).
sweep::NurbsCurve<double> exact_trajectory(const kernel::Motion<double>& m, const Vector3d& x) {
  sweep::refuse_poles(m);
  const auto h = sweep::point_trajectory(m, x);
  return sweep::to_nurbs(sweep::insert_knots(h, sweep::knots_for_positive_weights(h)));
}

double curvature(const Vector3d& v, const Vector3d& acc) {
  const double s = v.norm();
  if (!(s > 1e-12)) return std::numeric_limits<double>::quiet_NaN();
  return v.cross(acc).norm() / (s * s * s);
}

/// The quantity at t, for t inside one span (the caller keeps it off the joints).
std::function<double(double)> quantity_function(const kernel::Motion<double>& m,
                                                const PlotOptions& o) {
  switch (o.quantity) {
    case Quantity::speed:
    case Quantity::curvature: {
      auto jet = std::make_shared<CurveJet>(exact_trajectory(m, o.point));
      if (o.quantity == Quantity::speed) return [jet](double t) { return jet->at(t)[1].norm(); };
      return [jet](double t) {
        const auto x = jet->at(t);
        return curvature(x[1], x[2]);
      };
    }
    case Quantity::angular_speed: {
      // omega from the velocities of the origin and the unit points: v_i - v_0 = omega x r_i
      // with r_i = R e_i orthonormal, so sum r_i x (v_i - v_0) = 2 omega.
      auto jets = std::make_shared<std::vector<CurveJet>>();
      for (int i = 0; i < 4; ++i)
        jets->emplace_back(
            exact_trajectory(m, i == 0 ? Vector3d::Zero() : Vector3d(Vector3d::Unit(i - 1))));
      return [jets](double t) {
        const auto o0 = (*jets)[0].at(t);
        Vector3d w = Vector3d::Zero();
        for (std::size_t i = 1; i < 4; ++i) {
          const auto oi = (*jets)[i].at(t);
          w += (oi[0] - o0[0]).cross(oi[1] - o0[1]);
        }
        return 0.5 * w.norm();
      };
    }
    case Quantity::weights:
      return [&m](double t) { return kernel::evaluate(m.curve, t).real().norm2(); };
  }
  return {};
}

std::function<double(double)> quantity_function(const kernel::QuaternionSpline& spline,
                                                const PlotOptions& o) {
  const kernel::QuaternionSpline* s = &spline;
  const Vector3d x = o.point;
  switch (o.quantity) {
    case Quantity::speed:
      return [s, x](double t) { return s->point_velocity(t, x).norm(); };
    case Quantity::curvature:
      return [s, x](double t) {
        // The acceleration by a central difference of the exact velocity, inside the span.
        const auto it = std::upper_bound(s->knots.begin(), s->knots.end(), t);
        const double lo = it == s->knots.begin() ? s->a() : *(it - 1);
        const double hi = it == s->knots.end() ? s->b() : *it;
        const double h = 1e-5 * (hi - lo);
        const double t0 = std::max(lo, t - h), t1 = std::min(hi, t + h);
        const Vector3d acc = (s->point_velocity(t1, x) - s->point_velocity(t0, x)) / (t1 - t0);
        return curvature(s->point_velocity(t, x), acc);
      };
    case Quantity::angular_speed:
      return [s](double t) { return s->angular_velocity(t).norm(); };
    case Quantity::weights:
      return [](double) { return 1.0; };
  }
  return {};
}

std::string quantity_label(Quantity q, const std::string& units) {
  switch (q) {
    case Quantity::speed:
      return "speed (" + units + " per unit t)";
    case Quantity::angular_speed:
      return "angular speed (rad per unit t)";
    case Quantity::curvature:
      return "curvature (1/" + units + ")";
    case Quantity::weights:
      return "weight |Q0(t)|^2 / max";
  }
  return "";
}

}  // namespace

PlotSeries sample_quantity(const Motion& motion, const PlotOptions& o) {
  if (o.samples < 2 || o.samples > 1000000)
    throw Error(Errc::invalid_input,
                "--samples " + std::to_string(o.samples) + ": expected 2 to 1000000");
  if (!o.point.allFinite())
    throw Error(Errc::invalid_input, "--point: expected finite coordinates");
  const auto f = motion.is_rational() ? quantity_function(motion.rational(), o)
                                      : quantity_function(motion.spline(), o);
  const std::vector<double> breaks = motion.breakpoints();
  PlotSeries s;
  s.name = motion.label();
  s.keys = motion.key_parameters();
  s.a = motion.a();
  s.b = motion.b();
  const std::size_t spans = breaks.size() - 1;
  const bool per_span = spans <= static_cast<std::size_t>(o.samples) / 2;
  const int n = per_span ? std::max(2, o.samples / static_cast<int>(spans)) : o.samples;
  auto sample = [&](double t) {
    s.t.push_back(t);
    s.value.push_back(f(t));
  };
  if (per_span) {
    for (std::size_t k = 0; k < spans; ++k) {  // both sides of each joint, just inside
      const double t0 = breaks[k], t1 = breaks[k + 1], inset = 1e-9 * (t1 - t0);
      for (int j = 0; j <= n; ++j)
        sample(std::clamp(t0 + (t1 - t0) * j / n, t0 + inset, t1 - inset));
    }
  } else {
    for (int j = 0; j <= n; ++j) sample(s.a + (s.b - s.a) * j / n);
  }
  if (o.quantity == Quantity::weights) {
    double top = 0;
    for (double v : s.value) top = std::max(top, v);
    if (top > 0)
      for (double& v : s.value) v /= top;
  }
  s.min = std::numeric_limits<double>::infinity();
  s.max = -s.min;
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    const double v = s.value[i];
    if (!std::isfinite(v)) continue;
    if (v < s.min) {
      s.min = v;
      s.t_min = s.t[i];
    }
    if (v > s.max) {
      s.max = v;
      s.t_max = s.t[i];
    }
  }
  if (!std::isfinite(s.min))
    throw Error(Errc::numerical_failure,
                s.name + ": the " + to_string(o.quantity) + " is undefined everywhere");
  return s;
}

Canvas plot_figure(const std::vector<PlotSeries>& series, const PlotOptions& o,
                   const std::string& units) {
  if (series.empty()) throw Error(Errc::invalid_input, "plot: no motion given");
  Canvas canvas(o.width, o.height);
  const double left = 74, right_m = 18, top = 52,
               bottom = 46 + (series.size() > 1 ? 16.0 * static_cast<double>(series.size()) : 0);
  const double pw = o.width - left - right_m, ph = o.height - top - bottom;
  if (!(pw > 40 && ph > 40))
    throw Error(Errc::invalid_input, "--size " + std::to_string(o.width) + "," +
                                         std::to_string(o.height) + ": too small for the plot");
  double t0 = series[0].a, t1 = series[0].b, lo = 0, hi = 0;
  std::vector<double> finite;
  for (const auto& s : series) {
    t0 = std::min(t0, s.a);
    t1 = std::max(t1, s.b);
    lo = std::min(lo, s.min);
    hi = std::max(hi, s.max);
    for (double v : s.value)
      if (std::isfinite(v)) finite.push_back(v);
  }
  // A curvature spike (a cusp) would flatten the rest: cap the range at 1.3 x the 98th
  // percentile when the peak is far above it, and draw the clipped values on the frame.
  bool clipped = false;
  if (!finite.empty()) {
    const auto k = static_cast<std::size_t>(0.98 * static_cast<double>(finite.size() - 1));
    std::nth_element(finite.begin(), finite.begin() + static_cast<std::ptrdiff_t>(k), finite.end());
    const double p98 = finite[k];
    if (p98 > 0 && hi > 20 * p98) {
      hi = 1.3 * p98;
      clipped = true;
    }
  }
  if (o.quantity == Quantity::weights) hi = std::max(hi, 1.0);
  if (!(hi > lo)) hi = lo + 1;
  hi += 0.05 * (hi - lo);
  if (!(t1 > t0)) t1 = t0 + 1;
  auto X = [&](double t) { return left + (t - t0) / (t1 - t0) * pw; };
  auto Y = [&](double v) { return top + (hi - std::clamp(v, lo, hi)) / (hi - lo) * ph; };

  canvas.attribute("quantity", to_string(o.quantity));
  canvas.attribute("t-range", full_number(t0) + "," + full_number(t1));
  canvas.attribute("value-range", full_number(lo) + "," + full_number(hi));
  canvas.attribute("plot-box", short_number(left) + "," + short_number(top) + "," +
                                   short_number(pw) + "," + short_number(ph));

  std::string title = o.title;
  if (title.empty()) {
    const std::string of = " of the point " + point_text(o.point);
    switch (o.quantity) {
      case Quantity::speed:
        title = "Speed" + of + " along t";
        break;
      case Quantity::curvature:
        title = "Curvature of the trajectory" + of;
        break;
      case Quantity::angular_speed:
        title = "Angular speed along t";
        break;
      case Quantity::weights:
        title = "Weight |Q0(t)|^2 along t (near 0: near a pole)";
        break;
    }
    if (series.size() == 1) title += ": " + series[0].name;
  }
  const auto [fitted, fsize] = fit_text(title, o.width - 20, 15);
  canvas.text(Vector2d(o.width / 2.0, 22), fitted, fsize, Anchor::middle, Rgb{}, true);

  // Grid and ticks.
  canvas.begin_group("axes");
  Style grid;
  grid.stroke = Rgb{0.88, 0.88, 0.88};
  grid.width = 1;
  Style frame;
  frame.stroke = Rgb{0, 0, 0};
  frame.width = 1.2;
  const double ty = nice_below((hi - lo) / 5), tx = nice_below((t1 - t0) / 6);
  for (double v = std::ceil(lo / ty) * ty; v <= hi + 1e-9 * ty; v += ty) {
    canvas.polyline({{left, Y(v)}, {left + pw, Y(v)}}, grid);
    canvas.text(Vector2d(left - 6, Y(v) + 4), short_number(std::abs(v) < 1e-12 * ty ? 0 : v), 11,
                Anchor::end);
  }
  for (double t = std::ceil(t0 / tx) * tx; t <= t1 + 1e-9 * tx; t += tx) {
    canvas.polyline({{X(t), top}, {X(t), top + ph}}, grid);
    canvas.text(Vector2d(X(t), top + ph + 16), short_number(std::abs(t) < 1e-12 * tx ? 0 : t), 11,
                Anchor::middle);
  }
  canvas.polygon({{left, top}, {left + pw, top}, {left + pw, top + ph}, {left, top + ph}}, frame);
  canvas.text(Vector2d(left + pw / 2, top + ph + 34), "t", 12, Anchor::middle);
  canvas.text(Vector2d(left, top - 8),
              quantity_label(o.quantity, units) + (clipped ? " (clipped above the frame)" : ""), 11,
              Anchor::start);
  canvas.end_group();

  // The key parameters of each motion: dashed verticals numbered at the top.
  for (std::size_t si = 0; si < series.size(); ++si) {
    Style s;
    s.stroke = series.size() == 1 ? Rgb{0.35, 0.35, 0.35} : *trajectory_style(si).stroke;
    s.width = 0.9;
    s.dash = {3, 3};
    s.cls = "key-line";
    if (series[si].keys.size() > 200) continue;  // a wall of lines says nothing
    for (std::size_t k = 0; k < series[si].keys.size(); ++k) {
      const double x = X(series[si].keys[k]);
      canvas.polyline({{x, top}, {x, top + ph}}, s);
      if (si == 0 && series[si].keys.size() <= 40)
        canvas.text(Vector2d(x + 3, top + 11), std::to_string(k), 9, Anchor::start);
    }
  }

  // The curves, broken where the quantity is undefined.
  for (std::size_t si = 0; si < series.size(); ++si) {
    Style s = trajectory_style(si);
    s.cls = "series";
    std::vector<Vector2d> run;
    const auto& sr = series[si];
    for (std::size_t i = 0; i <= sr.t.size(); ++i) {
      if (i == sr.t.size() || !std::isfinite(sr.value[i])) {
        canvas.polyline(std::move(run), s);
        run.clear();
        continue;
      }
      run.emplace_back(X(sr.t[i]), Y(sr.value[i]));
    }
  }
  if (series.size() > 1) {
    canvas.begin_group("legend");
    for (std::size_t si = 0; si < series.size(); ++si) {
      const double y = o.height - 10 - 16.0 * static_cast<double>(series.size() - 1 - si);
      canvas.polyline({{left, y - 4}, {left + 28, y - 4}}, trajectory_style(si));
      canvas.text(Vector2d(left + 36, y), series[si].name, 11, Anchor::start);
    }
    canvas.end_group();
  }
  return canvas;
}

std::vector<PlotSeries> plot(const std::vector<Motion>& motions, const PlotOptions& o) {
  check_figure_path(o.output);
  if (motions.empty()) throw Error(Errc::invalid_input, "plot: no motion given");
  for (const Motion& m : motions)
    if (m.units() != motions.front().units())
      throw Error(Errc::invalid_input,
                  m.label() + ": its unit " + m.units() + " differs from the first motion's (" +
                      motions.front().units() + "); plot motions of one unit together");
  std::vector<PlotSeries> series;
  for (const Motion& m : motions) series.push_back(sample_quantity(m, o));
  plot_figure(series, o, motions.front().units()).write(o.output);
  return series;
}

}  // namespace qmotion::render
