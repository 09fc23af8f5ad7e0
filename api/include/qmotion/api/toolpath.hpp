// <qmotion/api/toolpath.hpp>: CAM output (`qmotion toolpath`): cutter-location points with
// certified chord and axis-angle bounds, written as APT CL data, CSV or G-code (3-axis, or a
// table-tilting A/C machine).
#pragma once
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <qmotion/cam/toolpath.hpp>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/motion.hpp>
#include <string>
#include <vector>

namespace qmotion {

struct ToolpathOptions {
  std::string output;                               ///< .apt/.cls, .csv, .nc/.ngc
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< tool reference point (moving space)
  Eigen::Vector3d axis = Eigen::Vector3d(0, 0, 1);  ///< tool axis (moving space), not zero
  double chord_tol = -1;                            ///< required: > 0, at most 1e6 (output unit)
  double angle_tol_deg = 0.5;                       ///< axis tolerance in degrees, in (0, 90)
  double max_step = 0;                              ///< chord length cap (0: none)
  double feed = 1000;                               ///< per minute, in the output unit
  bool arc_length = false;                          ///< CSV: add the arc length s
  std::string rotary;   ///< G-code: "" (3-axis) or "ac" (table-tilting A/C)
  bool c_hold = false;  ///< --rotary ac: keep the previous C where the axis is vertical
  /// G-code: the trajectory as Fanuc-style G06.2 NURBS blocks of degree <= 3 (exact where
  /// the trajectory has that degree, else a cubic fit) within chord_tol, certified (3-axis).
  bool nurbs = false;
  /// The unit of the output and of chord_tol, max_step and feed (default: the motion's;
  /// APT and G-code: mm or in, a motion in another unit is written in mm).
  std::string units;
};

/// The NURBS of `--nurbs` as written.
struct NurbsToolpath {
  /// Homogeneous poles (w, w x) in the output unit and knots on [0, 1], as written.
  kernel::BSpline<Eigen::Vector4d> curve =
      kernel::BSpline<Eigen::Vector4d>::make(0, {0.0, 1.0}, {Eigen::Vector4d(1, 0, 0, 0)});
  std::vector<double> t_knots;  ///< the knots in the motion's parameter
  bool exact = false;           ///< the trajectory itself, only rounded
  int spans = 0;
  double max_deviation_bound = 0;     ///< certified (plus the fit for a quaternion spline)
  double max_deviation_measured = 0;  ///< dense evaluation against the exact motion
};

/// What was written: the points with their parameters and machine angles, and the report.
struct Toolpath {
  std::vector<cam::ToolpathSample> samples;  ///< in the output unit (none with nurbs)
  std::optional<NurbsToolpath> nurbs;        ///< options.nurbs: the curve written
  std::vector<double> a_deg, c_deg;          ///< --rotary ac: machine angles per sample
  double path_length = 0;                    ///< of the exact trajectory (Gauss-Legendre)
  double max_chord_bound = 0;                ///< certified (plus the fit for a quaternion spline)
  double max_chord_measured = 0;             ///< dense evaluation, 32 per segment
  double max_angle_bound_deg = 0;
  std::string units;  ///< the output unit
  nlohmann::json report() const;
  double chord_tol = 0, angle_tol_deg = 0, feed = 0;
  std::string path;
};

/// The toolpath of options.point and options.axis under the motion (either kind), written
/// to options.output by its extension. A quaternion spline's trajectory is fitted within a
/// tenth of the chord tolerance first (sweep::fit_frames), the chords within the rest.
/// Errc::invalid_input names a bad option (zero axis, tolerance, format, a --rotary pose at
/// the A/C singularity without c_hold); nothing is written then.
Toolpath toolpath(const Motion& motion, const ToolpathOptions& options);

}  // namespace qmotion
