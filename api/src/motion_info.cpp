// api/src/motion_info.cpp
#include <qmotion/api/motion_info.hpp>
#include <qmotion/api/qspline.hpp>
#include <sstream>

#ifdef QMOTION_WITH_CGAL
#include <qmotion/io/exact_number.hpp>
#endif
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/kernel/motion_fit.hpp>
#include <qmotion/kernel/order.hpp>

namespace qmotion {
using namespace io;  // NOLINT: the formats this call reads and writes
namespace {

using json = nlohmann::json;

/// Residual of the motion at every recorded pose (null when a parameter is missing). Exact
/// Scalar: 0 where Q(t_i) is exactly proportional to P_i, else the double residual.
template <typename Scalar>
json interpolation_residuals(const kernel::QMotion<Scalar>& m,
                             const std::vector<kernel::Pose<Scalar>>& P, const MotionFile& f,
                             Scalar /*tag*/) {
  std::vector<Scalar> ts;
  const json& params = f.method.contains("parameters") ? f.method["parameters"] : json();
  for (std::size_t i = 0; i < P.size(); ++i) {
    std::optional<Scalar> t = P[i].t;
    if (params.is_array() && i < params.size()) {
      const Number n =
          read_number(params[i], f.source + ": method.parameters[" + std::to_string(i) + "]");
#ifdef QMOTION_WITH_CGAL
      if constexpr (kernel::is_exact_v<Scalar>) {
        t = exact_from_text(n.source());
      } else {
        t = n.value;
      }
#else
      t = n.value;
#endif
    }
    if (!t) return nullptr;
    ts.push_back(*t);
  }
  return json(kernel::pose_residuals(m, P, ts));
}

/// motion_info of the file f, read into `motion` (to_motion, which validates the method block).
json info_of(const MotionFile& f, const kernel::Motion<double>& motion, bool exact) {
  const kernel::QMotion<double>& m = motion.curve;
  if (exact && (m.degree() > kMaxExactInfoDegree || m.segments() > kMaxExactInfoSegments))
    throw Error(Errc::invalid_input,
                f.source + ": info --exact is limited to motions of degree " +
                    std::to_string(kMaxExactInfoDegree) + " and " +
                    std::to_string(kMaxExactInfoSegments) + " segments (this one: degree " +
                    std::to_string(m.degree()) + ", " + std::to_string(m.segments()) +
                    " segments): the exact order is an exact rational rank whose cost grows "
                    "as the fifth power of the degree; use info without --exact");
  json out;
  out["type"] = "q-motion";
  out["basis"] = m.basis == kernel::Basis::bezier ? "bezier" : "bspline";
  out["degree"] = m.degree();
  // Order: degree of a general point's trajectory with every common factor removed.
  // --exact: exactly from the file's digits. Otherwise: what the recorded construction
  // guarantees, or, for motions without one, a numerical rank.
  std::optional<int> recorded;
  if (const auto& p = motion.provenance)
    recorded = kernel::construction_order(p->translation, p->rotation_degree, p->translation_degree,
                                          std::max(p->translation_degree2, 0));
#ifdef QMOTION_WITH_CGAL
  if (exact) {
    out["order"] = kernel::motion_order(to_motion_exact(f));
    out["order_source"] = "exact";
  } else
#endif
      if (recorded) {
    out["order"] = *recorded;
    out["order_source"] = "construction";
  } else {
    out["order"] = kernel::motion_order(m);
    out["order_source"] = "numerical";
  }
  out["segments"] = m.segments();
  out["param_range"] = {m.a(), m.b()};
  out["units"] = f.units;
#ifdef QMOTION_WITH_CGAL
  if (exact) {
    out["plucker_residual"] = kernel::to_double(kernel::plucker_residual(to_motion_exact(f)));
    out["exact"] = true;
  } else {
    out["plucker_residual"] = kernel::plucker_residual(m);
  }
#else
  if (exact)
    throw Error(Errc::invalid_input,
                "--exact: this build has no exact arithmetic (QMOTION_WITH_CGAL=OFF)");
  out["plucker_residual"] = kernel::plucker_residual(m);
#endif
  json res = nullptr;
  if (motion.provenance) res = motion.provenance->residuals;
#ifdef QMOTION_WITH_CGAL
  if (exact)
    if (const auto poses = recorded_input_poses(f))
      // Rotations given as matrices or axis and angle: the double unit quaternion, exactly.
      res = interpolation_residuals(to_motion_exact(f),
                                    to_poses_exact(with_quaternion_rotations(*poses)), f,
                                    kernel::Rational(0));
#endif
  out["interpolation_residual"] = res;
  if (motion.provenance && motion.provenance->form == kernel::Form::fit) {
    // A fitted motion passes near its poses, not through them: its deviations, measured.
    const auto& p = *motion.provenance;
    const auto dev = kernel::fit_deviations(m, p.poses, p.parameters);
    out["fit"] = {{"tolerance", p.tolerance},
                  {"angle_tolerance_deg", p.angle_tolerance_deg},
                  {"worst_position", dev.worst_position},
                  {"worst_position_pose", dev.worst_position_pose},
                  {"worst_angle_deg", dev.worst_angle_deg},
                  {"worst_angle_pose", dev.worst_angle_pose}};
  }
  out["poles"] = kernel::find_poles(m, motion.label());
  if (f.method.is_object()) {
    // The record without its bulky members (copied member by member: the input poses and
    // factor control points of a 10^4-pose motion are 10^5 values not to copy).
    json method = json::object();
    for (const auto& [key, value] : f.method.items())
      if (key != "input_poses" && key.find("_control_points") == std::string::npos)
        method[key] = value;
    out["method"] = method;
  }
  return out;
}

}  // namespace

json motion_info(const MotionFile& f, bool exact) { return info_of(f, to_motion(f), exact); }

void require_in_interval(double t, double a, double b, const std::string& t_text) {
  if (t >= a && t <= b) return;
  std::ostringstream os;
  os.precision(17);
  os << "--t " << (t_text.empty() ? std::to_string(t) : t_text)
     << " is outside the motion's parameter interval [" << a << ", " << b << "]";
  throw Error(Errc::invalid_input, os.str());
}

json motion_eval(const MotionFile& f, double t, const Eigen::Vector3d& x, std::string* warning,
                 const std::string& t_text) {
  const kernel::QMotion<double> m = to_motion_double(f);
  require_in_interval(t, m.a(), m.b(), t_text);
  const auto q = kernel::evaluate(m, t);
  if (q.real().norm2() <= 1e-300)
    throw Error(Errc::numerical_failure,
                "the motion has a pole at t = " + (t_text.empty() ? std::to_string(t) : t_text) +
                    " (zero rotational part)");
  kernel::Quaternion<double> r = kernel::normalized(q.real());
  if (r.w() < 0) r = -r;
  json out;
  out["t"] = t;
  out["position"] = point_json(kernel::translation_vector(q));
  out["quaternion"] = {r.w(), r.x(), r.y(), r.z()};
  out["point"] = point_json(kernel::apply_point(q, x));
  const double pl = kernel::plucker_residual(q);
  if (pl > 1e-9 && warning)
    *warning = "violates the Plucker condition at t (relative residual " + std::to_string(pl) +
               "): not a rigid motion";
  return out;
}

json info_file(const std::string& path, bool exact) {
  auto read = read_motion_or_text(path);
  if (auto* f = std::get_if<MotionFile>(&read)) {
    if (exact) return motion_info(*f, exact);
    // Without --exact the control points' numbers are not read again: they go as soon as
    // the motion is built (to_motion(MotionFile&&) leaves the method and poses in f).
    const kernel::Motion<double> motion = to_motion(std::move(*f));
    return info_of(*f, motion, exact);
  }
  json doc = parse_json(std::get<std::string>(read), path, "method");
  if (is_qspline_document(doc)) {
    if (exact)
      throw Error(Errc::invalid_input, path +
                                           ": --exact is for rational motions (q-motion files); a "
                                           "quaternion spline is not rational");
    return qspline_info(doc, qspline_from_document(doc, path));
  }
  return motion_info(parse_motion(std::move(doc), path), exact);
}

json eval_file(const std::string& path, double t, const Eigen::Vector3d& point,
               std::string* warning, const std::string& t_text) {
  auto read = read_motion_or_text(path, /*with_method=*/false);
  if (auto* f = std::get_if<MotionFile>(&read)) return motion_eval(*f, t, point, warning, t_text);
  json doc = parse_json(std::get<std::string>(read), path, "method");
  if (is_qspline_document(doc))
    return qspline_eval(qspline_from_document(doc, path), t, point, t_text);
  return motion_eval(parse_motion(std::move(doc), path), t, point, warning, t_text);
}

}  // namespace qmotion
