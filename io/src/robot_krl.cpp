// io/src/robot_krl.cpp: KUKA KRL programs (.src with their .dat) read as pose files, each move
// with the tool and base the robot uses for it. Every statement is a construct this reader
// knows by its exact name, or it is refused.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <qmotion/kernel/quaternion.hpp>
#include <set>
#include <utility>

#include "robot_text.hpp"

namespace qmotion::io {
namespace krl {
using namespace robot;

/// Lines of KRL without comments (';' to the end of the line, FOLD markers included).
std::vector<Statement> krl_lines(const std::string& text, const std::string& source) {
  std::vector<Statement> out;
  for (auto& [line, code] : code_lines(text, ';'))
    out.push_back({std::move(code), source + ": line " + std::to_string(line)});
  return out;
}

/// What a KRL name is declared as.
struct KrlValue {
  std::string type;  ///< E6POS, POS, FRAME (a pose), FDAT or another type
  std::string value;
  Statement where;
};

/// The members of an aggregate {[TYPE:] NAME value, ...}, keys in capitals.
std::vector<std::pair<std::string, std::string>> members(const std::string& agg, const Statement& s,
                                                         std::string* type) {
  std::string body = trim(agg);
  if (body.size() < 2 || body.front() != '{' || body.back() != '}')
    refuse(s, "expected an aggregate {NAME value, ...}, found " + construct(body));
  body = body.substr(1, body.size() - 2);
  const auto colon = body.find(':');
  if (colon != std::string::npos && body.find_first_of("\"{[") > colon) {  // {E6POS: X ...}
    if (type) *type = upper(trim(body.substr(0, colon)));
    body = body.substr(colon + 1);
  }
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string& item : split_top(body)) {
    const auto sp = item.find_first_of(" \t");
    if (sp == std::string::npos) refuse(s, "aggregate member '" + item + "' has no value");
    out.emplace_back(upper(item.substr(0, sp)), trim(item.substr(sp)));
  }
  return out;
}

/// {X 1, Y 2, Z 3, A 4, B 5, C 6, ...} -> a pose (R = Rz(A) Ry(B) Rx(C), degrees).
PoseInput krl_aggregate(const std::string& agg, const Statement& s) {
  std::string type;
  const auto items = members(agg, s, &type);
  if (!type.empty() && type != "E6POS" && type != "POS" && type != "FRAME")
    refuse(s, "the aggregate is of type " + type + ", not a Cartesian pose (E6POS, POS, FRAME)");
  std::map<std::string, Number> v;
  static const std::set<std::string> extra{"S", "T", "E1", "E2", "E3", "E4", "E5", "E6"};
  for (const auto& [key, value] : items) {
    if (key.size() == 1 && std::string("XYZABC").find(key) != std::string::npos) {
      if (v.count(key)) refuse(s, "aggregate member " + key + " given twice");
      v[key] = number(value, s, "aggregate member " + key);
    } else if (extra.count(key)) {
      number(value, s, "aggregate member " + key);  // status, turn, external axes
    } else {
      refuse(s, "unknown aggregate member '" + key + "' (expected X, Y, Z, A, B, C, S, T, E1-E6)");
    }
  }
  for (const char* k : {"X", "Y", "Z", "A", "B", "C"})
    if (!v.count(k))
      refuse(s, std::string("the aggregate has no ") + k +
                    ": a partial aggregate keeps values from the robot's state, which a file "
                    "does not know");
  constexpr double deg = M_PI / 180.0;
  using Q = kernel::Quaternion<double>;
  auto about = [](int axis, double angle) {
    Eigen::Vector3d u = Eigen::Vector3d::Zero();
    u(axis) = std::sin(angle / 2);
    return Q(std::cos(angle / 2), u(0), u(1), u(2));
  };
  const Q q =
      about(2, v["A"].value * deg) * about(1, v["B"].value * deg) * about(0, v["C"].value * deg);
  return quaternion_pose({v["X"], v["Y"], v["Z"]}, Eigen::Quaterniond(q[0], q[1], q[2], q[3]));
}

/// Reads a declaration "[DECL] [GLOBAL] TYPE name = value" into `names`; false when the
/// statement is not one.
bool krl_declaration(const Statement& s, std::map<std::string, KrlValue>& names) {
  std::string t = s.text;
  std::string u = upper(t);
  auto drop = [&](const char* word) {
    const std::string w = std::string(word) + " ";
    if (u.rfind(w, 0) == 0) {
      t = trim(t.substr(w.size()));
      u = upper(t);
      return true;
    }
    return false;
  };
  const bool decl = drop("DECL");
  drop("GLOBAL");
  const auto eq = t.find('=');
  const auto sp = t.find_first_of(" \t");
  if (sp == std::string::npos || (eq != std::string::npos && eq < sp)) return false;
  const std::string type = upper(t.substr(0, sp));
  static const std::set<std::string> known{"E6POS", "POS",  "FRAME", "E6AXIS", "AXIS", "FDAT",
                                           "PDAT",  "LDAT", "INT",   "REAL",   "BOOL", "CHAR"};
  if (!decl && !known.count(type)) return false;
  const std::string rest = trim(t.substr(sp));
  const std::string name = upper(trim(rest.substr(0, std::min(rest.find('='), rest.size()))));
  if (name.empty() || !identifier(name))
    refuse(s, "a declaration of one name with '=' is expected, found " + construct(s.text));
  names[name] =
      KrlValue{type, eq == std::string::npos ? "" : trim(rest.substr(rest.find('=') + 1)), s};
  return true;
}

/// A target: an inline aggregate or a declared name.
PoseInput krl_target(const std::string& token, const Statement& s,
                     const std::map<std::string, KrlValue>& names) {
  const std::string tk = trim(token);
  if (!tk.empty() && tk.front() == '{') return krl_aggregate(tk, s);
  const auto it = names.find(upper(tk));
  if (it == names.end())
    refuse(s, "target '" + tk + "' is not declared in the program or in its .dat");
  const KrlValue& v = it->second;
  if (v.type != "E6POS" && v.type != "POS" && v.type != "FRAME")
    refuse(s, "target '" + tk + "' is declared " + v.type +
                  (v.type == "E6AXIS" || v.type == "AXIS"
                       ? " (joint angles): it has no Cartesian pose without the robot's kinematics"
                       : ", not a Cartesian pose"));
  if (v.value.empty()) refuse(v.where, "'" + tk + "' is declared without a value");
  return krl_aggregate(v.value, v.where);
}

/// The tool and base a move uses (unset: what the robot had before the program).
struct FrameState {
  std::optional<int> tool, base;
};

/// A move's target with its frames and statement.
struct Move {
  PoseInput pose;
  FrameState frames;
  Statement where;
};

/// A KUKA frame number, 0 to 999; nullopt for anything else.
std::optional<int> parsed_frame_number(const std::string& t) {
  int n = -1;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), n);
  if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size() || n < 0 || n > 999)
    return std::nullopt;
  return n;
}

