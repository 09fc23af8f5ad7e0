// io/src/machine_file.cpp: machine files and velocity limits (docs/cam.md).
#include <cmath>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/machine_file.hpp>
#include <qmotion/io/units.hpp>
#include <qmotion/kernel/error.hpp>
#include <sstream>

namespace qmotion::io {
namespace {

using json = nlohmann::json;

Eigen::Vector3d vec3(const json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3)
    throw Error(Errc::invalid_input, where + ": expected an array of three numbers");
  Eigen::Vector3d v;
  for (std::size_t i = 0; i < 3; ++i) v(static_cast<int>(i)) = read_number(j[i], where, i).value;
  if (!v.allFinite()) throw Error(Errc::invalid_input, where + ": expected finite numbers");
  return v;
}

double limit(const json& j, const std::string& where) {
  const double v = read_number(j, where).value;
  if (!(v > 0) || !std::isfinite(v))
    throw Error(Errc::invalid_input, where + ": expected a positive velocity limit");
  return v;
}

}  // namespace

MachineFile parse_machine_file(const std::string& text, const std::string& source) {
  const json doc = parse_json(text, source);
  if (!doc.is_object()) throw Error(Errc::invalid_input, source + ": expected a JSON object");
  for (auto it = doc.begin(); it != doc.end(); ++it)
    if (it.key() != "name" && it.key() != "units" && it.key() != "axes" && it.key() != "velocity" &&
        it.key() != "travel" && it.key() != "acceleration")
      throw Error(Errc::invalid_input,
                  source + ": unknown field \"" + it.key() +
                      "\" (expected name, units, axes, velocity, travel, acceleration)");
  MachineFile f;
  cam::Machine& m = f.machine;
  m.name = source;
  if (doc.contains("name")) {
    if (!doc["name"].is_string())
      throw Error(Errc::invalid_input, source + ": name: expected a string");
    m.name = doc["name"].get<std::string>();
  }
  m.units = "mm";
  if (doc.contains("units")) {
    if (!doc["units"].is_string())
      throw Error(Errc::invalid_input, source + ": units: expected a string such as \"mm\"");
    m.units = canonical_unit(doc["units"].get<std::string>(), source + ": units");
  }
  if (!doc.contains("axes") || !doc["axes"].is_array() || doc["axes"].size() != 2)
    throw Error(Errc::invalid_input, source + ": axes: expected an array of the two rotary axes");
  for (std::size_t i = 0; i < 2; ++i) {
    const json& a = doc["axes"][i];
    const std::string where = source + ": axes[" + std::to_string(i) + "]";
    if (!a.is_object()) throw Error(Errc::invalid_input, where + ": expected an object");
    for (auto it = a.begin(); it != a.end(); ++it)
      if (it.key() != "name" && it.key() != "on" && it.key() != "direction" && it.key() != "pivot")
        throw Error(Errc::invalid_input, where + ": unknown field \"" + it.key() +
                                             "\" (expected name, on, direction, pivot)");
    cam::RotaryAxis& ax = m.axes[i];
    if (!a.contains("name") || !a["name"].is_string() || a["name"].get<std::string>().size() != 1)
      throw Error(Errc::invalid_input, where + ": name: expected \"A\", \"B\" or \"C\"");
    ax.name = a["name"].get<std::string>()[0];
    const std::string on =
        a.contains("on") && a["on"].is_string() ? a["on"].get<std::string>() : "";
    if (on != "table" && on != "head")
      throw Error(Errc::invalid_input, where + ": on: expected \"table\" or \"head\"");
    ax.head = on == "head";
    if (!a.contains("direction")) throw Error(Errc::invalid_input, where + ": direction: missing");
    const Eigen::Vector3d d = vec3(a["direction"], where + ": direction");
    if (!(d.norm() > 1e-9))
      throw Error(Errc::invalid_input,
                  where + ": direction: a zero-length axis has no direction to turn about");
    ax.direction = d.normalized();
    ax.pivot = a.contains("pivot") ? vec3(a["pivot"], where + ": pivot") : Eigen::Vector3d::Zero();
  }
  const std::string problem = cam::machine_problem(m);
  if (!problem.empty()) throw Error(Errc::invalid_input, source + ": axes: " + problem);
  // Each of velocity, travel and acceleration: an object keyed by this machine's axis words.
  auto per_axis = [&](const char* field, const char* example, auto&& read) {
    if (!doc.contains(field)) return;
    const json& v = doc[field];
    if (!v.is_object())
      throw Error(Errc::invalid_input,
                  source + ": " + field + ": expected an object such as " + example);
    for (auto it = v.begin(); it != v.end(); ++it) {
      const std::string where = source + ": " + field + ": " + it.key();
      const std::string& k = it.key();
      std::size_t i = 5;
      for (std::size_t j = 0; j < 5; ++j)
        if (k.size() == 1 && k[0] == m.word(j)) i = j;
      if (i == 5)
        throw Error(Errc::invalid_input, where + ": not an axis of this machine (X, Y, Z, " +
                                             std::string(1, m.axes[0].name) + ", " +
                                             std::string(1, m.axes[1].name) + ")");
      read(i, it.value(), where);
    }
  };
  per_axis("velocity", "{\"X\": 20000, \"C\": 7200}",
           [&](std::size_t i, const json& v, const std::string& where) {
             f.velocity[m.word(i)] = limit(v, where);
           });
  per_axis(
      "travel", "{\"A\": [-120, 30], \"Z\": [-500, 0]}",
      [&](std::size_t i, const json& v, const std::string& where) {
        if (!v.is_array() || v.size() != 2)
          throw Error(Errc::invalid_input, where + ": expected [min, max]");
        const double lo = read_number(v[0], where, 0).value, hi = read_number(v[1], where, 1).value;
        if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi))
          throw Error(Errc::invalid_input, where + ": expected finite [min, max] with min < max");
        m.travel[i] = {lo, hi};
      });
  per_axis("acceleration", "{\"X\": 2000, \"C\": 1800}",
           [&](std::size_t i, const json& v, const std::string& where) {
             const double a = read_number(v, where).value;
             if (!(a > 0) || !std::isfinite(a))
               throw Error(Errc::invalid_input,
                           where + ": expected a positive acceleration (units or degrees per s²)");
             m.acceleration[i] = a;
           });
  return f;
}

MachineFile read_machine_file(const std::string& path) {
  return parse_machine_file(read_text_file(path, std::uintmax_t(1) << 20), path);
}

std::map<char, double> parse_axis_limits(const std::string& text, const std::string& where) {
  std::map<char, double> out;
  std::stringstream ss(text);
  for (std::string cell; std::getline(ss, cell, ',');) {
    const auto eq = cell.find('=');
    if (eq != 1 || std::string("XYZABC").find(cell[0]) == std::string::npos)
      throw Error(Errc::invalid_input,
                  where + " " + text + ": expected WORD=limit pairs such as X=20000,C=7200");
    if (out.count(cell[0]))
      throw Error(Errc::invalid_input, where + ": " + cell.substr(0, 1) + " is given twice");
    const double v = parse_number_text(cell.substr(2), where + " " + cell.substr(0, 1)).value;
    if (!(v > 0) || !std::isfinite(v))
      throw Error(Errc::invalid_input, where + " " + cell + ": expected a positive velocity limit");
    out[cell[0]] = v;
  }
  if (out.empty())
    throw Error(Errc::invalid_input, where + ": expected WORD=limit pairs such as X=20000,C=7200");
  return out;
}

}  // namespace qmotion::io
