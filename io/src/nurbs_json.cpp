// io/src/nurbs_json.cpp
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/json_text.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/kernel/error.hpp>

namespace qmotion::io {
namespace {
using json = nlohmann::json;

std::vector<double> read_array(const json& j, const std::string& where) {
  if (!j.is_array()) throw Error(Errc::invalid_input, where + ": expected an array of numbers");
  std::vector<double> v;
  for (std::size_t i = 0; i < j.size(); ++i) v.push_back(read_number(j[i], where, i).value);
  return v;
}

/// The NURBS documents streamed: one pole a line.
void curve_text(JsonText& t, const sweep::NurbsCurve<double>& c, const json& extra, int depth) {
  t.object({{"type", [&t](int) { t.out += "\"nurbs_curve\""; }},
            {"degree", [&t, &c](int) { t.integer(c.degree); }},
            {"knots", [&t, &c](int) { t.numbers(c.knots); }},
            {"control_points",
             [&t, &c](int d) {
               t.lines(c.points.size(), d, 3,
                       [&](JsonText& b, std::size_t i) { b.point(c.points[i], 3); });
             }},
            {"weights", [&t, &c](int) { t.numbers(c.weights); }}},
           extra, depth);
}

std::size_t pole_count(const sweep::NurbsSurface<double>& s) {
  std::size_t poles = 0;
  for (const auto& row : s.points) poles += row.size();
  return poles;
}

std::size_t pole_count(const std::vector<sweep::NurbsSurface<double>>& faces) {
  std::size_t poles = 0;
  for (const auto& f : faces) poles += pole_count(f);
  return poles;
}

void surface_text(JsonText& t, const sweep::NurbsSurface<double>& s, const json& extra, int depth) {
  const std::size_t row = s.points.empty() ? 0 : s.points.front().size();
  t.object({{"type", [&t](int) { t.out += "\"nurbs_surface\""; }},
            {"degree_u", [&t, &s](int) { t.integer(s.degree_u); }},
            {"degree_v", [&t, &s](int) { t.integer(s.degree_v); }},
            {"knots_u", [&t, &s](int) { t.numbers(s.knots_u); }},
            {"knots_v", [&t, &s](int) { t.numbers(s.knots_v); }},
            {"control_points",
             [&t, &s, row](int d) {
               t.lines(s.points.size(), d, 3 * row, [&](JsonText& r, std::size_t i) {
                 r.lines(s.points[i].size(), d + 1, 3,
                         [&](JsonText& b, std::size_t j) { b.point(s.points[i][j], 3); });
               });
             }},
            {"weights",
             [&t, &s, row](int d) {
               t.lines(s.weights.size(), d, row,
                       [&](JsonText& r, std::size_t i) { r.numbers(s.weights[i]); });
             }}},
           extra, depth);
}

void shell_text(JsonText& t, const std::vector<sweep::NurbsSurface<double>>& faces, bool closed,
                const json& extra) {
  const std::size_t poles = pole_count(faces);
  t.object({{"type", [&t](int) { t.out += "\"nurbs_shell\""; }},
            {"closed", [&t, closed](int) { t.out += closed ? "true" : "false"; }},
            {"faces",
             [&t, &faces, poles](int d) {
               t.lines(faces.size(), d, 4 * poles / std::max<std::size_t>(1, faces.size()),
                       [&](JsonText& b, std::size_t i) {
                         surface_text(b, faces[i], json::object(), d + 1);
                       });
             }}},
           extra, 0);
}

/// The document write(t) makes, whole, with its final newline; `reserve` bytes ahead.
template <typename Write>
std::string whole_text(std::size_t reserve, Write write) {
  JsonText t;
  t.out.reserve(reserve);
  write(t);
  t.out += '\n';
  return std::move(t.out);
}
}  // namespace

std::string curve_json_text(const sweep::NurbsCurve<double>& c, const json& extra) {
  return whole_text(64 + c.points.size() * 72 + c.knots.size() * 24,
                    [&](JsonText& t) { curve_text(t, c, extra, 0); });
}

std::string surface_json_text(const sweep::NurbsSurface<double>& s, const json& extra) {
  return whole_text(256 + pole_count(s) * 96, [&](JsonText& t) { surface_text(t, s, extra, 0); });
}

std::string shell_json_text(const std::vector<sweep::NurbsSurface<double>>& faces, bool closed,
                            const json& extra) {
  return whole_text(256 + pole_count(faces) * 96,
                    [&](JsonText& t) { shell_text(t, faces, closed, extra); });
}

void write_curve_json(const std::string& path, const sweep::NurbsCurve<double>& c,
                      const json& extra) {
  write_json_atomic(path, [&](JsonText& t) { curve_text(t, c, extra, 0); });
}

void write_surface_json(const std::string& path, const sweep::NurbsSurface<double>& s,
                        const json& extra) {
  write_json_atomic(path, [&](JsonText& t) { surface_text(t, s, extra, 0); });
}

void write_shell_json(const std::string& path,
                      const std::vector<sweep::NurbsSurface<double>>& faces, bool closed,
                      const json& extra) {
  write_json_atomic(path, [&](JsonText& t) { shell_text(t, faces, closed, extra); });
}

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

sweep::NurbsSurface<double> surface_from_json(const json& j, const std::string& where) {
  const json& type = require(j, "type", where);
  if (type != "nurbs_surface")
    throw Error(Errc::invalid_input,
                where + ": type: expected \"nurbs_surface\", found " + type.dump());
  sweep::NurbsSurface<double> s;
  for (const char* key : {"degree_u", "degree_v"}) {
    const json& d = require(j, key, where);
    if (!d.is_number_integer() || d.get<int>() < 1)
      throw Error(Errc::invalid_input, where + ": " + key + ": expected an integer >= 1");
  }
  s.degree_u = j["degree_u"].get<int>();
  s.degree_v = j["degree_v"].get<int>();
  s.knots_u = read_array(require(j, "knots_u", where), where + ": knots_u");
  s.knots_v = read_array(require(j, "knots_v", where), where + ": knots_v");
  const json& pts = require(j, "control_points", where);
  const json& w = require(j, "weights", where);
  if (!pts.is_array() || pts.empty() || !w.is_array() || w.size() != pts.size())
    throw Error(Errc::invalid_input,
                where + ": control_points and weights must be arrays of equal length");
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const std::string wi = where + ": control_points[" + std::to_string(i) + "]";
    if (!pts[i].is_array() || pts[i].size() != pts[0].size())
      throw Error(Errc::invalid_input, wi + ": rows must have equal length");
    s.points.emplace_back();
    s.weights.push_back(read_array(w[i], where + ": weights[" + std::to_string(i) + "]"));
    if (s.weights.back().size() != pts[i].size())
      throw Error(Errc::invalid_input,
                  where + ": weights[" + std::to_string(i) + "]: wrong length");
    for (std::size_t k = 0; k < s.weights.back().size(); ++k)
      if (!(s.weights.back()[k] > 0))
        throw Error(Errc::invalid_input,
                    where + ": weights[" + std::to_string(i) + "][" + std::to_string(k) + "] = " +
                        std::to_string(s.weights.back()[k]) + ": weights must be positive");
    for (std::size_t k = 0; k < pts[i].size(); ++k) {
      const auto p = read_array(pts[i][k], wi + "[" + std::to_string(k) + "]");
      if (p.size() != 3)
        throw Error(Errc::invalid_input, wi + "[" + std::to_string(k) + "]: expected 3 numbers");
      s.points.back().emplace_back(p[0], p[1], p[2]);
    }
  }
  auto iu = kernel::BSpline<double>::validate(s.degree_u, s.knots_u, s.points.size());
  if (!iu.empty()) throw Error(Errc::invalid_input, where + ": u: " + iu.front());
  auto iv = kernel::BSpline<double>::validate(s.degree_v, s.knots_v, s.points.front().size());
  if (!iv.empty()) throw Error(Errc::invalid_input, where + ": v: " + iv.front());
  return s;
}

}  // namespace qmotion::io