int frame_number(const std::string& text, const Statement& s, const char* what) {
  const std::string t = trim(text);
  const auto n = parsed_frame_number(t);
  if (!n) refuse(s, std::string(what) + ": expected a frame number 0 to 999, found '" + t + "'");
  return *n;
}

/// $TOOL = TOOL_DATA[n] or $NULLFRAME; $BASE = BASE_DATA[n], $WORLD or $NULLFRAME.
int assigned_frame(const std::string& rhs, const std::string& lhs, const Statement& s) {
  const std::string r = upper(trim(rhs));
  if (r == "$NULLFRAME" || (lhs == "$BASE" && r == "$WORLD")) return 0;
  const std::string table = lhs == "$TOOL" ? "TOOL_DATA[" : "BASE_DATA[";
  if (r.rfind(table, 0) == 0 && r.back() == ']')
    return frame_number(r.substr(table.size(), r.size() - table.size() - 1), s, lhs.c_str());
  refuse(s, lhs + " = " + trim(rhs) + ": the reader knows " + lhs + " = " + table + "n]" +
                (lhs == "$BASE" ? ", $WORLD" : "") + " and $NULLFRAME");
}

/// FDAT_ACT = name: the FDAT's TOOL_NO and BASE_NO.
void activate_fdat(const std::string& name, const Statement& s,
                   const std::map<std::string, KrlValue>& names, FrameState& frames) {
  const auto it = names.find(upper(trim(name)));
  if (it == names.end() || it->second.type != "FDAT")
    refuse(s, "FDAT_ACT = " + trim(name) + ": no FDAT of that name in the program or its .dat");
  const KrlValue& v = it->second;
  for (const auto& [key, value] : members(v.value, v.where, nullptr)) {
    if (key == "TOOL_NO") frames.tool = frame_number(value, v.where, "TOOL_NO");
    if (key == "BASE_NO") frames.base = frame_number(value, v.where, "BASE_NO");
    if (key == "IPO_FRAME" && upper(value) != "#BASE")
      refuse(v.where, "IPO_FRAME " + value +
                          ": the robot moves the workpiece past a fixed tool, which the reader "
                          "does not follow");
  }
}

