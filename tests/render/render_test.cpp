// tests/render/render_test.cpp: the pictures (render/render.hpp): the plotted quantities are the
// motion's derivatives, the PNG has its size and content, the SVG draws what it says, bad
// options are refused by name.
#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <io_test_util.hpp>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/api/qspline.hpp>
#include <qmotion/api/volume.hpp>
#include <qmotion/kernel/dual_quaternion.hpp>
#include <qmotion/render/render.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <random>
#include <sstream>
#include <string>

namespace qmotion {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector3d;

kernel::Motion<double> interpolated(const std::string& poses, const std::string& form = "") {
  qmotion::InterpolateOptions o;
  o.form = form;
  return qmotion::interpolate(io::read_poses(test::test_data(poses)), o).motion.rational();
}

/// The rigid map of a q-motion at t, through the kernel's own point map.
Eigen::Matrix<double, 3, 4> frame(const kernel::Motion<double>& m, double t) {
  const auto q = kernel::evaluate(m.curve, t);
  Eigen::Matrix<double, 3, 4> f;
  f.col(3) = kernel::apply_point(q, Vector3d(Vector3d::Zero()));
  for (int i = 0; i < 3; ++i)
    f.col(i) = kernel::apply_point(q, Vector3d(Vector3d::Unit(i))) - f.col(3);
  return f;
}

/// |omega| from rotation matrices at t -/+ h: skew(omega) = R' R^T.
double angular_speed_by_differences(const kernel::Motion<double>& m, double t, double h) {
  const Eigen::Matrix3d dR =
      (frame(m, t + h).leftCols<3>() - frame(m, t - h).leftCols<3>()) / (2 * h);
  const Eigen::Matrix3d W = dR * frame(m, t).leftCols<3>().transpose();
  return Vector3d(W(2, 1) - W(1, 2), W(0, 2) - W(2, 0), W(1, 0) - W(0, 1)).norm() / 2;
}

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / "qmotion_render_test";
  fs::create_directories(d);
  return d / name;
}

std::size_t count(const std::string& s, const std::string& needle) {
  std::size_t n = 0;
  for (auto p = s.find(needle); p != std::string::npos; p = s.find(needle, p + 1)) ++n;
  return n;
}

TEST(Plot, SpeedAndAngularSpeedAreTheMotionsDerivatives) {
  for (const auto& [poses, form] :
       {std::pair<std::string, std::string>{"poses/five_positions.json", ""},
        {"poses/helix_40.json", "bspline"}}) {
    const kernel::Motion<double> m = interpolated(poses, form);
    const qmotion::Motion any(m);
    render::PlotOptions o;
    o.point = Vector3d(3, -2, 5);
    o.samples = 200;
    const render::PlotSeries speed = render::sample_quantity(any, o);
    o.quantity = render::Quantity::angular_speed;
    const render::PlotSeries spin = render::sample_quantity(any, o);
    ASSERT_EQ(speed.t.size(), spin.t.size());
    ASSERT_GE(speed.t.size(), 200u);
    const double h = 1e-6 * (m.b() - m.a());
    double worst_speed = 0, worst_spin = 0;
    for (std::size_t i = 0; i < speed.t.size(); i += 7) {
      const double t = std::clamp(speed.t[i], m.a() + 2 * h, m.b() - 2 * h);
      if (std::abs(t - speed.t[i]) > 0) continue;  // the differences need room
      const Eigen::Vector4d x(3, -2, 5, 1);
      const double fd = ((frame(m, t + h) - frame(m, t - h)) * x).norm() / (2 * h);
      worst_speed = std::max(worst_speed, std::abs(speed.value[i] - fd) / fd);
      const double w = angular_speed_by_differences(m, t, h);
      worst_spin = std::max(worst_spin, std::abs(spin.value[i] - w) / std::max(w, 1e-3));
    }
    EXPECT_LT(worst_speed, 1e-6) << poses;
    EXPECT_LT(worst_spin, 1e-5) << poses;
    EXPECT_EQ(speed.keys.size(), m.provenance->parameters.size());
    EXPECT_LE(speed.min, speed.max);
  }
}

