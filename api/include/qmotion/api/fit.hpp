// <qmotion/api/fit.hpp>: many poses -> a lean B-spline Q-motion near them, with every option of
// the CLI's `fit` (the library call behind it; docs/fitting.md).
#pragma once
#include <qmotion/api/interpolate.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/kernel/motion_fit.hpp>
#include <string>

namespace qmotion {

/// The options of `qmotion fit`, by their CLI names. Negative degrees take the default 3.
struct FitOptions {
  double tol = 0;               ///< --tol: position tolerance in the poses' unit (required, > 0)
  double angle_tol_deg = 0.1;   ///< --angle-tol: rotation tolerance in degrees
  int degree = -1;              ///< --degree K: of Q_rot (2 to 25)
  int translation_degree = -1;  ///< --translation-degree L: of the translation (2 to 25)
  std::string param;            ///< --param: as interpolate's (given when every pose has t)
  bool between = false;         ///< --between: the tolerances hold along the whole motion
};

/// A fitted motion: what `interpolate` returns (the motion, its summary, the poses as given;
/// save() writes the file with method.form "fit") and the deviations at every pose.
struct FitResult : InterpolatedMotion {
  kernel::FitReport report;
  std::size_t control_points = 0;  ///< of the Q-motion (what the file and every export hold)
  std::size_t spans = 0;

  /// The report `qmotion fit` prints: poses, control points, spans, the worst position and
  /// angle deviation and where.
  std::string report_text() const;
  /// The same as JSON: poses, control_points, spans, continuity, the worst deviations with
  /// their pose and t, the tolerances, the deviation at every pose, and how the knots were
  /// found (insertion_rounds, knots_removed, solves).
  nlohmann::json report_json() const;
};

/// A B-spline Q-motion within options.tol of every pose's position and options.angle_tol_deg
/// of its rotation, with few control points (kernel::fit_bspline). Throws Errc::invalid_input
/// for bad options and Errc::numerical_failure for a stream no fit of the degrees can meet.
FitResult fit(const io::PoseSet& poses, const FitOptions& options);

}  // namespace qmotion