/// BAS(#WHAT, value): the KUKA base package's settings; #TOOL and #BASE select a frame.
void bas_call(const std::string& args_text, const Statement& s, FrameState& frames) {
  const auto args = split_top(args_text);
  const std::string what = upper(args.front());
  static const std::vector<std::string> settings{
      "#INITMOV", "#PTP_PARAMS", "#CP_PARAMS", "#PTP_DAT", "#CP_DAT", "#VEL_PTP",
      "#ACC_PTP", "#VEL_CP",     "#ACC_CP",    "#FRAMES",  "#TOOL",   "#BASE"};
  if (std::find(settings.begin(), settings.end(), what) == settings.end()) {
    std::string known;
    for (const auto& w : settings) known += (known.empty() ? "" : ", ") + w;
    refuse(s, "BAS(" + args.front() + ", ...) is not a setting the reader knows (" + known + ")");
  }
  if (what == "#TOOL" || what == "#BASE") {
    if (args.size() != 2) refuse(s, "BAS(" + what + ", n) expects a frame number");
    (what == "#TOOL" ? frames.tool : frames.base) = frame_number(args[1], s, what.c_str());
  }
}

/// The system variables whose assignment moves nothing and changes no frame.
bool harmless_system_variable(const std::string& name) {
  static const std::set<std::string> known{
      "$VEL",      "$VEL_AXIS",  "$ACC",        "$ACC_AXIS", "$APO",       "$ADVANCE",
      "$ORI_TYPE", "$CIRC_TYPE", "$BWDSTART",   "$H_POS",    "$OUT",       "$ANOUT",
      "$OV_PRO",   "$TIMER",     "$TIMER_STOP", "$LOAD",     "$GEAR_JERK", "$CP_VEL_TYPE"};
  return known.count(name) > 0;
}

/// What a program has read so far.
struct KrlState {
  std::map<std::string, KrlValue> names;
  FrameState frames;
  std::vector<Move> moves;
};

/// A PTP, LIN or CIRC move; false when `word` is not one.
bool krl_move(const std::string& word, const Statement& s, KrlState& st) {
  if (word != "PTP" && word != "LIN" && word != "CIRC") return false;
  auto args = split_top(s.text.substr(word.size()));
  // Approximation switches at the end: "LIN P1 C_DIS" splits as "P1 C_DIS".
  for (auto& a : args) {
    const std::string ua = upper(a);
    for (const char* c : {" C_PTP", " C_DIS", " C_VEL", " C_ORI", " C_SPL"})
      if (ua.size() > std::strlen(c) &&
          ua.compare(ua.size() - std::strlen(c), std::string::npos, c) == 0)
        a = trim(a.substr(0, a.size() - std::strlen(c)));
  }
  const std::size_t want = word == "CIRC" ? 2 : 1;
  if (args.size() != want || args.back().empty())
    refuse(s, word + " expects " + (want == 2 ? "an auxiliary and an end point" : "one target") +
                  ", found " + construct(s.text) +
                  (word == "CIRC" && args.size() > 2 ? " (CIRC with CA is not supported)" : ""));
  for (const auto& a : args) st.moves.push_back({krl_target(a, s, st.names), st.frames, s});
  return true;
}

