// io/qspline.hpp: the non-rational mode (SPEC §3) as library calls: poses -> a
// quaternion-spline motion file, and reading one back for `info` and `eval`.
#pragma once
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/kernel/motion_value.hpp>
#include <qmotion/kernel/qspline.hpp>
#include <string>
#include <variant>

namespace qmotion::io {

/// The options of `qmotion qspline`, by their CLI names.
struct QSplineOptions {
  std::string scheme;   ///< kks, quintic, quartic
  std::string tension;  ///< quintic: "A" (every key) or "a1,...,an" (one per key); default 0.5
  std::string param;    ///< a rule of `interpolate` (default: given when every pose has t)
};

/// A quaternion-spline motion as a value: the spline, its file document, a one-line
/// summary, its length unit and where it came from (a file name; empty when built here).
struct QSplineMotion {
  kernel::QuaternionSpline spline;
  nlohmann::json document;
  std::string summary;
  std::string units = "mm";
  std::string name;

  /// The name for messages: the file name, or "motion" for one built in memory.
  std::string label() const { return name.empty() ? std::string("motion") : name; }
};

/// The spline of the scheme through the poses (rotations and positions). The parameters of
/// the rule give the interval [t_0, t_n]; the quintic keeps them as its knots, KKS and the
/// quartic place the keys at uniform knots on that interval (recorded as method.uniform_keys
/// when the rule's parameters are not uniform). Throws Errc::invalid_input naming the option
/// or the poses, Errc::numerical_failure when KKS does not converge.
QSplineMotion qspline(const PoseSet& poses, const QSplineOptions& options);

/// Whether a parsed document is a quaternion-spline motion file.
bool is_qspline_document(const nlohmann::json& doc);

/// The spline a quaternion-spline document describes: quartic and quintic rebuilt from their
/// keys, KKS from its recorded control quaternions and points. Errc::invalid_input names the
/// field.
kernel::QuaternionSpline qspline_from_document(const nlohmann::json& doc,
                                               const std::string& source);

/// The motion a quaternion-spline document describes (qspline_from_document, with its unit
/// checked), named `source`.
QSplineMotion qspline_motion(const nlohmann::json& doc, const std::string& source);

/// A motion file of either kind: a rational q-motion or a quaternion spline.
using AnyMotion = std::variant<kernel::Motion<double>, QSplineMotion>;

/// Reads a motion file of either kind (SPEC §5), refusals naming the file and field.
AnyMotion load_any_motion(const std::string& path);

/// The length unit of either kind.
const std::string& units_of(const AnyMotion& m);

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

}  // namespace qmotion::io
