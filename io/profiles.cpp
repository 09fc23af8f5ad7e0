// io/profiles.cpp
#include "io/profiles.hpp"

#include <filesystem>
#include <sstream>
#include <vector>

#include "io/json_number.hpp"
#include "io/nurbs_json.hpp"
#include "io/occt.hpp"
#include "kernel/error.hpp"
#include "sweep/profiles.hpp"

namespace qmotion::io {
namespace {

std::vector<double> numbers(const std::string& text, std::size_t count, const std::string& where) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string cell;
  while (std::getline(ss, cell, ',')) v.push_back(parse_number_text(cell, where).value);
  if (v.size() != count)
    throw Error(Errc::invalid_input, where + ": expected " + std::to_string(count) +
                                         " comma-separated numbers, found '" + text + "'");
  return v;
}

}  // namespace

sweep::NurbsCurve<double> read_profile(const std::string& spec, const std::string& units) {
  const std::string where = "--profile " + spec;
  if (spec.rfind("segment:", 0) == 0) {
    const std::string rest = spec.substr(8);
    const auto colon = rest.find(':');
    if (colon == std::string::npos)
      throw Error(Errc::invalid_input, where + ": expected segment:x0,y0,z0:x1,y1,z1");
    const auto p = numbers(rest.substr(0, colon), 3, where),
               q = numbers(rest.substr(colon + 1), 3, where);
    if (p == q) throw Error(Errc::invalid_input, where + ": the two end points coincide");
    return sweep::segment<double>(Eigen::Vector3d(p[0], p[1], p[2]),
                                  Eigen::Vector3d(q[0], q[1], q[2]));
  }
  if (spec.rfind("circle:", 0) == 0) {
    const auto r = numbers(spec.substr(7), 1, where);
    if (!(r[0] > 0)) throw Error(Errc::invalid_input, where + ": the radius must be positive");
    return sweep::circle<double>(r[0]);
  }
  if (spec.rfind("arc:", 0) == 0) {
    const auto v = numbers(spec.substr(4), 3, where);
    try {
      return sweep::arc(v[0], v[1], v[2]);
    } catch (const Error& e) {
      throw Error(Errc::invalid_input, where + ": " + e.what());
    }
  }
  std::string ext = std::filesystem::path(spec).extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".step" || ext == ".stp" || ext == ".igs" || ext == ".iges") {
    const CadGeometry g = read_cad(spec, /*want_surface=*/false, units);
    for (std::size_t i = 0; i < g.curve.weights.size(); ++i)
      if (!(g.curve.weights[i] > 0))
        throw Error(Errc::invalid_input, spec + ": the profile curve has a non-positive weight");
    return g.curve;
  }
  if (ext == ".json") return curve_from_json(read_json_file(spec), spec);
  throw Error(
      Errc::invalid_input,
      where + ": expected a .json, .step, .stp, .igs or .iges file, or segment:, circle:, arc:");
}

}  // namespace qmotion::io