/// A statement that sets something: a system variable, PDAT_ACT / LDAT_ACT / FDAT_ACT, BAS.
/// False when it is none of these.
bool krl_setting(const std::string& u, const Statement& s, KrlState& st,
                 const RobotOptions& options, PoseSet& set) {
  const auto eq = s.text.find('=');
  if (u.rfind("BAS", 0) == 0 && trim(u.substr(3)).rfind('(', 0) == 0 && u.back() == ')') {
    const std::string inner = trim(s.text.substr(3));
    bas_call(inner.substr(1, inner.size() - 2), s, st.frames);
    return true;
  }
  if (eq == std::string::npos || (eq + 1 < u.size() && u[eq + 1] == '=')) return false;
  const std::string lhs = trim(u.substr(0, eq));
  const std::string name = lhs.substr(0, lhs.find_first_of("[. \t"));
  const std::string rhs = trim(s.text.substr(eq + 1));
  if (name == "$TOOL" || name == "$BASE") {
    if (lhs != name) refuse(s, construct(s.text) + ": the reader knows " + name + " = a frame");
    (name == "$TOOL" ? st.frames.tool : st.frames.base) = assigned_frame(rhs, name, s);
  } else if (name == "FDAT_ACT") {
    activate_fdat(rhs, s, st.names, st.frames);
  } else if (name == "PDAT_ACT" || name == "LDAT_ACT") {
    if (!identifier(rhs))
      refuse(s, name + " = " + rhs + ": expected the name of a " +
                    (name == "PDAT_ACT" ? "PDAT" : "LDAT"));
  } else if (name.rfind('$', 0) == 0) {
    if (!harmless_system_variable(name))
      unknown(s,
              construct(s.text) + " assigns the system variable " + name +
                  ", which the reader does not know",
              options, set);
  } else {
    unknown(s, construct(s.text) + " assigns '" + name + "' (the reader follows no variables)",
            options, set);
  }
  return true;
}

/// Control-flow words: the order of the moves would depend on run time.
bool control_flow(const std::string& word) {
  static const std::set<std::string> words{
      "IF",     "ELSE",  "ENDIF",  "FOR",  "ENDFOR",  "WHILE",     "ENDWHILE", "LOOP", "ENDLOOP",
      "REPEAT", "UNTIL", "SWITCH", "CASE", "DEFAULT", "ENDSWITCH", "GOTO",     "EXIT", "RETURN"};
  return words.count(word) > 0;
}

/// The words of a statement, split at blanks.
std::vector<std::string> words(const std::string& u) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while ((i = u.find_first_not_of(" \t", i)) != std::string::npos) {
    const std::size_t e = std::min(u.find_first_of(" \t", i), u.size());
    out.push_back(u.substr(i, e - i));
    i = e;
  }
  return out;
}

bool digits(const std::string& w) {
  return !w.empty() && w.find_first_not_of("0123456789") == std::string::npos;
}

/// WAIT SEC t, WAIT FOR condition, INTERRUPT ON/OFF/ENABLE/DISABLE n, and KUKA's standard
/// stop-message interrupt INTERRUPT DECL n WHEN $STOPMESS==TRUE DO IR_STOPM ( ).
bool passes_as_written(const std::string& u) {
  const auto w = words(u);
  if (w.size() >= 3 && w[0] == "WAIT" && (w[1] == "SEC" || w[1] == "FOR")) return true;
  if (w.size() == 3 && w[0] == "INTERRUPT" && digits(w[2]) &&
      (w[1] == "ON" || w[1] == "OFF" || w[1] == "ENABLE" || w[1] == "DISABLE"))
    return true;
  std::string joined;  // without blanks
  for (const auto& x : w) joined += x;
  const std::string head = "INTERRUPTDECL", tail = "WHEN$STOPMESS==TRUEDOIR_STOPM()";
  return w.size() >= 3 && w[0] == "INTERRUPT" && w[1] == "DECL" && digits(w[2]) &&
         joined.size() > head.size() + tail.size() && joined.rfind(head, 0) == 0 &&
         joined.compare(joined.size() - tail.size(), tail.size(), tail) == 0 &&
         digits(joined.substr(head.size(), joined.size() - head.size() - tail.size()));
}

