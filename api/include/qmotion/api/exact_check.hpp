// <qmotion/api/exact_check.hpp>: `qmotion check --exact`: a motion file verified in exact rational
// arithmetic against the poses it records (needs CGAL).
#pragma once
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace qmotion {

/// Most poses `check --exact` recomputes from (a B-spline motion through them has at most
/// kMaxExactInfoSegments segments): exact rational work grows quickly with their number.
inline constexpr std::size_t kMaxExactCheckPoses = 51;
/// Largest relative difference between the file's control points and the exact
/// recomputation's (after the best common scale) that still counts as agreement.
inline constexpr double kExactCheckAgreement = 1e-8;

/// Recomputes the motion of the file `motion_path` in CGAL::Exact_rational from the poses
/// its method block records, with the recorded form, methods, degrees and parametrisation
/// rule (poses given as rotation matrices or axis and angle enter as the unit quaternions
/// the double pipeline makes of them, taken exactly), and reports (JSON):
///   - `plucker`: whether the exact motion's Plucker polynomial is exactly zero, and the
///     file's own (double) Plucker residual;
///   - `interpolation`: the exact residual at every pose (0: exactly proportional), and the
///     file's largest residual;
///   - `file_deviation`: the largest relative difference of the file's control points from
///     the exact ones (after the best common scale), and of its recorded parameters;
///   - `order`: the degree of the trajectory of `point` (default: a point in general
///     position) after an exact polynomial gcd (CGAL's Polynomial package) removes the
///     common factors of its four homogeneous coordinates, beside the degree `trajectory`
///     writes for that point and the order the construction guarantees;
///   - `verified`: all of these agree (exact zeros, deviation within kExactCheckAgreement,
///     gcd order equal to the written degree).
/// Throws Errc::invalid_input when the file records no complete method (hand-written
/// files), for c1 motions (their velocities need square roots), and beyond the limits
/// kMaxExactCheckPoses, kMaxExactInfoDegree and kMaxExactInfoSegments.
nlohmann::json check_exact(const std::string& motion_path,
                           const std::optional<Eigen::Vector3d>& point = std::nullopt);

}  // namespace qmotion
