// `qmotion verify` (docs/guide/verify.md): a 3-axis finishing program of a ball cutter (D 6)
// over a 100 x 100 mm part, 101 G1 blocks a pass, at T = 0.01 mm (finishing_scene.hpp; the
// part on a 200 x 200 grid, 80 000 triangles). Counters: blocks, distance queries, the gouge's
// certified upper bound.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <qmotion/qmotion.hpp>
#include <string>

#include "finishing_scene.hpp"

namespace {

/// The program of `passes` passes over the part, written to a folder of this process.
qmotion::VerifyOptions finishing(int passes, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  qmotion::VerifyOptions o;
  o.part = (dir / "part.obj").string();
  o.program = (dir / "finish.ngc").string();
  o.tool = "cutter:ball,6,40";
  o.tol = 0.01;
  qmotion::bench::write_part(o.part, 200);
  qmotion::bench::write_program(o.program, passes, 3);
  return o;
}

std::filesystem::path scratch() {
  return std::filesystem::temp_directory_path() /
         ("qmotion_bench_verify_" + std::to_string(::getpid()));
}

/// Passes of 101 G1 blocks (100: 10^4 feeds, the goal), T = 0.01 mm.
void BM_VerifyFinishing(benchmark::State& state) {
  const qmotion::VerifyOptions o = finishing(static_cast<int>(state.range(0)), scratch());
  qmotion::VerifyReport r;
  for (auto _ : state) {
    r = qmotion::verify(o);
    // (Not on a double: under GCC, DoNotOptimize's "+m,r" may hand a double through a
    // general register and back, and the counter below read 49.5 for 0.154.)
    benchmark::DoNotOptimize(r.gouges.data());
  }
  state.counters["blocks"] = static_cast<double>(r.moves);
  state.counters["queries"] = static_cast<double>(r.queries);
  state.counters["gouge_upper_mm"] = r.gouge_upper;
  state.counters["gouge_lower_mm"] = r.gouge_lower;
  state.counters["certified"] = r.settled ? 1 : 0;
  std::filesystem::remove_all(scratch());
}
BENCHMARK(BM_VerifyFinishing)
    ->ArgName("passes")
    ->Arg(2)
    ->Arg(100)
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

/// The same with the stock left: a box from the part's bottom to 2 mm above its highest
/// point (docs/guide/verify.md, "Stock left"). Counters: the largest stock left's interval
/// and the mean's, and the cells evaluated.
void BM_VerifyStockLeft(benchmark::State& state) {
  qmotion::VerifyOptions o = finishing(static_cast<int>(state.range(0)), scratch());
  o.stock = "box:-50,-50,-40,50,50,-4";
  qmotion::VerifyReport r;
  for (auto _ : state) {
    r = qmotion::verify(o);
    benchmark::DoNotOptimize(r.gouges.data());
  }
  state.counters["blocks"] = static_cast<double>(r.moves);
  state.counters["cells"] = static_cast<double>(r.stock->cells);
  state.counters["max_lower_mm"] = r.stock->max_lower;
  state.counters["max_upper_mm"] = r.stock->max_upper;
  state.counters["mean_lower_mm"] = r.stock->mean_lower;
  state.counters["mean_upper_mm"] = r.stock->mean_upper;
  state.counters["max_certified"] = r.stock->max_settled ? 1 : 0;
  std::filesystem::remove_all(scratch());
}
BENCHMARK(BM_VerifyStockLeft)
    ->ArgName("passes")
    ->Arg(2)
    ->Arg(100)
    ->Unit(benchmark::kSecond)
    ->Iterations(1);
}  // namespace

BENCHMARK_MAIN();
