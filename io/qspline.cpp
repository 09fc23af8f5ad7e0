// io/qspline.cpp
#include <cmath>
#include <qmotion/io/interpolate.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/motion_info.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/qspline.hpp>
#include <qmotion/io/units.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/parametrization.hpp>
#include <qmotion/kernel/pose.hpp>
#include <sstream>

namespace qmotion::io {
namespace {

using json = nlohmann::json;
using kernel::QSplineScheme;
using kernel::Quaternion;

std::optional<QSplineScheme> scheme_from_string(const std::string& s) {
  for (auto k : {QSplineScheme::kks, QSplineScheme::quintic, QSplineScheme::quartic})
    if (s == kernel::to_string(k)) return k;
  return std::nullopt;
}

/// The figures of a KKS solve, as the file's method block and `info` give them.
json kks_record(const kernel::QuaternionSpline& s) {
  return {{"iterations", s.iterations},
          {"contraction", s.contraction},
          {"fixed_point_residual", s.fixed_point_residual},
          {"newton_steps", s.newton_steps},
          {"residual", s.residual}};
}

json quat_json(const Quaternion<double>& q) { return json{q.w(), q.x(), q.y(), q.z()}; }
json vec_json(const Eigen::Vector3d& v) { return json{v(0), v(1), v(2)}; }

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

/// An array of arrays of `width` finite numbers, named `field` in messages.
template <int Width>
std::vector<Eigen::Matrix<double, Width, 1>> rows(const json& doc, const char* field,
                                                  const std::string& source) {
  const json& a = require(doc, field, source);
  if (!a.is_array() || a.empty())
    throw Error(Errc::invalid_input, source + ": " + field + ": expected an array");
  std::vector<Eigen::Matrix<double, Width, 1>> out;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string where = source + ": " + field + "[" + std::to_string(i) + "]";
    if (!a[i].is_array() || a[i].size() != Width)
      throw Error(Errc::invalid_input, where + ": expected " + std::to_string(Width) + " numbers");
    Eigen::Matrix<double, Width, 1> v;
    for (int k = 0; k < Width; ++k)
      v(k) = read_number(a[i][static_cast<std::size_t>(k)], where).value;
    out.push_back(v);
  }
  return out;
}

std::vector<double> numbers(const json& doc, const char* field, const std::string& source) {
  const json& a = require(doc, field, source);
  if (!a.is_array())
    throw Error(Errc::invalid_input, source + ": " + field + ": expected an array");
  std::vector<double> out;
  for (std::size_t i = 0; i < a.size(); ++i)
    out.push_back(read_number_lazy(a[i], [&] {
                    return source + ": " + field + "[" + std::to_string(i) + "]";
                  }).value);
  return out;
}

std::vector<Quaternion<double>> quaternions(const json& doc, const char* field,
                                            const std::string& source) {
  std::vector<Quaternion<double>> q;
  for (const auto& v : rows<4>(doc, field, source)) {
    if (v.norm() == 0)
      throw Error(Errc::invalid_input, source + ": " + field + ": a zero quaternion");
    q.emplace_back(v(0), v(1), v(2), v(3));
  }
  return q;
}

}  // namespace

QSplineMotion qspline(const PoseSet& set, const QSplineOptions& o) {
  const auto scheme = scheme_from_string(o.scheme);
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
  QSplineMotion out;
  try {  // the kernel's refusals name keys; say which file they are in
    if (*scheme == QSplineScheme::quintic)
      out.spline = kernel::quintic_spline(keys, positions, t, alpha);
    else if (*scheme == QSplineScheme::quartic)
      out.spline = kernel::quartic_spline(keys, positions, a, b);
    else
      out.spline = kernel::kks_spline(keys, positions, a, b);
  } catch (const Error& e) {
    throw Error(e.code(), set.source + ": " + e.what());
  }
  const auto& s = out.spline;
  // Uniform constructions: are the rule's parameters where the keys are?
  double off = 0;
  for (std::size_t i = 0; i < t.size(); ++i) off = std::max(off, std::abs(t[i] - s.knots[i]));
  const bool moved = off > 1e-12 * (b - a);

  json doc;
  doc["type"] = "quaternion-spline";
  doc["scheme"] = kernel::to_string(s.scheme);
  doc["units"] = set.units;
  doc["param_range"] = {a, b};
  doc["knots"] = s.knots;
  json k = json::array(), p = json::array();
  for (const auto& q : s.keys) k.push_back(quat_json(q));
  for (const auto& x : s.positions) p.push_back(vec_json(x));
  doc["keys"] = k;
  doc["positions"] = p;
  if (s.scheme == QSplineScheme::quintic) doc["tension"] = s.tension;
  if (s.scheme == QSplineScheme::kks) {
    json c = json::array(), cp = json::array();
    for (const auto& q : s.ctrl) c.push_back(quat_json(q));
    for (const auto& x : s.pctrl) cp.push_back(vec_json(x));
    doc["control_quaternions"] = c;
    doc["control_positions"] = cp;
  }
  json method;
  method["param"] = kernel::to_string(rule);
  method["parameters"] = t;
  if (s.scheme != QSplineScheme::quintic) method["uniform_keys"] = moved;
  if (s.scheme == QSplineScheme::kks) method.update(kks_record(s));
  method["input_poses"] = poses_to_json(set);
  doc["method"] = method;
  out.document = doc;
  out.units = set.units;

  std::ostringstream os;
  os << kernel::to_string(s.scheme) << ", " << s.segments() << " segments";
  if (s.scheme == QSplineScheme::kks)
    os << ", " << s.iterations << " iterations + " << s.newton_steps
       << " Gauss-Newton steps, residual " << s.residual << " rad";
  if (moved)
    os << "; keys at uniform knots on [" << a << ", " << b << "] (the " << kernel::to_string(rule)
       << " parameters are not uniform)";
  out.summary = os.str();
  return out;
}

