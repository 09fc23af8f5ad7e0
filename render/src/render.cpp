// render/src/render.cpp
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

namespace qmotion::render {
using namespace io;  // NOLINT: the formats this call reads and writes

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

/// A rigid map x -> R x + p.
struct Rigid {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Vector3d p = Vector3d::Zero();
  Vector3d operator()(const Vector3d& x) const { return R * x + p; }
};

/// What the pictures need of either kind of motion: its interval, breakpoints, key
/// parameters, rigid map at t, and how to name it.
struct MotionAccess {
  double a = 0, b = 1;
  std::vector<double> breaks;  ///< a = x_0 < ... < x_r = b
  std::vector<double> keys;    ///< where the poses are interpolated (else the breakpoints)
  std::function<Rigid(double)> frame;
  std::string title, units;
};

MotionAccess access(const kernel::Motion<double>& m) {
  MotionAccess acc;
  acc.a = m.a();
  acc.b = m.b();
  acc.breaks = m.curve.curve.breakpoints();
  acc.keys = m.provenance ? m.provenance->parameters : acc.breaks;
  acc.frame = [&m](double t) {
    const Eigen::Matrix4d M = kernel::to_matrix4(kernel::evaluate(m.curve, t));
    if (!(std::abs(M(0, 0)) > 0))
      throw Error(Errc::numerical_failure,
                  m.label() + ": the motion has a pole at t = " + std::to_string(t));
    Rigid r;
    r.R = M.block<3, 3>(1, 1) / M(0, 0);
    r.p = M.block<3, 1>(1, 0) / M(0, 0);
    return r;
  };
  std::string how;
  if (m.provenance)
    how = std::string(kernel::to_string(m.provenance->form)) + ", " +
          kernel::to_string(m.provenance->rotation) + " + " +
          kernel::to_string(m.provenance->translation) + ", ";
  const int segs = m.segments();
  acc.title = m.label() + ": " + how + "degree " + std::to_string(m.degree()) + ", " +
              std::to_string(segs) + (segs == 1 ? " segment, " : " segments, ") +
              std::to_string(acc.keys.size()) + " key poses";
  acc.units = m.units;
  return acc;
}

MotionAccess access(const QSplineMotion& m) {
  MotionAccess acc;
  acc.a = m.spline.a();
  acc.b = m.spline.b();
  acc.breaks = m.spline.knots;
  acc.keys = m.spline.knots;
  acc.frame = [&m](double t) {
    Rigid r;
    r.R = kernel::rotation_matrix(m.spline.rotation(t));
    r.p = m.spline.position(t);
    return r;
  };
  acc.title = m.label() + ": " + m.summary;
  acc.units = m.units;
  return acc;
}

MotionAccess access(const AnyMotion& m) {
  return std::visit([](const auto& x) { return access(x); }, m);
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

}  // namespace

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

Canvas render_figure(const AnyMotion& motion, const RenderOptions& o, RenderResult* result) {
  const Vector3d toward = parse_view(o.view);
  Canvas canvas(o.width, o.height);  // checks the size
  if (o.frames < 0 || o.frames > 1000)
    throw Error(Errc::invalid_input,
                "--frames " + std::to_string(o.frames) + ": expected 0 to 1000 instants");
  if (!(o.object_size >= 0) || !std::isfinite(o.object_size))
    throw Error(Errc::invalid_input, "--object-size: expected a positive length");
  for (const Vector3d& x : o.points)
    if (!x.allFinite()) throw Error(Errc::invalid_input, "--point: expected finite coordinates");

  // The moving object, read before any work.
  std::optional<sweep::Profile<double>> object_profile = o.object_profile;
  std::vector<std::array<Vector3d, 3>> object_mesh;
  const bool cube = o.object.empty() || o.object == "cube";
  if (!cube && !object_profile) {
    if (lower_extension(o.object) == ".stl")
      object_mesh = read_stl(o.object);
    else
      object_profile = read_profile(o.object, units_of(motion));
  }

  const MotionAccess acc = access(motion);
  const std::vector<double> ts = span_samples(acc.breaks, 600, 8);
  std::vector<Rigid> frames_at_ts;
  frames_at_ts.reserve(ts.size());
  for (double t : ts) frames_at_ts.push_back(acc.frame(t));

  const std::vector<Vector3d> points =
      o.points.empty() ? std::vector<Vector3d>{Vector3d::Zero()} : o.points;
  std::vector<std::vector<Vector3d>> trajectories;
  for (const Vector3d& x : points) {
    trajectories.emplace_back();
    for (const Rigid& f : frames_at_ts) trajectories.back().push_back(f(x));
  }

  // The swept surface on a grid finer than its iso-lines: kIsoSub quads between two along
  // the profile; along t, 12 iso-lines, and quads enough to follow every span (4 a span, up
  // to 1200).
  constexpr int kIsoU = 12, kIsoV = 8, kIsoSub = 4;
  const int sub_u =
      std::clamp(static_cast<int>(4 * (acc.breaks.size() - 1) + kIsoU - 1) / kIsoU, kIsoSub, 100);
  struct SurfaceGrid {
    std::vector<std::vector<Vector3d>> p;  // [i along t][j along the profile]
  };
  std::vector<SurfaceGrid> grids;
  if (o.profile) {
    std::vector<Rigid> fu;
    for (int i = 0; i <= kIsoU * sub_u; ++i)
      fu.push_back(acc.frame(acc.a + (acc.b - acc.a) * i / (kIsoU * sub_u)));
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
      grids.push_back(std::move(g));
    }
  }

