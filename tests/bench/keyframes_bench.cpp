// tests/bench/keyframes_bench.cpp: certified glTF keyframes (sweep::place_keyframes) along
// the 40-pose helix (both kinds of motion) and the five sample poses' motion, at tolerances 1e-1 to
// 1e-4 mm for a body of radius 30 mm; beside it, the fewest uniform keys for which the same
// certificate holds on every interval (their count, and the time to find it); and `animate` end to
// end.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <qmotion/api/animate.hpp>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/api/qspline.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/sweep/keyframes.hpp>
#include <string>

namespace {
namespace qm = qmotion;

/// 1: the 40-pose helix's rational motion, 0: its kks spline (both of even speed);
/// 2: the five sample poses' rational motion (uneven speed and turning).
const qm::Motion& motion(std::int64_t which) {
  static const auto poses =
      qm::io::read_poses(std::string(QMOTION_TEST_DATA) + "/poses/helix_40.json");
  static const qm::Motion r = qm::interpolate(poses, {}).motion;
  static const qm::Motion s = [] {
    qm::QSplineOptions o;
    o.scheme = "kks";
    return qm::qspline(poses, o).motion;
  }();
  static const qm::Motion five =
      qm::interpolate(
          qm::io::read_poses(std::string(QMOTION_TEST_DATA) + "/poses/five_positions.json"), {})
          .motion;
  return which == 2 ? five : which == 1 ? r : s;
}

std::string label(std::int64_t which) {
  return which == 2 ? "five poses, rational" : which == 1 ? "helix, rational" : "helix, kks";
}

constexpr double kRadius = 30;

void BM_Keyframes(benchmark::State& state) {
  const qm::Motion& m = motion(state.range(0));
  qm::sweep::KeyframeOptions o;
  o.tol = std::pow(10.0, -static_cast<double>(state.range(1)));
  o.radius = kRadius;
  qm::sweep::Keyframes k;
  for (auto _ : state) k = qm::sweep::place_keyframes(m, o);
  state.counters["keys"] = static_cast<double>(k.keys.size());
  state.counters["bound"] = k.max_bound;
  state.SetLabel(label(state.range(0)) + ", tol 1e-" + std::to_string(state.range(1)) + " mm");
}
BENCHMARK(BM_Keyframes)->ArgsProduct({{1, 0, 2}, {1, 2, 3, 4}})->Unit(benchmark::kMillisecond);

/// The fewest uniform keys for which the same certificate holds on every interval: doubled
/// from 16 until it holds, then bisected between the last count that failed and it.
void BM_UniformKeyframes(benchmark::State& state) {
  const qm::Motion& m = motion(state.range(0));
  const double tol = std::pow(10.0, -static_cast<double>(state.range(1)));
  std::size_t n = 1;
  for (auto _ : state) {
    const qm::sweep::KeyframeBound bound(m, kRadius, 4);
    auto holds = [&](std::size_t count) {
      qm::sweep::Keyframe prev = qm::sweep::exact_key(m, m.a(), nullptr);
      for (std::size_t i = 1; i <= count; ++i) {
        const auto k = qm::sweep::exact_key(m, m.a() + (m.b() - m.a()) * i / count, &prev);
        if (!(bound(prev, k) <= tol)) return false;
        prev = k;
      }
      return true;
    };
    std::size_t lo = 8, hi = 16;  // lo fails (or is below the start), hi is tried
    while (!holds(hi)) {
      lo = hi;
      hi *= 2;
    }
    while (hi - lo > 1) {
      const std::size_t mid = (lo + hi) / 2;
      (holds(mid) ? hi : lo) = mid;
    }
    n = hi;
  }
  state.counters["keys"] = static_cast<double>(n + 1);
  state.SetLabel(label(state.range(0)) + ", tol 1e-" + std::to_string(state.range(1)) + " mm");
}
BENCHMARK(BM_UniformKeyframes)
    ->ArgsProduct({{1, 0, 2}, {1, 2, 3, 4}})
    ->Unit(benchmark::kMillisecond);

void BM_Animate(benchmark::State& state) {
  const qm::Motion& m = motion(state.range(0));
  qm::AnimateOptions o;
  o.output = (std::filesystem::temp_directory_path() / "qmotion_bench_animate.glb").string();
  o.body = "cutter:ball,6,30";
  o.tol = 1e-3;
  std::size_t keys = 0;
  for (auto _ : state) keys = qm::animate(m, o).keyframes;
  state.counters["keys"] = static_cast<double>(keys);
  state.SetLabel(label(state.range(0)) + ", ball cutter, tol 1e-3 mm, .glb");
  std::filesystem::remove(o.output);
}
BENCHMARK(BM_Animate)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
