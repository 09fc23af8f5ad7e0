// tests/surface_util.hpp: random rational surfaces for the tests of what writes or cuts them.
#pragma once
#include <cmath>
#include <qmotion/sweep/nurbs.hpp>
#include <random>
#include <utility>
#include <vector>

namespace qmotion::test {

/// A rational surface on the given knots: pole (i, j) near (i, j, 0), jittered by 0.3 and up to
/// 2 in z, weights in [0.4, 1.4), all drawn from the seed.
inline sweep::NurbsSurface<double> random_surface(int degree_u, std::vector<double> knots_u,
                                                  int degree_v, std::vector<double> knots_v,
                                                  unsigned seed) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  sweep::NurbsSurface<double> s{degree_u, degree_v, std::move(knots_u), std::move(knots_v), {}, {}};
  const std::size_t rows = s.knots_u.size() - std::size_t(degree_u) - 1,
                    cols = s.knots_v.size() - std::size_t(degree_v) - 1;
  s.points.assign(rows, {});
  s.weights.assign(rows, {});
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t j = 0; j < cols; ++j) {
      s.points[i].emplace_back(double(i) + 0.3 * u(g), double(j) + 0.3 * u(g), 2 * u(g));
      s.weights[i].push_back(0.4 + std::abs(u(g)));
    }
  return s;
}

}  // namespace qmotion::test
