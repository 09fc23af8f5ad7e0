// api/src/qspline.cpp: the non-rational mode as library calls (docs/guide/commands.md).
#include <cmath>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/api/motion_info.hpp>
#include <qmotion/api/qspline.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/units.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/parametrization.hpp>
#include <qmotion/kernel/pose.hpp>
#include <sstream>

namespace qmotion {
using namespace io;  // NOLINT: the formats this call reads and writes
namespace {

using json = nlohmann::json;
using kernel::QSplineScheme;
using kernel::Quaternion;

/// The figures of a KKS solve, as the file's method block and `info` give them.
json kks_record(const kernel::QuaternionSpline& s) {
  return {{"iterations", s.iterations},
          {"contraction", s.contraction},
          {"fixed_point_residual", s.fixed_point_residual},
          {"newton_steps", s.newton_steps},
          {"residual", s.residual}};
}

json quat_json(const Quaternion<double>& q) { return json{q.w(), q.x(), q.y(), q.z()}; }

/// --tension: one number for every key or one per key, finite and not negative.
std::vector<double> tensions(const std::string& text, std::size_t keys) {
  std::vector<double> a;
  if (text.empty()) return std::vector<double>(keys, 0.5);
  std::stringstream ss(text);
  for (std::string cell; std::getline(ss, cell, ',');) {
    const double v = parse_number_text(cell, "--tension").value;
    if (v < 0)
      throw Error(Errc::invalid_input, "--tension: a negative tension (" + cell +
                                           ") reverses the curve's direction at its key; "
                                           "expected numbers >= 0 (default 0.5)");
    a.push_back(v);
  }
  if (a.size() == 1) return std::vector<double>(keys, a.front());
  if (a.size() != keys)
    throw Error(Errc::invalid_input,
                "--tension: expected one tension for every pose or one per "
                "pose (" +
                    std::to_string(keys) + "), found " + std::to_string(a.size()));
  return a;
}

}  // namespace

QSplineResult qspline(const PoseSet& set, const QSplineOptions& o) {
  const auto scheme = qspline_scheme(o.scheme);
  if (!scheme)
    throw Error(Errc::invalid_input,
                "--scheme: expected kks, quintic or quartic, found '" + o.scheme + "'");
  if (*scheme != QSplineScheme::quintic && !o.tension.empty())
    throw Error(Errc::invalid_input, "--tension is for --scheme quintic");
  const kernel::ParamRule rule = param_rule(set, o.param);
  const auto poses = to_poses_double(set);
  const std::vector<double> t = kernel::parametrize(poses, rule);
  std::vector<Quaternion<double>> keys;
  std::vector<Eigen::Vector3d> positions;
  for (const auto& p : poses) {
    keys.push_back(p.rotation);
    positions.push_back(p.position);
  }
  const double a = t.front(), b = t.back();
  const std::vector<double> alpha =
      *scheme == QSplineScheme::quintic ? tensions(o.tension, keys.size()) : std::vector<double>();
  kernel::QuaternionSpline spline;
  try {  // the kernel's refusals name keys; say which file they are in
    spline = kernel::qspline(*scheme, keys, positions, t, alpha);
  } catch (const Error& e) {
    throw Error(e.code(), set.source + ": " + e.what());
  }
  const Motion motion(std::move(spline), set.units);
  const kernel::QuaternionSpline& s = motion.spline();
  // Uniform constructions: are the rule's parameters where the keys are?
  double off = 0;
  for (std::size_t i = 0; i < t.size(); ++i) off = std::max(off, std::abs(t[i] - s.knots[i]));
  const bool moved = off > 1e-12 * (b - a);

  json doc = qspline_document(motion);
  json method;
  method["param"] = kernel::to_string(rule);
  method["parameters"] = t;
  if (s.scheme != QSplineScheme::quintic) method["uniform_keys"] = moved;
  if (s.scheme == QSplineScheme::kks) method.update(kks_record(s));
  method["input_poses"] = poses_to_json(set);
  doc["method"] = method;

  std::ostringstream os;
  os << kernel::to_string(s.scheme) << ", " << s.segments() << " segments";
  if (s.scheme == QSplineScheme::kks)
    os << ", " << s.iterations << " iterations + " << s.newton_steps
       << " Gauss-Newton steps, residual " << s.residual << " rad";
  if (moved)
    os << "; keys at uniform knots on [" << a << ", " << b << "] (the " << kernel::to_string(rule)
       << " parameters are not uniform)";
  return QSplineResult{motion, os.str(), std::move(doc)};
}

void QSplineResult::save(const std::string& path) const {
  write_file_atomic(path, document.dump(1) + "\n");
}

std::vector<double> qspline_key_residuals(const kernel::QuaternionSpline& s) {
  std::vector<double> res;
  for (std::size_t i = 0; i < s.keys.size(); ++i) {
    const auto want = kernel::DualQuaternion<double>::pose(s.positions[i], s.keys[i]);
    const auto got =
        kernel::DualQuaternion<double>::pose(s.position(s.knots[i]), s.rotation(s.knots[i]));
    res.push_back(kernel::pose_residual(got, want));
  }
  return res;
}

json qspline_info(const json& doc, const kernel::QuaternionSpline& s) {
  json out;
  out["type"] = "quaternion-spline";
  out["scheme"] = kernel::to_string(s.scheme);
  out["basis"] = "quaternion-spline";
  out["degree"] = nullptr;  // not a polynomial motion: trajectories are approximated
  out["order"] = nullptr;
  out["segments"] = s.segments();
  out["param_range"] = {s.a(), s.b()};
  out["units"] = doc.contains("units") ? doc["units"] : json("mm");
  out["knots"] = s.knots;
  out["plucker_residual"] = 0.0;
  out["interpolation_residual"] = qspline_key_residuals(s);
  out["poles"] = json::array();
  if (s.scheme == QSplineScheme::quintic) out["tension"] = s.tension;
  if (s.scheme == QSplineScheme::kks) out.update(kks_record(s));
  if (doc.contains("method") && doc["method"].is_object() && doc["method"].contains("uniform_keys"))
    out["uniform_keys"] = doc["method"]["uniform_keys"];
  return out;
}

json qspline_eval(const kernel::QuaternionSpline& s, double t, const Eigen::Vector3d& point,
                  const std::string& t_text) {
  require_in_interval(t, s.a(), s.b(), t_text);
  Quaternion<double> r = s.rotation(t);
  if (r.w() < 0) r = -r;
  const Eigen::Vector3d p = s.position(t);
  json out;
  out["t"] = t;
  out["position"] = point_json(p);
  out["quaternion"] = quat_json(r);
  out["point"] = point_json(kernel::rotate(r, point) + p);
  out["angular_velocity"] = point_json(s.angular_velocity(t));
  return out;
}

}  // namespace qmotion
