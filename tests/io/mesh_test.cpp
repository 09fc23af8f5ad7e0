// tests/io/mesh_test.cpp mirrors io/mesh.hpp: meshes of swept solids measured by the test's
// own distance to the exact sweep (a tube: the union of the moving circles), read back from
// the files written.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <qmotion/api/evaluate.hpp>
#include <qmotion/api/export.hpp>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/io/profiles.hpp>
#include <qmotion/sweep/surface.hpp>
#include <sstream>

#include "io_test_util.hpp"
#include "sanitized_size.hpp"

namespace qmotion::test {
namespace {
namespace fs = std::filesystem;
using V3 = Eigen::Vector3d;

const kernel::Motion<double>& coil() {
  static const kernel::Motion<double> m =
      qmotion::interpolate(io::read_poses(test_data("self_intersection/coil_open.json")), {})
          .motion.rational();
  return m;
}

/// The rigid map of the motion at t: x -> R x + p.
std::pair<Eigen::Matrix3d, V3> frame(double t) {
  const auto M = kernel::evaluate(coil(), t);
  const V3 p = kernel::apply_point(M, V3(V3::Zero()));
  Eigen::Matrix3d R;
  for (int i = 0; i < 3; ++i) R.col(i) = kernel::apply_point(M, V3(V3::Unit(i))) - p;
  return {R, p};
}

/// The distance from x to the boundary of the solid swept by the disk of radius r in the
/// moving x-y plane: the tube (the union of the moving circles: the least distance to the
/// circle over t, a scan then golden sections) and the two end disks.
double distance_to_tube(const V3& x, double r) {
  const double a = coil().a(), b = coil().b();
  const auto circle = [&](double t) {
    const auto [R, p] = frame(t);
    const V3 y = R.transpose() * (x - p);
    return std::hypot(std::hypot(y(0), y(1)) - r, y(2));
  };
  const auto disk = [&](double t) {
    const auto [R, p] = frame(t);
    const V3 y = R.transpose() * (x - p);
    return std::hypot(std::max(0.0, std::hypot(y(0), y(1)) - r), y(2));
  };
  const int n = 240;
  int best = 0;
  double dbest = HUGE_VAL;
  for (int i = 0; i <= n; ++i) {
    const double d = circle(a + (b - a) * i / n);
    if (d < dbest) {
      dbest = d;
      best = i;
    }
  }
  double lo = a + (b - a) * std::max(0, best - 1) / n, hi = a + (b - a) * std::min(n, best + 1) / n;
  for (int it = 0; it < 60; ++it) {
    const double m1 = lo + (hi - lo) * 0.382, m2 = lo + (hi - lo) * 0.618;
    if (circle(m1) < circle(m2)) {
      hi = m2;
    } else {
      lo = m1;
    }
  }
  return std::min({dbest, circle(0.5 * (lo + hi)), disk(a), disk(b)});
}

struct ReadMesh {
  std::vector<V3> v;
  std::vector<std::array<int, 3>> f;
};

/// The test's own reader of binary little-endian PLY with double x, y, z and uchar/int faces.
ReadMesh read_ply(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::size_t nv = 0, nf = 0;
  bool binary = false;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream ss(line);
    std::string w, what;
    ss >> w;
    if (w == "format") binary = line.find("binary_little_endian") != std::string::npos;
    if (w == "element") {
      ss >> what;
      (what == "vertex" ? nv : nf) = std::stoul(line.substr(line.rfind(' ') + 1));
    }
  }
  EXPECT_TRUE(binary);
  ReadMesh m;
  for (std::size_t i = 0; i < nv; ++i) {
    double c[3];
    in.read(reinterpret_cast<char*>(c), sizeof c);
    m.v.emplace_back(c[0], c[1], c[2]);
  }
  for (std::size_t i = 0; i < nf; ++i) {
    unsigned char k = 0;
    std::int32_t id[3];
    in.read(reinterpret_cast<char*>(&k), 1);
    EXPECT_EQ(k, 3);
    in.read(reinterpret_cast<char*>(id), sizeof id);
    m.f.push_back({id[0], id[1], id[2]});
  }
  EXPECT_TRUE(in.good());
  return m;
}

TEST(Mesh, SolidMeshesAreClosedOrientedAndWithinTheDeflection) {
  const double r = 3;
  const auto profile = io::read_profile("circle:3", "mm");
  for (double D : steps({1.0, 0.1, 0.01})) {
    SCOPED_TRACE("deflection " + std::to_string(D));
    qmotion::ExportOptions o;
    o.output = scratch_path("mesh", "tube.ply").string();
    o.solid = true;
    o.deflection = D;
    const qmotion::ExportResult res =
        qmotion::export_geometry(coil(), qmotion::Geometry::sweep(profile), o);
    ASSERT_TRUE(res.mesh.has_value());
    EXPECT_LE(res.mesh->max_deviation, D);
    EXPECT_TRUE(res.mesh->closed);
    EXPECT_TRUE(res.mesh->oriented);
    const ReadMesh m = read_ply(o.output);
    ASSERT_EQ(m.v.size(), res.mesh->vertices.size());
    ASSERT_EQ(m.f.size(), res.mesh->triangles.size());
    // Closed and consistently oriented, by the test's own count: every directed edge once,
    // its reverse once.
    std::map<std::pair<int, int>, int> directed;
    for (const auto& t : m.f)
      for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
    for (const auto& [e, n] : directed) {
      ASSERT_EQ(n, 1) << "edge " << e.first << "-" << e.second;
      ASSERT_EQ(directed.count({e.second, e.first}), 1u) << "open edge";
    }
    // Outward: the divergence theorem gives the solid's volume, positive, within what the
    // chords cut off (a few deflections times the area).
    double volume = 0, area = 0;
    for (const auto& t : m.f) {
      volume += m.v[t[0]].dot(m.v[t[1]].cross(m.v[t[2]])) / 6;
      area += (m.v[t[1]] - m.v[t[0]]).cross(m.v[t[2]] - m.v[t[0]]).norm() / 2;
    }
    ASSERT_TRUE(res.volume.has_value());
    EXPECT_GT(volume, 0);
    EXPECT_NEAR(volume, *res.volume, 2 * D * area);
    // Vertices on the exact sweep, and the deviation at centroids and edge midpoints within
    // D, by the test's own distance (a sample of about 600 triangles).
    const std::size_t step = std::max<std::size_t>(1, m.f.size() / 600);
    double vertex = 0, dev = 0;
    for (std::size_t i = 0; i < m.f.size(); i += step) {
      const auto& t = m.f[i];
      for (int k = 0; k < 3; ++k) {
        vertex = std::max(vertex, distance_to_tube(m.v[t[k]], r));
        dev = std::max(dev, distance_to_tube((m.v[t[k]] + m.v[t[(k + 1) % 3]]) / 2, r));
      }
      dev = std::max(dev, distance_to_tube((m.v[t[0]] + m.v[t[1]] + m.v[t[2]]) / 3, r));
    }
    EXPECT_LE(vertex, 1e-9 * 30);  // the coil is about 30 mm across
    EXPECT_LE(dev, D);
    EXPECT_LE(dev, res.mesh->max_deviation * (1 + 1e-6) + 1e-12);  // the report bounds ours
  }
}

TEST(Mesh, EveryFormatHoldsTheSameTriangles) {
  const auto profile = io::read_profile("rect:4,2", "mm");
  qmotion::ExportOptions o;
  o.solid = true;
  o.deflection = 0.1;
  o.output = scratch_path("mesh", "box.ply").string();
  const auto ply = qmotion::export_geometry(coil(), qmotion::Geometry::sweep(profile), o);
  const std::size_t n = ply.mesh->triangles.size();
  o.output = scratch_path("mesh", "box.stl").string();  // binary: 80 + 4 + 50 per triangle
  qmotion::export_geometry(coil(), qmotion::Geometry::sweep(profile), o);
  EXPECT_EQ(fs::file_size(o.output), 84 + 50 * n);
  {
    std::ifstream in(o.output, std::ios::binary);
    in.seekg(80);
    std::uint32_t count = 0;
    in.read(reinterpret_cast<char*>(&count), 4);
    EXPECT_EQ(count, n);
    float rec[12];
    in.read(reinterpret_cast<char*>(rec), sizeof rec);
    const auto& t = ply.mesh->triangles.front();
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(rec[3 + 3 * k + c], ply.mesh->vertices[t[k]](c), 1e-5);
  }
  o.ascii = true;
  o.output = scratch_path("mesh", "box_ascii.stl").string();
  qmotion::export_geometry(coil(), qmotion::Geometry::sweep(profile), o);
  std::ifstream stl(o.output);
  std::size_t facets = 0;
  for (std::string line; std::getline(stl, line);)
    facets += line.find("facet normal") != std::string::npos;
  EXPECT_EQ(facets, n);
  o.ascii = false;
  o.output = scratch_path("mesh", "box.obj").string();
  qmotion::export_geometry(coil(), qmotion::Geometry::sweep(profile), o);
  std::ifstream obj(o.output);
  std::size_t faces = 0, verts = 0;
  for (std::string line; std::getline(obj, line);) {
    faces += line.rfind("f ", 0) == 0;
    verts += line.rfind("v ", 0) == 0;
  }
  EXPECT_EQ(faces, n);
  EXPECT_EQ(verts, ply.mesh->vertices.size());
}

TEST(EvaluateGrid, EqualsPointwiseEvaluationSerialAndParallel) {
  // The exact sweep of the coil by a circle: degree 9 x 2, C0 knots in v.
  const auto faces = qmotion::sweep_nurbs(coil(), io::read_profile("circle:3", "mm"));
  const auto& s = faces.front();
  std::vector<double> us, vs;
  const double u0 = s.knots_u.front(), u1 = s.knots_u.back();
  const double v0 = s.knots_v.front(), v1 = s.knots_v.back();
  for (int i = 0; i <= 400; ++i) us.push_back(u0 + (u1 - u0) * i / 400);
  for (int j = 0; j <= 60; ++j) vs.push_back(v0 + (v1 - v0) * j / 60);
  for (double k : s.knots_v) vs.push_back(k);  // the knots themselves, C0 joints included
  const auto serial = qmotion::evaluate_grid(s, us, vs, false);
  const auto parallel = qmotion::evaluate_grid(s, us, vs, true);
  ASSERT_EQ(serial.size(), us.size() * vs.size());
  double worst = 0;
  for (std::size_t i = 0; i < us.size(); i += 7)
    for (std::size_t j = 0; j < vs.size(); ++j) {
      const V3 ref = sweep::evaluate(s, us[i], vs[j]);
      worst = std::max(worst, (serial[i * vs.size() + j] - ref).norm());
    }
  EXPECT_LE(worst, 1e-12 * 30);
  for (std::size_t k = 0; k < serial.size(); ++k) ASSERT_EQ(serial[k], parallel[k]) << k;
  EXPECT_TRUE(throws_error([&] { qmotion::evaluate_grid(s, {u1 + 1}, vs); }, Errc::invalid_input,
                           {"u[0]", "outside"}));
  EXPECT_TRUE(
      throws_error([&] { qmotion::evaluate_grid(s, us, {NAN}); }, Errc::invalid_input, {"v[0]"}));
}

TEST(Mesh, BadMeshOptionsAreRefusedAndWriteNothing) {
  const auto profile = io::read_profile("circle:3", "mm");
  const std::string out = scratch_path("mesh", "bad.stl").string();
  auto with = [&](auto change) {
    qmotion::ExportOptions o;
    o.output = out;
    change(o);
    return
        [o, &profile] { qmotion::export_geometry(coil(), qmotion::Geometry::sweep(profile), o); };
  };
  EXPECT_TRUE(throws_error(with([](qmotion::ExportOptions& o) { o.deflection = -1; }),
                           Errc::invalid_input, {"--deflection"}));
  EXPECT_TRUE(throws_error(with([](qmotion::ExportOptions& o) { o.deflection = NAN; }),
                           Errc::invalid_input, {"--deflection"}));
  EXPECT_TRUE(throws_error(with([](qmotion::ExportOptions& o) { o.angle_deg = 0; }),
                           Errc::invalid_input, {"--angle"}));
  EXPECT_TRUE(throws_error(with([](qmotion::ExportOptions& o) {
                             o.deflection = 0.1;
                             o.output = "x.step";
                           }),
                           Errc::invalid_input, {"--deflection", "mesh"}));
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace qmotion::test