TEST(Plot, CurvatureOfARotationAboutOneAxisIsTheCircles) {
  // Rotations about z only, no translation: every point runs on a circle about z.
  io::PoseSet set = io::parse_poses_json(
      R"({"poses":[
      {"t":0,"position":[0,0,0],"rotation":{"axis_angle":{"axis":[0,0,1],"angle_deg":0}}},
      {"t":0.3,"position":[0,0,0],"rotation":{"axis_angle":{"axis":[0,0,1],"angle_deg":40}}},
      {"t":0.7,"position":[0,0,0],"rotation":{"axis_angle":{"axis":[0,0,1],"angle_deg":110}}},
      {"t":1,"position":[0,0,0],"rotation":{"axis_angle":{"axis":[0,0,1],"angle_deg":150}}}]})",
      "coaxial");
  const qmotion::Motion m(qmotion::interpolate(set, {}).motion);
  render::PlotOptions o;
  o.quantity = render::Quantity::curvature;
  o.point = Vector3d(4, 0, 7);  // radius 4 about z
  const render::PlotSeries k = render::sample_quantity(m, o);
  for (double v : k.value) EXPECT_NEAR(v, 0.25, 1e-9);
  o.quantity = render::Quantity::weights;
  const render::PlotSeries w = render::sample_quantity(m, o);
  EXPECT_NEAR(w.max, 1.0, 1e-15);
  EXPECT_GT(w.min, 0.0);
}

TEST(Plot, QuaternionSplineSpeedMatchesItsPositions) {
  qmotion::QSplineOptions qo;
  qo.scheme = "quartic";
  const qmotion::Motion q =
      qmotion::qspline(io::read_poses(test::test_data("poses/five_positions.json")), qo).motion;
  render::PlotOptions o;
  o.point = Vector3d(1, 2, 3);
  const render::PlotSeries s = render::sample_quantity(q, o);
  const double h = 1e-6;
  for (std::size_t i = 1; i + 1 < s.t.size(); i += 11) {
    const double t = s.t[i];
    const double fd =
        (q.spline().place(t + h, o.point) - q.spline().place(t - h, o.point)).norm() / (2 * h);
    EXPECT_NEAR(s.value[i], fd, 1e-5 * fd) << t;
  }
}

TEST(Render, SvgDrawsWhatTheResultCounts) {
  const kernel::Motion<double> m = interpolated("poses/five_positions.json");
  render::RenderOptions o;
  o.points = {Vector3d(0, 0, 0), Vector3d(0, 0, 20), Vector3d(10, 0, 0)};
  o.frames = 5;
  o.profile = sweep::single_edge(sweep::NurbsCurve<double>{
      2, {0, 0, 0, 1, 1, 1}, {{-10, 0, 10}, {0, 0, -10}, {10, 0, 10}}, {1, 1, 1}});
  render::RenderResult r;
  const std::string svg = render::render_figure(qmotion::Motion(m), o, &r).svg();
  EXPECT_EQ(r.trajectories, 3);
  EXPECT_EQ(r.object_poses, 5);
  EXPECT_EQ(r.key_poses, 5);
  EXPECT_EQ(r.key_markers, 5);
  EXPECT_EQ(count(svg, "class=\"trajectory\""), 3u);
  EXPECT_EQ(count(svg, "class=\"object-pose\""), 5u);
  EXPECT_EQ(count(svg, "class=\"key-marker\""), 5u);
  // In greyscale the trajectories stay apart by their dash patterns: pairwise different.
  std::vector<std::string> dashes;
  for (auto p = svg.find("class=\"trajectory\""); p != std::string::npos;
       p = svg.find("class=\"trajectory\"", p + 1)) {
    const std::string element = svg.substr(p, svg.find("/>", p) - p);
    const auto d = element.find("stroke-dasharray=\"");
    dashes.push_back(d == std::string::npos ? "solid"
                                            : element.substr(d, element.find('"', d + 18) - d));
  }
  ASSERT_EQ(dashes.size(), 3u);
  EXPECT_NE(dashes[0], dashes[1]);
  EXPECT_NE(dashes[1], dashes[2]);
  EXPECT_NE(dashes[0], dashes[2]);
  EXPECT_EQ(count(svg, "class=\"surface\""), static_cast<std::size_t>(r.surface_quads));
  EXPECT_GT(r.surface_quads, 100);
  EXPECT_GT(count(svg, "class=\"iso-line\""), 100u);
  // Every cube face drawn faces the viewer: 3 of 6 per pose at most, at least 1.
  const std::size_t key_faces = count(svg, "class=\"key-face\"");
  EXPECT_GE(key_faces, 5u);
  EXPECT_LE(key_faces, 15u);
  // The content fits the page.
  EXPECT_GT(r.scale, 0);
  for (const auto& k : m.provenance->poses) {
    const Vector3d p = k.position;
    const Eigen::Vector2d px = r.origin + r.scale * Eigen::Vector2d(p.dot(r.right), -p.dot(r.up));
    EXPECT_GT(px.x(), 0);
    EXPECT_LT(px.x(), o.width);
    EXPECT_GT(px.y(), 30);  // below the title
    EXPECT_LT(px.y(), o.height);
  }
}

