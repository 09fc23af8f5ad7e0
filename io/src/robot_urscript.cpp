// io/src/robot_urscript.cpp: Universal Robots URScript programs (.script) read as pose files:
// the pose targets of movel, movej, movep and movec, in millimetres, for one TCP. Every
// statement is a construct this reader knows by its exact name, or it is refused.
#include <charconv>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "robot_text.hpp"

namespace qmotion::io {
namespace urscript {
using namespace robot;

/// Lines of URScript without '#' comments, and without the step markers ($ 1 "...") that
/// PolyScope writes.
std::vector<Statement> script_lines(const std::string& text, const std::string& source) {
  std::vector<Statement> out;
  for (auto& [line, code] : code_lines(text, '#', true))
    if (!(code.size() > 2 && code[0] == '$' && code[1] == ' '))
      out.push_back({std::move(code), source + ": line " + std::to_string(line)});
  return out;
}

/// A length in metres as millimetres, its text shifted by three decimal places so that exact
/// readers get the number as written.
Number millimetres(const Number& metres) {
  std::string t = metres.text.str();
  std::string sign;
  if (!t.empty() && (t[0] == '-' || t[0] == '+')) {
    sign = t[0] == '-' ? "-" : "";
    t = t.substr(1);
  }
  int exponent = 3;
  if (const auto e = t.find_first_of("eE"); e != std::string::npos) {
    exponent += std::stoi(t.substr(e + 1));
    t = t.substr(0, e);
  }
  const auto dot = t.find('.');
  std::string digits = t;
  if (dot != std::string::npos) {
    digits = t.substr(0, dot) + t.substr(dot + 1);
    exponent -= static_cast<int>(t.size() - dot - 1);
  }
  if (exponent >= 0) {
    digits += std::string(static_cast<std::size_t>(exponent), '0');
  } else {
    const auto frac = static_cast<std::size_t>(-exponent);
    if (digits.size() <= frac) digits = std::string(frac - digits.size() + 1, '0') + digits;
    digits.insert(digits.size() - frac, ".");
  }
  while (digits.size() > 1 && digits[0] == '0' && digits[1] != '.') digits.erase(0, 1);
  if (digits.find('.') != std::string::npos) {
    while (digits.back() == '0') digits.pop_back();
    if (digits.back() == '.') digits.pop_back();
  }
  Number mm;
  mm.text = (digits == "0" ? "" : sign) + digits;
  std::from_chars(mm.text.begin(), mm.text.end(), mm.value);  // the shifted text, rounded once
  return mm;
}

/// A pose: its frame, and for a literal its position numbers as written (in millimetres).
struct ScriptPose {
  Frame frame;
  std::optional<std::array<Number, 3>> position;
};

/// p[x, y, z, rx, ry, rz]: metres and a rotation vector (radians).
ScriptPose pose_literal(const std::string& text, const Statement& s) {
  const auto inner = split_top(std::string_view(text).substr(2, text.size() - 3));
  if (inner.size() != 6)
    refuse(s, "a pose p[x, y, z, rx, ry, rz] has 6 numbers, found " + construct(text));
  std::array<Number, 3> p;
  Eigen::Vector3d r;
  for (std::size_t k = 0; k < 3; ++k) {
    p[k] = millimetres(number(inner[k], s, "pose position"));
    r(static_cast<int>(k)) = number(inner[k + 3], s, "pose rotation vector").value;
  }
  const double angle = r.norm();
  ScriptPose out;
  if (angle > 0) out.frame.q = Eigen::Quaterniond(Eigen::AngleAxisd(angle, r / angle));
  out.frame.p = {p[0].value, p[1].value, p[2].value};
  out.position = p;
  return out;
}

/// A pose expression: a literal, a variable holding a pose, or pose_trans(a, b).
ScriptPose pose_value(const std::string& expr, const Statement& s,
                      const std::map<std::string, std::optional<ScriptPose>>& vars) {
  const std::string e = trim(expr);
  if (e.size() > 3 && e.rfind("p[", 0) == 0 && e.back() == ']') return pose_literal(e, s);
  if (e.rfind("pose_trans", 0) == 0 && trim(e.substr(10)).rfind('(', 0) == 0 && e.back() == ')') {
    const std::string inner = trim(e.substr(10));
    const auto args = split_top(std::string_view(inner).substr(1, inner.size() - 2));
    if (args.size() != 2) refuse(s, "pose_trans expects two poses, found " + construct(e));
    return {pose_value(args[0], s, vars).frame * pose_value(args[1], s, vars).frame, std::nullopt};
  }
  if (identifier(e)) {
    const auto it = vars.find(e);
    if (it == vars.end()) refuse(s, "'" + e + "' is not assigned in the program");
    if (!it->second) refuse(s, "'" + e + "' does not hold a pose the program gives");
    return *it->second;
  }
  if (!e.empty() && e.front() == '[')
    refuse(s, construct(e) +
                  " is a list of joint angles: it has no Cartesian pose without the "
                  "robot's kinematics");
  refuse(s, construct(e) +
                " is not a pose the reader knows (p[...], a pose variable or "
                "pose_trans)");
}

/// Calls that move nothing and change no frame.
bool harmless(const std::string& name) {
  static const std::set<std::string> names{"sleep",
                                           "sync",
                                           "textmsg",
                                           "popup",
                                           "set_digital_out",
                                           "set_standard_digital_out",
                                           "set_configurable_digital_out",
                                           "set_tool_digital_out",
                                           "set_analog_out",
                                           "set_standard_analog_out",
                                           "set_payload",
                                           "set_payload_cog",
                                           "set_payload_mass",
                                           "set_target_payload",
                                           "set_tool_voltage",
                                           "set_gravity"};
  return names.count(name) > 0;
}

/// What a program has read so far.
struct ScriptState {
  std::map<std::string, std::optional<ScriptPose>> vars;  ///< nullopt: not a pose
  std::optional<Frame> tcp;                               ///< nullopt: the installation's
  std::vector<std::pair<ScriptPose, std::optional<Frame>>> moves;
  std::vector<Statement> where;
  int routines = 0;
};

/// name = expression (global, local or plain).
void assignment(const std::string& name, const std::string& expr, const Statement& s,
                ScriptState& st, const RobotOptions& o, PoseSet& set) {
  const std::string e = trim(expr);
  const bool literal = !e.empty() && (std::isdigit(static_cast<unsigned char>(e[0])) ||
                                      e[0] == '-' || e[0] == '"' || e == "True" || e == "False");
  if (e.rfind("p[", 0) == 0 || e.rfind("pose_trans", 0) == 0 || st.vars.count(e)) {
    st.vars[name] = pose_value(e, s, st.vars);
  } else if (literal) {
    st.vars[name] = std::nullopt;
  } else {
    st.vars[name] = std::nullopt;
    unknown(s, construct(s.text) + " assigns '" + name + "' a value the reader does not evaluate",
            o, set);
  }
}

/// name(args) as a statement.
void call(const std::string& name, const std::string& args_text, const Statement& s,
          ScriptState& st, const RobotOptions& o, PoseSet& set) {
  const auto args = split_top(args_text);
  if (name == "movel" || name == "movej" || name == "movep" || name == "movec") {
    const std::size_t want = name == "movec" ? 2 : 1;
    if (args.size() < want || args.front().empty())
      refuse(s, name + " expects " + (want == 2 ? "a via pose and an end pose" : "a pose"));
    for (std::size_t i = 0; i < want; ++i) {
      st.moves.emplace_back(pose_value(args[i], s, st.vars), st.tcp);
      st.where.push_back(s);
    }
  } else if (name == "set_tcp") {
    if (args.size() != 1) refuse(s, "set_tcp expects one pose");
    st.tcp = pose_value(args[0], s, st.vars).frame;
  } else if (harmless(name)) {
  } else {
    unknown(s, construct(s.text) + " calls " + name + ", which the reader does not know", o, set);
  }
}

void script_statement(const Statement& s, ScriptState& st, const RobotOptions& o, PoseSet& set) {
  std::string t = s.text;
  const std::string word = t.substr(0, t.find_first_of(" \t(=:"));
  if (word == "def") {
    if (++st.routines > 1)
      refuse(s,
             "a second routine: the order the routines run in is not in the file (give the "
             "moves in one def)");
    return;
  }
  if (word == "end" && t == "end") return;
  static const std::set<std::string> flow{"if",  "elif", "else",   "while", "for",      "thread",
                                          "run", "kill", "return", "break", "continue", "halt"};
  if (flow.count(word))
    return unknown(s,
                   construct(t) +
                       " is control flow: the order of the moves would depend on "
                       "run time",
                   o, set);
  if (word == "global" || word == "local") t = trim(t.substr(word.size()));
  const std::string name = t.substr(0, t.find_first_of(" \t(="));
  const std::string rest = trim(t.substr(name.size()));
  if (identifier(name) && rest.size() > 1 && rest[0] == '=' && rest[1] != '=')
    return assignment(name, rest.substr(1), s, st, o, set);
  if (identifier(name) && rest.size() >= 2 && rest.front() == '(' && rest.back() == ')')
    return call(name, rest.substr(1, rest.size() - 2), s, st, o, set);
  unknown(s,
          construct(t) +
              " is not understood (the URScript reader knows movel, movej, movep and movec to "
              "poses, pose variables, set_tcp and calls that move nothing)",
          o, set);
}

}  // namespace urscript

PoseSet parse_urscript(const std::string& text, const std::string& source,
                       const RobotOptions& options) {
  using namespace urscript;
  if (options.given())
    throw Error(Errc::invalid_input,
                source +
                    ": --robot-config, --tool and --base are for KUKA and ABB programs; a "
                    "URScript program sets its TCP itself (set_tcp)");
  ScriptState st;
  PoseSet set;
  set.source = source;
  set.units = "mm";
  for (const Statement& s : script_lines(text, source)) script_statement(s, st, options, set);
  // One TCP throughout: the poses as written. Otherwise every pose is expressed for the TCP of
  // the first move, which needs every TCP known.
  const auto& first = st.moves.empty() ? std::optional<Frame>() : st.moves.front().second;
  for (std::size_t i = 0; i < st.moves.size(); ++i) {
    auto& [pose, tcp] = st.moves[i];
    const bool same = tcp.has_value() == first.has_value() &&
                      (!tcp || (tcp->p == first->p && tcp->q.coeffs() == first->q.coeffs()));
    if (same && pose.position) {
      set.poses.push_back(quaternion_pose(*pose.position, pose.frame.q));
      continue;
    }
    if (!same && (!tcp || !first))
      refuse(st.where[i],
             "set_tcp changes the TCP between moves from the installation's, which "
             "the program does not give: set it before the first move");
    set.poses.push_back(pose_of(same ? pose.frame : pose.frame * tcp->inverse() * *first));
  }
  return finished(std::move(set), source, "movel, movej, movep, movec");
}

}  // namespace qmotion::io
