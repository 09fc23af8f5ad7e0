// io/src/profiles.cpp
#include <filesystem>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/io/point_text.hpp>
#include <qmotion/io/profiles.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <sstream>
#include <vector>

namespace qmotion::io {
namespace {

std::vector<double> numbers(const std::string& text, std::size_t count, const std::string& where) {
  std::vector<double> v = parse_numbers(text, where);
  if (v.size() != count)
    throw Error(Errc::invalid_input, where + ": expected " + std::to_string(count) +
                                         " comma-separated numbers, found '" + text + "'");
  return v;
}

Eigen::Vector3d point3(const std::string& text, const std::string& where) {
  const auto p = numbers(text, 3, where);
  return Eigen::Vector3d(p[0], p[1], p[2]);
}

/// The profile of the edges, after checking that each ends where the next starts and that
/// no weight is non-positive; closed when the last ends where the first starts.
sweep::Profile<double> wire_profile(std::vector<sweep::NurbsCurve<double>> edges,
                                    const std::string& where) {
  if (edges.empty()) throw Error(Errc::invalid_input, where + ": the profile has no curve");
  Eigen::Vector3d lo = edges.front().points.front(), hi = lo;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    for (const auto& p : edges[k].points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    for (double w : edges[k].weights)
      if (!(w > 0))
        throw Error(Errc::invalid_input, where + ": edge " + std::to_string(k + 1) +
                                             " of the profile has a non-positive weight");
  }
  const double tol = 1e-9 * (hi - lo).norm();
  for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
    const double gap = (edges[k].points.back() - edges[k + 1].points.front()).norm();
    if (gap > tol) {
      std::ostringstream os;
      os << where << ": the profile's wire has a gap: edge " << k + 1 << " ends " << gap
         << " away from where edge " << k + 2 << " starts";
      throw Error(Errc::invalid_input, os.str());
    }
  }
  const double closing = (edges.back().points.back() - edges.front().points.front()).norm();
  sweep::Profile<double> p{std::move(edges), false};
  p.closed = closing <= tol;
  return p;
}

}  // namespace

sweep::Profile<double> profile_from_json(const nlohmann::json& doc, const std::string& where) {
  if (!doc.is_array()) return sweep::single_edge(curve_from_json(doc, where));
  std::vector<sweep::NurbsCurve<double>> edges;
  for (std::size_t k = 0; k < doc.size(); ++k)
    edges.push_back(curve_from_json(doc[k], where + ": curve " + std::to_string(k + 1)));
  return wire_profile(std::move(edges), where);
}

sweep::Profile<double> read_profile(const std::string& spec, const std::string& units) {
  const std::string where = "--profile " + spec;
  if (spec.rfind("polyline:", 0) == 0) {
    std::vector<Eigen::Vector3d> pts;
    std::stringstream ss(spec.substr(9));
    std::string cell;
    while (std::getline(ss, cell, ':')) pts.push_back(point3(cell, where));
    try {
      return sweep::polyline(pts);
    } catch (const Error& e) {
      throw Error(Errc::invalid_input, where + ": " + e.what());
    }
  }
  if (spec.rfind("rect:", 0) == 0) {
    const auto v = numbers(spec.substr(5), 2, where);
    try {
      return sweep::rect(v[0], v[1]);
    } catch (const Error& e) {
      throw Error(Errc::invalid_input, where + ": " + e.what());
    }
  }
  if (spec.rfind("segment:", 0) == 0) {
    const std::string rest = spec.substr(8);
    const auto colon = rest.find(':');
    if (colon == std::string::npos)
      throw Error(Errc::invalid_input, where + ": expected segment:x0,y0,z0:x1,y1,z1");
    const auto p = numbers(rest.substr(0, colon), 3, where),
               q = numbers(rest.substr(colon + 1), 3, where);
    if (p == q) throw Error(Errc::invalid_input, where + ": the two end points coincide");
    return sweep::single_edge(sweep::segment<double>(Eigen::Vector3d(p[0], p[1], p[2]),
                                                     Eigen::Vector3d(q[0], q[1], q[2])));
  }
  if (spec.rfind("circle:", 0) == 0) {
    const auto r = numbers(spec.substr(7), 1, where);
    if (!(r[0] > 0)) throw Error(Errc::invalid_input, where + ": the radius must be positive");
    return sweep::single_edge(sweep::circle<double>(r[0]));
  }
  if (spec.rfind("arc:", 0) == 0) {
    const auto v = numbers(spec.substr(4), 3, where);
    try {
      return sweep::single_edge(sweep::arc(v[0], v[1], v[2]));
    } catch (const Error& e) {
      throw Error(Errc::invalid_input, where + ": " + e.what());
    }
  }
  const std::string ext = lower_extension(spec);
  if (ext == ".step" || ext == ".stp" || ext == ".igs" || ext == ".iges") {
    return wire_profile(read_cad(spec, /*want_surface=*/false, units).wire, spec);
  }
  if (ext == ".json") return profile_from_json(read_json_file(spec), spec);
  throw Error(
      Errc::invalid_input,
      where +
          ": expected a .json, .step, .stp, .igs or .iges file, or segment:, polyline:, rect:, "
          "circle:, arc:");
}

}  // namespace qmotion::io
