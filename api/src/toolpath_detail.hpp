// api/src/toolpath_detail.hpp: what the toolpath writers share: number printing, arc
// length of the exact trajectory, and the NURBS G-code writer.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <qmotion/api/toolpath.hpp>
#include <qmotion/cam/controller.hpp>
#include <qmotion/cam/tool_trajectories.hpp>
#include <qmotion/sweep/solid.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace qmotion::toolpath_detail {

constexpr double kPi = 3.14159265358979323846;

/// x printed with `digits` decimals (no "-0").
inline std::string num(double x, int digits = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits,
                std::abs(x) < 0.5 * std::pow(10.0, -digits) ? 0.0 : x);
  return buf;
}

/// x rounded to `digits` decimals: the value `num(x, digits)` reads back as.
inline double rounded(double x, int digits) {
  const double q = std::pow(10.0, digits);
  return std::round(x * q) / q;
}

/// The length of the exact trajectory over [t0, t1] (Gauss-Legendre on the velocity).
inline double arc_length(const cam::ToolTrajectories& src, double t0, double t1) {
  double len = 0;
  for (const auto& [node, w] : sweep::detail::gauss_legendre())
    len += w * (t1 - t0) / 2 * src.exact_velocity((t0 + t1) / 2 + (t1 - t0) / 2 * node).norm();
  return len;
}

/// The fewest decimals (at least `least`) that print every value so that it reads back
/// unchanged.
inline int exact_decimals(const std::vector<double>& v, int least) {
  for (int d = least; d < 17; ++d)
    if (std::all_of(v.begin(), v.end(),
                    [&](double x) { return std::strtod(num(x, d).c_str(), nullptr) == x; }))
      return d;
  return 17;
}

/// Decimals of the NURBS G-code's coordinates and weights.
constexpr int kNurbsDigits = 6;

/// The G1 program into os in tp's dialect: the header comments (what is certified, the path
/// mode's assumption), units, the path mode, the feed mode, the blocks
/// (toolpath_gcode.cpp). `feeds`: inverse time's F per block and its decimals.
void write_gcode(const Toolpath& tp, const std::vector<std::pair<double, int>>& feeds,
                 int axis_digits, cam::Dialect dialect, const cam::PathMode& mode,
                 std::ostringstream& os);

/// `--nurbs`: Fanuc G06.2 blocks of the trajectory into os (toolpath_nurbs.cpp).
void nurbs_toolpath(Toolpath& tp, const cam::ToolTrajectories& src, double k, double tol,
                    const cam::PathMode& mode, std::ostringstream& os);

}  // namespace qmotion::toolpath_detail