  // Extent of the figure's content, for the default object size.
  Eigen::AlignedBox3d box;
  for (const auto& tr : trajectories)
    for (const Vector3d& p : tr) box.extend(p);
  for (const Rigid& f : frames_at_ts) box.extend(f.p);
  for (const auto& g : grids)
    for (const auto& row : g.p)
      for (const Vector3d& p : row) box.extend(p);
  const double extent = box.diagonal().norm();
  const double size = o.object_size > 0 ? o.object_size : (extent > 0 ? extent / 10 : 1.0);

  // The instants: evenly spaced frames, then the keys.
  std::vector<double> frame_ts;
  for (int k = 0; k < o.frames; ++k)
    frame_ts.push_back(o.frames == 1 ? acc.a : acc.a + (acc.b - acc.a) * k / (o.frames - 1));
  std::vector<Rigid> frame_maps, key_maps;
  for (double t : frame_ts) frame_maps.push_back(acc.frame(t));
  for (double t : acc.keys) key_maps.push_back(acc.frame(t));

  // The view: right and up on the page, depth towards the viewer.
  const Vector3d world_up = std::abs(toward.z()) > 0.99 ? Vector3d::UnitY() : Vector3d::UnitZ();
  const Vector3d right = world_up.cross(toward).normalized();
  const Vector3d up = toward.cross(right);
  const Rgb base_object{0.80, 0.80, 0.80}, key_object{0.98, 0.86, 0.62},
      surface_colour{0.62, 0.74, 0.90};
  const Vector3d light = (toward + 0.5 * up + 0.35 * right).normalized();
  auto shade = [&](Rgb c, const Vector3d& n) {
    const double nn = n.norm();
    const double f = nn > 0 ? 0.5 + 0.5 * std::abs(n.dot(light)) / nn : 0.75;
    return scaled(c, f);
  };

