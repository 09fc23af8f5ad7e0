// sweep/src/volume_written.cpp: what is written is what was certified (docs/guide/volume.md,
// "What is written is what was certified"): float32 rounding of a binary STL's vertices,
// and the closedness of the mesh measured on the coordinates a reader of the file sees.
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <qmotion/kernel/error.hpp>

#include "volume_detail.hpp"

namespace qmotion::sweep::mesher {

double float32_rounding(double largest) {
  return std::sqrt(3.0) * std::ldexp(largest, -24) * (1 + 1e-6);
}

double float32_written(const Eigen::AlignedBox3d& box, double T, const VolumeRounding& rounding) {
  // Every vertex lies within T of V, which the box holds.
  const double reach = box.min().cwiseAbs().cwiseMax(box.max().cwiseAbs()).maxCoeff() + T;
  if (!(rounding.scale > 0) || !(reach * rounding.scale < 1e30))
    throw Error(Errc::invalid_input, "volume: the coordinates do not fit a float32 STL");
  return float32_rounding(reach);
}

void round_to_float32(std::vector<Eigen::Vector3d>& vertices, double scale) {
  tbb::parallel_for(std::size_t(0), vertices.size(), [&](std::size_t v) {
    for (int k = 0; k < 3; ++k)
      vertices[v](k) = static_cast<double>(static_cast<float>(scale * vertices[v](k))) / scale;
  });
}

bool closed_as_written(const std::vector<Eigen::Vector3d>& vertices,
                       const std::vector<std::array<int, 3>>& triangles) {
  const std::size_t n = vertices.size();
  if (triangles.empty() || n > std::size_t(INT32_MAX)) return false;
  // Weld: vertices with equal coordinates get the id of the first of them in sorted order.
  std::vector<int> order(n), id(n);
  std::iota(order.begin(), order.end(), 0);
  auto less = [&](int a, int b) {
    const auto &p = vertices[static_cast<std::size_t>(a)],
               &q = vertices[static_cast<std::size_t>(b)];
    return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
  };
  tbb::parallel_sort(order.begin(), order.end(), less);
  for (std::size_t i = 0; i < n; ++i) {
    const int v = order[i];
    const bool same = i > 0 && vertices[static_cast<std::size_t>(order[i - 1])] ==
                                   vertices[static_cast<std::size_t>(v)];
    id[static_cast<std::size_t>(v)] = same ? id[static_cast<std::size_t>(order[i - 1])] : v;
  }
  // Directed edges by their first vertex (counting sort), then each must occur once and its
  // reverse once.
  std::vector<std::uint32_t> start(n + 1, 0);
  for (const auto& t : triangles)
    for (int v : t) {
      if (v < 0 || static_cast<std::size_t>(v) >= n) return false;
      ++start[static_cast<std::size_t>(id[static_cast<std::size_t>(v)]) + 1];
    }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> to(3 * triangles.size());
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = id[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])],
                b = id[static_cast<std::size_t>(t[static_cast<std::size_t>((k + 1) % 3)])];
      if (a == b) return false;  // a triangle that welding made degenerate
      to[fill[static_cast<std::size_t>(a)]++] = b;
    }
  std::atomic<bool> closed{true};
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t a) {
    for (std::uint32_t e = start[a]; e < start[a + 1] && closed; ++e) {
      const int b = to[e];
      auto count = [&](std::size_t from, int target) {
        return std::count(to.begin() + start[from], to.begin() + start[from + 1], target);
      };
      if (count(a, b) != 1 || count(static_cast<std::size_t>(b), static_cast<int>(a)) != 1)
        closed = false;
    }
  });
  return closed;
}

}  // namespace qmotion::sweep::mesher
