// <qmotion/api/qspline.hpp>: the non-rational mode as library calls (docs/guide/commands.md):
// poses -> a quaternion-spline motion, and its `info` and `eval` reports.
#pragma once
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/io/qspline_file.hpp>
#include <qmotion/kernel/qspline.hpp>
#include <qmotion/motion.hpp>
#include <string>

namespace qmotion {

/// The options of `qmotion qspline`, by their CLI names.
struct QSplineOptions {
  std::string scheme;   ///< kks, quintic, quartic
  std::string tension;  ///< quintic: "A" (every key) or "a1,...,an" (one per key); default 0.5
  std::string param;    ///< a rule of `interpolate` (default: given when every pose has t)
};

/// A new quaternion-spline motion: the motion, a one-line summary of the solve, and its file
/// (docs/formats.md: keys, positions, knots, the scheme's own fields and the method with the
/// input poses as given).
struct QSplineResult {
  Motion motion;
  std::string summary;
  nlohmann::json document;
  /// Writes the document to `path` atomically, as `qmotion qspline` does.
  void save(const std::string& path) const;
};

/// The spline of the scheme through the poses (rotations and positions). The parameters of
/// the rule give the interval [t_0, t_n]; the quintic keeps them as its knots, KKS and the
/// quartic place the keys at uniform knots on that interval (recorded as method.uniform_keys
/// when the rule's parameters are not uniform). Throws Errc::invalid_input naming the option
/// or the poses, Errc::numerical_failure when KKS does not converge.
QSplineResult qspline(const io::PoseSet& poses, const QSplineOptions& options);

/// pose_residual of the spline at every key against the key's pose.
std::vector<double> qspline_key_residuals(const kernel::QuaternionSpline& spline);

/// `info` for a quaternion-spline file: type, scheme, basis, degree and order (null: not
/// rational), segments, param_range, units, plucker_residual (0: rotation and translation are
/// separate), interpolation_residual per key, poles (none), and for KKS iterations,
/// contraction, fixed_point_residual, newton_steps, residual.
nlohmann::json qspline_info(const nlohmann::json& doc, const kernel::QuaternionSpline& spline);

/// `eval` at t: position, quaternion (w >= 0), the image of point, and the angular velocity
/// (fixed frame, radians per unit of t). Errc::invalid_input for t outside the interval.
nlohmann::json qspline_eval(const kernel::QuaternionSpline& spline, double t,
                            const Eigen::Vector3d& point, const std::string& t_text);

}  // namespace qmotion
