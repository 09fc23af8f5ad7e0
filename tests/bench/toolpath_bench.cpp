// tests/bench/toolpath_bench.cpp: the guaranteed toolpath sampler (certified chords and
// axes, cam::sample_toolpath) in points per second along the 40-pose helix's B-spline
// motion, and the time to write a 10^4-point toolpath (APT, CSV, G-code) through
// qmotion::toolpath (--max-step sets the count); NURBS G-code (--nurbs) against G1 moves;
// a table-tilting A/C machine's certified program against the workpiece certificate alone.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/api/toolpath.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/sweep/surface.hpp>
#include <string>

namespace {
namespace qm = qmotion;

const qm::kernel::Motion<double>& helix() {
  static const qm::kernel::Motion<double> m =
      qm::interpolate(qm::io::read_poses(std::string(QMOTION_TEST_DATA) + "/poses/helix_40.json"),
                      {})
          .motion.rational();
  return m;
}

void BM_Sampler(benchmark::State& state) {
  const auto& m = helix();
  const auto h = qm::sweep::trajectory(m, Eigen::Vector3d(1, 0, 2));
  const auto d = qm::sweep::trajectories(m, {Eigen::Vector4d(0, 1, 0, 1)}).front();
  qm::cam::SamplerOptions o;
  o.chord_tol = std::pow(10.0, -static_cast<double>(state.range(0)));
  std::size_t points = 0;
  for (auto _ : state) {
    const auto s = qm::cam::sample_toolpath(h, d, o);
    points = s.samples.size();
    benchmark::DoNotOptimize(s.max_chord_bound);
  }
  state.counters["points"] = static_cast<double>(points);
  state.counters["points_per_s"] = benchmark::Counter(
      static_cast<double>(points), benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel("chord tol 1e-" + std::to_string(state.range(0)) + " mm");
}
BENCHMARK(BM_Sampler)->Arg(1)->Arg(2)->Arg(3)->Arg(4)->Unit(benchmark::kMillisecond);

void BM_Write10k(benchmark::State& state) {
  const char* ext[] = {".apt", ".csv", ".ngc"};
  const qm::Motion m = helix();
  qm::ToolpathOptions o;
  o.output = (std::filesystem::temp_directory_path() /
              (std::string("qmotion_bench_tp") + ext[state.range(0)]))
                 .string();
  o.point = Eigen::Vector3d(1, 0, 2);
  o.axis = Eigen::Vector3d(1, 0, 1);
  o.chord_tol = 0.01;
  o.max_step = 0.05;  // about 10^4 points along the helix
  std::size_t points = 0;
  for (auto _ : state) points = qm::toolpath(m, o).samples.size();
  state.counters["points"] = static_cast<double>(points);
  state.SetLabel(ext[state.range(0)]);
  std::filesystem::remove(o.output);
}
BENCHMARK(BM_Write10k)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

/// --nurbs: the certified cubic (cam::cam_nurbs: fit, rounding, certificate) and the
/// G-code, against the linear toolpath at the same chord tolerance (angle tolerance 89
/// degrees, so that only the chord decides).
void BM_Nurbs(benchmark::State& state) {
  const qm::Motion m = helix();
  qm::ToolpathOptions o;
  o.output = (std::filesystem::temp_directory_path() / "qmotion_bench_tpn.ngc").string();
  o.point = Eigen::Vector3d(1, 0, 2);
  o.chord_tol = std::pow(10.0, -static_cast<double>(state.range(0)));
  o.angle_tol_deg = 89;
  o.nurbs = state.range(1) != 0;
  std::size_t blocks = 0;
  for (auto _ : state) {
    const auto tp = qm::toolpath(m, o);
    blocks = tp.nurbs ? tp.nurbs->curve.ctrl().size() : tp.samples.size();
  }
  state.counters["blocks"] = static_cast<double>(blocks);
  state.SetLabel(std::string(o.nurbs ? "G06.2" : "G1") + ", chord tol 1e-" +
                 std::to_string(state.range(0)) + " mm");
  std::filesystem::remove(o.output);
}
BENCHMARK(BM_Nurbs)->ArgsProduct({{1, 2, 3, 4}, {0, 1}})->Unit(benchmark::kMillisecond);

/// tests/data/poses/tilt_150.json (150 mm off the pivot, the axis tilting 20-60 degrees):
/// G-code for a table A/C machine, certified for its linear interpolation of the axes, and
/// inverse-time feeds (BM_MachineToolpath), against the 3-axis program the workpiece
/// certificate alone needs (BM_WorkpieceToolpath), at chord tolerances 1e-1 ... 1e-3 mm.
void toolpath_on(benchmark::State& state, const std::string& rotary) {
  static const qm::Motion m = [] {
    qm::InterpolateOptions io;
    io.form = "bspline";
    return qm::interpolate(
               qm::io::read_poses(std::string(QMOTION_TEST_DATA) + "/poses/tilt_150.json"), io)
        .motion;
  }();
  qm::ToolpathOptions o;
  o.output =
      (std::filesystem::temp_directory_path() / ("qmotion_bench_m" + rotary + ".ngc")).string();
  o.chord_tol = std::pow(10.0, -static_cast<double>(state.range(0)));
  o.rotary = rotary;
  if (!rotary.empty()) o.feed_mode = "inverse-time";
  std::size_t points = 0;
  for (auto _ : state) points = qm::toolpath(m, o).samples.size();
  state.counters["points"] = static_cast<double>(points);
  state.SetLabel((rotary.empty() ? std::string("3-axis") : "A/C, G93") + ", chord tol 1e-" +
                 std::to_string(state.range(0)) + " mm");
  std::filesystem::remove(o.output);
}
void BM_MachineToolpath(benchmark::State& state) { toolpath_on(state, "ac"); }
void BM_WorkpieceToolpath(benchmark::State& state) { toolpath_on(state, ""); }
BENCHMARK(BM_MachineToolpath)->DenseRange(1, 3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WorkpieceToolpath)->DenseRange(1, 3)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