  std::vector<Face> faces;
  std::vector<std::pair<std::vector<Vector3d>, Style>> object_curves;
  auto add_object = [&](const Rigid& f, bool key) {
    if (!object_mesh.empty()) {
      for (const auto& tri : object_mesh) {
        Face face;
        for (const Vector3d& x : tri) face.points.push_back(f(x));
        const Vector3d n = (face.points[1] - face.points[0]).cross(face.points[2] - face.points[0]);
        face.style.fill = shade(key ? key_object : base_object, n);
        face.style.cls = key ? "key-face" : "object-face";
        faces.push_back(std::move(face));
      }
    } else if (object_profile) {
      Style s;
      s.stroke = key ? Rgb{0.1, 0.1, 0.1} : Rgb{0.45, 0.45, 0.45};
      s.width = key ? 1.8 : 1.0;
      s.cls = key ? "key-curve" : "object-curve";
      for (const auto& edge : object_profile->edges) {
        std::vector<Vector3d> line;
        const double v0 = edge.knots.front(), v1 = edge.knots.back();
        for (int j = 0; j <= 48; ++j)
          line.push_back(f(sweep::evaluate(edge, v0 + (v1 - v0) * j / 48)));
        object_curves.emplace_back(std::move(line), s);
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
        if (n.dot(toward) <= 0) continue;  // a back face of the convex cube
        face.style.fill = shade(key ? key_object : base_object, n);
        face.style.stroke = key ? Rgb{0.1, 0.1, 0.1} : Rgb{0.35, 0.35, 0.35};
        face.style.width = key ? 1.4 : 0.8;
        face.style.cls = key ? "key-face" : "object-face";
        faces.push_back(std::move(face));
      }
    }
  };
  for (const Rigid& f : frame_maps) add_object(f, false);
  // With many keys their objects would hide everything: markers only.
  if (key_maps.size() <= kMaxKeyObjects)
    for (const Rigid& f : key_maps) add_object(f, true);
  int quads = 0;
  for (const auto& g : grids) {
    for (std::size_t i = 0; i + 1 < g.p.size(); ++i)
      for (std::size_t j = 0; j + 1 < g.p[i].size(); ++j) {
        Face face;
        face.points = {g.p[i][j], g.p[i + 1][j], g.p[i + 1][j + 1], g.p[i][j + 1]};
        const Vector3d n = (face.points[2] - face.points[0]).cross(face.points[3] - face.points[1]);
        face.style.fill = shade(surface_colour, n);
        face.style.stroke = *face.style.fill;  // hides the seams between quads
        face.style.width = 0.4;
        face.style.cls = "surface";
        if (i % static_cast<std::size_t>(sub_u) == 0) face.iso_edges.push_back(3);  // t = const
        if (i + 1 == g.p.size() - 1) face.iso_edges.push_back(1);
        if (j % kIsoSub == 0) face.iso_edges.push_back(0);  // profile parameter = const
        if (j + 1 == g.p[i].size() - 1) face.iso_edges.push_back(2);
        face.iso_style.stroke = Rgb{0.15, 0.2, 0.3};
        face.iso_style.width = 0.7;
        face.iso_style.cls = "iso-line";
        faces.push_back(std::move(face));
        ++quads;
      }
  }

  // Fit everything drawn into the page between the title and the legend.
  const double title_band = 34, margin = 16;
  std::vector<std::pair<std::string, Style>> legend;
  for (std::size_t i = 0; i < points.size(); ++i)
    legend.emplace_back("trajectory of " + point_text(points[i]), trajectory_style(i));
  if (o.profile) {
    Style s;
    s.fill = surface_colour;
    s.stroke = Rgb{0.15, 0.2, 0.3};
    legend.emplace_back("swept surface (iso-lines of t and of the profile)", s);
  }
  {
    Style s;
    s.fill = Rgb{1, 1, 1};
    s.stroke = Rgb{0, 0, 0};
    legend.emplace_back("key pose k", s);
  }
  const double legend_row = 18, scale_bar_room = 190;
  std::vector<std::vector<std::size_t>> rows(1);
  double x_used = margin;
  for (std::size_t i = 0; i < legend.size(); ++i) {
    const double w = 30 + Canvas::text_width(legend[i].first, 11) + 16;
    if (x_used + w > o.width - scale_bar_room && !rows.back().empty()) {
      rows.emplace_back();
      x_used = margin;
    }
    rows.back().push_back(i);
    x_used += w;
  }
  const double bottom_band = 14 + legend_row * static_cast<double>(rows.size());
  const double axes_room = 70;  // the axis triad, bottom left of the drawing area
  Eigen::AlignedBox2d pbox;
  auto flat = [&](const Vector3d& p) { return Vector2d(p.dot(right), -p.dot(up)); };
  for (const auto& tr : trajectories)
    for (const Vector3d& p : tr) pbox.extend(flat(p));
  for (const Face& f : faces)
    for (const Vector3d& p : f.points) pbox.extend(flat(p));
  for (const auto& c : object_curves)
    for (const Vector3d& p : c.first) pbox.extend(flat(p));
  const double area_w = o.width - 2 * margin, area_h = o.height - title_band - bottom_band - margin;
  const Vector2d span = pbox.sizes();
  if (!(area_w > 10 && area_h > 10))
    throw Error(Errc::invalid_input, "--size " + std::to_string(o.width) + "," +
                                         std::to_string(o.height) +
                                         ": too small for the figure and its legend");
  double scale =
      std::min(span.x() > 0 ? area_w / span.x() : 1e300, span.y() > 0 ? area_h / span.y() : 1e300);
  if (!(scale < 1e300)) scale = 1;
  // Keep the triad's corner clear when the content reaches it: shrink a little.
  if (area_h > 2 * axes_room && area_w > 2 * axes_room) scale *= 0.94;
  const Vector2d centre_px(margin + area_w / 2, title_band + area_h / 2);
  const Vector2d origin = centre_px - scale * pbox.center();
  auto project = [&](const Vector3d& p) -> Vector2d { return origin + scale * flat(p); };

