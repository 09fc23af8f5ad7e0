// `qmotion verify` (docs/guide/verify.md): a 3-axis finishing program of a ball cutter (D 6)
// over a 100 x 100 mm part, 101 G1 blocks a pass, at T = 0.01 mm. The part is the height
// field z = 4 sin(x / 12) cos(y / 17) - 10 on a 200 x 200 grid (80 000 triangles), closed by
// sides and a bottom at z = -40; each block ends where a ball dropped onto the height field
// touches it (sampled on 12 rings of 48 points), so the chords between them may gouge by
// their sag. Counters: blocks, distance queries, the gouge's certified upper bound.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <qmotion/qmotion.hpp>
#include <string>

namespace {

double height(double x, double y) { return 4 * std::sin(x / 12) * std::cos(y / 17) - 10; }

/// The tip of a ball of radius r dropped onto the height field above (x, y).
double drop(double x, double y, double r) {
  const double pi = 3.14159265358979323846;
  double best = height(x, y);
  for (int ring = 1; ring <= 12; ++ring)
    for (int k = 0; k < 48; ++k) {
      const double s = r * ring / 12, a = 2 * pi * k / 48;
      const double lift = std::sqrt(std::max(0.0, r * r - s * s)) - r;
      best = std::max(best, height(x + s * std::cos(a), y + s * std::sin(a)) + lift);
    }
  return best;
}

void write_part(const std::string& path, int n) {
  std::ofstream o(path);
  auto at = [n](int i, int j) { return 1 + j * (n + 1) + i; };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -50 + 100.0 * i / n, y = -50 + 100.0 * j / n;
      o << "v " << x << ' ' << y << ' ' << height(x, y) << '\n';
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      o << "f " << at(i, j) << ' ' << at(i + 1, j) << ' ' << at(i + 1, j + 1) << '\n';
      o << "f " << at(i, j) << ' ' << at(i + 1, j + 1) << ' ' << at(i, j + 1) << '\n';
    }
  // The rim, counterclockwise seen from above, its copy on the bottom, and a fan under it.
  std::vector<std::pair<int, int>> rim;
  for (int i = 0; i < n; ++i) rim.emplace_back(i, 0);
  for (int j = 0; j < n; ++j) rim.emplace_back(n, j);
  for (int i = n; i > 0; --i) rim.emplace_back(i, n);
  for (int j = n; j > 0; --j) rim.emplace_back(0, j);
  const int first = (n + 1) * (n + 1) + 1, m = static_cast<int>(rim.size());
  for (const auto& [i, j] : rim)
    o << "v " << -50 + 100.0 * i / n << ' ' << -50 + 100.0 * j / n << " -40\n";
  o << "v 0 0 -40\n";
  for (int k = 0; k < m; ++k) {
    const int k1 = (k + 1) % m;
    const int t0 =
        at(rim[static_cast<std::size_t>(k)].first, rim[static_cast<std::size_t>(k)].second);
    const int t1 =
        at(rim[static_cast<std::size_t>(k1)].first, rim[static_cast<std::size_t>(k1)].second);
    o << "f " << t0 << ' ' << first + k << ' ' << first + k1 << '\n';
    o << "f " << t0 << ' ' << first + k1 << ' ' << t1 << '\n';
    o << "f " << first + m << ' ' << first + k1 << ' ' << first + k << '\n';
  }
}

void write_program(const std::string& path, int passes, double r) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  std::fprintf(f, "G21 G90 G17\nG0 Z20\n");
  for (int p = 0; p < passes; ++p) {
    const double y = passes > 1 ? -49.5 + 99.0 * p / (passes - 1) : 0;
    for (int i = 0; i <= 100; ++i) {
      const double x = p % 2 ? 45 - 0.9 * i : -45 + 0.9 * i;
      if (i == 0)
        std::fprintf(f, "G0 X%.4f Y%.4f\nG1 Z%.4f F2000\n", x, y, drop(x, y, r));
      else
        std::fprintf(f, "G1 X%.4f Y%.4f Z%.4f\n", x, y, drop(x, y, r));
    }
    std::fprintf(f, "G0 Z20\n");
  }
  std::fprintf(f, "M2\n");
  std::fclose(f);
}

/// The program of `passes` passes over the part, written to a folder of this process.
qmotion::VerifyOptions finishing(int passes, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  qmotion::VerifyOptions o;
  o.part = (dir / "part.obj").string();
  o.program = (dir / "finish.ngc").string();
  o.tool = "cutter:ball,6,40";
  o.tol = 0.01;
  write_part(o.part, 200);
  write_program(o.program, passes, 3);
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
