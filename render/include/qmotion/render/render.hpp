// <qmotion/render/render.hpp>: pictures of motions, the way seed 004's figures show them (`qmotion
// render`, `qmotion plot`, and the demo's figure): the moving object at evenly spaced times, the
// key poses numbered, trajectories, the swept surface as shaded iso-parameter lines, axes and a
// scale bar; and plots of a quantity along t. SVG or PNG (cairo).
#pragma once
#include <Eigen/Core>
#include <array>
#include <optional>
#include <qmotion/motion.hpp>
#include <qmotion/render/canvas.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <string>
#include <vector>

namespace qmotion::render {

struct RenderOptions {
  std::string output;  ///< .svg or .png
  /// Orthographic view: iso, top, front, side, or a direction "x,y,z" pointing from the
  /// scene towards the viewer. z is up on the page (y for views along z).
  std::string view = "iso";
  int width = 960, height = 720;  ///< pixels
  int frames = 7;                 ///< the object at this many evenly spaced times (0: none)
  /// Points of the moving space whose trajectories are drawn (default: the origin).
  std::vector<Eigen::Vector3d> points;
  /// The profile whose kinematic surface is drawn as shaded iso-parameter lines.
  std::optional<sweep::Profile<double>> profile;
  /// The moving object: "cube" (a cube about the moving origin, scaled to the motion), a
  /// profile as `--profile` reads it, or an STL mesh (.stl) of the moving space.
  std::string object = "cube";
  double object_size = 0;  ///< the cube's edge (0: a tenth of the figure's extent)
  std::string title;       ///< default: the motion's name, kind, degree and key poses
  /// The stored profile of `object` (set by render when it reads one; callers may set it
  /// directly with object = "profile").
  std::optional<sweep::Profile<double>> object_profile;
  /// A swept volume to draw as shaded triangles among the other faces (qmotion::render_volume
  /// fills it from `render --body`): vertices in the motion's space, outward triangles.
  std::vector<Eigen::Vector3d> volume_vertices;
  std::vector<std::array<int, 3>> volume_triangles;
  std::string volume_label;  ///< its legend entry, e.g. "swept volume of cutter:ball,6,20"
};

/// What was drawn, and the projection (screen = origin + scale (x.right, -x.up)).
struct RenderResult {
  std::string path;
  int width = 0, height = 0;
  int trajectories = 0;  ///< polylines of class "trajectory"
  int object_poses = 0;  ///< evenly spaced instants (class "object-pose" markers)
  int key_poses = 0;     ///< the motion's keys (where it interpolates, else its breakpoints)
  /// Key markers drawn (class "key-marker": a numbered ring for every key up to 40 keys,
  /// else for every ceil(n / 20)-th and the last, a dot for the others up to 200 keys); the
  /// keys' objects are drawn up to 12 keys.
  int key_markers = 0;
  int surface_quads = 0;
  int volume_triangles = 0;  ///< triangles of the swept volume drawn (class "swept-volume")
  double scale = 0;          ///< pixels per unit of length
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  ///< pixel position of the world origin
  Eigen::Vector3d right = Eigen::Vector3d::UnitX(), up = Eigen::Vector3d::UnitZ(),
                  toward_viewer = Eigen::Vector3d::UnitY();
  double object_size = 0;
};

/// The unit direction towards the viewer of a --view value; Errc::invalid_input otherwise.
Eigen::Vector3d parse_view(const std::string& view);

/// "W,H" of --size; Errc::invalid_input unless two integers in [16, 20000].
std::pair<int, int> parse_size(const std::string& text);

/// The figure of the motion (either kind), not written. `result` receives the counts and
/// the projection. Errc::invalid_input names a bad view, size, frame count or object.
Canvas render_figure(const Motion& motion, const RenderOptions& options,
                     RenderResult* result = nullptr);

/// render_figure written to options.output (.svg or .png, atomically).
RenderResult render(const Motion& motion, const RenderOptions& options);

/// A quantity along t, as `qmotion plot` draws it.
enum class Quantity { speed, angular_speed, curvature, weights };
Quantity parse_quantity(const std::string& name);  ///< speed, angular-speed, curvature, weights
const char* to_string(Quantity q);

struct PlotOptions {
  std::string output;  ///< .svg or .png
  Quantity quantity = Quantity::speed;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< speed and curvature: of this point
  int width = 900, height = 500;
  int samples = 600;  ///< per motion, shared out over its spans, ends included
  std::string title;  ///< default: the quantity and the point
};

/// One motion's curve: the quantity at parameters t (NaN where undefined, e.g. the curvature
/// where the point stands still), the key parameters, and where it peaks.
struct PlotSeries {
  std::string name;
  std::vector<double> t, value;
  std::vector<double> keys;
  double a = 0, b = 1;  ///< the motion's interval
  double min = 0, max = 0, t_min = 0, t_max = 0;
};

/// The quantity sampled along the motion, span by span (both sides of every joint, so a
/// jump shows): speed |x'(t)| and curvature |x' x x''| / |x'|^3 of the point's trajectory,
/// the angular speed |omega(t)| in radians per unit of t, and for a rational motion the
/// weight |Q0(t)|^2 over its largest sampled value (where it nears 0 the motion nears a
/// pole; 1 throughout for a quaternion spline). Exact derivatives of the trajectories'
/// NURBS for a q-motion; the spline's own derivatives for a quaternion spline (its
/// acceleration by a central difference).
PlotSeries sample_quantity(const Motion& motion, const PlotOptions& options);

/// The plot of the motions' series on one set of axes (the first motion's key parameters
/// marked; a legend when there are several), not written.
Canvas plot_figure(const std::vector<PlotSeries>& series, const PlotOptions& options,
                   const std::string& units);

/// Samples each motion and writes the plot to options.output; returns the series.
std::vector<PlotSeries> plot(const std::vector<Motion>& motions, const PlotOptions& options);

}  // namespace qmotion::render
