// Swept volumes (docs/guide/volume.md): the enclosing mesh of a ball cutter (D 6, L 20) on
// the 60 mm helix, as the number of spans and 1/T grow. T is a fraction of the swept
// volume's bounding-box diagonal (sampled here as the command samples it): 4e-3, 2e-3 and
// the default 1e-3. Counters: triangles, certified vertex distance over T, distance
// queries, time pieces. And the exact faces of a sphere (the pipe and its caps) as the
// spans grow.
#include <benchmark/benchmark.h>

#include <qmotion/io/bodies.hpp>
#include <qmotion/qmotion.hpp>
#include <string>

namespace {

qmotion::Motion helix(int poses) {
  auto p = qmotion::io::read_poses(std::string(QMOTION_TEST_DATA) + "/poses/helix_40.json");
  p.poses.resize(static_cast<std::size_t>(poses));
  return qmotion::interpolate(p, {}).motion;
}

double diagonal(const qmotion::Motion& m, const qmotion::sweep::Body& body) {
  const auto mesh = qmotion::sweep::triangulate(body, 1e-2 * qmotion::sweep::radius(body));
  Eigen::AlignedBox3d box;
  const int n = 64 * m.segments();
  for (int i = 0; i <= n; ++i)
    for (const auto& v : mesh.vertices) box.extend(m.place(m.a() + (m.b() - m.a()) * i / n, v));
  return box.diagonal().norm();
}

qmotion::SweptVolume run(benchmark::State& state, const qmotion::Motion& m, double T,
                         const char* spec = "cutter:ball,6,20") {
  const auto body = qmotion::io::read_body(spec);
  qmotion::SweptVolume v;
  for (auto _ : state) {
    v = qmotion::swept_volume(m, body, T);
    benchmark::DoNotOptimize(v.triangles.data());
  }
  state.counters["triangles"] = static_cast<double>(v.triangles.size());
  state.counters["bound_over_T"] = v.distance_bound / T;
  state.counters["queries"] = static_cast<double>(v.distance_queries);
  state.counters["pieces"] = static_cast<double>(v.time_pieces);
  state.counters["T_mm"] = T;
  return v;
}

/// The 8-pose helix, T in thousandths of the swept volume's diagonal (1: the default).
void BM_Volume(benchmark::State& state) {
  const qmotion::Motion m = helix(8);
  const double d = diagonal(m, qmotion::io::read_body("cutter:ball,6,20"));
  run(state, m, 1e-3 * static_cast<double>(state.range(0)) * d);
}
BENCHMARK(BM_Volume)
    ->ArgName("T_permille")
    ->Arg(4)
    ->Arg(2)
    ->Arg(1)
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

/// More spans of the same helix at one absolute tolerance, 0.5 mm.
void BM_VolumeSpans(benchmark::State& state) {
  run(state, helix(static_cast<int>(state.range(0)) + 1), 0.5);
}
BENCHMARK(BM_VolumeSpans)
    ->ArgName("spans")
    ->Arg(4)
    ->Arg(8)
    ->Arg(16)
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

/// Issue 51's scenes: the 8-pose helix (0) and the tilting 10-pose B-spline of
/// tests/data/poses/tilt_150.json (1); a ball cutter D 6, L 20 (0) and a flat cutter D 10,
/// L 20 (1); T in micrometres, 0 for the default (1e-3 of the diagonal).
void BM_VolumeScene(benchmark::State& state) {
  const qmotion::Motion m =
      state.range(0) == 0
          ? helix(8)
          : qmotion::interpolate(
                qmotion::io::read_poses(std::string(QMOTION_TEST_DATA) + "/poses/tilt_150.json"),
                {})
                .motion;
  const char* spec = state.range(1) == 0 ? "cutter:ball,6,20" : "cutter:flat,10,20";
  const double T = state.range(2) > 0 ? 1e-3 * static_cast<double>(state.range(2))
                                      : 1e-3 * diagonal(m, qmotion::io::read_body(spec));
  const qmotion::SweptVolume v = run(state, m, T, spec);
  state.counters["smallest_cell_mm"] = v.grid_step;
  state.counters["largest_cell_mm"] = v.largest_cell;
  state.counters["hull_pieces"] = static_cast<double>(v.hull_pieces);
}
BENCHMARK(BM_VolumeScene)
    ->ArgNames({"scene", "cutter", "T_um"})
    ->Args({0, 0, 0})
    ->Args({0, 1, 0})
    ->Args({1, 0, 0})
    ->Args({1, 1, 0})
    ->Args({0, 0, 50})
    ->Args({0, 1, 50})
    ->Args({1, 0, 50})
    ->Args({1, 1, 50})
    ->Args({0, 0, 10})
    ->Args({0, 1, 10})
    ->Args({1, 0, 10})
    ->Args({1, 1, 10})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

/// The exact faces of sphere:3 (the pipe and its caps) on the helix of 8, 16 and 40 poses:
/// no tolerance, so the work grows with the spans only.
void BM_VolumeExactPipe(benchmark::State& state) {
  const qmotion::Motion m = helix(static_cast<int>(state.range(0)));
  const auto body = qmotion::io::read_body("sphere:3");
  qmotion::sweep::PipeShell p;
  for (auto _ : state) {
    p = qmotion::exact_swept_volume(m, body);
    benchmark::DoNotOptimize(p.shell.faces.data());
  }
  state.counters["faces"] = static_cast<double>(p.shell.faces.size());
  state.counters["degree"] = p.degree_t;
  state.counters["pieces"] = static_cast<double>(p.pieces);
}
BENCHMARK(BM_VolumeExactPipe)
    ->ArgName("poses")
    ->Arg(8)
    ->Arg(16)
    ->Arg(40)
    ->Unit(benchmark::kMillisecond);

/// Mesh bodies against their bounding boxes, on the 8-pose helix at T = 2 mm: 0 the box
/// 12 x 6 x 10, 1 the L-shaped bracket in it (tests/data/bodies/bracket.obj, 20 triangles,
/// not convex), 2 the box 24 x 24 x 50, 3 a tool holder in it (a solid of revolution of
/// 10 080 triangles).
void BM_VolumeMeshBody(benchmark::State& state) {
  const qmotion::Motion m = helix(8);
  qmotion::sweep::Body body;
  switch (state.range(0)) {
    case 0:
      body = qmotion::io::read_body("box:12,6,10");
      break;
    case 1:
      body = qmotion::io::read_body(std::string(QMOTION_TEST_DATA) + "/bodies/bracket.obj");
      break;
    case 2:
      body = qmotion::io::read_body("box:24,24,50");
      break;
    default: {
      body.kind = qmotion::sweep::Body::Kind::mesh;
      body.spec = "holder";
      body.mesh = qmotion::sweep::detail::revolve(
          {{0, 0}, {3, 0}, {3, 20}, {5, 22}, {8, 22}, {8, 30}, {12, 34}, {12, 50}, {0, 50}}, 720);
      for (auto& v : body.mesh.vertices) v.z() -= 25;
      qmotion::sweep::index_mesh(body);
    }
  }
  qmotion::SweptVolume v;
  for (auto _ : state) {
    v = qmotion::swept_volume(m, body, 2.0);
    benchmark::DoNotOptimize(v.triangles.data());
  }
  state.counters["triangles"] = static_cast<double>(v.triangles.size());
  state.counters["bound_over_T"] = v.distance_bound / 2.0;
  state.counters["body_triangles"] = static_cast<double>(
      body.kind == qmotion::sweep::Body::Kind::mesh ? body.mesh.triangles.size() : 12);
}
BENCHMARK(BM_VolumeMeshBody)
    ->ArgName("body")
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Arg(3)
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
