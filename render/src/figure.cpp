// render/src/figure.cpp: a motion drawn as a figure: the object at evenly spaced instants and
// at the numbered keys, the points' trajectories, the swept surface with its iso-lines, axes,
// a scale bar and a legend, in an orthographic view.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
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

Eigen::Vector3d parse_view(const std::string& view) {
  if (view == "iso") return Vector3d(1, 1, 1).normalized();
  if (view == "top") return Vector3d::UnitZ();
  if (view == "front") return -Vector3d::UnitY();
  if (view == "side") return Vector3d::UnitX();
  Vector3d d;
  try {
    d = io::parse_point(view, "--view");
  } catch (const Error&) {
    d = Vector3d::Zero();
  }
  if (!d.allFinite() || !(d.norm() > 0))
    throw Error(Errc::invalid_input,
                "--view " + view + ": expected iso, top, front, side or a direction x,y,z");
  return d.normalized();
}

std::pair<int, int> parse_size(const std::string& text) {
  const auto comma = text.find(',');
  auto bad = [&] {
    return Error(Errc::invalid_input,
                 "--size " + text + ": expected W,H in pixels, each from 16 to 20000");
  };
  if (comma == std::string::npos) throw bad();
  int wh[2];
  const std::string parts[2] = {text.substr(0, comma), text.substr(comma + 1)};
  for (int i = 0; i < 2; ++i) {
    const std::string& p = parts[i];
    if (p.empty() || p.size() > 6 || p.find_first_not_of("0123456789") != std::string::npos)
      throw bad();
    wh[i] = std::stoi(p);
    if (wh[i] < 16 || wh[i] > 20000) throw bad();
  }
  return {wh[0], wh[1]};
}