TEST(Render, SweptVolumeCoversTheShadowOfEverySampledPointOfIt) {
  // render --body: the enclosing mesh drawn; every point of the swept sphere set, placed by
  // the motion at a random t, projects into one of the drawn triangles (the mesh encloses V,
  // so its shadow covers V's).
  const qmotion::Motion m(interpolated("poses/five_positions.json"));
  render::RenderOptions o;
  o.output = scratch("volume.svg").string();
  o.frames = 3;
  const render::RenderResult r = qmotion::render_volume(m, o, "sphere:6", 4.0);
  EXPECT_GT(r.volume_triangles, 500);
  std::ifstream in(o.output);
  const std::string svg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(count(svg, "class=\"swept-volume\""), static_cast<std::size_t>(r.volume_triangles));
  EXPECT_NE(svg.find("swept volume of sphere:6"), std::string::npos);
  std::vector<std::array<Eigen::Vector2d, 3>> tris;
  for (auto p = svg.find("<polygon points=\""); p != std::string::npos;
       p = svg.find("<polygon points=\"", p + 1)) {
    const auto end = svg.find("/>", p);
    if (svg.substr(p, end - p).find("class=\"swept-volume\"") == std::string::npos) continue;
    const std::size_t from = p + std::string("<polygon points=\"").size();
    std::string pts = svg.substr(from, svg.find('"', from) - from);
    for (char& c : pts)
      if (c == ',') c = ' ';
    std::istringstream is(pts);
    std::array<Eigen::Vector2d, 3> t;
    for (auto& v : t) is >> v.x() >> v.y();
    tris.push_back(t);
  }
  ASSERT_EQ(tris.size(), static_cast<std::size_t>(r.volume_triangles));
  std::mt19937 g(3);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> n(0, 1);
  for (int i = 0; i < 300; ++i) {
    const double t = m.a() + (m.b() - m.a()) * u(g);
    const Vector3d x = m.place(t, Vector3d(6 * Vector3d(n(g), n(g), n(g)).normalized()));
    const Eigen::Vector2d q = r.origin + r.scale * Eigen::Vector2d(x.dot(r.right), -x.dot(r.up));
    bool inside = false;
    for (const auto& tr : tris) {
      const Eigen::Vector2d a = tr[1] - tr[0], b = tr[2] - tr[0], c = q - tr[0];
      const double det = a.x() * b.y() - a.y() * b.x();
      if (std::abs(det) < 1e-12) continue;
      const double l1 = (c.x() * b.y() - c.y() * b.x()) / det,
                   l2 = (a.x() * c.y() - a.y() * c.x()) / det;
      if (l1 >= -1e-3 && l2 >= -1e-3 && l1 + l2 <= 1 + 1e-3) {
        inside = true;
        break;
      }
    }
    ASSERT_TRUE(inside) << "a point of the swept volume at t = " << t << " projects outside";
  }
  // A bad body is refused before anything is written.
  o.output = scratch("bad_volume.svg").string();
  EXPECT_THROW(qmotion::render_volume(m, o, "sphere:-1"), Error);
  EXPECT_FALSE(fs::exists(o.output));
}

