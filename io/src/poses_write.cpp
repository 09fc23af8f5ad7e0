// io/src/poses_write.cpp: poses written as JSON text (streamed) or as a JSON value, each
// number as its source text where a double would lose it.
#include <qmotion/io/json_text.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/kernel/error.hpp>
#include <sstream>

namespace qmotion::io {

using json = nlohmann::json;

namespace {
/// Whether a number is written as its source text (a string): a decimal of at most 15
/// digits survives the trip through double (shortest round-trip printing), and so does one
/// read without its text (it was that printing already); anything longer, and every "p/q",
/// keeps its text.
bool keeps_text(const Number& n) {
  if (n.text.empty()) return false;
  const auto digits = std::count_if(n.text.begin(), n.text.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c));
  });
  return n.text.find('/') != std::string::npos || digits > 15;
}

void number_text(JsonText& t, const Number& n) {
  if (keeps_text(n))
    t.string(n.text.str());
  else
    t.number(n.value);
}

/// The poses array, one pose a line ({"position","rotation","t"} in sorted order).
template <typename P, typename Write>
void pose_lines(JsonText& t, const std::vector<P>& poses, const std::string& units, int depth,
                Write write) {
  t.object({{"poses",
             [&](int d) {
               t.lines(poses.size(), d, 8, [&](JsonText& b, std::size_t i) { write(b, poses[i]); });
             }},
            {"units", [&](int) { t.string(units); }}},
           depth);
}
}  // namespace

void poses_text(JsonText& t, const PoseSet& set, int depth) {
  auto nums = [](JsonText& t, const auto* v, std::size_t n) {
    t.out += '[';
    for (std::size_t i = 0; i < n; ++i) {
      if (i) t.out += ',';
      number_text(t, v[i]);
    }
    t.out += ']';
  };
  pose_lines(t, set.poses, set.units, depth, [&](JsonText& t, const PoseInput& p) {
    t.out += "{\"position\":";
    nums(t, p.position.data(), 3);
    t.out += ",\"rotation\":{";
    const auto& v = p.rotation.values;
    switch (p.rotation.kind) {
      case RotationInput::Kind::quaternion:
        t.out += "\"quaternion\":";
        nums(t, v.data(), v.size());
        break;
      case RotationInput::Kind::matrix:
        t.out += "\"matrix\":[";
        for (std::size_t r = 0; r < 3; ++r) {
          if (r) t.out += ',';
          nums(t, v.data() + 3 * r, 3);
        }
        t.out += ']';
        break;
      case RotationInput::Kind::axis_angle:
        t.out += "\"axis_angle\":{\"angle_deg\":";
        number_text(t, v[3]);
        t.out += ",\"axis\":";
        nums(t, v.data(), 3);
        t.out += '}';
        break;
    }
    t.out += '}';
    if (p.t) {
      t.out += ",\"t\":";
      number_text(t, *p.t);
    }
    t.out += '}';
  });
}

void poses_text(JsonText& t, const std::vector<Pose<double>>& poses, const std::string& units,
                int depth) {
  pose_lines(t, poses, units, depth, [](JsonText& t, const Pose<double>& p) {
    t.out += "{\"position\":";
    t.point(p.position, 3);
    t.out += ",\"rotation\":{\"quaternion\":";
    t.point(std::array<double, 4>{p.rotation.w(), p.rotation.x(), p.rotation.y(), p.rotation.z()},
            4);
    t.out += '}';
    if (p.t) {
      t.out += ",\"t\":";
      t.number(*p.t);
    }
    t.out += '}';
  });
}

json poses_to_json(const PoseSet& set) {
  auto num = [](const Number& n) -> json {
    if (keeps_text(n)) return n.text.str();
    return n.value;
  };
  json poses = json::array();
  for (const auto& p : set.poses) {
    json j;
    if (p.t) j["t"] = num(*p.t);
    j["position"] = {num(p.position[0]), num(p.position[1]), num(p.position[2])};
    json vals = json::array();
    for (const auto& v : p.rotation.values) vals.push_back(num(v));
    switch (p.rotation.kind) {
      case RotationInput::Kind::quaternion:
        j["rotation"]["quaternion"] = vals;
        break;
      case RotationInput::Kind::matrix:
        j["rotation"]["matrix"] = {
            {vals[0], vals[1], vals[2]}, {vals[3], vals[4], vals[5]}, {vals[6], vals[7], vals[8]}};
        break;
      case RotationInput::Kind::axis_angle:
        j["rotation"]["axis_angle"] = {{"axis", {vals[0], vals[1], vals[2]}},
                                       {"angle_deg", vals[3]}};
        break;
    }
    poses.push_back(j);
  }
  return json{{"units", set.units}, {"poses", poses}};
}

json poses_to_json(const std::vector<Pose<double>>& poses, const std::string& units) {
  json out = json::array();
  for (const auto& p : poses) {
    json j;
    if (p.t) j["t"] = *p.t;
    j["position"] = {p.position(0), p.position(1), p.position(2)};
    j["rotation"]["quaternion"] = {p.rotation.w(), p.rotation.x(), p.rotation.y(), p.rotation.z()};
    out.push_back(j);
  }
  return json{{"units", units}, {"poses", out}};
}

}  // namespace qmotion::io