bool is_qspline_document(const json& doc) {
  return doc.is_object() && doc.contains("type") && doc["type"] == "quaternion-spline";
}

kernel::QuaternionSpline qspline_from_document(const json& doc, const std::string& source) {
  const json& sj = require(doc, "scheme", source);
  const auto scheme = scheme_from_string(sj.is_string() ? sj.get<std::string>() : "");
  if (!scheme)
    throw Error(Errc::invalid_input, source + ": scheme: expected kks, quintic or quartic");
  const auto keys = quaternions(doc, "keys", source);
  std::vector<Eigen::Vector3d> positions = rows<3>(doc, "positions", source);
  const std::vector<double> knots = numbers(doc, "knots", source);
  if (positions.size() != keys.size() || knots.size() != keys.size())
    throw Error(Errc::invalid_input,
                source + ": keys, positions and knots: expected one of each per key");
  if (knots.size() < 2 || !(knots.front() < knots.back()))
    throw Error(Errc::invalid_input, source + ": knots: expected at least two, increasing");
  // Every field is read (and refused, naming it) before the kernel builds the spline; the
  // kernel's refusals name keys, so say which file they are in.
  const std::vector<double> alpha =
      *scheme == QSplineScheme::quintic ? numbers(doc, "tension", source) : std::vector<double>();
  std::vector<Quaternion<double>> ctrl;
  std::vector<Eigen::Vector3d> pctrl;
  if (*scheme == QSplineScheme::kks) {  // the recorded solution, not a new solve
    ctrl = quaternions(doc, "control_quaternions", source);
    pctrl = rows<3>(doc, "control_positions", source);
    for (std::size_t i = 1; i < knots.size(); ++i)
      if (!(std::abs((knots[i] - knots[i - 1]) -
                     (knots.back() - knots.front()) / static_cast<double>(knots.size() - 1)) <=
            1e-9 * (knots.back() - knots.front())))
        throw Error(Errc::invalid_input, source + ": knots: a kks spline has uniform knots");
  }
  kernel::QuaternionSpline s;
  try {
    if (*scheme == QSplineScheme::quintic)
      return kernel::quintic_spline(keys, positions, knots, alpha);
    if (*scheme == QSplineScheme::quartic)
      return kernel::quartic_spline(keys, positions, knots.front(), knots.back());
    s = kernel::kks_from_control(keys, positions, knots.front(), knots.back(), ctrl, pctrl);
  } catch (const Error& e) {
    throw Error(e.code(), source + ": " + e.what());
  }
  // The solve's record (numbers, or their text from a text-preserving parse).
  const json none;
  const json& m = doc.contains("method") && doc["method"].is_object() ? doc["method"] : none;
  auto get = [&](const char* key) {
    if (!m.is_object() || !m.contains(key)) return 0.0;
    const double v = read_number(m[key], source + ": method." + key).value;
    return std::isfinite(v) && v >= 0 && v < 1e9 ? v : 0.0;
  };
  s.iterations = static_cast<int>(get("iterations"));
  s.contraction = get("contraction");
  s.fixed_point_residual = get("fixed_point_residual");
  s.newton_steps = static_cast<int>(get("newton_steps"));
  return s;
}

QSplineMotion qspline_motion(const json& doc, const std::string& source) {
  QSplineMotion m;
  m.spline = qspline_from_document(doc, source);
  m.document = doc;
  m.name = source;
  if (doc.contains("units")) {
    if (!doc["units"].is_string())
      throw Error(Errc::invalid_input, source + ": units: expected a unit name such as \"mm\"");
    m.units = canonical_unit(doc["units"].get<std::string>(), source + ": units");
  }
  m.summary = std::string(kernel::to_string(m.spline.scheme)) + ", " +
              std::to_string(m.spline.segments()) + " segments";
  return m;
}

AnyMotion load_any_motion(const std::string& path) {
  std::string text = read_text_file(path);
  if (auto f = parse_motion_fast(text, path)) {
    std::string().swap(text);  // read: its megabytes go before the motion is built
    return to_motion(*f);
  }
  json doc = parse_json(text, path, "method");  // one parse for either kind
  if (is_qspline_document(doc)) {
    QSplineMotion m = qspline_motion(doc, path);
    m.document = json::parse(text, nullptr, false);  // as written: numbers as numbers
    return m;
  }
  return to_motion(parse_motion(std::move(doc), path));
}

const std::string& units_of(const AnyMotion& m) {
  return std::visit([](const auto& x) -> const std::string& { return x.units; }, m);
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
  out["position"] = vec_json(p);
  out["quaternion"] = quat_json(r);
  out["point"] = vec_json(kernel::rotate(r, point) + p);
  out["angular_velocity"] = vec_json(s.angular_velocity(t));
  return out;
}

}  // namespace qmotion::io
