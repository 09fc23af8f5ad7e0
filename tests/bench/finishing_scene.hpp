// The finishing scene of verify's benchmark and its peers (tests/bench/verify_bench.cpp,
// verify_peers.cpp): a 100 x 100 mm part, the height field z = 4 sin(x / 12) cos(y / 17) - 10
// on an n x n grid, closed by sides and a bottom at z = -40, and a ball cutter's program of
// 101 G1 blocks a pass, each block ending where the ball dropped onto the height field
// touches it (sampled on 12 rings of 48 points), so that the chords between them may gouge
// by their sag.
#pragma once
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace qmotion::bench {

inline double height(double x, double y) { return 4 * std::sin(x / 12) * std::cos(y / 17) - 10; }

/// The tip of a ball of radius r dropped onto the height field above (x, y).
inline double drop(double x, double y, double r) {
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

inline void write_part(const std::string& path, int n) {
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

/// `passes` passes along x from -45 to 45 (y evenly from -49.5 to 49.5), each of `blocks`
/// G1 blocks.
inline void write_program(const std::string& path, int passes, double r, int blocks = 100) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  std::fprintf(f, "G21 G90 G17\nG0 Z20\n");
  for (int p = 0; p < passes; ++p) {
    const double y = passes > 1 ? -49.5 + 99.0 * p / (passes - 1) : 0;
    for (int i = 0; i <= blocks; ++i) {
      const double step = 90.0 / blocks, x = p % 2 ? 45 - step * i : -45 + step * i;
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

}  // namespace qmotion::bench
