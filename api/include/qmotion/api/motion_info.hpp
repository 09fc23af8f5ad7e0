// <qmotion/api/motion_info.hpp>: what `qmotion info` and `qmotion eval` report, as library calls.
#pragma once
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <qmotion/io/motion_json.hpp>
#include <string>

namespace qmotion {

/// Largest motion `info --exact` takes (bounded work): the exact order is the rank of a
/// 4n x 4n exact rational matrix per segment, measured at 6 s for degree 20 and 8 s for
/// 37 segments of degree 6 (exact B-spline knots have large denominators).
inline constexpr int kMaxExactInfoDegree = 20;
inline constexpr int kMaxExactInfoSegments = 50;

/// The `info` report of docs/formats.md: type, basis, degree, order (+ order_source), segments,
/// param_range, units, plucker_residual, interpolation_residual (per recorded pose), poles,
/// method. `exact`: order and residuals in CGAL::Exact_rational from the file's digits.
nlohmann::json motion_info(const io::MotionFile& motion, bool exact = false);

/// Refuses (Errc::invalid_input) a parameter t outside [a, b], spelling it as `t_text`
/// (default: its value) in the message, as `eval` does for every kind of motion.
void require_in_interval(double t, double a, double b, const std::string& t_text = "");

/// The `eval` report at t: position (image of the moving origin), quaternion (unit, w >= 0)
/// and the image of `point`. Throws Errc::invalid_input for t outside the interval and
/// Errc::numerical_failure at a pole. `warning` receives a Plucker violation, if any;
/// `t_text` is how messages spell t (default: its value).
nlohmann::json motion_eval(const io::MotionFile& motion, double t,
                           const Eigen::Vector3d& point = Eigen::Vector3d::Zero(),
                           std::string* warning = nullptr, const std::string& t_text = "");

/// `qmotion info FILE` for a motion file of either kind: motion_info for a Q-motion,
/// qspline_info for a quaternion spline (where `exact` is refused: it is not rational).
nlohmann::json info_file(const std::string& path, bool exact = false);

/// `qmotion eval FILE --t T` for a motion file of either kind: motion_eval for a Q-motion,
/// qspline_eval (with the angular velocity) for a quaternion spline.
nlohmann::json eval_file(const std::string& path, double t,
                         const Eigen::Vector3d& point = Eigen::Vector3d::Zero(),
                         std::string* warning = nullptr, const std::string& t_text = "");

}  // namespace qmotion
