// tests/bench/spline_bench.cpp: spline motions for 10^2, 10^3, 10^4 poses (target: linear
// growth, 10^4 poses under 50 ms) and the kinematic surface of a 10^3-pose motion.
#include <benchmark/benchmark.h>

#include <qmotion/kernel/spline_interpolation.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <qmotion/sweep/surface.hpp>
#include <random>

namespace {
using namespace qmotion;

std::vector<kernel::Pose<double>> poses(int n, std::vector<double>& t) {
  std::mt19937 g(1);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<kernel::Pose<double>> P;
  t.clear();
  for (int i = 0; i < n; ++i) {
    kernel::Pose<double> p;
    p.position = Eigen::Vector3d(u(g), u(g), u(g)) * 100;
    p.rotation = kernel::from_axis_angle(Eigen::Vector3d(u(g), u(g), u(g)), 3 * u(g));
    P.push_back(p);
    t.push_back(i);
  }
  return P;
}

void BM_BSplineMotion(benchmark::State& st) {
  std::vector<double> t;
  const auto P = poses(static_cast<int>(st.range(0)), t);
  for (auto _ : st)
    benchmark::DoNotOptimize(kernel::interpolate_bspline(P, t, kernel::SplineOptions{}));
  st.SetComplexityN(st.range(0));
}
BENCHMARK(BM_BSplineMotion)
    ->RangeMultiplier(10)
    ->Range(100, 10000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity(benchmark::oN);

void BM_C1Motion(benchmark::State& st) {
  std::vector<double> t;
  const auto P = poses(static_cast<int>(st.range(0)), t);
  for (auto _ : st)
    benchmark::DoNotOptimize(kernel::interpolate_c1(P, t, kernel::TranslationMethod::tr));
  st.SetComplexityN(st.range(0));
}
BENCHMARK(BM_C1Motion)
    ->RangeMultiplier(10)
    ->Range(100, 10000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity(benchmark::oN);

void BM_SurfaceOf1000PoseMotion(benchmark::State& st) {  // circle profile: 9 poles along v
  std::vector<double> t;
  const auto P = poses(1000, t);
  const auto r = kernel::interpolate_bspline(P, t, kernel::SplineOptions{});
  const auto prof = sweep::circle(5.0);
  for (auto _ : st) benchmark::DoNotOptimize(sweep::kinematic_nurbs(r, prof));
}
BENCHMARK(BM_SurfaceOf1000PoseMotion)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
