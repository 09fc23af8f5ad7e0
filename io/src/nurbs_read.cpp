// io/src/nurbs_read.cpp: read_nurbs_file (nurbs_json.hpp): NURBS files scanned in place, a
// row at a time, with the tree reader behind for anything unusual.
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/paged_text.hpp>
#include <qmotion/kernel/error.hpp>
#include <set>

#include "json_simd.hpp"

namespace qmotion::io {
namespace {
namespace sj = simd::sj;
using json = nlohmann::json;
/// Called with each part of the text once read: its pages may go.
using Done = std::function<void(std::string_view)>;

/// A degree the scanner takes (a larger one goes to the tree, which words any refusal).
bool degree_member(std::string_view raw, int& out) {
  return simd::integer_value(raw, 1, 1000, out);
}

bool doubles_member(std::string_view raw, std::vector<double>& out) {
  std::vector<Number> n;
  if (!simd::read_member(raw, [&](sj::value v) { return simd::numbers(v, n, /*lean=*/true); }))
    return false;
  out.clear();
  out.reserve(n.size());
  for (const auto& x : n) out.push_back(x.value);
  return true;
}

/// Rows of [x, y, z] into `out`.
bool points_member(std::string_view raw, std::vector<Eigen::Vector3d>& out) {
  std::vector<Number> n;
  const bool ok = simd::number_rows(
      raw, 3,
      [&](std::size_t rows, std::size_t width) {
        if (width != 3) return false;
        n.resize(rows * 3);
        return true;
      },
      [&](std::size_t i) { return n.data() + 3 * i; }, /*lean=*/true);
  if (!ok) return false;
  out.clear();
  out.reserve(n.size() / 3);
  for (std::size_t i = 0; i + 2 < n.size(); i += 3)
    out.emplace_back(n[i].value, n[i + 1].value, n[i + 2].value);
  return true;
}

/// The members of the object `text`, each key once; false otherwise.
bool unique_members(std::string_view text, std::vector<simd::Member>& out) {
  if (!simd::members(text, out)) return false;
  std::set<std::string_view> keys;
  for (const auto& m : out)
    if (!keys.insert(m.key).second) return false;
  return true;
}

/// A nurbs_surface object, validated as surface_from_json validates it; false for anything
/// that function would refuse (it then words it) or that the scanner does not take.
bool fast_surface(std::string_view text, sweep::NurbsSurface<double>& s, const Done& done) {
  std::vector<simd::Member> m;
  if (!unique_members(text, m)) return false;
  int known = 0;  // of the seven members a surface has (each once: unique_members)
  for (const auto& [key, raw] : m) {
    bool ok = true;
    if (key == "type") {
      std::string t;
      ok = simd::string_value(raw, t) && t == "nurbs_surface";
    } else if (key == "degree_u" || key == "degree_v") {
      ok = degree_member(raw, key == "degree_u" ? s.degree_u : s.degree_v);
    } else if (key == "knots_u" || key == "knots_v") {
      ok = doubles_member(raw, key == "knots_u" ? s.knots_u : s.knots_v);
    } else if (key == "control_points") {
      ok = simd::elements(raw, [&](std::string_view row) {
        const bool read = points_member(row, s.points.emplace_back());
        done(row);
        return read;
      });
    } else if (key == "weights") {
      ok = simd::elements(
          raw, [&](std::string_view row) { return doubles_member(row, s.weights.emplace_back()); });
    } else {
      if (!simd::check_slice(raw, 1)) return false;
      continue;  // another member: not one of the seven
    }
    if (!ok) return false;
    ++known;
  }
  if (known != 7 || s.points.empty() || s.weights.size() != s.points.size()) return false;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    if (s.points[i].size() != s.points[0].size() || s.weights[i].size() != s.points[i].size())
      return false;
    for (double w : s.weights[i])
      if (!(w > 0)) return false;
  }
  return kernel::BSpline<double>::validate(s.degree_u, s.knots_u, s.points.size()).empty() &&
         kernel::BSpline<double>::validate(s.degree_v, s.knots_v, s.points[0].size()).empty();
}

/// A nurbs_curve object, validated as curve_from_json validates it (weights optional).
bool fast_curve(std::string_view text, sweep::NurbsCurve<double>& c) {
  std::vector<simd::Member> m;
  if (!unique_members(text, m)) return false;
  bool type = false, degree = false, knots = false, points = false, weights = false;
  for (const auto& [key, raw] : m) {
    bool ok = true;
    if (key == "type") {
      std::string t;
      ok = type = simd::string_value(raw, t) && t == "nurbs_curve";
    } else if (key == "degree") {
      ok = degree = degree_member(raw, c.degree);
    } else if (key == "knots") {
      ok = knots = doubles_member(raw, c.knots);
    } else if (key == "control_points") {
      ok = points = points_member(raw, c.points);
    } else if (key == "weights") {
      ok = weights = doubles_member(raw, c.weights);
    } else {
      ok = simd::check_slice(raw, 1);
    }
    if (!ok) return false;
  }
  if (!type || !degree || !knots || !points) return false;
  if (!weights) c.weights.assign(c.points.size(), 1.0);
  if (c.weights.size() != c.points.size()) return false;
  for (double w : c.weights)
    if (!(w > 0)) return false;
  return kernel::BSpline<double>::validate(c.degree, c.knots, c.points.size()).empty();
}

/// The file read by the scanner; std::nullopt when anything is unusual.
std::optional<NurbsFile> fast_file(std::string_view text, bool surface, const Done& done) {
  std::vector<simd::Member> root;
  if (!unique_members(text, root)) return std::nullopt;
  NurbsFile f;
  std::string type;
  for (const auto& [key, raw] : root) {
    if (key == "type" && !simd::string_value(raw, type)) return std::nullopt;
    if (key == "units" && raw.front() == '"' && !simd::string_value(raw, f.units))
      return std::nullopt;
  }
  if (!surface) {
    if (!fast_curve(text, f.curve)) return std::nullopt;
    return f;
  }
  if (type != "nurbs_shell") {
    if (!fast_surface(text, f.faces.emplace_back(), done)) return std::nullopt;
    return f;
  }
  for (const auto& [key, raw] : root) {
    bool ok = true;
    if (key == "faces") {
      ok = simd::elements(raw, [&](std::string_view face) {
        const bool read = fast_surface(face, f.faces.emplace_back(), done);
        done(face);
        return read;
      });
    } else if (key != "type" && key != "units") {
      ok = simd::check_slice(raw, 1);
    }
    if (!ok) return std::nullopt;
  }
  if (f.faces.empty()) return std::nullopt;
  return f;
}

/// The file read through the tree: every refusal worded.
NurbsFile tree_file(const json& doc, const std::string& path, bool surface) {
  NurbsFile f;
  if (doc.is_object() && doc.contains("units") && doc["units"].is_string())
    f.units = doc["units"].get<std::string>();
  if (!surface) {
    f.curve = curve_from_json(doc, path);
  } else if (doc.is_object() && doc.value("type", "") == "nurbs_shell") {
    if (!doc.contains("faces") || !doc["faces"].is_array() || doc["faces"].empty())
      throw Error(Errc::invalid_input, path + ": faces: expected an array of nurbs_surface");
    for (std::size_t k = 0; k < doc["faces"].size(); ++k)
      f.faces.push_back(
          surface_from_json(doc["faces"][k], path + ": face " + std::to_string(k + 1)));
  } else {
    f.faces.push_back(surface_from_json(doc, path));
  }
  return f;
}

}  // namespace

NurbsFile read_nurbs_file(const std::string& path, bool surface) {
  PagedText text = PagedText::read(path);
  const std::string_view view = text.view();
  const auto done = [&](std::string_view part) {
    text.release_before(static_cast<std::size_t>(part.data() + part.size() - view.data()));
  };
  if (auto f = fast_file(view, surface, done)) return std::move(*f);
  return tree_file(parse_json(text.whole(path), path), path, surface);
}

}  // namespace qmotion::io
