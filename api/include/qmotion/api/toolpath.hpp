// <qmotion/api/toolpath.hpp>: CAM output (`qmotion toolpath`): cutter-location points with
// certified chord and axis-angle bounds for the numbers as written, as APT CL data, CSV or
// G-code (3-axis, or a 5-axis machine whose own linear interpolation of its axes the bounds
// cover), with feed per minute or inverse-time feed.
#pragma once
#include <Eigen/Core>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <qmotion/cam/machine.hpp>
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
  std::string rotary;        ///< G-code: "" (3-axis), "ac" or "bc" (table-tilting machines)
  std::string machine_file;  ///< G-code: a machine file (docs/cam.md) instead of `rotary`
  std::optional<cam::Machine> machine;  ///< G-code: the machine itself, instead of either
  bool c_hold = false;  ///< a machine: keep the singular axis's angle where it is undefined
  /// "" or "units-per-minute" (G94, one F), or "inverse-time" (G-code G1 only: G93, an F
  /// per block so that the tool tip moves at `feed` along the exact trajectory).
  std::string feed_mode;
  /// Inverse-time only: the largest velocity of each axis word (X, Y, Z in the output unit
  /// per minute, rotary axes in degrees per minute); blocks slow down to respect them. A
  /// machine file's limits apply unless these name the axis.
  std::map<char, double> axis_limits;
  /// G-code: the trajectory as Fanuc-style G06.2 NURBS blocks of degree <= 3 (exact where
  /// the trajectory has that degree, else a cubic fit) within chord_tol, certified (3-axis).
  bool nurbs = false;
  /// The unit of the output and of chord_tol, max_step and feed (default: the motion's;
  /// APT and G-code: mm or in, a motion in another unit is written in mm).
  std::string units;
  /// G-code: the controller whose words the program uses: "linuxcnc" (the default), "fanuc"
  /// (the default of --nurbs, whose G06.2 is Fanuc's) or "siemens" (docs/cam.md).
  std::string dialect;
  /// G-code G1, 3-axis: the part of chord_tol left to the controller's blending (G64 P Q,
  /// G642 CTOL), the chords taking the rest; 0 (the default): exact path (G61, G60 G601).
  double controller_tol = 0;
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
  std::vector<cam::ToolpathSample> samples;    ///< in the output unit (none with nurbs)
  std::optional<NurbsToolpath> nurbs;          ///< options.nurbs: the curve written
  std::optional<cam::Machine> machine;         ///< the machine the G-code drives
  std::vector<cam::MachineAxes> machine_axes;  ///< with a machine: per sample, as written
  std::string feed_mode = "units-per-minute";
  std::map<char, double> axis_limits;  ///< the limits applied (inverse-time)
  std::vector<double> block_minutes;   ///< inverse-time: the time of every G1 block
  std::size_t limited_blocks = 0;      ///< blocks slowed down by an axis limit
  double machining_time_min = 0;       ///< at the feeds (and velocity limits) alone
  /// G1 G-code: each block from rest to rest on a trapezoidal profile under the machine's
  /// accelerations (an upper bound under exact stop; equal to the above without limits).
  double machining_time_accel_min = 0;
  std::string dialect;        ///< G-code: the controller's words
  std::string path_mode;      ///< G-code: the path-mode words the program commands
  double controller_tol = 0;  ///< G-code: the part of the tolerance the controller may use
  /// A machine with travel: the branch the first block took ("nearer" to the machine's zero,
  /// or "other" when the nearer one leaves travel on the way); "" without travel.
  std::string branch;
  double path_length = 0;  ///< of the exact trajectory (Gauss-Legendre)
  /// Certified for the numbers as written (and, with a machine, for its interpolation),
  /// plus the fit for a quaternion spline.
  double max_chord_bound = 0;
  double max_chord_measured = 0;  ///< the written chords, 32 exact points per segment
  double max_angle_bound_deg = 0;
  double rounding_bound = 0;  ///< the largest distance of a written point from the exact one
  /// A quaternion spline's fit (sweep::fit_frames) at the tool point: proven, in every
  /// budget above, and sampled beside it; 0 for a rational motion.
  double fit_bound = 0, fit_measured = 0;
  /// With a machine: the certified tip and axis deviation of its interpolation from the
  /// chord and the blend (included in the bounds above); measured at 15 points inside each
  /// block, the tip's distance from the chord at the same s and from the exact trajectory
  /// (a polyline through 33 of its points).
  double machine_bound = 0, machine_angle_bound_deg = 0, machine_measured = 0, tip_measured = 0;
  std::string units;  ///< the output unit
  nlohmann::json report() const;
  double chord_tol = 0, angle_tol_deg = 0, feed = 0;
  std::string path;
};

/// The toolpath of options.point and options.axis under the motion (either kind), written
/// to options.output by its extension. A quaternion spline's trajectory is fitted within a
/// tenth of the chord tolerance first (sweep::fit_frames), the chords within the rest.
/// Errc::invalid_input names a bad option (zero axis, tolerance, format, a machine file, a
/// feed mode the format cannot carry, a pose at the machine's singularity without c_hold, an
/// axis that leaves its travel on both branches); nothing is written then.
Toolpath toolpath(const Motion& motion, const ToolpathOptions& options);

}  // namespace qmotion
