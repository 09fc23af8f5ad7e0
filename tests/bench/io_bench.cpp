// tests/bench/io_bench.cpp: reading and writing motion files of 10^2..10^4 poses, side by
// side with nlohmann's DOM reader (the reference the fast reader falls back to) and with
// std::ofstream writing the same bytes.
//   build/tests/bench/bench_io --benchmark_filter=/10000
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <qmotion/api/export.hpp>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/api/motion_info.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/poses.hpp>
#include <sstream>

namespace {
using namespace qmotion;

/// A helix of n poses turning about a wobbling axis, as JSON text (17 digits per number).
std::string helix_poses(int n) {
  std::ostringstream os;
  os.precision(17);
  os << R"({"units": "mm", "poses": [)";
  for (int i = 0; i < n; ++i) {
    const double t = double(i) / (n - 1), a = t * 40 * M_PI;
    const double ang = a / 2 + 0.3 * std::sin(7 * t);
    double ax[3] = {0.3 * std::sin(5 * t), 0.2, 1.0};
    const double l = std::sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
    os << (i ? "," : "") << R"({"t": )" << t << R"(, "position": [)" << 60 * std::cos(a) << ", "
       << 60 * std::sin(a) << ", " << 400 * t << R"(], "rotation": {"quaternion": [)"
       << std::cos(ang / 2);
    for (double c : ax) os << ", " << std::sin(ang / 2) * c / l;
    os << "]}}";
  }
  os << "]}";
  return os.str();
}

/// The B-spline motion file through n poses, as qmotion interpolate writes it.
const std::string& motion_text(int n) {
  static std::map<int, std::string> cache;
  auto& s = cache[n];
  if (s.empty()) {
    qmotion::InterpolateOptions opt;
    opt.form = "bspline";
    s = qmotion::interpolate(io::parse_poses_json(helix_poses(n), "helix"), opt).text();
  }
  return s;
}

void BM_ReadMotion(benchmark::State& state) {  // simdjson, no DOM for the curve
  const std::string& text = motion_text(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(io::parse_motion_text(text, "m.json"));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * text.size()));
}

void BM_ReadMotionSimdDom(benchmark::State& state) {  // simdjson into nlohmann's DOM
  const std::string& text = motion_text(static_cast<int>(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(io::parse_motion(io::parse_json(text, "m.json", "method"), "m.json"));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * text.size()));
}

void BM_ReadMotionNlohmann(benchmark::State& state) {  // the reference reader, as before
  const std::string& text = motion_text(static_cast<int>(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(io::parse_motion(io::parse_json_reference(text, "m.json"), "m.json"));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * text.size()));
}

void BM_Info(benchmark::State& state) {  // read and describe (qmotion info)
  const std::string& text = motion_text(static_cast<int>(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(qmotion::motion_info(io::parse_motion_text(text, "m.json"), false));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * text.size()));
}

void BM_WriteMotion(benchmark::State& state) {  // motion value to file (qmotion interpolate)
  const std::string& text = motion_text(static_cast<int>(state.range(0)));
  const auto m = io::to_motion(io::parse_motion_text(text, "m.json"));
  const std::string path = "bench_io_motion.json";
  std::size_t bytes = 0;  // of the file written, read once afterwards
  for (auto _ : state) io::save_motion(m, path);
  bytes = io::read_text_file(path).size();
  std::remove(path.c_str());
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes));
}

void BM_WriteMotionTree(benchmark::State& state) {  // before: nlohmann's tree, dumped
  const std::string& text = motion_text(static_cast<int>(state.range(0)));
  const auto m = io::to_motion(io::parse_motion_text(text, "m.json"));
  const std::string path = "bench_io_motion_tree.json";
  std::size_t bytes = 0;
  for (auto _ : state) io::write_file_atomic(path, io::motion_document(m).dump(1) + "\n");
  bytes = io::read_text_file(path).size();
  std::remove(path.c_str());
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes));
}

void BM_OfstreamSameBytes(benchmark::State& state) {  // the floor: the bytes alone
  const std::string& text = motion_text(static_cast<int>(state.range(0)));
  const std::string path = "bench_io_plain.json";
  for (auto _ : state) std::ofstream(path, std::ios::binary) << text;
  std::remove(path.c_str());
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * text.size()));
}

/// The exact trajectory of (1, 0, 2) under the n-pose motion, as trajectory writes it.
const sweep::NurbsCurve<double>& trajectory(int n) {
  static std::map<int, sweep::NurbsCurve<double>> cache;
  auto it = cache.find(n);
  if (it == cache.end()) {
    const auto m = io::to_motion(io::parse_motion_text(motion_text(n), "m.json"));
    it = cache.emplace(n, qmotion::trajectory_nurbs(m, Eigen::Vector3d(1, 0, 2))).first;
  }
  return it->second;
}

const nlohmann::json kTrajectoryExtra{{"units", "mm"}, {"continuity", 2}};

void BM_WriteTrajectoryJson(benchmark::State& state) {  // streamed (trajectory -o .json)
  const auto& c = trajectory(static_cast<int>(state.range(0)));
  const std::string path = "bench_io_trajectory.json";
  for (auto _ : state) io::write_curve_json(path, c, kTrajectoryExtra);
  const std::size_t bytes = io::read_text_file(path).size();
  std::remove(path.c_str());
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes));
}

void BM_WriteTrajectoryJsonWhole(benchmark::State& state) {  // the text whole, then written
  const auto& c = trajectory(static_cast<int>(state.range(0)));
  const std::string path = "bench_io_trajectory_whole.json";
  for (auto _ : state) io::write_file_atomic(path, io::curve_json_text(c, kTrajectoryExtra));
  std::remove(path.c_str());
}

void BM_TrajectoryJsonTextOnly(benchmark::State& state) {  // the formatting share
  const auto& c = trajectory(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(io::curve_json_text(c, kTrajectoryExtra));
}

void BM_WriteTrajectoryJsonTree(benchmark::State& state) {  // before: nlohmann's tree, dumped
  const auto& c = trajectory(static_cast<int>(state.range(0)));
  const std::string path = "bench_io_trajectory_tree.json";
  for (auto _ : state) {
    nlohmann::json doc = io::curve_to_json(c);
    doc.update(kTrajectoryExtra);
    io::write_file_atomic(path, doc.dump(1) + "\n");
  }
  std::remove(path.c_str());
}

void BM_OfstreamSameTrajectoryBytes(benchmark::State& state) {  // the floor
  const std::string text =
      io::curve_json_text(trajectory(static_cast<int>(state.range(0))), kTrajectoryExtra);
  const std::string path = "bench_io_trajectory_plain.json";
  for (auto _ : state) std::ofstream(path, std::ios::binary) << text;
  std::remove(path.c_str());
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * text.size()));
}

}  // namespace

BENCHMARK(BM_WriteTrajectoryJson)->Arg(100)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WriteTrajectoryJsonWhole)->Arg(100)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TrajectoryJsonTextOnly)->Arg(100)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WriteTrajectoryJsonTree)->Arg(100)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OfstreamSameTrajectoryBytes)->Arg(100)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadMotion)->Arg(100)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadMotionSimdDom)->Arg(100)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadMotionNlohmann)->Arg(100)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Info)->Arg(100)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WriteMotion)->Arg(100)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WriteMotionTree)->Arg(100)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OfstreamSameBytes)->Arg(100)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