namespace {

constexpr int kIsoU = 12, kIsoV = 8, kIsoSub = 4;  // iso-lines along t, along the profile
constexpr double kTitleBand = 34, kMargin = 16, kLegendRow = 18, kScaleBarRoom = 190,
                 kAxesRoom = 70;

void check_figure_options(const RenderOptions& o) {
  if (o.frames < 0 || o.frames > 1000)
    throw Error(Errc::invalid_input,
                "--frames " + std::to_string(o.frames) + ": expected 0 to 1000 instants");
  if (!(o.object_size >= 0) || !std::isfinite(o.object_size))
    throw Error(Errc::invalid_input, "--object-size: expected a positive length");
  for (const Vector3d& x : o.points)
    if (!x.allFinite()) throw Error(Errc::invalid_input, "--point: expected finite coordinates");
  for (const auto& t : o.volume_triangles)
    for (int k : t)
      if (k < 0 || static_cast<std::size_t>(k) >= o.volume_vertices.size())
        throw Error(Errc::invalid_input, "the swept volume's triangle refers to vertex " +
                                             std::to_string(k) + " of " +
                                             std::to_string(o.volume_vertices.size()));
}

/// The object drawn at the instants and keys: a cube (neither set), a profile's curves, or
/// an STL mesh; read before any work.
struct MovingObject {
  std::optional<sweep::Profile<double>> profile;
  std::vector<std::array<Vector3d, 3>> mesh;
};

MovingObject moving_object(const Motion& motion, const RenderOptions& o) {
  MovingObject m{o.object_profile, {}};
  const bool cube = o.object.empty() || o.object == "cube";
  if (!cube && !m.profile) {
    if (lower_extension(o.object) == ".stl")
      m.mesh = read_stl(o.object);
    else
      m.profile = read_profile(o.object, motion.units());
  }
  return m;
}

/// The swept surface of one profile edge on a grid: p[i along t][j along the profile].
struct SurfaceGrid {
  std::vector<std::vector<Vector3d>> p;
};

/// What the figure shows, in space: the points' trajectories, the swept surface on a grid
/// finer than its iso-lines (kIsoSub quads between two along the profile; along t, kIsoU
/// iso-lines and sub_u quads between two, enough to follow every span), the rigid maps at
/// the instants and at the keys, and the object's size.
struct Scene {
  std::vector<Vector3d> points;
  std::vector<std::vector<Vector3d>> trajectories;
  int sub_u = kIsoSub;
  std::vector<SurfaceGrid> grids;
  std::vector<Rigid> frame_maps, key_maps;
  double size = 1;
};

Scene sample_scene(const Motion& motion, const RenderOptions& o) {
  Scene s;
  const std::vector<double> breaks = motion.breakpoints();
  const double a = motion.a(), b = motion.b();
  const std::vector<double> ts = span_samples(breaks, 600, 8);
  std::vector<Rigid> frames_at_ts;
  frames_at_ts.reserve(ts.size());
  for (double t : ts) frames_at_ts.push_back(rigid_at(motion, t));

  s.points = o.points.empty() ? std::vector<Vector3d>{Vector3d::Zero()} : o.points;
  for (const Vector3d& x : s.points) {
    s.trajectories.emplace_back();
    for (const Rigid& f : frames_at_ts) s.trajectories.back().push_back(f(x));
  }

  // Along t: 4 quads a span, up to 1200.
  s.sub_u = std::clamp(static_cast<int>(4 * (breaks.size() - 1) + kIsoU - 1) / kIsoU, kIsoSub, 100);
  if (o.profile) {
    std::vector<Rigid> fu;
    for (int i = 0; i <= kIsoU * s.sub_u; ++i)
      fu.push_back(rigid_at(motion, a + (b - a) * i / (kIsoU * s.sub_u)));
    for (const auto& edge : o.profile->edges) {
      const double v0 = edge.knots.front(), v1 = edge.knots.back();
      std::vector<Vector3d> xs;
      for (int j = 0; j <= kIsoV * kIsoSub; ++j)
        xs.push_back(sweep::evaluate(edge, v0 + (v1 - v0) * j / (kIsoV * kIsoSub)));
      SurfaceGrid g;
      for (const Rigid& f : fu) {
        g.p.emplace_back();
        for (const Vector3d& x : xs) g.p.back().push_back(f(x));
      }
      s.grids.push_back(std::move(g));
    }
  }

  // Extent of the figure's content, for the default object size.
  Eigen::AlignedBox3d box;
  for (const auto& tr : s.trajectories)
    for (const Vector3d& p : tr) box.extend(p);
  for (const Rigid& f : frames_at_ts) box.extend(f.p);
  for (const auto& g : s.grids)
    for (const auto& row : g.p)
      for (const Vector3d& p : row) box.extend(p);
  const double extent = box.diagonal().norm();
  s.size = o.object_size > 0 ? o.object_size : (extent > 0 ? extent / 10 : 1.0);

  // The instants: evenly spaced frames, then the keys.
  for (int k = 0; k < o.frames; ++k)
    s.frame_maps.push_back(rigid_at(motion, o.frames == 1 ? a : a + (b - a) * k / (o.frames - 1)));
  for (double t : motion.key_parameters()) s.key_maps.push_back(rigid_at(motion, t));
  return s;
}

/// The orthographic view: right and up on the page, depth towards the viewer, and a light
/// a little above and right of the viewer.
struct View {
  Vector3d toward, right, up, light;

