// render/src/drawing.hpp: what the figure and the plot share (private to render/): rigid
// maps of a motion, parameters span by span, number and point text, trajectory styles, text
// that fits, and the depth-sorted faces of a scene.
#pragma once
#include <Eigen/Core>
#include <cstddef>
#include <qmotion/motion.hpp>
#include <qmotion/render/canvas.hpp>
#include <string>
#include <utility>
#include <vector>

namespace qmotion::render::detail {

/// Text for SVG or HTML: &, <, > and " escaped.
std::string escape_xml(const std::string& s);

using Eigen::Vector2d;
using Eigen::Vector3d;

/// A rigid map x -> R x + p.
struct Rigid {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Vector3d p = Vector3d::Zero();
  Vector3d operator()(const Vector3d& x) const { return R * x + p; }
};

/// The rigid map of the motion at t.
Rigid rigid_at(const Motion& m, double t);

/// Parameters covering [a, b] span by span (about `total` of them, at least `per_span` + 1
/// a span, at most 2e5), each span's ends included.
std::vector<double> span_samples(const std::vector<double>& breaks, int total, int per_span_min);

/// 1, 2 or 5 times a power of ten, the largest not above x (x > 0).
double nice_below(double x);

/// A number in six significant digits, and in all seventeen.
std::string short_number(double v);
std::string full_number(double v);

/// "(x, y, z)" in short numbers.
std::string point_text(const Vector3d& x);

/// Trajectory styles: colour and dash differ at once, so they stay apart in greyscale.
Style trajectory_style(std::size_t i);

/// The colour scaled by f (shading).
Rgb scaled(Rgb c, double f);

/// A title that fits in `width` pixels: the font shrinks from `size` down to 8 pixels,
/// then the text is cut with an ellipsis.
std::pair<std::string, double> fit_text(std::string s, double width, double size);

/// Past this many key poses their objects are not drawn (markers only).
constexpr std::size_t kMaxKeyObjects = 12;

/// A face of the depth-sorted scene: a polygon in space, its style, and which of its edges
/// are iso-parameter lines to stroke after the fill.
struct Face {
  std::vector<Vector3d> points;
  Style style;
  std::vector<int> iso_edges;  ///< edge k joins points[k] and points[k + 1 mod n]
  Style iso_style;
  double depth = 0;
};

}  // namespace qmotion::render::detail
