// tests/bench/interpolation_bench.cpp: time to interpolate 5, 10 and 20 poses with each
// rotation x translation method (Bezier motions, double).
#include <benchmark/benchmark.h>

#include <qmotion/kernel/interpolation.hpp>
#include <random>

namespace {
using namespace qmotion::kernel;

/// Poses along a smooth screw-like path with a wobble: well-conditioned for Bezier
/// interpolation at uniform parameters.
std::vector<Pose<double>> path_poses(int count) {
  std::vector<Pose<double>> p;
  for (int i = 0; i < count; ++i) {
    const double s = static_cast<double>(i) / (count - 1);
    Pose<double> q;
    q.t = s;
    q.position = Eigen::Vector3d(100 * s, 30 * std::sin(3 * s), 20 * s * s);
    q.rotation = from_axis_angle(Eigen::Vector3d(0.3, 1.0, 0.2 + s), 2.0 * s);
    p.push_back(q);
  }
  return p;
}

void BM_Interpolate(benchmark::State& st) {
  const int count = static_cast<int>(st.range(0));
  InterpolationOptions o;
  o.rotation = static_cast<RotationMethod>(st.range(1));
  o.translation = static_cast<TranslationMethod>(st.range(2));
  const auto poses = path_poses(count);
  std::vector<double> t;
  for (const auto& p : poses) t.push_back(*p.t);
  st.SetLabel(std::string(to_string(o.rotation)) + "+" + to_string(o.translation));
  try {
    for (auto _ : st) benchmark::DoNotOptimize(interpolate_bezier(poses, t, o));
  } catch (const qmotion::Error& e) {  // a refusal (e.g. TRT with many poses) is a result too
    st.SkipWithError(e.what());
  }
}
BENCHMARK(BM_Interpolate)
    ->ArgsProduct({{5, 10, 20}, {0, 1, 2}, {0, 1, 2}})
    ->ArgNames({"poses", "rot", "trans"})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
