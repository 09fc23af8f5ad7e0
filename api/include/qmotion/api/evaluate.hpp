// <qmotion/api/evaluate.hpp>: batch evaluation of our NURBS surfaces on parameter grids, on every
// core.
#pragma once
#include <Eigen/Core>
#include <qmotion/sweep/nurbs.hpp>
#include <vector>

namespace qmotion {

/// S(us[i], vs[j]) for every pair, row-major (index i * vs.size() + j). Rows are shared out
/// over the cores (oneTBB) when `parallel` and the grid is large enough to pay; each row
/// costs one contraction of the poles with the u basis, each point degree_v + 1 terms.
/// Errc::invalid_input when a parameter is outside the surface's rectangle or not finite.
std::vector<Eigen::Vector3d> evaluate_grid(const sweep::NurbsSurface<double>& s,
                                           const std::vector<double>& us,
                                           const std::vector<double>& vs, bool parallel = true);

}  // namespace qmotion
