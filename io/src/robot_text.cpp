// io/src/robot_text.cpp: the pieces the robot-program readers share (robot_text.hpp).
#include "robot_text.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <utility>

namespace qmotion::io::robot {

std::string upper(std::string_view s) {
  std::string u(s);
  for (auto& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(b, e - b + 1));
}

std::vector<std::pair<int, std::string>> code_lines(const std::string& text, char comment,
                                                    bool single_quotes) {
  std::vector<std::pair<int, std::string>> out;
  std::size_t pos = 0;
  for (int line = 1; pos <= text.size(); ++line) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    const std::string_view l(text.data() + pos, end - pos);
    pos = end + 1;
    bool quoted = false;
    std::size_t cut = l.size();
    for (std::size_t i = 0; i < l.size(); ++i) {
      if (l[i] == '"' || (single_quotes && l[i] == '\'')) quoted = !quoted;
      if (l[i] == comment && !quoted) {
        cut = i;
        break;
      }
    }
    std::string t = trim(l.substr(0, cut));
    if (!t.empty()) out.emplace_back(line, std::move(t));
  }
  return out;
}

void unknown(const Statement& s, const std::string& why, const RobotOptions& options,
             PoseSet& set) {
  if (!options.skip_unknown) refuse(s, why);
  set.warnings.push_back(s.where + ": " + why + "; skipped (--skip-unknown)");
}

std::string construct(const std::string& text) {
  const std::string t = trim(text);
  return "'" + (t.size() > 60 ? t.substr(0, 57) + "..." : t) + "'";
}

Number number(const std::string& token, const Statement& s, const std::string& what) {
  const std::string t = trim(token);
  double v = 0;
  const char* end = t.data() + t.size();
  const char* first = t.data() + (t.size() > 1 && t[0] == '+' ? 1 : 0);
  const auto r = std::from_chars(first, end, v);
  if (t.empty() || r.ec != std::errc() || r.ptr != end || !std::isfinite(v))
    refuse(s, what + ": expected a number, found '" + t + "'");
  Number n;
  n.value = v;
  n.text = std::string(first, end);
  return n;
}

std::vector<std::string> split_top(std::string_view s) {
  std::vector<std::string> out;
  int depth = 0;
  bool quoted = false;
  std::size_t start = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '"') quoted = !quoted;
    if (quoted) continue;
    if (c == '[' || c == '{' || c == '(') ++depth;
    if (c == ']' || c == '}' || c == ')') --depth;
    if (c == ',' && depth == 0) {
      out.push_back(trim(s.substr(start, i - start)));
      start = i + 1;
    }
  }
  out.push_back(trim(s.substr(start)));
  return out;
}

bool identifier(std::string_view s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

Frame frame_of(const PoseInput& pose) {
  const auto& v = pose.rotation.values;
  Frame f;
  f.q = Eigen::Quaterniond(v[0].value, v[1].value, v[2].value, v[3].value).normalized();
  f.p = {pose.position[0].value, pose.position[1].value, pose.position[2].value};
  return f;
}

PoseInput quaternion_pose(const std::array<Number, 3>& p, const Eigen::Quaterniond& q) {
  PoseInput pose;
  pose.position = p;
  pose.rotation.kind = RotationInput::Kind::quaternion;
  for (const double c : {q.w(), q.x(), q.y(), q.z()}) {  // computed: no source text
    Number n;
    n.value = c;
    pose.rotation.values.push_back(n);
  }
  return pose;
}

PoseInput pose_of(const Frame& f) {
  std::array<Number, 3> p;
  for (int k = 0; k < 3; ++k) p[static_cast<std::size_t>(k)].value = f.p(k);
  return quaternion_pose(p, f.q);
}

PoseSet finished(PoseSet set, const std::string& source, const char* instructions) {
  if (set.poses.size() < 2)
    throw Error(Errc::invalid_input, source + ": needs at least two poses; the program moves to " +
                                         std::to_string(set.poses.size()) + " Cartesian target" +
                                         (set.poses.size() == 1 ? "" : "s") + " (" + instructions +
                                         ")");
  if (set.poses.size() > kMaxPoses)
    throw Error(Errc::invalid_input, source + ": more than " + std::to_string(kMaxPoses) +
                                         " poses (the limit of a pose file)");
  return set;
}

}  // namespace qmotion::io::robot
