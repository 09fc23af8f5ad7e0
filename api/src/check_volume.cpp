// api/src/check_volume.cpp: `qmotion check VOLUME --body B` (docs/guide/volume.md): a volume
// mesh against the swept volume, by sampling of its own.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <qmotion/api/volume.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/bodies.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/units.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/trajectory.hpp>
#include <random>
#include <sstream>

namespace qmotion {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<K::Point_3>;

/// The mesh of a volume file in the motion's unit: `qmotion volume`'s JSON (scaled from its
/// declared unit), or STL/OBJ/PLY read and checked as a closed, oriented body.
sweep::TriangleMesh read_volume(const std::string& path, const Motion& m) {
  if (io::lower_extension(path) != ".json") return io::read_body(path).mesh;
  const std::string text = io::read_text_file(path);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(Errc::invalid_input, path + ": not JSON: " + e.what());
  }
  if (!j.is_object() || j.value("kind", "") != "swept_volume_mesh")
    throw Error(Errc::invalid_input,
                path + ": not a swept-volume mesh (\"kind\": \"swept_volume_mesh\")");
  const double f =
      io::unit_factor(io::canonical_unit(j.value("units", ""), path + ": units"), m.units());
  sweep::TriangleMesh mesh;
  try {
    for (const auto& v : j.at("vertices"))
      mesh.vertices.emplace_back(f * v.at(0).get<double>(), f * v.at(1).get<double>(),
                                 f * v.at(2).get<double>());
    const int n = static_cast<int>(mesh.vertices.size());
    for (const auto& t : j.at("triangles")) {
      std::array<int, 3> tri{t.at(0).get<int>(), t.at(1).get<int>(), t.at(2).get<int>()};
      for (int k : tri)
        if (k < 0 || k >= n)
          throw Error(Errc::invalid_input,
                      path + ": triangle " + std::to_string(mesh.triangles.size()) +
                          " names vertex " + std::to_string(k) + ", of " + std::to_string(n));
      mesh.triangles.push_back(tri);
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(Errc::invalid_input, path + ": vertices or triangles: " + e.what());
  }
  io::require_closed_oriented(mesh, path);
  return mesh;
}

/// The distance from x to the body placed by the motion: 256 times, then golden sections
/// about the best (an upper bound of the distance to the swept volume).
double distance_to_swept(const Motion& m, const sweep::Body& body, const Eigen::Vector3d& x) {
  auto dist = [&](double t) {
    const Eigen::Matrix4d f = m.frame(t);
    return sweep::signed_distance(body,
                                  f.block<3, 3>(1, 1).transpose() * (x - f.block<3, 1>(1, 0)));
  };
  const int n = 256;
  int best = 0;
  double fbest = HUGE_VAL;
  for (int j = 0; j <= n; ++j) {
    const double f = dist(m.a() + (m.b() - m.a()) * j / n);
    if (f < fbest) fbest = f, best = j;
  }
  double lo = m.a() + (m.b() - m.a()) * std::max(0, best - 1) / n;
  double hi = m.a() + (m.b() - m.a()) * std::min(n, best + 1) / n;
  for (int it = 0; it < 40; ++it) {
    const double a = lo + (hi - lo) * 0.382, b = lo + (hi - lo) * 0.618;
    const double fa = dist(a), fb = dist(b);
    fbest = std::min({fbest, fa, fb});
    if (fa < fb)
      hi = b;
    else
      lo = a;
  }
  return std::max(fbest, 0.0);
}

}  // namespace

nlohmann::json check_volume(const std::string& path, const Motion& motion,
                            const std::string& body_spec, int samples) {
  if (samples < 1 || samples > 10'000'000)
    throw Error(Errc::invalid_input, "check: the samples must be 1 to 10^7");
  if (motion.is_rational()) sweep::refuse_poles(motion.rational());
  const sweep::Body body = io::read_body(body_spec);
  const sweep::TriangleMesh mesh = read_volume(path, motion);
  CgalMesh cm;
  std::vector<CgalMesh::Vertex_index> idx;
  for (const auto& p : mesh.vertices) idx.push_back(cm.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
  for (const auto& t : mesh.triangles) cm.add_face(idx[t[0]], idx[t[1]], idx[t[2]]);
  const CGAL::Side_of_triangle_mesh<CgalMesh, K> side(cm);

  const double rho = sweep::radius(body);
  const auto fine = sweep::triangulate(body, 1e-4 * rho);
  std::mt19937 g(31);
  std::uniform_real_distribution<double> u(0, 1);
  std::uniform_int_distribution<std::size_t> pick(0, fine.vertices.size() - 1);
  std::size_t outside = 0;
  for (int i = 0; i < samples; ++i) {
    const double t = motion.a() + (motion.b() - motion.a()) * u(g);
    Eigen::Vector3d x = fine.vertices[pick(g)];
    if (i % 2 == 0) {  // a midpoint: inside a convex body; a mesh's only where it says so
      const Eigen::Vector3d mid = 0.5 * (x + fine.vertices[pick(g)]);
      if (body.kind != sweep::Body::Kind::mesh || sweep::signed_distance(body, mid) < 0) x = mid;
    }
    const Eigen::Vector3d p = motion.place(t, x);
    outside += side(K::Point_3(p.x(), p.y(), p.z())) == CGAL::ON_UNBOUNDED_SIDE;
  }
  const std::size_t stride = std::max<std::size_t>(1, mesh.vertices.size() / 20000);
  std::vector<double> d((mesh.vertices.size() + stride - 1) / stride);
  tbb::parallel_for(std::size_t(0), d.size(), [&](std::size_t i) {
    d[i] = distance_to_swept(motion, body, mesh.vertices[i * stride]);
  });
  double volume = 0;
  for (const auto& t : mesh.triangles)
    volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6;
  return {{"file", path},
          {"body", body.spec},
          {"units", motion.units()},
          {"samples", samples},
          {"outside", outside},
          {"encloses", outside == 0},
          {"vertex_distance", d.empty() ? 0.0 : *std::max_element(d.begin(), d.end())},
          {"vertices_measured", d.size()},
          {"triangles", mesh.triangles.size()},
          {"vertices", mesh.vertices.size()},
          {"volume", volume},
          {"closed", true}};
}

}  // namespace qmotion
