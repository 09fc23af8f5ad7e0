// render/src/drawing.cpp: what the figure and the plot share.
#include "drawing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace qmotion::render::detail {

/// The rigid map of the motion at t.
Rigid rigid_at(const Motion& m, double t) {
  const Eigen::Matrix4d f = m.frame(t);
  Rigid r;
  r.R = f.block<3, 3>(1, 1);
  r.p = f.block<3, 1>(1, 0);
  return r;
}

/// Parameters covering [a, b] span by span (about `total` of them, at least `per_span` + 1
/// a span, at most 2e5), each span's ends included.
std::vector<double> span_samples(const std::vector<double>& breaks, int total, int per_span_min) {
  const std::size_t spans = breaks.size() - 1;
  std::vector<double> ts;
  if (spans > 200000 / static_cast<std::size_t>(per_span_min + 1)) {  // too many: uniform
    const double a = breaks.front(), b = breaks.back();
    for (int i = 0; i <= total; ++i) ts.push_back(a + (b - a) * i / total);
    return ts;
  }
  const int n = std::max(per_span_min, static_cast<int>(std::ceil(double(total) / spans)));
  for (std::size_t s = 0; s < spans; ++s)
    for (int j = (s == 0 ? 0 : 1); j <= n; ++j)
      ts.push_back(breaks[s] + (breaks[s + 1] - breaks[s]) * j / n);
  return ts;
}

/// 1, 2 or 5 times a power of ten, the largest not above x (x > 0).
double nice_below(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= x * (1 + 1e-12)) return m * p;
  return p;
}

std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", std::abs(v) < 1e-300 ? 0.0 : v);
  return buf;
}

std::string full_number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string point_text(const Vector3d& x) {
  return "(" + short_number(x.x()) + ", " + short_number(x.y()) + ", " + short_number(x.z()) + ")";
}

/// Trajectory styles: colour and dash differ at once, so they stay apart in greyscale.
Style trajectory_style(std::size_t i) {
  static const std::array<Rgb, 5> colours = {Rgb{0.75, 0.12, 0.08}, Rgb{0.08, 0.28, 0.70},
                                             Rgb{0.05, 0.50, 0.20}, Rgb{0.50, 0.10, 0.60},
                                             Rgb{0.05, 0.05, 0.05}};
  static const std::array<std::vector<double>, 5> dashes = {
      std::vector<double>{}, std::vector<double>{9, 4}, std::vector<double>{2, 3.5},
      std::vector<double>{11, 3, 2, 3}, std::vector<double>{5, 5}};
  Style s;
  s.stroke = colours[i % colours.size()];
  s.dash = dashes[i % dashes.size()];
  s.width = 2;
  return s;
}

Rgb scaled(Rgb c, double f) { return Rgb{c.r * f, c.g * f, c.b * f}; }

/// A title that fits in `width` pixels: the font shrinks from `size` down to 8 pixels,
/// then the text is cut with an ellipsis.
std::pair<std::string, double> fit_text(std::string s, double width, double size) {
  while (size > 8 && Canvas::text_width(s, size) > width) size -= 0.5;
  if (Canvas::text_width(s, size) > width) {
    while (!s.empty() && Canvas::text_width(s + "...", size) > width) {
      s.pop_back();
      while (!s.empty() && (static_cast<unsigned char>(s.back()) & 0xC0) == 0x80) s.pop_back();
      if (!s.empty() && (static_cast<unsigned char>(s.back()) & 0xC0) == 0xC0) s.pop_back();
    }
    s += "...";
  }
  return {s, size};
}

}  // namespace qmotion::render::detail