  explicit View(const Vector3d& toward_viewer) : toward(toward_viewer) {
    const Vector3d world_up = std::abs(toward.z()) > 0.99 ? Vector3d::UnitY() : Vector3d::UnitZ();
    right = world_up.cross(toward).normalized();
    up = toward.cross(right);
    light = (toward + 0.5 * up + 0.35 * right).normalized();
  }
  /// The colour of a face of normal n.
  Rgb shade(Rgb c, const Vector3d& n) const {
    const double nn = n.norm();
    const double f = nn > 0 ? 0.5 + 0.5 * std::abs(n.dot(light)) / nn : 0.75;
    return scaled(c, f);
  }
  /// The point on the page, before scaling (y down).
  Vector2d flat(const Vector3d& p) const { return Vector2d(p.dot(right), -p.dot(up)); }
};

const Rgb kBaseObject{0.80, 0.80, 0.80}, kKeyObject{0.98, 0.86, 0.62},
    kSurfaceColour{0.62, 0.74, 0.90}, kVolumeColour{0.90, 0.70, 0.62};

/// The scene as faces to sort by depth and curves on top: the object at every instant and
/// key, and the swept surface's quads with their iso-lines.
struct Drawing {
  std::vector<Face> faces;
  std::vector<std::pair<std::vector<Vector3d>, Style>> object_curves;
  int volume_triangles = 0;
  int quads = 0;
};

void add_object(Drawing& d, const MovingObject& object, double size, const View& view,
                const Rigid& f, bool key) {
  if (!object.mesh.empty()) {
    for (const auto& tri : object.mesh) {
      Face face;
      for (const Vector3d& x : tri) face.points.push_back(f(x));
      const Vector3d n = (face.points[1] - face.points[0]).cross(face.points[2] - face.points[0]);
      face.style.fill = view.shade(key ? kKeyObject : kBaseObject, n);
      face.style.cls = key ? "key-face" : "object-face";
      d.faces.push_back(std::move(face));
    }
  } else if (object.profile) {
    Style s;
    s.stroke = key ? Rgb{0.1, 0.1, 0.1} : Rgb{0.45, 0.45, 0.45};
    s.width = key ? 1.8 : 1.0;
    s.cls = key ? "key-curve" : "object-curve";
    for (const auto& edge : object.profile->edges) {
      std::vector<Vector3d> line;
      const double v0 = edge.knots.front(), v1 = edge.knots.back();
      for (int j = 0; j <= 48; ++j)
        line.push_back(f(sweep::evaluate(edge, v0 + (v1 - v0) * j / 48)));
      d.object_curves.emplace_back(std::move(line), s);
    }
  } else {
    std::array<Vector3d, 8> c;
    for (int i = 0; i < 8; ++i)
      c[static_cast<std::size_t>(i)] =
          f(0.5 * size * Vector3d(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
    static const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                    {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
      Face face;
      for (int k : q) face.points.push_back(c[static_cast<std::size_t>(k)]);
      const Vector3d n = (face.points[1] - face.points[0]).cross(face.points[3] - face.points[0]);
      if (n.dot(view.toward) <= 0) continue;  // a back face of the convex cube
      face.style.fill = view.shade(key ? kKeyObject : kBaseObject, n);
      face.style.stroke = key ? Rgb{0.1, 0.1, 0.1} : Rgb{0.35, 0.35, 0.35};
      face.style.width = key ? 1.4 : 0.8;
      face.style.cls = key ? "key-face" : "object-face";
      d.faces.push_back(std::move(face));
    }
  }
}

void add_surface(Drawing& d, const Scene& scene, const View& view) {
  for (const auto& g : scene.grids) {
    for (std::size_t i = 0; i + 1 < g.p.size(); ++i)
      for (std::size_t j = 0; j + 1 < g.p[i].size(); ++j) {
        Face face;
        face.points = {g.p[i][j], g.p[i + 1][j], g.p[i + 1][j + 1], g.p[i][j + 1]};
        const Vector3d n = (face.points[2] - face.points[0]).cross(face.points[3] - face.points[1]);
        face.style.fill = view.shade(kSurfaceColour, n);
        face.style.stroke = *face.style.fill;  // hides the seams between quads
        face.style.width = 0.4;
        face.style.cls = "surface";
        if (i % static_cast<std::size_t>(scene.sub_u) == 0)
          face.iso_edges.push_back(3);  // t = const
        if (i + 1 == g.p.size() - 1) face.iso_edges.push_back(1);
        if (j % kIsoSub == 0) face.iso_edges.push_back(0);  // profile parameter = const
        if (j + 1 == g.p[i].size() - 1) face.iso_edges.push_back(2);
        face.iso_style.stroke = Rgb{0.15, 0.2, 0.3};
        face.iso_style.width = 0.7;
        face.iso_style.cls = "iso-line";
        d.faces.push_back(std::move(face));
        ++d.quads;
      }
  }
}

/// The swept volume's triangles, shaded like the surface but warmer, seams hidden.
void add_volume(Drawing& d, const RenderOptions& o, const View& view) {
  for (const auto& t : o.volume_triangles) {
    Face face;
    for (int k : t) face.points.push_back(o.volume_vertices[static_cast<std::size_t>(k)]);
    const Vector3d n = (face.points[1] - face.points[0]).cross(face.points[2] - face.points[0]);
    face.style.fill = view.shade(kVolumeColour, n);
    face.style.stroke = *face.style.fill;
    face.style.width = 0.3;
    face.style.cls = "swept-volume";
    d.faces.push_back(std::move(face));
    ++d.volume_triangles;
  }
}

Drawing draw_scene_objects(const Scene& scene, const MovingObject& object, const View& view) {
  Drawing d;
  for (const Rigid& f : scene.frame_maps) add_object(d, object, scene.size, view, f, false);
  // With many keys their objects would hide everything: markers only.
  if (scene.key_maps.size() <= kMaxKeyObjects)
    for (const Rigid& f : scene.key_maps) add_object(d, object, scene.size, view, f, true);
  add_surface(d, scene, view);
  return d;
}

/// The legend's entries in rows, and the projection that fits everything drawn into the
/// page between the title and the legend.
struct Layout {
  std::vector<std::pair<std::string, Style>> legend;
  std::vector<std::vector<std::size_t>> rows;
  double bottom_band = 0;
  double scale = 1;
  Vector2d origin;
  Vector2d project(const View& view, const Vector3d& p) const {
    return origin + scale * view.flat(p);
  }
};

Layout layout(const Scene& scene, const Drawing& d, const View& view, const RenderOptions& o) {
  Layout l;
  for (std::size_t i = 0; i < scene.points.size(); ++i)
    l.legend.emplace_back("trajectory of " + point_text(scene.points[i]), trajectory_style(i));
  if (o.profile) {
    Style s;
    s.fill = kSurfaceColour;
    s.stroke = Rgb{0.15, 0.2, 0.3};
    l.legend.emplace_back("swept surface (iso-lines of t and of the profile)", s);
  }
  if (!o.volume_triangles.empty()) {
    Style s;
    s.fill = kVolumeColour;
    s.stroke = kVolumeColour;
    l.legend.emplace_back(o.volume_label.empty() ? "swept volume" : o.volume_label, s);
  }
  {
    Style s;
    s.fill = Rgb{1, 1, 1};
    s.stroke = Rgb{0, 0, 0};
    l.legend.emplace_back("key pose k", s);
  }
  l.rows.resize(1);
  double x_used = kMargin;
  for (std::size_t i = 0; i < l.legend.size(); ++i) {
    const double w = 30 + Canvas::text_width(l.legend[i].first, 11) + 16;
    if (x_used + w > o.width - kScaleBarRoom && !l.rows.back().empty()) {
      l.rows.emplace_back();
      x_used = kMargin;
    }
    l.rows.back().push_back(i);
    x_used += w;
  }
  l.bottom_band = 14 + kLegendRow * static_cast<double>(l.rows.size());
  Eigen::AlignedBox2d pbox;
  for (const auto& tr : scene.trajectories)
    for (const Vector3d& p : tr) pbox.extend(view.flat(p));
  for (const Face& f : d.faces)
    for (const Vector3d& p : f.points) pbox.extend(view.flat(p));
  for (const auto& c : d.object_curves)
    for (const Vector3d& p : c.first) pbox.extend(view.flat(p));
  const double area_w = o.width - 2 * kMargin,
               area_h = o.height - kTitleBand - l.bottom_band - kMargin;
  const Vector2d span = pbox.sizes();
  if (!(area_w > 10 && area_h > 10))
    throw Error(Errc::invalid_input, "--size " + std::to_string(o.width) + "," +
                                         std::to_string(o.height) +
                                         ": too small for the figure and its legend");
  l.scale =
      std::min(span.x() > 0 ? area_w / span.x() : 1e300, span.y() > 0 ? area_h / span.y() : 1e300);
  if (!(l.scale < 1e300)) l.scale = 1;
  // Keep the triad's corner clear when the content reaches it: shrink a little.
  if (area_h > 2 * kAxesRoom && area_w > 2 * kAxesRoom) l.scale *= 0.94;
  const Vector2d centre_px(kMargin + area_w / 2, kTitleBand + area_h / 2);
  l.origin = centre_px - l.scale * pbox.center();
  return l;
}

/// The faces far to near, each with its iso-lines, then the object's curves.
void paint_scene(Canvas& canvas, Drawing& d, const View& view, const Layout& l) {
  for (Face& f : d.faces) {
    f.depth = 0;
    for (const Vector3d& p : f.points) f.depth += p.dot(view.toward);
    f.depth /= static_cast<double>(f.points.size());
  }
  std::stable_sort(d.faces.begin(), d.faces.end(),
                   [](const Face& x, const Face& y) { return x.depth < y.depth; });
  canvas.begin_group("scene");
  for (const Face& f : d.faces) {
    std::vector<Vector2d> poly;
    for (const Vector3d& p : f.points) poly.push_back(l.project(view, p));
    canvas.polygon(poly, f.style);
    for (int e : f.iso_edges) {
      const std::size_t k = static_cast<std::size_t>(e);
      canvas.polyline({poly[k], poly[(k + 1) % poly.size()]}, f.iso_style);
    }
  }
  canvas.end_group();
  for (const auto& [line, style] : d.object_curves) {
    std::vector<Vector2d> pl;
    for (const Vector3d& p : line) pl.push_back(l.project(view, p));
    canvas.polyline(std::move(pl), style);
  }
}

/// Trajectories, then the instants and the numbered keys on top; returns the key markers
/// drawn.
int paint_marks(Canvas& canvas, const Scene& scene, const View& view, const Layout& l) {
  for (std::size_t i = 0; i < scene.trajectories.size(); ++i) {
    std::vector<Vector2d> pl;
    for (const Vector3d& p : scene.trajectories[i]) pl.push_back(l.project(view, p));
    Style s = trajectory_style(i);
    s.cls = "trajectory";
    canvas.polyline(std::move(pl), s);
  }
  for (const Rigid& f : scene.frame_maps) {
    Style s;
    s.fill = Rgb{0.2, 0.2, 0.2};
    s.cls = "object-pose";
    canvas.circle(l.project(view, f.p), 2.2, s);
  }
  // Every key is marked; past 40 keys only every step-th (20 of them) carries its number
  // and a ring, the others a dot (none past 200 keys).
  const auto& keys = scene.key_maps;
  const std::size_t step = keys.size() <= 40 ? 1 : (keys.size() + 19) / 20;
  int key_markers = 0;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    Style s;
    s.fill = Rgb{1, 1, 1};
    s.stroke = Rgb{0, 0, 0};
    s.width = 1.3;
    s.cls = "key-marker";
    const Vector2d c = l.project(view, keys[k].p);
    const bool numbered = k % step == 0 || k + 1 == keys.size();
    key_markers += numbered || keys.size() <= 200;
    if (!numbered && keys.size() > 200) continue;  // dots denser than pixels: a smear
    if (!numbered) {
      s.stroke.reset();
      s.fill = Rgb{0.1, 0.1, 0.1};
      canvas.circle(c, 1.6, s);
      continue;
    }
    const std::string label = std::to_string(k);
    const double font = label.size() == 1 ? 10.5 : label.size() == 2 ? 9 : 8;
    canvas.circle(c, std::max(8.5, 0.5 * Canvas::text_width(label, font) + 3), s);
    canvas.text(c + Vector2d(0, 0.36 * font), label, font, Anchor::middle);
  }
  return key_markers;
}

/// The axis triad, bottom left of the drawing area.
void paint_axes(Canvas& canvas, const View& view, const Layout& l, const RenderOptions& o) {
  canvas.begin_group("axes");
  const Vector2d c(kMargin + 30, o.height - l.bottom_band - 34);
  const char* names[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    const Vector3d e = Vector3d::Unit(i);
    const Vector2d d(e.dot(view.right), -e.dot(view.up));
    Style s;
    s.stroke = Rgb{0.1, 0.1, 0.1};
    s.width = 1.4;
    if (d.norm() < 0.1) {  // along the line of sight
      canvas.circle(c, 3.5, s);
      canvas.text(c + Vector2d(7, -5), names[i], 11, Anchor::start);
      continue;
    }
    const Vector2d tip = c + 26 * d;
    canvas.polyline({c, tip}, s);
    const Vector2d u = d.normalized(), n(-u.y(), u.x());
    Style head = s;
    head.fill = Rgb{0.1, 0.1, 0.1};
    canvas.polygon({tip, tip - 6 * u + 3 * n, tip - 6 * u - 3 * n}, head);
    canvas.text(tip + 9 * u + Vector2d(0, 4), names[i], 11, Anchor::middle);
  }
  canvas.end_group();
}

/// The scale bar, bottom right.
void paint_scale_bar(Canvas& canvas, const Layout& l, const RenderOptions& o,
                     const std::string& units) {
  canvas.begin_group("scale-bar");
  const double length = nice_below(150 / l.scale);
  const double w = length * l.scale, y = o.height - 12.0, x1 = o.width - kMargin, x0 = x1 - w;
  Style s;
  s.stroke = Rgb{0, 0, 0};
  s.width = 2;
  canvas.polyline({{x0, y}, {x1, y}}, s);
  canvas.polyline({{x0, y - 5}, {x0, y + 1}}, s);
  canvas.polyline({{x1, y - 5}, {x1, y + 1}}, s);
  canvas.text(Vector2d((x0 + x1) / 2, y - 7), short_number(length) + " " + units, 11,
              Anchor::middle);
  canvas.end_group();
}

/// The legend, bottom left, a row at a time.
void paint_legend(Canvas& canvas, const Layout& l, const RenderOptions& o) {
  canvas.begin_group("legend");
  for (std::size_t r = 0; r < l.rows.size(); ++r) {
    const double y = o.height - 10 - kLegendRow * static_cast<double>(l.rows.size() - 1 - r);
    double x = kMargin;
    for (std::size_t i : l.rows[r]) {
      const auto& [label, style] = l.legend[i];
      if (label == "key pose k") {
        canvas.circle(Vector2d(x + 12, y - 4), 6.5, style);
        canvas.text(Vector2d(x + 12, y - 0.8), "k", 9, Anchor::middle);
      } else if (style.fill) {
        canvas.polygon({{x, y - 9}, {x + 24, y - 9}, {x + 24, y + 1}, {x, y + 1}}, style);
      } else {
        canvas.polyline({{x, y - 4}, {x + 24, y - 4}}, style);
      }
      canvas.text(Vector2d(x + 30, y), label, 11, Anchor::start);
      x += 30 + Canvas::text_width(label, 11) + 16;
    }
  }
  canvas.end_group();
}

}  // namespace

Canvas render_figure(const Motion& motion, const RenderOptions& o, RenderResult* result) {
  const View view(parse_view(o.view));
  Canvas canvas(o.width, o.height);  // checks the size
  check_figure_options(o);
  const MovingObject object = moving_object(motion, o);
  const Scene scene = sample_scene(motion, o);
  Drawing drawing = draw_scene_objects(scene, object, view);
  add_volume(drawing, o, view);
  const Layout l = layout(scene, drawing, view, o);

  canvas.attribute("view", o.view);
  canvas.attribute("toward-viewer", full_number(view.toward.x()) + "," +
                                        full_number(view.toward.y()) + "," +
                                        full_number(view.toward.z()));
  canvas.attribute("scale", full_number(l.scale));
  canvas.attribute("origin", full_number(l.origin.x()) + "," + full_number(l.origin.y()));
  canvas.attribute("object-size", full_number(scene.size));
  canvas.attribute("units", motion.units());
  const auto [title, fsize] =
      fit_text(o.title.empty() ? motion.label() + ": " + motion.summary() : o.title,
               o.width - 2 * kMargin, 15);
  canvas.text(Vector2d(o.width / 2.0, 22), title, fsize, Anchor::middle, Rgb{}, true);
  paint_scene(canvas, drawing, view, l);
  const int key_markers = paint_marks(canvas, scene, view, l);
  paint_axes(canvas, view, l, o);
  paint_scale_bar(canvas, l, o, motion.units());
  paint_legend(canvas, l, o);

  if (result) {
    result->width = o.width;
    result->height = o.height;
    result->trajectories = static_cast<int>(scene.trajectories.size());
    result->object_poses = static_cast<int>(scene.frame_maps.size());
    result->key_poses = static_cast<int>(scene.key_maps.size());
    result->key_markers = key_markers;
    result->surface_quads = drawing.quads;
    result->volume_triangles = drawing.volume_triangles;
    result->scale = l.scale;
    result->origin = l.origin;
    result->right = view.right;
    result->up = view.up;
    result->toward_viewer = view.toward;
    result->object_size = scene.size;
  }
  return canvas;
}

RenderResult render(const Motion& motion, const RenderOptions& options) {
  check_figure_path(options.output);
  RenderResult r;
  const Canvas canvas = render_figure(motion, options, &r);
  canvas.write(options.output);
  r.path = options.output;
  return r;
}

}  // namespace qmotion::render
