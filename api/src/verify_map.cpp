// api/src/verify_map.cpp: verify's map: the part coloured by the stock left and the gouges
// (docs/guide/verify.md, "The map").
#include <algorithm>
#include <cmath>
#include <numeric>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/mesh.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/render/canvas.hpp>
#include <sstream>

#include "verify_stock.hpp"

namespace qmotion::detail {
namespace {

render::Rgb mix(const render::Rgb& a, const render::Rgb& b, double k) {
  k = std::clamp(k, 0.0, 1.0);
  return {a.r + k * (b.r - a.r), a.g + k * (b.g - a.g), a.b + k * (b.b - a.b)};
}

/// Gouged past tol: red, darker to 10 tol. Within tol: light grey (on size). Stock left past
/// tol: blue, darker on a log scale up to `top`.
render::Rgb colour(double v, double tol, double top) {
  if (v < -tol) return mix({1, 0.55, 0.55}, {0.75, 0, 0}, std::log(-v / tol) / std::log(10.0));
  if (v <= tol) return {0.92, 0.92, 0.92};
  return mix({0.72, 0.84, 1}, {0.04, 0.14, 0.62},
             std::log(v / tol) / std::log(std::max(top, 10 * tol) / tol));
}

unsigned char byte(double c) { return static_cast<unsigned char>(std::lround(255 * c)); }

std::string mm(double v) {
  std::ostringstream os;
  os.precision(3);
  os << v << " mm";
  return os.str();
}

/// The part seen from above (along -z): the triangles facing up, far ones first, each in the
/// mean of its corners' colours; the scale beneath.
void write_picture(const std::string& path, const sweep::TriangleMesh& mesh,
                   const std::vector<render::Rgb>& colours, const StockLeft& s, double tol) {
  Eigen::AlignedBox2d box;
  for (const Eigen::Vector3d& v : mesh.vertices) box.extend(Eigen::Vector2d(v.x(), v.y()));
  const double w = std::max(box.sizes().x(), 1e-9), h = std::max(box.sizes().y(), 1e-9);
  const int width = 900, margin = 20, legend = 70;
  const double scale = (width - 2 * margin) / std::max(w, h * 0.75);
  const int height = static_cast<int>(std::ceil(h * scale)) + 2 * margin + legend;
  render::Canvas canvas(width, std::clamp(height, 16, 20000));
  canvas.attribute("view", "top");
  auto at = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector2d(margin + (p.x() - box.min().x()) * scale,
                           margin + (box.max().y() - p.y()) * scale);
  };
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    const Eigen::Vector3d &a = mesh.vertices[static_cast<std::size_t>(t[0])],
                          &b = mesh.vertices[static_cast<std::size_t>(t[1])],
                          &c = mesh.vertices[static_cast<std::size_t>(t[2])];
    if ((b - a).cross(c - a).z() > 0) order.push_back(i);
  }
  auto height_of = [&](std::size_t i) {
    double z = 0;
    for (int v : mesh.triangles[i]) z += mesh.vertices[static_cast<std::size_t>(v)].z();
    return z;
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return height_of(a) < height_of(b); });
  canvas.begin_group("part");
  for (std::size_t i : order) {
    render::Rgb c{0, 0, 0};
    std::vector<Eigen::Vector2d> corners;
    for (int v : mesh.triangles[i]) {
      const render::Rgb& k = colours[static_cast<std::size_t>(v)];
      c = {c.r + k.r / 3, c.g + k.g / 3, c.b + k.b / 3};
      corners.push_back(at(mesh.vertices[static_cast<std::size_t>(v)]));
    }
    render::Style style;
    style.fill = c;
    style.stroke = c;
    style.width = 0.3;
    canvas.polygon(corners, style);
  }
  canvas.end_group();
  const double y = height - legend + 18.0;
  const double top = std::max(s.max_upper, 10 * tol);
  canvas.begin_group("scale");
  const double steps[] = {-10 * tol, -2 * tol, 0, 2 * tol, std::sqrt(2 * tol * top), top};
  const char* names[] = {"gouge 10 T", "gouge 2 T", "on size", "2 T", "", ""};
  for (int k = 0; k < 6; ++k) {
    render::Style style;
    style.fill = colour(steps[k], tol, top);
    style.stroke = render::Rgb{0.3, 0.3, 0.3};
    const double x = margin + k * 140.0;
    canvas.polygon({{x, y}, {x + 24, y}, {x + 24, y + 16}, {x, y + 16}}, style);
    const std::string label = names[k][0] ? std::string(names[k]) : mm(steps[k]);
    canvas.text({x + 30, y + 13}, label, 12, render::Anchor::start);
  }
  canvas.text({double(margin), y + 40},
              "stock left at most " + mm(s.max_upper) + ", mean " + mm(s.mean_estimate) +
                  " (T = " + mm(tol) + ", seen from above)",
              12, render::Anchor::start);
  canvas.end_group();
  canvas.write(path);
}

}  // namespace

void write_stock_map(const std::string& path, const sweep::Body& part, const StockLeft& s,
                     double tol) {
  const sweep::TriangleMesh& mesh = part.mesh;
  std::vector<render::Rgb> colours(mesh.vertices.size());
  for (std::size_t i = 0; i < colours.size(); ++i)
    colours[i] = colour(s.vertex_values[i], tol, s.max_upper);
  if (io::lower_extension(path) != ".ply") return write_picture(path, mesh, colours, s, tol);
  io::Mesh m;
  m.vertices = mesh.vertices;
  m.triangles = mesh.triangles;
  for (const render::Rgb& c : colours) m.colours.push_back({byte(c.r), byte(c.g), byte(c.b)});
  io::write_mesh(path, m, false);
}

}  // namespace qmotion::detail
