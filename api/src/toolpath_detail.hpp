// api/src/toolpath_detail.hpp: what the toolpath's computations share: number printing (the
// formats' own, io/toolpath_files.hpp), arc length of the exact trajectory, and the NURBS
// toolpath.
#pragma once
#include <algorithm>
#include <cmath>
#include <qmotion/api/toolpath.hpp>
#include <qmotion/cam/controller.hpp>
#include <qmotion/cam/tool_trajectories.hpp>
#include <qmotion/io/toolpath_files.hpp>
#include <qmotion/sweep/solid.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace qmotion::toolpath_detail {

constexpr double kPi = 3.14159265358979323846;

using io::kNurbsDigits;
using io::rounded;

/// The length of the exact trajectory over [t0, t1] (Gauss-Legendre on the velocity).
inline double arc_length(const cam::ToolTrajectories& src, double t0, double t1) {
  double len = 0;
  for (const auto& [node, w] : sweep::detail::gauss_legendre())
    len += w * (t1 - t0) / 2 * src.exact_velocity((t0 + t1) / 2 + (t1 - t0) / 2 * node).norm();
  return len;
}

/// What tp's file states besides its blocks.
inline io::ToolpathHeader header(const Toolpath& tp) {
  io::ToolpathHeader h;
  h.units = tp.units;
  h.feed = tp.feed;
  h.chord_tol = tp.chord_tol;
  h.inverse_time = tp.feed_mode == "inverse-time";
  h.machine = tp.machine;
  h.axis_limits = tp.axis_limits;
  return h;
}

/// `--nurbs`: Fanuc G06.2 blocks of the trajectory into os (toolpath_nurbs.cpp).
void nurbs_toolpath(Toolpath& tp, const cam::ToolTrajectories& src, double k, double tol,
                    const cam::PathMode& mode, std::ostringstream& os);

}  // namespace qmotion::toolpath_detail
