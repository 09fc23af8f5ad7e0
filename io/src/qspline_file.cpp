// io/src/qspline_file.cpp: quaternion-spline motion files (docs/formats.md), and reading a
// motion file of either kind.
#include <cmath>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/qspline_file.hpp>
#include <qmotion/io/units.hpp>
#include <qmotion/kernel/error.hpp>

namespace qmotion::io {
namespace {

using json = nlohmann::json;
using kernel::QSplineScheme;
using kernel::Quaternion;

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

std::optional<kernel::QSplineScheme> qspline_scheme(const std::string& s) {
  return kernel::qspline_scheme_from_string(s);
}

bool is_qspline_document(const json& doc) {
  return doc.is_object() && doc.contains("type") && doc["type"] == "quaternion-spline";
}

kernel::QuaternionSpline qspline_from_document(const json& doc, const std::string& source) {
  const json& sj = require(doc, "scheme", source);
  const auto scheme = qspline_scheme(sj.is_string() ? sj.get<std::string>() : "");
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

Motion qspline_motion(const json& doc, const std::string& source) {
  std::string units = "mm";
  if (doc.contains("units")) {
    if (!doc["units"].is_string())
      throw Error(Errc::invalid_input, source + ": units: expected a unit name such as \"mm\"");
    units = canonical_unit(doc["units"].get<std::string>(), source + ": units");
  }
  return Motion(qspline_from_document(doc, source), std::move(units), source);
}

json qspline_document(const Motion& motion) {
  const kernel::QuaternionSpline& s = motion.spline();
  auto quat = [](const Quaternion<double>& q) { return json{q.w(), q.x(), q.y(), q.z()}; };
  json doc;
  doc["type"] = "quaternion-spline";
  doc["scheme"] = kernel::to_string(s.scheme);
  doc["units"] = motion.units();
  doc["param_range"] = {s.a(), s.b()};
  doc["knots"] = s.knots;
  json k = json::array(), p = json::array();
  for (const auto& q : s.keys) k.push_back(quat(q));
  for (const auto& x : s.positions) p.push_back(point_json(x));
  doc["keys"] = k;
  doc["positions"] = p;
  if (s.scheme == QSplineScheme::quintic) doc["tension"] = s.tension;
  if (s.scheme == QSplineScheme::kks) {
    json c = json::array(), cp = json::array();
    for (const auto& q : s.ctrl) c.push_back(quat(q));
    for (const auto& x : s.pctrl) cp.push_back(point_json(x));
    doc["control_quaternions"] = c;
    doc["control_positions"] = cp;
  }
  return doc;
}

void save_motion(const Motion& motion, const std::string& path) {
  if (motion.is_rational())
    save_motion(motion.rational(), path);
  else
    write_file_atomic(path, qspline_document(motion).dump(1) + "\n");
}

Motion load_motion(const std::string& path) {
  auto read = read_motion_or_text(path);
  if (auto* f = std::get_if<MotionFile>(&read)) return to_motion(std::move(*f));
  json doc = parse_json(std::get<std::string>(read), path, "method");  // either kind
  if (is_qspline_document(doc)) return qspline_motion(doc, path);
  return to_motion(parse_motion(std::move(doc), path));
}

}  // namespace qmotion::io
