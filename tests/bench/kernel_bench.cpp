// tests/bench/kernel_bench.cpp: cost of the kernel's building blocks (Google Benchmark).
#include <benchmark/benchmark.h>

#include <qmotion/kernel/motion.hpp>
#include <random>

namespace {
using namespace qmotion::kernel;

std::vector<DualQuaternion<double>> random_dq(int n, unsigned seed) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<DualQuaternion<double>> c;
  for (int i = 0; i < n; ++i) {
    DualQuaternion<double> q;
    for (int k = 0; k < 8; ++k) q[k] = u(g);
    c.push_back(q);
  }
  return c;
}

void BM_DeCasteljauDualQuaternion(benchmark::State& st) {
  const Bernstein<DualQuaternion<double>> p(random_dq(static_cast<int>(st.range(0)) + 1, 1));
  double t = 0.37;
  for (auto _ : st) benchmark::DoNotOptimize(evaluate(p, t));
}
BENCHMARK(BM_DeCasteljauDualQuaternion)->Arg(4)->Arg(8)->Arg(16);

void BM_BernsteinProductDualQuaternion(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const Bernstein<DualQuaternion<double>> p(random_dq(n + 1, 2)), q(random_dq(n + 1, 3));
  for (auto _ : st) benchmark::DoNotOptimize(product(p, q));
}
BENCHMARK(BM_BernsteinProductDualQuaternion)->Arg(4)->Arg(8);

void BM_MatrixSplineOfMotion(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const QMotion<double> m{Basis::bezier,
                          BSpline<DualQuaternion<double>>::from_bezier(
                              Bernstein<DualQuaternion<double>>(random_dq(n + 1, 4)))};
  for (auto _ : st) benchmark::DoNotOptimize(matrix_spline(m));
}
BENCHMARK(BM_MatrixSplineOfMotion)->Arg(4)->Arg(8);

void BM_SplineProduct(benchmark::State& st) {
  const int pieces = static_cast<int>(st.range(0));
  std::vector<double> k(4, 0.0);
  for (int i = 1; i < pieces; ++i) k.push_back(static_cast<double>(i) / pieces);
  k.insert(k.end(), 4, 1.0);
  const auto c = random_dq(static_cast<int>(k.size()) - 4, 5);
  const auto s = BSpline<DualQuaternion<double>>::make(3, k, c);
  for (auto _ : st) benchmark::DoNotOptimize(product(s, s));
}
BENCHMARK(BM_SplineProduct)->Arg(10)->Arg(100);

}  // namespace

BENCHMARK_MAIN();
