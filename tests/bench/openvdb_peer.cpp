// The swept volume against the route a user takes today (issues 31 and 51): stamp the body
// at N + 1 times (N from 10 to 1000) and union the stamps with OpenVDB (meshToLevelSet,
// csgUnion, volumeToMesh), at a voxel size equal to qmotion's tolerance T; then the same
// level set dilated by what a careful user would add to miss nothing (how far a point gets
// from both neighbouring stamps, the stamps' triangulation error and the voxels'), meshed
// plainly and with OpenVDB's adaptivity. On one sample of the true swept volume (points
// on and inside the body at random times, drawn from the body's own fine triangulation),
// each result is asked which points it misses:
// - qmotion's mesh by CGAL's Side_of_triangle_mesh;
// - the stamped level set by its own sign, trilinear, with the distance outside.
// Beside that: each mesh's vertices' distance to the swept volume (at most 4000 vertices,
// the upper bound of sweep::SweptVolumeTree), the triangles, and the time.
// Prints a Markdown table (tests/bench/bench_page.py puts it into docs/benchmarks.md);
// --smoke runs one short case (CTest).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Composite.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <qmotion/io/bodies.hpp>
#include <qmotion/qmotion.hpp>
#include <qmotion/sweep/swept_volume.hpp>
#include <random>
#include <string>
#include <vector>