/// One statement of the program.
void krl_statement(const Statement& s, KrlState& st, const RobotOptions& options, PoseSet& set) {
  std::string u = upper(s.text);
  if (u.rfind("GLOBAL ", 0) == 0) u = trim(u.substr(7));
  const std::string word = u.substr(0, u.find_first_of(" \t({=["));
  if (word == "DEF" || word == "END" || u == "HALT" || u == "INI" ||
      (u.rfind('&', 0) == 0 && identifier(u.substr(1, u.find_first_of(" \t") - 1))) ||
      passes_as_written(u))
    return;
  if (control_flow(word))
    return unknown(
        s, construct(s.text) + " is control flow: the order of the moves would depend on run time",
        options, set);
  if (word.size() > 4 && word.substr(word.size() - 4) == "_REL")
    refuse(s, construct(s.text) + " is a relative motion: its pose depends on where the robot is");
  if (word == "SPTP" || word == "SLIN" || word == "SCIRC" || word == "SPLINE" ||
      word == "PTP_SPLINE")
    refuse(s, construct(s.text) + " is a spline motion, which the reader does not read");
  if (krl_move(word, s, st) || krl_declaration(s, st.names) || krl_setting(u, s, st, options, set))
    return;
  if (word == "DECL") refuse(s, "unreadable declaration " + construct(s.text));
  if (identifier(word) && u.size() > word.size() && trim(u.substr(word.size())).front() == '(')
    return unknown(s,
                   construct(s.text) + " calls the routine " + trim(s.text.substr(0, word.size())) +
                       ", whose moves are not in this file",
                   options, set);
  unknown(s,
          construct(s.text) +
              " is not understood (the KRL reader knows PTP, LIN and CIRC to "
              "Cartesian targets, declarations and motion parameters)",
          options, set);
}

/// TOOL_DATA[n] and BASE_DATA[n] of a $config.dat; everything else in it is the controller's
/// and is not read.
std::pair<std::map<int, Frame>, std::map<int, Frame>> read_config(const std::string& text,
                                                                  const std::string& source) {
  std::pair<std::map<int, Frame>, std::map<int, Frame>> out;
  for (const Statement& s : krl_lines(text, source)) {
    const std::string u = upper(s.text);
    const bool tool = u.rfind("TOOL_DATA", 0) == 0, base = u.rfind("BASE_DATA", 0) == 0;
    const auto open = u.find('['), close = u.find(']'), eq = u.find('=');
    if (!(tool || base) || open == std::string::npos || close == std::string::npos ||
        eq == std::string::npos || !(open < close && close < eq) ||
        !trim(u.substr(9, open - 9)).empty() || !trim(u.substr(close + 1, eq - close - 1)).empty())
      continue;  // not an entry TOOL_DATA[n] = {...} or BASE_DATA[n] = {...}
    const int n = frame_number(u.substr(open + 1, close - open - 1), s, "frame number");
    (tool ? out.first : out.second)[n] = frame_of(krl_aggregate(s.text.substr(eq + 1), s));
  }
  return out;
}

std::string frame_name(const char* table, std::optional<int> n) {
  return n ? std::string(table) + "[" + std::to_string(*n) + "]" : "the robot's frame (not set)";
}

/// The first move whose tool (or base) differs from the first move's, or nullptr.
const Move* differing(const std::vector<Move>& moves, bool tool) {
  for (const Move& m : moves)
    if ((tool ? m.frames.tool : m.frames.base) !=
        (tool ? moves.front().frames.tool : moves.front().frames.base))
      return &m;
  return nullptr;
}

/// "this move uses TOOL_DATA[2], line 5 uses TOOL_DATA[1]"
std::string two_frames(const Move& a, const Move& b, bool tool) {
  const char* table = tool ? "TOOL_DATA" : "BASE_DATA";
  return "this move uses " + frame_name(table, tool ? b.frames.tool : b.frames.base) + ", " +
         a.where.line() + " uses " + frame_name(table, tool ? a.frames.tool : a.frames.base);
}

