// api/src/fit.cpp
#include <algorithm>
#include <cmath>
#include <qmotion/api/fit.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/parametrization.hpp>
#include <sstream>

namespace qmotion {
namespace {
/// The least continuity of the motion at its interior breakpoints (its degree when it has none).
int least_continuity(const Motion& m) {
  const auto c = m.continuity();
  return c.empty() ? m.rational().degree() : *std::min_element(c.begin(), c.end());
}
}  // namespace

FitResult fit(const io::PoseSet& set, const FitOptions& o) {
  if (!(o.tol > 0) || !std::isfinite(o.tol))
    throw Error(Errc::invalid_input,
                "--tol: expected a positive length in the poses' unit (" + set.units + ")");
  const kernel::ParamRule rule = param_rule(set, o.param);
  const auto poses = io::to_poses_double(set);
  kernel::FitOptions ko;
  ko.tol = o.tol;
  ko.angle_tol_deg = o.angle_tol_deg;
  ko.between = o.between;
  if (o.degree >= 0) ko.k = o.degree;
  if (o.translation_degree >= 0) ko.l = o.translation_degree;
  kernel::FittedMotion fm = kernel::fit_bspline(poses, kernel::parametrize(poses, rule), ko);
  fm.motion.units = set.units;
  fm.motion.provenance->param = kernel::to_string(rule);
  const std::size_t control_points = fm.motion.curve.curve.ctrl().size();
  const std::size_t spans = fm.motion.curve.curve.breakpoints().size() - 1;
  FitResult r{InterpolatedMotion{Motion(std::move(fm.motion)), {}, {}, set, nullptr},
              std::move(fm.report), control_points, spans};
  std::ostringstream os;
  os.precision(4);
  os << "fit, degree " << r.motion.rational().degree() << ", " << r.spans << " spans, "
     << r.control_points << " control points from " << poses.size() << " poses, C"
     << least_continuity(r.motion);
  r.summary = os.str();
  return r;
}

std::string FitResult::report_text() const {
  const auto& p = *motion.rational().provenance;
  std::ostringstream os;
  os.precision(6);
  os << "poses: " << p.poses.size() << "\n"
     << "control points: " << control_points << " (Q-motion of degree "
     << motion.rational().degree() << "; factors "
     << motion.rational().factors->rotation.ctrl().size() << " + "
     << motion.rational().factors->translation.ctrl().size() << ")\n"
     << "spans: " << spans << "\n"
     << "continuity: C" << least_continuity(motion) << "\n"
     << "knots: " << report.insertion_rounds << " rounds of insertion, " << report.knots_removed
     << " removed, " << report.solves << " least-squares solves\n"
     << "worst position deviation: " << report.worst_position << " " << motion.units()
     << " at pose " << report.worst_position_pose
     << " (t = " << p.parameters[report.worst_position_pose] << "), tolerance " << p.tolerance
     << "\n"
     << "worst angle deviation: " << report.worst_angle_deg << " deg at pose "
     << report.worst_angle_pose << " (t = " << p.parameters[report.worst_angle_pose]
     << "), tolerance " << p.angle_tolerance_deg << "\n";
  if (report.between) {
    const auto at = [&](std::size_t i) {
      return " between poses " + std::to_string(i) + " and " + std::to_string(i + 1);
    };
    os << "between poses, position: at most " << report.between_position_bound << " "
       << motion.units() << " (proven)" << at(report.between_position_interval) << "; sampled "
       << report.between_position_sampled << "\n"
       << "between poses, angle: at most " << report.between_angle_bound_deg << " deg (proven)"
       << at(report.between_angle_interval) << "; sampled " << report.between_angle_sampled_deg
       << "\n";
  }
  return os.str();
}

nlohmann::json FitResult::report_json() const {
  const auto& p = *motion.rational().provenance;
  nlohmann::json between = nullptr;  // the tolerances held at the poses only
  if (report.between)
    between = {{"position_bound", report.between_position_bound},
               {"position_interval", report.between_position_interval},
               {"angle_bound_deg", report.between_angle_bound_deg},
               {"angle_interval", report.between_angle_interval},
               {"position_sampled", report.between_position_sampled},
               {"angle_sampled_deg", report.between_angle_sampled_deg}};
  return {{"poses", p.poses.size()},
          {"between", between},
          {"control_points", control_points},
          {"spans", spans},
          {"degree", motion.rational().degree()},
          {"continuity", least_continuity(motion)},
          {"units", motion.units()},
          {"tolerance", p.tolerance},
          {"angle_tolerance_deg", p.angle_tolerance_deg},
          {"worst_position", report.worst_position},
          {"worst_position_pose", report.worst_position_pose},
          {"worst_position_t", p.parameters[report.worst_position_pose]},
          {"worst_angle_deg", report.worst_angle_deg},
          {"worst_angle_pose", report.worst_angle_pose},
          {"worst_angle_t", p.parameters[report.worst_angle_pose]},
          {"position_deviation", report.position_deviation},
          {"angle_deviation_deg", report.angle_deviation_deg},
          {"insertion_rounds", report.insertion_rounds},
          {"knots_removed", report.knots_removed},
          {"solves", report.solves}};
}

}  // namespace qmotion
