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

void run(benchmark::State& state, const qmotion::Motion& m, double T) {
  const auto body = qmotion::io::read_body("cutter:ball,6,20");
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

}  // namespace

BENCHMARK_MAIN();