namespace {

using V3 = Eigen::Vector3d;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<K::Point_3>;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

qmotion::Motion helix(int poses) {
  auto p = qmotion::io::read_poses(std::string(QMOTION_TEST_DATA) + "/poses/helix_40.json");
  p.poses.resize(static_cast<std::size_t>(poses));
  return qmotion::interpolate(p, {}).motion;
}

struct Result {
  std::string what;
  double seconds = 0;
  std::size_t triangles = 0;
  int missed = 0, missed_inside = 0;  // of all points; of those inside the body
  double missed_by = 0;               // the largest distance outside of a missed point
  double vertex_worst = 0;            // the largest distance of a vertex to the swept volume
};

/// The largest distance to the swept volume over at most 4000 of the vertices.
double vertex_distance(const qmotion::sweep::SweptVolumeTree& tree,
                       const std::vector<V3>& vertices) {
  double worst = 0;
  const std::size_t stride = std::max<std::size_t>(1, vertices.size() / 4000);
  for (std::size_t i = 0; i < vertices.size(); i += stride)
    worst = std::max(worst, std::max(0.0, tree.query(vertices[i], -HUGE_VAL).signed_upper));
  return worst;
}

/// Returns how many sample points qmotion's mesh misses (certified: none).
int run_case(const char* body_spec, int poses, const std::vector<int>& stamps, double T_rel,
             std::FILE* out) {
  const qmotion::Motion m = helix(poses);
  const qmotion::sweep::Body body = qmotion::io::read_body(body_spec);
  const double rho = qmotion::sweep::radius(body);
  // The sample: 20 000 points of the swept volume, on the body's boundary (vertices of a
  // triangulation within 1e-4 rho, which lie on it) and between two of them (inside).
  const auto fine = qmotion::sweep::triangulate(body, 1e-4 * rho);
  std::mt19937 g(2026);
  std::uniform_real_distribution<double> u(0, 1);
  std::uniform_int_distribution<std::size_t> pick(0, fine.vertices.size() - 1);
  std::vector<V3> sample;
  Eigen::AlignedBox3d box;
  for (int i = 0; i < 20000; ++i) {
    const double t = m.a() + (m.b() - m.a()) * u(g);
    const V3 x = i % 2 ? fine.vertices[pick(g)]
                       : V3(0.5 * (fine.vertices[pick(g)] + fine.vertices[pick(g)]));
    sample.push_back(m.place(t, x));
    box.extend(sample.back());
  }
  const double T = T_rel * box.diagonal().norm();
  const qmotion::sweep::SweptVolumeTree tree(m, body, 0.1 * T);
  std::vector<Result> rows;

  {  // qmotion
    Result r;
    r.what = "qmotion `volume`";
    const auto t0 = std::chrono::steady_clock::now();
    const qmotion::SweptVolume v = qmotion::swept_volume(m, body, T);
    r.seconds = seconds_since(t0);
    r.triangles = v.triangles.size();
    CgalMesh cm;
    std::vector<CgalMesh::Vertex_index> idx;
    for (const auto& p : v.vertices) idx.push_back(cm.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
    for (const auto& t : v.triangles) cm.add_face(idx[t[0]], idx[t[1]], idx[t[2]]);
    const CGAL::Side_of_triangle_mesh<CgalMesh, K> side(cm);
    for (std::size_t i = 0; i < sample.size(); ++i) {
      const V3& x = sample[i];
      const bool out = side(K::Point_3(x.x(), x.y(), x.z())) == CGAL::ON_UNBOUNDED_SIDE;
      r.missed += out;
      r.missed_inside += out && i % 2 == 0;
    }
    r.vertex_worst = vertex_distance(tree, v.vertices);
    rows.push_back(r);
  }

  // The stamps: the body's triangulation within T / 4, placed at N + 1 even times.
  const auto coarse = qmotion::sweep::triangulate(body, 0.25 * T);
  std::vector<openvdb::Vec3I> tris;
  for (const auto& t : coarse.triangles)
    tris.emplace_back(static_cast<openvdb::Index32>(t[0]), static_cast<openvdb::Index32>(t[1]),
                      static_cast<openvdb::Index32>(t[2]));
  const auto xform = openvdb::math::Transform::createLinearTransform(T);
  // The union of the N + 1 stamps, with `band` voxels of narrow band outside.
  auto stamp = [&](int N, float band) {
    openvdb::FloatGrid::Ptr grid;
    for (int i = 0; i <= N; ++i) {
      const Eigen::Matrix4d f = m.frame(m.a() + (m.b() - m.a()) * i / N);
      std::vector<openvdb::Vec3s> pts;
      for (const auto& v : coarse.vertices) {
        const V3 p = f.block<3, 1>(1, 0) + f.block<3, 3>(1, 1) * v;
        pts.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                         static_cast<float>(p.z()));
      }
      auto one = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*xform, pts, tris, band);
      if (!grid)
        grid = one;
      else
        openvdb::tools::csgUnion(*grid, *one);
    }
    return grid;
  };
  // The level iso of the grid as a mesh (adaptivity as volumeToMesh takes it), and what it
  // misses of the sample (the grid's trilinear value above iso) and how far.
  auto measure = [&](const openvdb::FloatGrid& grid, double iso, double adaptivity, Result& r) {
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> triangles;
    std::vector<openvdb::Vec4I> quads;
    openvdb::tools::volumeToMesh(grid, points, triangles, quads, iso, adaptivity);
    r.seconds += seconds_since(t0);
    r.triangles = triangles.size() + 2 * quads.size();
    const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(grid);
    for (std::size_t i = 0; i < sample.size(); ++i) {
      const V3& x = sample[i];
      const double phi = sampler.wsSample(openvdb::Vec3R(x.x(), x.y(), x.z())) - iso;
      if (phi > 0) {
        ++r.missed;
        r.missed_inside += i % 2 == 0;
        r.missed_by = std::max(r.missed_by, phi);
      }
    }
    std::vector<V3> verts;
    for (const auto& p : points) verts.emplace_back(p.x(), p.y(), p.z());
    r.vertex_worst = vertex_distance(tree, verts);
  };
  for (int N : stamps) {
    {  // As a user stamps today: the level set's zero.
      Result r;
      r.what = "OpenVDB, " + std::to_string(N) + " stamps";
      const auto t0 = std::chrono::steady_clock::now();
      const auto grid = stamp(N, 3.0f);
      r.seconds = seconds_since(t0);
      measure(*grid, 0.0, 0.0, r);
      rows.push_back(r);
    }
    // A careful user's certificate by construction: the level set dilated by how far a
    // point of the body gets from both neighbouring stamps (measured at 16 times between
    // them, on the stamps' vertices), plus the stamps' triangulation error (T / 4) and the
    // voxels' (half a diagonal).
    double reach = 0;
    for (int i = 0; i < N; ++i) {
      const Eigen::Matrix4d f0 = m.frame(m.a() + (m.b() - m.a()) * i / N),
                            f1 = m.frame(m.a() + (m.b() - m.a()) * (i + 1) / N);
      for (int k = 1; k < 16; ++k) {
        const Eigen::Matrix4d f = m.frame(m.a() + (m.b() - m.a()) * (i + k / 16.0) / N);
        for (const auto& v : coarse.vertices) {
          const V3 x = f.block<3, 1>(1, 0) + f.block<3, 3>(1, 1) * v;
          const double d0 = (x - f0.block<3, 1>(1, 0) - f0.block<3, 3>(1, 1) * v).norm(),
                       d1 = (x - f1.block<3, 1>(1, 0) - f1.block<3, 3>(1, 1) * v).norm();
          reach = std::max(reach, std::min(d0, d1));
        }
      }
    }
    const double iso = reach + 0.25 * T + 0.5 * std::sqrt(3.0) * T;
    Result dilated, adaptive;
    char what[160];
    std::snprintf(what, sizeof what, "OpenVDB, %d stamps, level set dilated by %.3g mm", N, iso);
    dilated.what = what;
    adaptive.what = dilated.what + ", adaptivity 0.5";
    const auto t0 = std::chrono::steady_clock::now();
    const auto grid = stamp(N, static_cast<float>(std::ceil(iso / T) + 3));
    dilated.seconds = adaptive.seconds = seconds_since(t0);
    measure(*grid, iso, 0.0, dilated);
    measure(*grid, iso, 0.5, adaptive);
    rows.push_back(dilated);
    rows.push_back(adaptive);
  }
  std::fprintf(out, "\n%s on the %d-pose helix, T = %.4g mm (%.0e of the diagonal):\n\n", body_spec,
               poses, T, T_rel);
  std::fprintf(out,
               "| method | time (s) | triangles | missed of 20 000 (of the 10 000 inside the "
               "body) | missed by (mm) | vertex distance (mm) | time / qmotion's |\n"
               "| --- | --- | --- | --- | --- | --- | --- |\n");
  for (const auto& r : rows)
    std::fprintf(out, "| %s | %.3f | %zu | %d (%d) | %.3g | %.3g | %.2f |\n", r.what.c_str(),
                 r.seconds, r.triangles, r.missed, r.missed_inside, r.missed_by, r.vertex_worst,
                 r.seconds / rows.front().seconds);
  return rows.front().missed;
}

}  // namespace

int main(int argc, char** argv) {
  openvdb::initialize();
  const bool smoke = argc > 1 && std::strcmp(argv[1], "--smoke") == 0;
  int missed = 0;
  if (smoke) {
    missed += run_case("cutter:ball,6,20", 5, {10}, 8e-3, stdout);
  } else {
    missed += run_case("cutter:ball,6,20", 8, {10, 30, 100, 300, 1000}, 4e-3, stdout);
    missed += run_case("box:4,6,8", 8, {10, 30, 100, 300, 1000}, 4e-3, stdout);
  }
  if (missed > 0) std::fprintf(stderr, "openvdb_peer: qmotion's mesh missed %d points\n", missed);
  return missed > 0 ? 1 : 0;
}