  canvas.attribute("view", o.view);
  canvas.attribute("toward-viewer", full_number(toward.x()) + "," + full_number(toward.y()) + "," +
                                        full_number(toward.z()));
  canvas.attribute("scale", full_number(scale));
  canvas.attribute("origin", full_number(origin.x()) + "," + full_number(origin.y()));
  canvas.attribute("object-size", full_number(size));
  canvas.attribute("units", acc.units);

  // Title.
  {
    const auto [title, fsize] =
        fit_text(o.title.empty() ? acc.title : o.title, o.width - 2 * margin, 15);
    canvas.text(Vector2d(o.width / 2.0, 22), title, fsize, Anchor::middle, Rgb{}, true);
  }

  // The scene, far faces first.
  for (Face& f : faces) {
    f.depth = 0;
    for (const Vector3d& p : f.points) f.depth += p.dot(toward);
    f.depth /= static_cast<double>(f.points.size());
  }
  std::stable_sort(faces.begin(), faces.end(),
                   [](const Face& x, const Face& y) { return x.depth < y.depth; });
  canvas.begin_group("scene");
  for (const Face& f : faces) {
    std::vector<Vector2d> poly;
    for (const Vector3d& p : f.points) poly.push_back(project(p));
    canvas.polygon(poly, f.style);
    for (int e : f.iso_edges) {
      const std::size_t k = static_cast<std::size_t>(e);
      canvas.polyline({poly[k], poly[(k + 1) % poly.size()]}, f.iso_style);
    }
  }
  canvas.end_group();
  for (const auto& [line, style] : object_curves) {
    std::vector<Vector2d> pl;
    for (const Vector3d& p : line) pl.push_back(project(p));
    canvas.polyline(std::move(pl), style);
  }