/// An option's frame number (--tool, --base).
int option_frame(const std::string& value, const char* option) {
  const auto n = parsed_frame_number(value);
  if (!n)
    throw Error(
        Errc::invalid_input,
        std::string(option) + ": expected a KUKA frame number 0 to 999, found '" + value + "'");
  return *n;
}

/// The poses as written: the moves must share one tool and one base.
std::vector<PoseInput> as_written(std::vector<Move> moves, const RobotOptions& o,
                                  const std::string& source) {
  if (!o.tool.empty() || !o.base.empty())
    throw Error(Errc::invalid_input, source +
                                         ": --tool and --base need --robot-config for a KRL "
                                         "program (its TOOL_DATA and BASE_DATA)");
  for (const bool tool : {true, false})
    if (const Move* m = differing(moves, tool))
      refuse(m->where,
             two_frames(moves.front(), *m, tool) +
                 ": give --robot-config with the frames (and --tool) to map them into one");
  std::vector<PoseInput> out;
  for (Move& m : moves) out.push_back(std::move(m.pose));
  return out;
}

/// The poses mapped with a $config.dat: the TCP of --tool, in the base of --base (the world).
std::vector<PoseInput> mapped(const std::vector<Move>& moves, const RobotOptions& o) {
  const auto [tools, bases] = read_config(*o.config_text, o.config_path);
  auto lookup = [&](const std::map<int, Frame>& table, int n, const char* name) {
    if (n == 0) return Frame{};
    const auto it = table.find(n);
    if (it == table.end())
      throw Error(Errc::invalid_input,
                  o.config_path + ": has no " + name + "[" + std::to_string(n) + "]");
    return it->second;
  };
  for (const Move& m : moves)
    if (!m.frames.tool || !m.frames.base)
      refuse(m.where, std::string("the move's ") + (m.frames.tool ? "base" : "tool") +
                          " is not set in the program (no FDAT_ACT, $TOOL / $BASE or BAS before "
                          "it), so it cannot be mapped");
  int tool = *moves.front().frames.tool;
  if (!o.tool.empty())
    tool = option_frame(o.tool, "--tool");
  else if (const Move* m = differing(moves, true))
    refuse(m->where, two_frames(moves.front(), *m, true) +
                         ": name the TCP to express every pose for with --tool");
  const Frame to =
      lookup(bases, o.base.empty() ? 0 : option_frame(o.base, "--base"), "BASE_DATA").inverse();
  const Frame tcp = lookup(tools, tool, "TOOL_DATA");
  std::vector<PoseInput> out;
  for (const Move& m : moves) {
    const Frame world = lookup(bases, *m.frames.base, "BASE_DATA") * frame_of(m.pose);
    out.push_back(pose_of(to * world * lookup(tools, *m.frames.tool, "TOOL_DATA").inverse() * tcp));
  }
  return out;
}

}  // namespace krl

PoseSet parse_krl(const std::string& text, const std::string& source,
                  const std::optional<std::string>& dat_text, const std::string& dat_source,
                  const RobotOptions& options) {
  using namespace krl;
  KrlState st;
  if (dat_text)
    for (const Statement& s : krl_lines(*dat_text, dat_source)) {
      const std::string u = upper(s.text);
      if (u.rfind("DEFDAT", 0) == 0 || u == "ENDDAT" ||
          (u.rfind('&', 0) == 0 && identifier(u.substr(1, u.find_first_of(" \t") - 1))))
        continue;
      if (!krl_declaration(s, st.names))
        refuse(s, "a .dat holds declarations; " + construct(s.text) + " is not one");
    }
  PoseSet set;
  set.source = source;
  set.units = "mm";
  for (const Statement& s : krl_lines(text, source)) {
    const std::string u = upper(s.text);
    const std::string word = u.substr(0, u.find_first_of(" \t({"));
    if (word == "DEFDAT" || word == "ENDDAT") continue;
    krl_statement(s, st, options, set);
  }
  if (!st.moves.empty())
    set.poses = options.config_text ? mapped(st.moves, options)
                                    : as_written(std::move(st.moves), options, source);
  return finished(std::move(set), source, "PTP, LIN, CIRC");
}

}  // namespace qmotion::io
