// tests/bench/qspline_bench.cpp: the non-rational schemes: time to build each from 5, 100
// and 10^4 keys (linear growth expected), and orientations evaluated per second.
// The papers' Matlab figures: KKS 0.36 s for 401 frames, quintic 0.087 s for 401 frames,
// quartic 0.054 s for 101 frames (BM_Frames: build from 10 keys, then evaluate the frames).
// BM_Fit: the fitted geometry (sweep::fit_frames, degree 5) of a 10-key spline for the
// corners of a 2 x 1 rectangle, at 1e-3, 1e-6 and 1e-9 of the size; counters: poles, spans.
#include <benchmark/benchmark.h>

#include <cmath>
#include <qmotion/kernel/qspline.hpp>
#include <qmotion/sweep/fit.hpp>
#include <vector>

namespace {
using qmotion::kernel::Quaternion;
using qmotion::kernel::QuaternionSpline;

struct Keys {
  std::vector<Quaternion<double>> q;
  std::vector<Eigen::Vector3d> p;
};

Keys keys(int n) {  // 0.5 rad key distance, the axis turning by pi/2 in the x-y plane
  Keys k;
  k.q.push_back(Quaternion<double>(1, 0, 0, 0));
  for (int i = 0; i < n; ++i) {
    if (i) {
      const Eigen::Vector3d axis(std::cos(1.5708 * i), std::sin(1.5708 * i), 0);
      k.q.push_back(k.q.back() * qmotion::kernel::from_axis_angle(axis, 1.0));
    }
    k.p.emplace_back(i, std::sin(0.3 * i), 0);
  }
  return k;
}

QuaternionSpline build(int scheme, const Keys& k) {
  const double b = static_cast<double>(k.q.size() - 1);
  if (scheme == 0) return qmotion::kernel::kks_spline(k.q, k.p, 0, b);
  if (scheme == 1) {
    std::vector<double> u;
    for (std::size_t i = 0; i < k.q.size(); ++i) u.push_back(static_cast<double>(i));
    return qmotion::kernel::quintic_spline(k.q, k.p, u, std::vector<double>(k.q.size(), 0.5));
  }
  return qmotion::kernel::quartic_spline(k.q, k.p, 0, b);
}

const char* kNames[] = {"kks", "quintic", "quartic"};

void BM_Build(benchmark::State& state) {
  const Keys k = keys(static_cast<int>(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(build(static_cast<int>(state.range(0)), k));
  state.SetLabel(kNames[state.range(0)]);
  state.SetItemsProcessed(state.iterations() * state.range(1));
}
BENCHMARK(BM_Build)->ArgsProduct({{0, 1, 2}, {5, 100, 10000}})->Unit(benchmark::kMicrosecond);

void BM_Orientations(benchmark::State& state) {
  const QuaternionSpline s = build(static_cast<int>(state.range(0)), keys(100));
  double u = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.rotation(u));
    u += 0.37;
    if (u > s.b()) u -= s.b();
  }
  state.SetLabel(kNames[state.range(0)]);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Orientations)->Arg(0)->Arg(1)->Arg(2);

void BM_Frames(benchmark::State& state) {
  const Keys k = keys(10);
  const int frames = static_cast<int>(state.range(1));
  for (auto _ : state) {
    const QuaternionSpline s = build(static_cast<int>(state.range(0)), k);
    for (int f = 0; f < frames; ++f) benchmark::DoNotOptimize(s.rotation(s.b() * f / (frames - 1)));
  }
  state.SetLabel(kNames[state.range(0)]);
}
BENCHMARK(BM_Frames)->Args({0, 401})->Args({1, 401})->Args({2, 101})->Unit(benchmark::kMicrosecond);

void BM_Fit(benchmark::State& state) {
  const QuaternionSpline s = build(static_cast<int>(state.range(0)), keys(10));
  const std::vector<Eigen::Vector3d> corners{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  qmotion::sweep::FrameFitOptions o;
  o.tol = std::pow(10.0, -static_cast<double>(state.range(1))) * 10;  // the size is about 10
  qmotion::sweep::FrameFit f;
  for (auto _ : state) f = qmotion::sweep::fit_frames(s, corners, o);
  state.counters["poles"] = static_cast<double>(f.matrix.ctrl().size());
  state.counters["spans"] = f.spans;
  state.SetLabel(std::string(kNames[state.range(0)]) + " tol 1e-" + std::to_string(state.range(1)));
}
BENCHMARK(BM_Fit)->ArgsProduct({{0, 1, 2}, {3, 6, 9}})->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