  // Trajectories, then the instants and the numbered keys on top.
  for (std::size_t i = 0; i < trajectories.size(); ++i) {
    std::vector<Vector2d> pl;
    for (const Vector3d& p : trajectories[i]) pl.push_back(project(p));
    Style s = trajectory_style(i);
    s.cls = "trajectory";
    canvas.polyline(std::move(pl), s);
  }
  for (const Rigid& f : frame_maps) {
    Style s;
    s.fill = Rgb{0.2, 0.2, 0.2};
    s.cls = "object-pose";
    canvas.circle(project(f.p), 2.2, s);
  }
  // Every key is marked; past 40 keys only every step-th (20 of them) carries its number
  // and a ring, the others a dot (none past 200 keys).
  const std::size_t step = key_maps.size() <= 40 ? 1 : (key_maps.size() + 19) / 20;
  int key_markers = 0;
  for (std::size_t k = 0; k < key_maps.size(); ++k) {
    Style s;
    s.fill = Rgb{1, 1, 1};
    s.stroke = Rgb{0, 0, 0};
    s.width = 1.3;
    s.cls = "key-marker";
    const Vector2d c = project(key_maps[k].p);
    const bool numbered = k % step == 0 || k + 1 == key_maps.size();
    key_markers += numbered || key_maps.size() <= 200;
    if (!numbered && key_maps.size() > 200) continue;  // dots denser than pixels: a smear
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

  // The axis triad, bottom left of the drawing area.
  {
    canvas.begin_group("axes");
    const Vector2d c(margin + 30, o.height - bottom_band - 34);
    const char* names[3] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i) {
      const Vector3d e = Vector3d::Unit(i);
      const Vector2d d(e.dot(right), -e.dot(up));
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

  // The scale bar, bottom right.
  {
    canvas.begin_group("scale-bar");
    const double length = nice_below(150 / scale);
    const double w = length * scale, y = o.height - 12.0, x1 = o.width - margin, x0 = x1 - w;
    Style s;
    s.stroke = Rgb{0, 0, 0};
    s.width = 2;
    canvas.polyline({{x0, y}, {x1, y}}, s);
    canvas.polyline({{x0, y - 5}, {x0, y + 1}}, s);
    canvas.polyline({{x1, y - 5}, {x1, y + 1}}, s);
    canvas.text(Vector2d((x0 + x1) / 2, y - 7), short_number(length) + " " + acc.units, 11,
                Anchor::middle);
    canvas.end_group();
  }

  // The legend, bottom left, a row at a time.
  {
    canvas.begin_group("legend");
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const double y = o.height - 10 - legend_row * static_cast<double>(rows.size() - 1 - r);
      double x = margin;
      for (std::size_t i : rows[r]) {
        const auto& [label, style] = legend[i];
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

  if (result) {
    result->width = o.width;
    result->height = o.height;
    result->trajectories = static_cast<int>(trajectories.size());
    result->object_poses = static_cast<int>(frame_maps.size());
    result->key_poses = static_cast<int>(key_maps.size());
    result->key_markers = key_markers;
    result->surface_quads = quads;
    result->scale = scale;
    result->origin = origin;
    result->right = right;
    result->up = up;
    result->toward_viewer = toward;
    result->object_size = size;
  }
  return canvas;
}

RenderResult render(const AnyMotion& motion, const RenderOptions& options) {
  check_figure_path(options.output);
  RenderResult r;
  const Canvas canvas = render_figure(motion, options, &r);
  canvas.write(options.output);
  r.path = options.output;
  return r;
}

// ---- plots ---------------------------------------------------------------------------------

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

std::function<double(double)> quantity_function(const QSplineMotion& m, const PlotOptions& o) {
  const kernel::QuaternionSpline* s = &m.spline;
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

PlotSeries sample_quantity(const AnyMotion& motion, const PlotOptions& o) {
  if (o.samples < 2 || o.samples > 1000000)
    throw Error(Errc::invalid_input,
                "--samples " + std::to_string(o.samples) + ": expected 2 to 1000000");
  if (!o.point.allFinite())
    throw Error(Errc::invalid_input, "--point: expected finite coordinates");
  const MotionAccess acc = access(motion);
  const auto f = std::visit([&](const auto& m) { return quantity_function(m, o); }, motion);
  PlotSeries s;
  s.name = std::visit([](const auto& m) { return m.label(); }, motion);
  s.keys = acc.keys;
  s.a = acc.a;
  s.b = acc.b;
  const std::size_t spans = acc.breaks.size() - 1;
  const bool per_span = spans <= static_cast<std::size_t>(o.samples) / 2;
  const int n = per_span ? std::max(2, o.samples / static_cast<int>(spans)) : o.samples;
  auto sample = [&](double t) {
    s.t.push_back(t);
    s.value.push_back(f(t));
  };
  if (per_span) {
    for (std::size_t k = 0; k < spans; ++k) {  // both sides of each joint, just inside
      const double t0 = acc.breaks[k], t1 = acc.breaks[k + 1], inset = 1e-9 * (t1 - t0);
      for (int j = 0; j <= n; ++j)
        sample(std::clamp(t0 + (t1 - t0) * j / n, t0 + inset, t1 - inset));
    }
  } else {
    for (int j = 0; j <= n; ++j) sample(acc.a + (acc.b - acc.a) * j / n);
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

std::vector<PlotSeries> plot(const std::vector<AnyMotion>& motions, const PlotOptions& o) {
  check_figure_path(o.output);
  if (motions.empty()) throw Error(Errc::invalid_input, "plot: no motion given");
  for (const AnyMotion& m : motions)
    if (units_of(m) != units_of(motions.front()))
      throw Error(Errc::invalid_input,
                  std::visit([](const auto& x) { return x.label(); }, m) + ": its unit " +
                      units_of(m) + " differs from the first motion's (" +
                      units_of(motions.front()) + "); plot motions of one unit together");
  std::vector<PlotSeries> series;
  for (const AnyMotion& m : motions) series.push_back(sample_quantity(m, o));
  plot_figure(series, o, units_of(motions.front())).write(o.output);
  return series;
}

}  // namespace qmotion::render
