// <qmotion/api/compare.hpp>: the schemes side by side for one pose set (`qmotion compare`): what a
// user weighs when choosing between the rational motions and the quaternion splines.
#pragma once
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <qmotion/io/poses.hpp>
#include <string>
#include <vector>

namespace qmotion {

struct CompareOptions {
  std::string param;  ///< the parametrisation rule for every scheme (empty: as interpolate)
  /// The point whose trajectory length is measured (default: the moving origin).
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  /// The profile of the sweeps whose poles are counted (a read_profile spec); empty: the
  /// segment from the moving origin along x, a tenth of the poses' extent long.
  std::string profile;
  double rel_tol = 1e-6;  ///< the quaternion splines' fit, relative to the sweep's size
  int samples = 2000;     ///< parameters at which velocities are measured
};

/// One scheme's figures, or why it failed (`error`, the scheme's refusal message).
struct SchemeFigures {
  std::string scheme;  ///< "elliptic bspline", "c1", "kks", "quintic", "quartic"
  bool rational = false;
  std::optional<std::string> error;
  double max_angular_velocity = 0;      ///< rad per unit of t
  double max_angular_acceleration = 0;  ///< rad per unit of t squared (central differences)
  double trajectory_length = 0;         ///< of options.point
  int sweep_poles = 0;                  ///< all faces of the profile's sweep
  int sweep_degree_u = 0;
  double sweep_deviation = 0;   ///< 0 for exact (rational) sweeps, else the fit's measurement
  double max_key_residual = 0;  ///< pose_residual at the poses
};

/// Builds the elliptic B-spline, c1, KKS, quintic (tension 0.5) and quartic motions through
/// the poses on one parameter interval and measures each on the same grid. A scheme that
/// refuses the poses is reported with its message, not thrown.
std::vector<SchemeFigures> compare_schemes(const io::PoseSet& poses, const CompareOptions& options);

/// The figures as JSON (one object per scheme).
nlohmann::json to_json(const std::vector<SchemeFigures>& figures);

/// The figures as an aligned text table.
std::string to_table(const std::vector<SchemeFigures>& figures);

}  // namespace qmotion
