// <qmotion/cam/tool_trajectories.hpp>: what a toolpath follows under a motion of either kind:
// the trajectories of the tool point and of its axis as homogeneous B-splines (exact for a
// rational motion, fitted within a tenth of the chord tolerance for a quaternion spline), the
// exact placement and velocity of the point for measurements, and the motion's breakpoints
// and continuity.
#pragma once
#include <Eigen/Core>
#include <functional>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/motion.hpp>
#include <qmotion/sweep/fit.hpp>
#include <qmotion/sweep/solid.hpp>
#include <qmotion/sweep/surface.hpp>
#include <qmotion/sweep/trajectory.hpp>
#include <string>
#include <utility>
#include <vector>

namespace qmotion::cam {

struct ToolTrajectories {
  kernel::BSpline<Eigen::Vector4d> h;  ///< the tool point's trajectory (homogeneous)
  kernel::BSpline<Eigen::Vector4d> d;  ///< the tool axis's (a direction: weight 0)
  std::function<Eigen::Vector3d(double)> exact_point;     ///< the point on the motion itself
  std::function<Eigen::Vector3d(double)> exact_velocity;  ///< its velocity
  /// The fit's proven deviation bound at the point and at the axis's tip 100 units out (0:
  /// exact); every budget takes this one.
  double fit_error = 0;
  double fit_measured = 0;     ///< the fit's sampled deviation, reported beside the bound
  std::vector<double> breaks;  ///< the motion's breakpoints and its continuity inside
  std::vector<int> continuity;
};

/// The trajectories of `point` and of the direction `axis` under the motion. A rational
/// motion's are exact; Errc::numerical_failure when it has a pole (the tool would run to
/// infinity). A quaternion spline's rigid maps are fitted (sweep::fit_frames) within
/// `tol` / 10 at the point and at the axis's tip 100 units out, proven (fit_error), which
/// holds the fitted axis within 2e-3 x tol / 10 radians.
inline ToolTrajectories tool_trajectories(const qmotion::Motion& motion,
                                          const Eigen::Vector3d& point, const Eigen::Vector3d& axis,
                                          double tol) {
  const Eigen::Vector3d x = point;
  const Eigen::Vector4d direction(0, axis(0), axis(1), axis(2));
  if (motion.is_rational()) {
    const kernel::Motion<double>& m = motion.rational();
    const auto poles = kernel::find_poles(m.curve, m.label());
    if (!poles.empty())
      throw Error(Errc::numerical_failure,
                  m.label() + ": the motion has a pole at t = " + std::to_string(poles.front()) +
                      ": the tool would run to infinity there");
    const auto h = sweep::trajectory(m, x);
    const auto d = sweep::trajectories(m, {direction}).front();
    const auto dh = kernel::derivative(h);
    std::vector<double> breaks = h.breakpoints();
    std::vector<int> continuity;
    for (std::size_t i = 1; i + 1 < breaks.size(); ++i)
      continuity.push_back(kernel::continuity_at(h, breaks[i]));
    return ToolTrajectories{
        h,
        d,
        [h](double t) {
          const Eigen::Vector4d y = kernel::evaluate(h, t);
          return Eigen::Vector3d(y.tail<3>() / y(0));
        },
        [h, dh](double t) { return sweep::detail::point_and_tangent(h, dh, t).second; },
        0.0,
        0.0,
        std::move(breaks),
        std::move(continuity)};
  }
  sweep::FrameFitOptions fo;
  fo.tol = 0.1 * tol;
  const Eigen::Vector3d tip = x + 100 * axis.normalized();
  const sweep::FrameFit fit = sweep::fit_frames(motion, {x, tip}, fo);
  return ToolTrajectories{sweep::apply(fit.matrix, Eigen::Vector4d(1, x(0), x(1), x(2))),
                          sweep::apply(fit.matrix, direction),
                          [motion, x](double t) { return motion.place(t, x); },
                          [motion, x](double t) { return motion.point_velocity(t, x); },
                          fit.max_deviation_bound,
                          fit.max_deviation,
                          motion.breakpoints(),
                          motion.continuity()};
}

}  // namespace qmotion::cam