TEST(Render, ObjectsFromAMeshOrAProfileArePlacedAtEveryInstant) {
  const qmotion::Motion m(interpolated("poses/five_positions.json"));
  const fs::path stl = scratch("tetrahedron.stl");
  {
    std::ofstream f(stl);
    f << "solid t\n";
    const char* tris[4] = {"0 0 0|8 0 0|0 8 0", "0 0 0|0 0 8|8 0 0", "0 0 0|0 8 0|0 0 8",
                           "8 0 0|0 0 8|0 8 0"};
    for (const char* t : tris) {
      std::string v(t);
      f << "facet normal 0 0 0\nouter loop\n";
      for (std::size_t a = 0, b; a != std::string::npos; a = b == std::string::npos ? b : b + 1) {
        b = v.find('|', a);
        f << "vertex " << v.substr(a, b == std::string::npos ? b : b - a) << "\n";
      }
      f << "endloop\nendfacet\n";
    }
    f << "endsolid t\n";
  }
  render::RenderOptions o;
  o.object = stl.string();
  o.frames = 3;
  render::RenderResult r;
  std::string svg = render::render_figure(m, o, &r).svg();
  EXPECT_EQ(count(svg, "class=\"object-face\""), 4u * 3u);  // every triangle, both sides
  EXPECT_EQ(count(svg, "class=\"key-face\""), 4u * 5u);
  o.object = "segment:0,0,0:6,0,0";
  svg = render::render_figure(m, o, &r).svg();
  EXPECT_EQ(count(svg, "class=\"object-curve\""), 3u);
  EXPECT_EQ(count(svg, "class=\"key-curve\""), 5u);
  o.object = "segment:0,0,0";
  EXPECT_TRUE(test::throws_error([&] { render::render_figure(m, o); }, Errc::invalid_input,
                                 {"segment:0,0,0"}));
}

TEST(Render, ManyKeysAreMarkedWithoutSmearingTheFigure) {
  std::string doc = "{\"poses\":[";
  for (int i = 0; i < 300; ++i) {
    const double a = 0.1 * i;
    doc += (i ? "," : "") + std::string("{\"t\":") + std::to_string(i) + ",\"position\":[" +
           std::to_string(50 * std::cos(a)) + "," + std::to_string(50 * std::sin(a)) + "," +
           std::to_string(a) + "],\"rotation\":{\"axis_angle\":{\"axis\":[0,0,1],\"angle_deg\":" +
           std::to_string(a * 180 / M_PI) + "}}}";
  }
  doc += "]}";
  qmotion::InterpolateOptions io_opt;
  io_opt.form = "bspline";
  const qmotion::Motion m(qmotion::interpolate(io::parse_poses_json(doc, "helix"), io_opt).motion);
  render::RenderOptions o;
  render::RenderResult r;
  const std::string svg = render::render_figure(m, o, &r).svg();
  EXPECT_EQ(r.key_poses, 300);
  EXPECT_EQ(r.key_markers, 21);  // keys 0, 15, ..., 285 and the last
  EXPECT_EQ(count(svg, "class=\"key-marker\""), 21u);
  EXPECT_EQ(count(svg, "class=\"key-face\""), 0u);  // 300 cubes would hide everything
  EXPECT_NE(svg.find(">299</text>"), std::string::npos);
  EXPECT_EQ(count(svg, "class=\"object-pose\""), 7u);
}

TEST(Render, PngHasItsSizeAndIsNotBlank) {
  const kernel::Motion<double> m = interpolated("poses/five_positions.json");
  render::RenderOptions o;
  o.output = scratch("figure.png").string();
  o.width = 420;
  o.height = 300;
  fs::remove(o.output);
  render::render(qmotion::Motion(m), o);
  cairo_surface_t* s = cairo_image_surface_create_from_png(o.output.c_str());
  ASSERT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
  EXPECT_EQ(cairo_image_surface_get_width(s), 420);
  EXPECT_EQ(cairo_image_surface_get_height(s), 300);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  std::size_t inked = 0;
  for (int y = 0; y < 300; ++y)
    for (int x = 0; x < 420; ++x) {
      const unsigned char* px = data + y * stride + 4 * x;  // B, G, R, A
      inked += (px[0] < 245 || px[1] < 245 || px[2] < 245);
    }
  cairo_surface_destroy(s);
  const double share = static_cast<double>(inked) / (420.0 * 300.0);
  EXPECT_GT(share, 0.03);
  EXPECT_LT(share, 0.7);
  // The plot as PNG too.
  render::PlotOptions po;
  po.output = scratch("plot.png").string();
  po.width = 500;
  po.height = 260;
  render::plot({qmotion::Motion(m)}, po);
  s = cairo_image_surface_create_from_png(po.output.c_str());
  ASSERT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
  EXPECT_EQ(cairo_image_surface_get_width(s), 500);
  EXPECT_EQ(cairo_image_surface_get_height(s), 260);
  cairo_surface_destroy(s);
}

