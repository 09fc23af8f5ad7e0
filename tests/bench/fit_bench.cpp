// tests/bench/fit_bench.cpp: `fit` on dense, noisy samples of a smooth motion (noise below a
// third of the tolerances) at 10^3, 10^4 and 10^5 poses and two tolerance levels: control
// points against poses (goal: at least 10x fewer), worst deviations, and time (goal: linear,
// 10^5 poses in a few seconds). The peer is what a user does without it: a B-spline Q-motion
// interpolating every pose.
#include <benchmark/benchmark.h>

#include <map>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/motion_fit.hpp>
#include <string>

#include "fit_streams.hpp"

namespace {
using namespace qmotion;

/// Level 0: 0.01 mm and 0.05 degrees; level 1: 0.001 mm and 0.01 degrees.
kernel::FitOptions level(int i) {
  kernel::FitOptions o;
  o.tol = i == 0 ? 0.01 : 0.001;
  o.angle_tol_deg = i == 0 ? 0.05 : 0.01;
  return o;
}

const test::Stream& stream(std::size_t n, int lv) {
  static std::map<std::pair<std::size_t, int>, test::Stream> cache;
  auto& s = cache[{n, lv}];
  if (s.poses.empty()) {
    const auto o = level(lv);
    s = test::noisy_stream(n, o.tol / 3.5, o.angle_tol_deg / 3.5, 17);
  }
  return s;
}

void BM_FitPoses(benchmark::State& st) {
  const std::size_t n = static_cast<std::size_t>(st.range(0));
  const int lv = static_cast<int>(st.range(1));
  const auto& s = stream(n, lv);
  std::size_t points = 0;
  double pos = 0, ang = 0;
  for (auto _ : st) {
    const auto f = kernel::fit_bspline(s.poses, s.t, level(lv));
    points = f.motion.curve.curve.ctrl().size();
    pos = f.report.worst_position;
    ang = f.report.worst_angle_deg;
    benchmark::DoNotOptimize(points);
  }
  st.counters["poses"] = static_cast<double>(n);
  st.counters["control_points"] = static_cast<double>(points);
  st.counters["poses_per_control_point"] = static_cast<double>(n) / static_cast<double>(points);
  st.counters["worst_mm"] = pos;
  st.counters["worst_deg"] = ang;
}
BENCHMARK(BM_FitPoses)
    ->ArgsProduct({{1000, 10000, 100000}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// The three source motions of test::sources (a Bezier, a B-spline on uneven parameters, a KKS
/// quaternion spline), sampled at n poses with bounded noise (below a third of the
/// tolerances) or Gaussian noise (standard deviations a quarter of them, so a few poses of a
/// long stream lie beyond the tolerance), fitted at level 0, at the poses or `--between`.
/// A stream the fit refuses is reported as refused, with the reason and the time it took.
void BM_FitSources(benchmark::State& st) {
  const std::size_t n = static_cast<std::size_t>(st.range(0));
  const auto source = static_cast<std::size_t>(st.range(1));
  const bool gaussian = st.range(2) != 0, between = st.range(3) != 0;
  static const auto all = test::sources();
  kernel::FitOptions o = level(0);
  o.between = between;
  const test::Stream s =
      gaussian ? test::samples(all[source].second, n, o.tol / 4, o.angle_tol_deg / 4, true)
               : test::samples(all[source].second, n, o.tol / 3.5, o.angle_tol_deg / 3.5);
  std::size_t points = 0;
  double pos = 0, bound = 0;
  std::string refused;
  for (auto _ : st) {
    try {
      const auto f = kernel::fit_bspline(s.poses, s.t, o);
      points = f.motion.curve.curve.ctrl().size();
      pos = f.report.worst_position;
      bound = f.report.between_position_bound;
    } catch (const Error& e) {  // the time until the refusal, and its reason
      refused = e.what();
    }
    benchmark::DoNotOptimize(points);
  }
  if (!refused.empty()) {  // the message's end names the pose that cannot be met
    const auto at = refused.find("split; ");
    st.SetLabel(std::string(all[source].first) + (gaussian ? ", gaussian" : ", bounded") +
                (between ? ", between" : "") + ", refused (exit 3): " +
                (at == std::string::npos ? refused.substr(0, 120) : refused.substr(at + 7)));
    return;
  }
  st.SetLabel(std::string(all[source].first) + (gaussian ? ", gaussian" : ", bounded") +
              (between ? ", between" : ""));
  st.counters["poses_per_control_point"] = static_cast<double>(n) / static_cast<double>(points);
  st.counters["control_points"] = static_cast<double>(points);
  st.counters["worst_mm"] = pos;
  if (between) st.counters["between_bound_mm"] = bound;
}
BENCHMARK(BM_FitSources)
    ->ArgsProduct({{1000, 10000, 100000}, {0, 1, 2}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

void BM_Peer_InterpolateAll(benchmark::State& st) {
  const std::size_t n = static_cast<std::size_t>(st.range(0));
  const auto& s = stream(n, static_cast<int>(st.range(1)));
  std::size_t points = 0;
  for (auto _ : st) {
    const auto m = kernel::interpolate_bspline(s.poses, s.t, kernel::SplineOptions{});
    points = m.curve.curve.ctrl().size();
    benchmark::DoNotOptimize(points);
  }
  st.counters["poses"] = static_cast<double>(n);
  st.counters["control_points"] = static_cast<double>(points);
}
BENCHMARK(BM_Peer_InterpolateAll)
    ->ArgsProduct({{1000, 10000, 100000}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
