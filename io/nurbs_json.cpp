// io/nurbs_json.cpp
#include "io/nurbs_json.hpp"

#include "io/json_number.hpp"
#include "kernel/error.hpp"

namespace qmotion::io {
namespace {
using json = nlohmann::json;

json point_json(const Eigen::Vector3d& p) { return json{p(0), p(1), p(2)}; }

std::vector<double> read_array(const json& j, const std::string& where) {
  if (!j.is_array()) throw Error(Errc::invalid_input, where + ": expected an array of numbers");
  std::vector<double> v;
  for (std::size_t i = 0; i < j.size(); ++i)
    v.push_back(read_number(j[i], where + "[" + std::to_string(i) + "]").value);
  return v;
}

}  // namespace

json curve_to_json(const sweep::NurbsCurve<double>& c) {
  json pts = json::array();
  for (const auto& p : c.points) pts.push_back(point_json(p));
  return json{{"type", "nurbs_curve"},
              {"degree", c.degree},
              {"knots", c.knots},
              {"control_points", pts},
              {"weights", c.weights}};
}

json surface_to_json(const sweep::NurbsSurface<double>& s) {
  json pts = json::array();
  for (const auto& row : s.points) {
    json r = json::array();
    for (const auto& p : row) r.push_back(point_json(p));
    pts.push_back(r);
  }
  return json{{"type", "nurbs_surface"}, {"degree_u", s.degree_u}, {"degree_v", s.degree_v},
              {"knots_u", s.knots_u},    {"knots_v", s.knots_v},   {"control_points", pts},
              {"weights", s.weights}};
}

sweep::NurbsCurve<double> curve_from_json(const json& j, const std::string& where) {
  const json& type = require(j, "type", where);
  if (type != "nurbs_curve")
    throw Error(Errc::invalid_input,
                where + ": type: expected \"nurbs_curve\", found " + type.dump());
  sweep::NurbsCurve<double> c;
  const json& deg = require(j, "degree", where);
  if (!deg.is_number_integer() || deg.get<int>() < 1)
    throw Error(Errc::invalid_input,
                where + ": degree: expected an integer >= 1, found " + deg.dump());
  c.degree = deg.get<int>();
  c.knots = read_array(require(j, "knots", where), where + ": knots");
  const json& pts = require(j, "control_points", where);
  if (!pts.is_array())
    throw Error(Errc::invalid_input, where + ": control_points: expected an array of [x,y,z]");
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto p = read_array(pts[i], where + ": control_points[" + std::to_string(i) + "]");
    if (p.size() != 3)
      throw Error(Errc::invalid_input,
                  where + ": control_points[" + std::to_string(i) + "]: expected 3 numbers");
    c.points.emplace_back(p[0], p[1], p[2]);
  }
  if (j.contains("weights")) {
    c.weights = read_array(j["weights"], where + ": weights");
    if (c.weights.size() != c.points.size())
      throw Error(Errc::invalid_input, where + ": weights: " + std::to_string(c.weights.size()) +
                                           " weights for " + std::to_string(c.points.size()) +
                                           " control points");
    for (std::size_t i = 0; i < c.weights.size(); ++i)
      if (!(c.weights[i] > 0))
        throw Error(Errc::invalid_input, where + ": weights[" + std::to_string(i) +
                                             "] = " + std::to_string(c.weights[i]) +
                                             ": weights must be positive");
  } else {
    c.weights.assign(c.points.size(), 1.0);
  }
  const auto issues = kernel::BSpline<double>::validate(c.degree, c.knots, c.points.size());
  if (!issues.empty()) throw Error(Errc::invalid_input, where + ": " + issues.front());
  return c;
}

}  // namespace qmotion::io
