// io/src/robot_programs.cpp: KUKA KRL and ABB RAPID programs read as pose files. Each reader
// knows a small set of statements; anything else is refused, never skipped.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <map>
#include <qmotion/io/robot_programs.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/quaternion.hpp>
#include <set>
#include <string_view>
#include <utility>
#include <vector>

namespace qmotion::io {
namespace {

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

/// A statement and where it starts: "file: line N".
struct Statement {
  std::string text;
  std::string where;
};

[[noreturn]] void refuse(const Statement& s, const std::string& why) {
  throw Error(Errc::invalid_input, s.where + ": " + why);
}

/// The construct a statement starts with, for messages.
std::string construct(const std::string& text) {
  const std::string t = trim(text);
  return "'" + (t.size() > 60 ? t.substr(0, 57) + "..." : t) + "'";
}

/// A number with its text; refuses anything else.
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

/// Splits at commas outside brackets and braces.
std::vector<std::string> split_top(std::string_view s) {
  std::vector<std::string> out;
  int depth = 0;
  std::size_t start = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
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

PoseInput quaternion_pose(const std::array<Number, 3>& p, const kernel::Quaternion<double>& q) {
  PoseInput pose;
  pose.position = p;
  pose.rotation.kind = RotationInput::Kind::quaternion;
  for (int c = 0; c < 4; ++c) {  // computed: no source text
    Number n;
    n.value = q[c];
    pose.rotation.values.push_back(n);
  }
  return pose;
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

// --- KUKA KRL ----------------------------------------------------------------------------

/// Lines of KRL without comments (';' to the end of the line, FOLD markers included).
std::vector<Statement> krl_lines(const std::string& text, const std::string& source) {
  std::vector<Statement> out;
  std::size_t pos = 0;
  for (int line = 1; pos <= text.size(); ++line) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    std::string_view l(text.data() + pos, end - pos);
    bool quoted = false;
    std::size_t cut = l.size();
    for (std::size_t i = 0; i < l.size(); ++i) {
      if (l[i] == '"') quoted = !quoted;
      if (l[i] == ';' && !quoted) {
        cut = i;
        break;
      }
    }
    const std::string t = trim(l.substr(0, cut));
    if (!t.empty()) out.push_back({t, source + ": line " + std::to_string(line)});
    pos = end + 1;
  }
  return out;
}

/// What a KRL name is declared as.
struct KrlValue {
  std::string type;  ///< E6POS, POS, FRAME (a pose) or another type
  std::string value;
  Statement where;
};

/// {X 1, Y 2, Z 3, A 4, B 5, C 6, ...} -> a pose (R = Rz(A) Ry(B) Rx(C), degrees).
PoseInput krl_aggregate(const std::string& agg, const Statement& s) {
  std::string body = trim(agg);
  if (body.size() < 2 || body.front() != '{' || body.back() != '}')
    refuse(s, "expected a Cartesian aggregate {X .., Y .., Z .., A .., B .., C ..}, found " +
                  construct(body));
  body = body.substr(1, body.size() - 2);
  if (const auto colon = body.find(':'); colon != std::string::npos) {  // {E6POS: X ...}
    const std::string type = upper(trim(body.substr(0, colon)));
    if (type != "E6POS" && type != "POS" && type != "FRAME")
      refuse(s, "the aggregate is of type " + type + ", not a Cartesian pose (E6POS, POS, FRAME)");
    body = body.substr(colon + 1);
  }
  std::map<std::string, Number> v;
  for (const std::string& item : split_top(body)) {
    const auto sp = item.find_first_of(" \t");
    const std::string key = upper(item.substr(0, sp));
    if (sp == std::string::npos) refuse(s, "aggregate member '" + item + "' has no value");
    static const std::set<std::string> extra{"S", "T", "E1", "E2", "E3", "E4", "E5", "E6"};
    if (key.size() == 1 && std::string("XYZABC").find(key) != std::string::npos) {
      if (v.count(key)) refuse(s, "aggregate member " + key + " given twice");
      v[key] = number(item.substr(sp), s, "aggregate member " + key);
    } else if (extra.count(key)) {
      number(item.substr(sp), s, "aggregate member " + key);  // status, turn, external axes
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
  return quaternion_pose({v["X"], v["Y"], v["Z"]}, q);
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
  if (name.empty() || name.find_first_of(" \t,[") != std::string::npos)
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

/// Statements that change no pose: motion parameters, FOLD bookkeeping, waits.
bool krl_harmless(const std::string& u) {
  static const char* prefixes[] = {"$VEL",       "$ACC",      "$APO",   "$ADVANCE", "$ORI_TYPE",
                                   "$CIRC_TYPE", "$BWDSTART", "$H_POS", "PDAT_ACT", "FDAT_ACT",
                                   "LDAT_ACT",   "BAS(",      "BAS (",  "WAIT SEC", "HALT",
                                   "INI",        "&"};
  for (const char* p : prefixes)
    if (u.rfind(p, 0) == 0) return true;
  return false;
}

}  // namespace

PoseSet parse_krl(const std::string& text, const std::string& source,
                  const std::optional<std::string>& dat_text, const std::string& dat_source) {
  std::map<std::string, KrlValue> names;
  if (dat_text)
    for (const Statement& s : krl_lines(*dat_text, dat_source)) {
      const std::string u = upper(s.text);
      if (u.rfind("DEFDAT", 0) == 0 || u == "ENDDAT" || u.rfind("&", 0) == 0) continue;
      if (!krl_declaration(s, names))
        refuse(s, "a .dat holds declarations; " + construct(s.text) + " is not one");
    }
  PoseSet set;
  set.source = source;
  set.units = "mm";
  for (const Statement& s : krl_lines(text, source)) {
    const std::string u = upper(s.text);
    const std::string word = u.substr(0, u.find_first_of(" \t({"));
    if (word == "DEF" || word == "GLOBAL" || word == "END" || word == "DEFDAT" ||
        word == "ENDDAT" || krl_harmless(u))
      continue;
    if (u.rfind("$TOOL", 0) == 0 || u.rfind("$BASE", 0) == 0)
      refuse(s, construct(s.text) +
                    " changes the frame the targets are given in; give the poses in one frame");
    if (word == "PTP" || word == "LIN" || word == "CIRC") {
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
        refuse(s,
               word + " expects " + (want == 2 ? "an auxiliary and an end point" : "one target") +
                   ", found " + construct(s.text) +
                   (word == "CIRC" && args.size() > 2 ? " (CIRC with CA is not supported)" : ""));
      for (const auto& a : args) set.poses.push_back(krl_target(a, s, names));
      continue;
    }
    if (krl_declaration(s, names)) continue;
    if (word == "DECL") refuse(s, "unreadable declaration " + construct(s.text));
    if (word.size() > 4 && word.substr(word.size() - 4) == "_REL")
      refuse(s,
             construct(s.text) + " is a relative motion: its pose depends on where the robot is");
    refuse(s, construct(s.text) +
                  " is not understood (the KRL reader knows PTP, LIN and CIRC to "
                  "Cartesian targets, declarations and motion parameters)");
  }
  return finished(std::move(set), source, "PTP, LIN, CIRC");
}

// --- ABB RAPID ---------------------------------------------------------------------------

namespace {

/// RAPID statements without '!' comments: MODULE / PROC lines alone, the rest up to ';'.
std::vector<Statement> rapid_statements(const std::string& text, const std::string& source) {
  std::vector<Statement> out;
  std::string current;
  int start = 0;
  std::size_t pos = 0;
  for (int line = 1; pos <= text.size(); ++line) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    std::string_view l(text.data() + pos, end - pos);
    pos = end + 1;
    bool quoted = false;
    std::string code;
    for (char c : l) {
      if (c == '"') quoted = !quoted;
      if (c == '!' && !quoted) break;
      code += c;
    }
    const std::string t = trim(code);
    if (t.empty()) continue;
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

/// [[x, y, z], [q1, q2, q3, q4], ...] -> a pose.
PoseInput rapid_robtarget(const std::string& value, const Statement& s) {
  const std::string v = trim(value);
  if (v.size() < 2 || v.front() != '[' || v.back() != ']')
    refuse(s, "expected a robtarget [[x,y,z],[q1,q2,q3,q4],...], found " + construct(v));
  const auto parts = split_top(std::string_view(v).substr(1, v.size() - 2));
  auto numbers = [&](const std::string& p, std::size_t count, const char* what) {
    if (p.size() < 2 || p.front() != '[' || p.back() != ']')
      refuse(s, std::string(what) + ": expected [" + std::to_string(count) + " numbers], found '" +
                    p + "'");
    const auto items = split_top(std::string_view(p).substr(1, p.size() - 2));
    if (items.size() != count)
      refuse(s, std::string(what) + ": expected " + std::to_string(count) + " numbers, found " +
                    std::to_string(items.size()));
    std::vector<Number> out;
    for (const auto& it : items) out.push_back(number(it, s, what));
    return out;
  };
  if (parts.size() != 4)
    refuse(s, "a robtarget has 4 parts (trans, rot, robconf, extax), found " +
                  std::to_string(parts.size()));
  const auto p = numbers(parts[0], 3, "robtarget trans");
  const auto q = numbers(parts[1], 4, "robtarget rot");
  numbers(parts[2], 4, "robtarget robconf");
  numbers(parts[3], 6, "robtarget extax");
  const double norm = std::sqrt(q[0].value * q[0].value + q[1].value * q[1].value +
                                q[2].value * q[2].value + q[3].value * q[3].value);
  if (!(std::abs(norm - 1) <= 1e-6))
    refuse(s, "robtarget rot [q1, q2, q3, q4] is not a unit quaternion (|q| = " +
                  std::to_string(norm) + ", expected 1 within 1e-6)");
  PoseInput pose;
  pose.position = {p[0], p[1], p[2]};
  pose.rotation.kind = RotationInput::Kind::quaternion;
  pose.rotation.values = q;  // q1 is the scalar part, as qmotion's w
  return pose;
}

}  // namespace

PoseSet parse_rapid(const std::string& text, const std::string& source) {
  std::map<std::string, std::pair<std::string, Statement>> data;  // name -> (type, value)
  PoseSet set;
  set.source = source;
  set.units = "mm";
  int procs = 0;
  static const std::set<std::string> harmless{
      "CONFJ", "CONFL", "SINGAREA", "WAITTIME", "TPWRITE", "TPERASE", "SETDO",  "SETAO", "SETGO",
      "SET",   "RESET", "PULSEDO",  "ACCSET",   "VELSET",  "WAITDI",  "WAITDO", "STOP"};
  for (const Statement& s : rapid_statements(text, source)) {
    std::string t = s.text;
    std::string u = upper(t);
    for (const char* scope : {"LOCAL ", "TASK "})
      if (u.rfind(scope, 0) == 0) {
        t = trim(t.substr(std::strlen(scope)));
        u = upper(t);
      }
    const std::string word = u.substr(0, u.find_first_of(" \t(\\"));
    if (word == "MODULE" || word == "ENDMODULE" || word == "ENDPROC") continue;
    if (word == "PROC") {
      if (++procs > 1)
        refuse(s,
               "a second routine: the order the routines run in is not in the file (give "
               "the moves in one PROC)");
      continue;
    }
    if (word == "CONST" || word == "PERS" || word == "VAR") {
      const std::string rest = trim(t.substr(word.size()));
      const auto sp = rest.find_first_of(" \t");
      if (sp == std::string::npos) refuse(s, "unreadable declaration " + construct(t));
      const std::string type = upper(rest.substr(0, sp));
      const std::string decl = trim(rest.substr(sp));
      const auto assign = decl.find(":=");
      const std::string name = upper(trim(decl.substr(0, assign)));
      Statement value{assign == std::string::npos ? std::string() : trim(decl.substr(assign + 2)),
                      s.where};
      data[name] = std::make_pair(type, value);
      continue;
    }
    if (word == "MOVEJ" || word == "MOVEL" || word == "MOVEC") {
      auto args = split_top(t.substr(word.size()));
      while (!args.empty() && !args.front().empty() && args.front().front() == '\\')
        args.erase(args.begin());  // \Conc and other switches
      const std::size_t want = word == "MOVEC" ? 2 : 1;
      if (args.size() < want + 3)
        refuse(s, construct(t) + ": expected " + (want == 2 ? "CirPoint, ToPoint" : "ToPoint") +
                      ", speed, zone and tool");
      for (std::size_t i = 0; i < want; ++i) {
        const std::string a = args[i];
        if (!a.empty() && a.front() == '[') {
          set.poses.push_back(rapid_robtarget(a, s));
          continue;
        }
        const auto it = data.find(upper(a));
        if (it == data.end()) refuse(s, "target '" + a + "' is not declared in the module");
        if (it->second.first != "ROBTARGET")
          refuse(s, "target '" + a + "' is a " + it->second.first + ", not a robtarget");
        if (it->second.second.text.empty())
          refuse(it->second.second, "robtarget '" + a + "' is declared without a value");
        set.poses.push_back(rapid_robtarget(it->second.second.text, it->second.second));
      }
      continue;
    }
    if (word == "MOVEABSJ")
      refuse(s, construct(t) +
                    " moves to joint angles: it has no Cartesian pose without the "
                    "robot's kinematics");
    if (harmless.count(word)) continue;
    refuse(s, construct(t) +
                  " is not understood (the RAPID reader knows MoveJ, MoveL and MoveC "
                  "to robtargets, declarations and settings that move nothing)");
  }
  return finished(std::move(set), source, "MoveJ, MoveL, MoveC");
}

}  // namespace qmotion::io
