// io/src/robot_rapid.cpp: ABB RAPID modules (.mod, .prg) read as pose files: robtargets in the
// world frame through their work objects, for one tool. Every statement is a construct this
// reader knows by its exact name, or it is refused.
#include <cstring>
#include <map>
#include <set>
#include <utility>

#include "robot_text.hpp"

namespace qmotion::io {
namespace rapid {
using namespace robot;

/// RAPID statements without '!' comments: MODULE / PROC lines alone, the rest up to ';'.
std::vector<Statement> rapid_statements(const std::string& text, const std::string& source) {
  std::vector<Statement> out;
  std::string current;
  int start = 0;
  for (const auto& [line, t] : code_lines(text, '!')) {
    const std::string u = upper(t);
    const std::string word = u.substr(0, u.find_first_of(" \t("));
    if (current.empty() &&
        (word == "MODULE" || word == "ENDMODULE" || word == "PROC" || word == "ENDPROC" ||
         (word == "LOCAL" && u.find(" PROC ") != std::string::npos))) {
      out.push_back({t, source + ": line " + std::to_string(line)});
      continue;
    }
    if (current.empty()) start = line;
    std::size_t from = 0;
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t[i] == ';') {
        current += t.substr(from, i - from);
        out.push_back({trim(current), source + ": line " + std::to_string(start)});
        current.clear();
        from = i + 1;
        start = line;
      }
    current += t.substr(from);
    if (!trim(current).empty())
      current += ' ';
    else
      current.clear();
  }
  if (!trim(current).empty())
    throw Error(Errc::invalid_input,
                source + ": line " + std::to_string(start) + ": the statement has no closing ';'");
  return out;
}

/// "[a, b, ...]" -> its items, refused unless there are `count`.
std::vector<std::string> items(const std::string& text, std::size_t count, const Statement& s,
                               const std::string& what) {
  const std::string p = trim(text);
  if (p.size() < 2 || p.front() != '[' || p.back() != ']')
    refuse(s, what + ": expected [" + std::to_string(count) + " items], found " + construct(p));
  auto out = split_top(std::string_view(p).substr(1, p.size() - 2));
  if (out.size() != count)
    refuse(s, what + ": expected " + std::to_string(count) + " items, found " +
                  std::to_string(out.size()));
  return out;
}

/// [[x, y, z], [q1, q2, q3, q4]] -> a pose (numbers as written), q unit within 1e-6.
PoseInput rapid_pose(const std::string& trans, const std::string& rot, const Statement& s,
                     const std::string& what) {
  std::vector<Number> p, q;
  for (const auto& it : items(trans, 3, s, what + " trans")) p.push_back(number(it, s, what));
  for (const auto& it : items(rot, 4, s, what + " rot")) q.push_back(number(it, s, what));
  const double norm = std::sqrt(q[0].value * q[0].value + q[1].value * q[1].value +
                                q[2].value * q[2].value + q[3].value * q[3].value);
  if (!(std::abs(norm - 1) <= 1e-6))
    refuse(s, what + " rot [q1, q2, q3, q4] is not a unit quaternion (|q| = " +
                  std::to_string(norm) + ", expected 1 within 1e-6)");
  PoseInput pose;
  pose.position = {p[0], p[1], p[2]};
  pose.rotation.kind = RotationInput::Kind::quaternion;
  pose.rotation.values = q;  // q1 is the scalar part, as qmotion's w
  return pose;
}

/// [[x, y, z], [q1, q2, q3, q4], robconf, extax] -> a pose.
PoseInput rapid_robtarget(const std::string& value, const Statement& s) {
  const std::string v = trim(value);
  if (v.size() < 2 || v.front() != '[' || v.back() != ']')
    refuse(s, "expected a robtarget [[x,y,z],[q1,q2,q3,q4],...], found " + construct(v));
  const auto parts = split_top(std::string_view(v).substr(1, v.size() - 2));
  if (parts.size() != 4)
    refuse(s, "a robtarget has 4 parts (trans, rot, robconf, extax), found " +
                  std::to_string(parts.size()));
  PoseInput pose = rapid_pose(parts[0], parts[1], s, "robtarget");
  for (const auto& it : items(parts[2], 4, s, "robtarget robconf")) number(it, s, "robconf");
  for (const auto& it : items(parts[3], 6, s, "robtarget extax")) number(it, s, "extax");
  return pose;
}

/// A declared name: its type (in capitals) and value.
struct Data {
  std::string type;
  Statement value;
};
using Names = std::map<std::string, Data>;

const Data& declared(const Names& data, const std::string& name, const std::string& type,
                     const Statement& s, const char* what) {
  const auto it = data.find(upper(name));
  if (it == data.end())
    refuse(s, std::string(what) + " '" + name + "' is not declared in the module");
  if (it->second.type != upper(type))
    refuse(s, std::string(what) + " '" + name + "' is a " + it->second.type + ", not a " + type);
  if (it->second.value.text.empty())
    refuse(it->second.value, std::string(what) + " '" + name + "' is declared without a value");
  return it->second;
}

/// A work object's frame: uframe · oframe (wobj0: the world).
Frame work_object(const Names& data, const std::string& name, const Statement& s) {
  if (upper(name) == "WOBJ0") return {};
  const Data& d = declared(data, name, "wobjdata", s, "work object");
  const auto parts = items(d.value.text, 5, d.value, "wobjdata");
  if (upper(parts[0]) != "FALSE")
    refuse(d.value, "work object '" + name +
                        "' is held by the robot (robhold TRUE), which the reader does not follow");
  if (upper(parts[1]) != "TRUE")
    refuse(d.value, "work object '" + name +
                        "' is moved by a mechanical unit (ufprog FALSE), which the reader does "
                        "not follow");
  Frame f[2];
  for (int k = 0; k < 2; ++k) {
    const auto pose = items(parts[static_cast<std::size_t>(3 + k)], 2, d.value,
                            k == 0 ? "wobjdata uframe" : "wobjdata oframe");
    f[k] = frame_of(rapid_pose(pose[0], pose[1], d.value, k == 0 ? "uframe" : "oframe"));
  }
  return f[0] * f[1];
}

/// A tool's frame on the flange (tool0: the flange).
Frame tool_frame(const Names& data, const std::string& name, const Statement& s) {
  if (upper(name) == "TOOL0") return {};
  const Data& d = declared(data, name, "tooldata", s, "tool");
  const auto parts = items(d.value.text, 3, d.value, "tooldata");
  if (upper(parts[0]) != "TRUE")
    refuse(d.value,
           "tool '" + name + "' is stationary (robhold FALSE), which the reader does not follow");
  const auto pose = items(parts[1], 2, d.value, "tooldata tframe");
  return frame_of(rapid_pose(pose[0], pose[1], d.value, "tframe"));
}

/// A move: its target, tool and work object.
struct Move {
  PoseInput pose;
  std::string tool, wobj;
  Statement where;
};

/// "p10 \ID:=3" -> the positional part and the optional arguments (name in capitals -> value).
std::string positional(const std::string& arg, std::map<std::string, std::string>& optional) {
  std::size_t cut = arg.size();
  int depth = 0;
  for (std::size_t i = 0; i < arg.size(); ++i) {
    if (arg[i] == '[' || arg[i] == '(') ++depth;
    if (arg[i] == ']' || arg[i] == ')') --depth;
    if (arg[i] == '\\' && depth == 0) {
      if (cut == arg.size()) cut = i;
      const std::size_t next = arg.find('\\', i + 1);
      const std::string o = arg.substr(i + 1, next == std::string::npos ? next : next - i - 1);
      const auto assign = o.find(":=");
      optional[upper(trim(o.substr(0, assign)))] =
          assign == std::string::npos ? "" : trim(o.substr(assign + 2));
      if (next == std::string::npos) break;
      i = next - 1;
    }
  }
  return trim(arg.substr(0, cut));
}

void rapid_move(const std::string& word, const std::string& t, const Statement& s,
                const Names& data, std::vector<Move>& moves) {
  std::map<std::string, std::string> optional;
  std::vector<std::string> args;
  for (const auto& a : split_top(t.substr(word.size()))) {
    std::string p = positional(a, optional);
    if (!p.empty()) args.push_back(std::move(p));
  }
  const std::size_t want = word == "MOVEC" ? 2 : 1;
  if (args.size() != want + 3)
    refuse(s, construct(t) + ": expected " + (want == 2 ? "CirPoint, ToPoint" : "ToPoint") +
                  ", speed, zone and tool");
  if (!identifier(args[want + 2]))
    refuse(s, "the tool '" + args[want + 2] + "' is not a name of a tooldata");
  const std::string wobj = optional.count("WOBJ") ? optional["WOBJ"] : "wobj0";
  for (std::size_t i = 0; i < want; ++i) {
    const std::string a = args[i];
    if (!a.empty() && a.front() == '[') {
      moves.push_back({rapid_robtarget(a, s), args[want + 2], wobj, s});
      continue;
    }
    const Data& d = declared(data, a, "robtarget", s, "target");
    moves.push_back({rapid_robtarget(d.value.text, d.value), args[want + 2], wobj, s});
  }
}

/// Moves that go to a robtarget in a way the reader does not follow.
bool other_move(const std::string& word) {
  static const std::set<std::string> words{
      "MOVELDO",   "MOVEJDO", "MOVECDO",   "MOVELSYNC", "MOVEJSYNC", "MOVECSYNC", "MOVEEXTJ",
      "SEARCHL",   "SEARCHC", "TRIGGL",    "TRIGGJ",    "TRIGGC",    "ARCL",      "ARCC",
      "ARCLSTART", "ARCLEND", "ARCCSTART", "ARCCEND",   "SPOTL",     "SPOTJ",     "MOVEL_REL"};
  return words.count(word) > 0;
}

bool control_flow(const std::string& word) {
  static const std::set<std::string> words{
      "IF",   "ELSEIF",  "ELSE",    "ENDIF", "FOR",    "ENDFOR", "WHILE", "ENDWHILE", "TEST",
      "CASE", "DEFAULT", "ENDTEST", "GOTO",  "RETURN", "EXIT",   "RAISE", "RETRY",    "TRYNEXT"};
  return words.count(word) > 0;
}

/// Statements that move nothing and change no frame.
bool harmless(const std::string& word) {
  static const std::set<std::string> words{"CONFJ",   "CONFL",   "SINGAREA", "WAITTIME", "TPWRITE",
                                           "TPERASE", "SETDO",   "SETAO",    "SETGO",    "SET",
                                           "RESET",   "PULSEDO", "ACCSET",   "VELSET",   "WAITDI",
                                           "WAITDO",  "STOP",    "WAITUNTIL"};
  return words.count(word) > 0;
}

/// One statement: a declaration, a move or a construct the reader knows; otherwise refused.
void rapid_statement(const Statement& s, Names& data, std::vector<Move>& moves, int& procs,
                     const RobotOptions& options, PoseSet& set) {
  std::string t = s.text;
  std::string u = upper(t);
  for (const char* scope : {"LOCAL ", "TASK "})
    if (u.rfind(scope, 0) == 0) {
      t = trim(t.substr(std::strlen(scope)));
      u = upper(t);
    }
  const std::string word = u.substr(0, u.find_first_of(" \t(\\:"));
  if (word == "MODULE" || word == "ENDMODULE" || word == "ENDPROC" || harmless(word)) return;
  if (word == "PROC") {
    if (++procs > 1)
      refuse(s,
             "a second routine: the order the routines run in is not in the file (give "
             "the moves in one PROC)");
    return;
  }
  if (word == "CONST" || word == "PERS" || word == "VAR") {
    const std::string rest = trim(t.substr(word.size()));
    const auto sp = rest.find_first_of(" \t");
    if (sp == std::string::npos) refuse(s, "unreadable declaration " + construct(t));
    const std::string decl = trim(rest.substr(sp));
    const auto assign = decl.find(":=");
    data[upper(trim(decl.substr(0, assign)))] = Data{
        upper(rest.substr(0, sp)),
        {assign == std::string::npos ? std::string() : trim(decl.substr(assign + 2)), s.where}};
    return;
  }
  if (word == "MOVEJ" || word == "MOVEL" || word == "MOVEC")
    return rapid_move(word, t, s, data, moves);
  if (word == "MOVEABSJ")
    refuse(s, construct(t) +
                  " moves to joint angles: it has no Cartesian pose without the robot's "
                  "kinematics");
  if (other_move(word))
    refuse(s, construct(t) + " moves the robot in a way the RAPID reader does not follow");
  if (control_flow(word))
    return unknown(
        s, construct(t) + " is control flow: the order of the moves would depend on run time",
        options, set);
  if (u.find(":=") != std::string::npos && identifier(word))
    return unknown(s,
                   construct(t) + " assigns '" + trim(t.substr(0, word.size())) +
                       "' (the reader follows no variables)",
                   options, set);
  if (identifier(word))
    return unknown(s,
                   construct(t) + " calls the routine " + t.substr(0, word.size()) +
                       ", whose moves are not in this file",
                   options, set);
  unknown(s,
          construct(t) +
              " is not understood (the RAPID reader knows MoveJ, MoveL and MoveC to robtargets, "
              "declarations and settings that move nothing)",
          options, set);
}

/// The poses in the world frame, for one tool.
std::vector<PoseInput> world_poses(std::vector<Move> moves, const Names& data,
                                   const RobotOptions& o) {
  std::vector<PoseInput> out;
  const Move* other = nullptr;
  for (const Move& m : moves)
    if (upper(m.tool) != upper(moves.front().tool) && !other) other = &m;
  if (other && o.tool.empty())
    refuse(other->where, "this move uses the tool '" + other->tool + "', " +
                             moves.front().where.line() + " uses '" + moves.front().tool +
                             "': name the TCP to express every pose for with --tool");
  const bool map_tool = !o.tool.empty() && (other || upper(o.tool) != upper(moves.front().tool));
  const Frame tcp = map_tool ? tool_frame(data, o.tool, {o.tool, "--tool"}) : Frame{};
  for (Move& m : moves) {
    const bool in_world = upper(m.wobj) == "WOBJ0";
    if (in_world && !map_tool) {
      out.push_back(std::move(m.pose));
      continue;
    }
    Frame f = work_object(data, m.wobj, m.where) * frame_of(m.pose);
    if (map_tool) f = f * tool_frame(data, m.tool, m.where).inverse() * tcp;
    out.push_back(pose_of(f));
  }
  return out;
}

}  // namespace rapid

PoseSet parse_rapid(const std::string& text, const std::string& source,
                    const RobotOptions& options) {
  using namespace rapid;
  if (options.config_text || !options.config_path.empty() || !options.base.empty())
    throw Error(Errc::invalid_input,
                source +
                    ": --robot-config and --base are for KUKA programs; a RAPID module "
                    "declares its work objects and tools itself");
  Names data;
  std::vector<Move> moves;
  PoseSet set;
  set.source = source;
  set.units = "mm";
  int procs = 0;
  for (const Statement& s : rapid_statements(text, source))
    rapid_statement(s, data, moves, procs, options, set);
  if (!moves.empty()) set.poses = world_poses(std::move(moves), data, options);
  return finished(std::move(set), source, "MoveJ, MoveL, MoveC");
}

}  // namespace qmotion::io
