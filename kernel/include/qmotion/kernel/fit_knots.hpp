// <qmotion/kernel/fit_knots.hpp>: interior knots for a fit (motion_fit.hpp): whether every span
// holds enough parameters, and knots that equidistribute a density.
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

namespace qmotion::kernel::detail {

/// The interior knots x increase strictly and each span holds at least `least` parameters.
inline bool spans_hold(const std::vector<double>& x, const std::vector<double>& t,
                       std::size_t least) {
  std::size_t i = 0;
  for (std::size_t s = 0; s <= x.size(); ++s) {
    const std::size_t i0 = i;
    while (i < t.size() && (s == x.size() || t[i] < x[s])) ++i;
    if (i - i0 < least || (s > 0 && s < x.size() && !(x[s - 1] < x[s]))) return false;
  }
  return true;
}

/// A knot density: piecewise constant, `weight[s]` knots over [edge[s], edge[s + 1]].
struct KnotDensity {
  std::vector<double> edge, weight;
};

/// `count` interior knots that equidistribute the density; ok = false when a span would
/// hold fewer than `least` poses.
inline std::vector<double> equidistributed(const KnotDensity& k, const std::vector<double>& t,
                                           std::size_t count, std::size_t least, bool* ok) {
  std::vector<double> F(k.weight.size() + 1, 0.0);  // cumulative at the edges
  for (std::size_t s = 0; s < k.weight.size(); ++s) F[s + 1] = F[s] + k.weight[s];
  std::vector<double> x;
  for (std::size_t j = 1; j <= count; ++j) {
    const double target = F.back() * static_cast<double>(j) / static_cast<double>(count + 1);
    const std::size_t s = std::min(
        static_cast<std::size_t>(std::upper_bound(F.begin(), F.end(), target) - F.begin()) - 1,
        k.weight.size() - 1);
    const double frac = (target - F[s]) / (F[s + 1] - F[s]);
    x.push_back(k.edge[s] + std::clamp(frac, 0.0, 1.0) * (k.edge[s + 1] - k.edge[s]));
  }
  *ok = spans_hold(x, t, least);
  return x;
}

}  // namespace qmotion::kernel::detail