TEST(Render, BadOptionsAreRefusedByName) {
  const qmotion::Motion m(interpolated("poses/five_positions.json"));
  auto with = [&](auto edit) {
    render::RenderOptions o;
    o.output = scratch("bad.svg").string();
    edit(o);
    return [o, &m] { render::render(m, o); };
  };
  using test::throws_error;
  EXPECT_TRUE(throws_error(with([](render::RenderOptions& o) { o.view = "sideways"; }),
                           Errc::invalid_input, {"--view sideways", "iso, top, front, side"}));
  EXPECT_TRUE(throws_error(with([](render::RenderOptions& o) { o.view = "0,0,0"; }),
                           Errc::invalid_input, {"--view 0,0,0"}));
  EXPECT_TRUE(throws_error(with([](render::RenderOptions& o) { o.width = 0; }), Errc::invalid_input,
                           {"--size 0,720"}));
  EXPECT_TRUE(throws_error(with([](render::RenderOptions& o) { o.frames = -1; }),
                           Errc::invalid_input, {"--frames -1"}));
  EXPECT_TRUE(throws_error(with([](render::RenderOptions& o) { o.object = "missing.stl"; }),
                           Errc::invalid_input, {"missing.stl"}));
  std::ofstream(scratch("garbage.stl")) << "not a mesh\n";
  EXPECT_TRUE(throws_error(
      with([](render::RenderOptions& o) { o.object = scratch("garbage.stl").string(); }),
      Errc::invalid_input, {"garbage.stl: not a readable STL mesh"}));
  EXPECT_TRUE(throws_error(with([](render::RenderOptions& o) { o.output = "figure.pdf"; }),
                           Errc::invalid_input, {"figure.pdf", ".svg or .png"}));
  EXPECT_FALSE(fs::exists(scratch("bad.svg")));
  for (const std::string size : {"0,100", "100", "100,x", "20001,100", "-5,100", ""})
    EXPECT_TRUE(
        throws_error([&] { render::parse_size(size); }, Errc::invalid_input, {"--size " + size}));
  EXPECT_EQ(render::parse_size("640,480"), std::make_pair(640, 480));
  EXPECT_TRUE(throws_error([] { render::parse_quantity("jerk"); }, Errc::invalid_input,
                           {"--quantity jerk"}));
  EXPECT_EQ(render::parse_quantity("angular-speed"), render::Quantity::angular_speed);
  render::PlotOptions po;
  po.output = scratch("bad_plot.svg").string();
  po.samples = 1;
  EXPECT_TRUE(throws_error([&] { render::plot({m}, po); }, Errc::invalid_input, {"--samples 1"}));
  EXPECT_FALSE(fs::exists(po.output));
}

TEST(Render, ViewsLookAlongTheirAxes) {
  EXPECT_TRUE(render::parse_view("top").isApprox(Vector3d(0, 0, 1)));
  EXPECT_TRUE(render::parse_view("front").isApprox(Vector3d(0, -1, 0)));
  EXPECT_TRUE(render::parse_view("side").isApprox(Vector3d(1, 0, 0)));
  EXPECT_TRUE(render::parse_view("iso").isApprox(Vector3d(1, 1, 1).normalized()));
  EXPECT_TRUE(render::parse_view("0,0,-2").isApprox(Vector3d(0, 0, -1)));
  // Top view: x to the right, y up the page.
  const qmotion::Motion m(interpolated("poses/five_positions.json"));
  render::RenderOptions o;
  o.view = "top";
  render::RenderResult r;
  render::render_figure(m, o, &r);
  EXPECT_TRUE(r.right.isApprox(Vector3d::UnitX()));
  EXPECT_TRUE(r.up.isApprox(Vector3d::UnitY()));
}

}  // namespace
}  // namespace qmotion
