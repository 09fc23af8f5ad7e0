// io/src/gcode_read.cpp: G-code read as LinuxCNC's interpreter reads it, for the subset a
// CAM system's toolpath uses (docs/formats.md, "G-code read by verify").
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/gcode.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/kernel/error.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace qmotion::io {
namespace {

/// The modal state of the interpreter between blocks.
struct State {
  int motion = -1;  ///< 0 to 3, -1 before the first
  int plane = 17;
  double unit = 1;  ///< mm per program unit (G21: 1, G20: 25.4)
  bool incremental = false;
  bool inverse_time = false;
  double feed = 0;  ///< G94: mm/min
  Eigen::Vector3d at = Eigen::Vector3d::Zero();
  std::array<double, 3> abc{};
};

/// One block: its words by letter, its G codes, and whether it ends the program.
struct Block {
  std::map<char, double> words;
  std::vector<int> g;
  bool end = false;
};

[[noreturn]] void refuse(const std::string& where, const std::string& why) {
  throw Error(Errc::invalid_input, where + ": " + why);
}

/// The line with its comments removed and its blanks dropped (the interpreter ignores
/// spaces inside words), in upper case.
std::string code_of(const std::string& line, const std::string& where) {
  std::string out;
  bool in_comment = false;
  for (char ch : line) {
    if (in_comment) {
      if (ch == '(') refuse(where, "a comment opened inside a comment");
      if (ch == ')') in_comment = false;
      continue;
    }
    if (ch == '(') {
      in_comment = true;
    } else if (ch == ';') {
      break;
    } else if (!std::isspace(static_cast<unsigned char>(ch))) {
      out += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    }
  }
  if (in_comment) refuse(where, "a comment that is not closed on its line");
  return out;
}

/// The number that starts at s[i]: an optional sign, digits and at most one point, at least
/// one digit.
double number_at(const std::string& s, std::size_t& i, const std::string& where, char letter) {
  const std::size_t start = i;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  bool digit = false, point = false;
  for (; i < s.size(); ++i) {
    if (std::isdigit(static_cast<unsigned char>(s[i]))) {
      digit = true;
    } else if (s[i] == '.' && !point) {
      point = true;
    } else {
      break;
    }
  }
  if (!digit) {
    if (i < s.size() && (s[i] == '#' || s[i] == '['))
      refuse(where, std::string("the word ") + letter +
                        " holds a parameter or an expression, which verify does not read");
    refuse(where, std::string("the word ") + letter + " has no number");
  }
  // At most 10^12 in any unit: beyond it a double keeps no micrometres, and a longer string
  // of digits is no coordinate at all.
  const double v = std::strtod(s.substr(start, i - start).c_str(), nullptr);
  if (!(std::abs(v) <= 1e12))
    refuse(where, std::string("the word ") + letter + "'s number is beyond 10^12");
  return v;
}

Block parse_block(const std::string& code, const std::string& where) {
  Block b;
  static const std::string kAllowed = "GMFXYZABCIJKRPN";
  std::size_t i = 0;
  if (!code.empty() && code[0] == '/') refuse(where, "block delete ('/') is not read by verify");
  while (i < code.size()) {
    const char letter = code[i++];
    if (kAllowed.find(letter) == std::string::npos) {
      if (std::isalpha(static_cast<unsigned char>(letter)))
        refuse(where, std::string("the word ") + letter +
                          " is not read by verify (it reads G0-G3, G17-G21, G90, G91, G93, G94, "
                          "F, X Y Z, A B C, I J K, R, P, N, M2 and M30)");
      refuse(where, std::string("'") + letter + "' where a word's letter was expected");
    }
    const double v = number_at(code, i, where, letter);
    if (letter == 'N') continue;
    if (letter == 'G') {
      const double r = std::round(v);
      static const int kG[] = {0, 1, 2, 3, 17, 18, 19, 20, 21, 90, 91, 93, 94};
      if (r != v || r < 0 || r > 99 ||
          std::find(std::begin(kG), std::end(kG), static_cast<int>(r)) == std::end(kG))
        refuse(where, "G" + kernel::detail::format_double(v) +
                          " is not read by verify (it reads G0-G3, G17-G19, G20, G21, G90, G91, "
                          "G93 and G94)");
      b.g.push_back(static_cast<int>(r));
      continue;
    }
    if (letter == 'M') {
      if (v != 2 && v != 30)
        refuse(where,
               "M" + kernel::detail::format_double(v) + " is not read by verify (only M2 and M30)");
      b.end = true;
      continue;
    }
    if (!b.words.emplace(letter, v).second)
      refuse(where, std::string("two ") + letter + " words on one line");
  }
  // One code of each modal group, as the interpreter requires.
  auto group = [](int g) { return g <= 3 ? 1 : g <= 19 ? 2 : g <= 21 ? 6 : g <= 91 ? 3 : 5; };
  for (std::size_t a = 0; a < b.g.size(); ++a)
    for (std::size_t c = a + 1; c < b.g.size(); ++c)
      if (group(b.g[a]) == group(b.g[c]))
        refuse(where, "G" + std::to_string(b.g[a]) + " and G" + std::to_string(b.g[c]) +
                          " on one line belong to the same modal group");
  return b;
}

/// The centre of an R arc in the plane (u, v) from `from` to `to`: positive R the arc of at
/// most half a turn, negative the longer one.
Eigen::Vector3d r_centre(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double R,
                         int plane, bool clockwise, const std::string& where) {
  const auto [u, v, w] = cam::plane_axes(plane);
  const double du = to(u) - from(u), dv = to(v) - from(v), chord = std::hypot(du, dv);
  if (!(chord > 0)) refuse(where, "an arc given by R whose end is its start");
  const double half = chord / 2, r = std::abs(R);
  if (r < half * (1 - 1e-9)) refuse(where, "the arc's radius R is too small to reach its end");
  const double h = std::sqrt(std::max(0.0, r * r - half * half));
  // The centre lies to the left of the chord for a counterclockwise arc of at most half a
  // turn; the longer arc and the clockwise turn each move it to the other side.
  const double side = (clockwise ? -1.0 : 1.0) * (R > 0 ? 1.0 : -1.0);
  Eigen::Vector3d c = from;
  c(u) = from(u) + du / 2 - side * h * dv / chord;
  c(v) = from(v) + dv / 2 + side * h * du / chord;
  (void)w;
  return c;
}

/// The arc of a G2/G3 block, whose end is already in m.to.
void make_arc(cam::Move& m, const Block& b, const State& s, int g, const std::string& where) {
  const auto [u, v, w] = cam::plane_axes(s.plane);
  static const char kOffset[3] = {'I', 'J', 'K'};
  const bool has_r = b.words.count('R') > 0;
  const bool has_offset = b.words.count(kOffset[u]) > 0 || b.words.count(kOffset[v]) > 0;
  if (b.words.count(kOffset[w]) > 0)
    refuse(where,
           std::string("the word ") + kOffset[w] + " names the axis normal to the arc's plane");
  m.kind = cam::Move::Kind::arc;
  m.plane = s.plane;
  if (has_r && has_offset) refuse(where, "an arc given both by R and by its centre");
  if (has_r) {
    m.centre = r_centre(m.from, m.to, b.words.at('R') * s.unit, s.plane, g == 2, where);
  } else if (has_offset) {
    m.centre = m.from;
    for (int k : {u, v}) {
      const auto it = b.words.find(kOffset[k]);
      if (it != b.words.end()) m.centre(k) += it->second * s.unit;
    }
  } else {
    refuse(where, "an arc with neither R nor the centre's offsets in its plane");
  }
  int turns = 1;
  if (const auto p = b.words.find('P'); p != b.words.end()) {
    if (p->second != std::round(p->second) || p->second < 1 || p->second > 1000)
      refuse(where, "P, the arc's turns, must be a whole number from 1 to 1000");
    turns = static_cast<int>(p->second);
  }
  m.turns = g == 3 ? turns : -turns;
  const double r0 = std::hypot(m.from(u) - m.centre(u), m.from(v) - m.centre(v));
  const double r1 = std::hypot(m.to(u) - m.centre(u), m.to(v) - m.centre(v));
  if (!(r0 > 0) || !(r1 > 0)) refuse(where, "an arc whose centre is its start or its end");
  // Stricter than LinuxCNC, which accepts somewhat more (docs/formats.md).
  if (std::abs(r0 - r1) > 0.002 + 1e-3 * std::max(r0, r1))
    refuse(where, "the arc's radius differs from start (" + kernel::detail::format_double(r0) +
                      " mm) to end (" + kernel::detail::format_double(r1) +
                      " mm) by more than 0.002 mm + 0.1 %");
}

/// The move of a block with motion mode g, or false when it moves nothing.
bool block_move(const Block& b, State& s, int g, int line, const std::string& where, cam::Move& m) {
  static const char kAxes[6] = {'X', 'Y', 'Z', 'A', 'B', 'C'};
  bool any = false;
  m.from = s.at;
  m.abc_from = s.abc;
  m.to = s.at;
  m.abc_to = s.abc;
  for (int k = 0; k < 6; ++k) {
    const auto it = b.words.find(kAxes[k]);
    if (it == b.words.end()) continue;
    any = true;
    double& target = k < 3 ? m.to(k) : m.abc_to[static_cast<std::size_t>(k - 3)];
    const double value = k < 3 ? it->second * s.unit : it->second;
    target = s.incremental ? target + value : value;
  }
  if (!any) {
    if (g >= 2 &&
        b.words.count('I') + b.words.count('J') + b.words.count('K') + b.words.count('R') > 0)
      refuse(where, "an arc with no axis word");
    return false;
  }
  if (g < 2)
    for (char c : {'I', 'J', 'K', 'R', 'P'})
      if (b.words.count(c) > 0)
        refuse(where, std::string("the word ") + c + " belongs to an arc (G2, G3), not to G" +
                          std::to_string(g));
  m.line = line;
  m.kind = g == 0 ? cam::Move::Kind::traverse : cam::Move::Kind::feed;
  m.inverse_time = s.inverse_time;
  if (g != 0) {
    if (s.inverse_time && b.words.count('F') == 0)
      refuse(where, "a feed move under G93 (inverse time) without its F word");
    if (!(s.feed > 0)) refuse(where, "a feed move with no feed rate (F)");
    m.feed = s.feed;
  }
  if (g >= 2) make_arc(m, b, s, g, where);
  s.at = m.to;
  s.abc = m.abc_to;
  return true;
}

}  // namespace

cam::Program parse_gcode(const std::string& text, const std::string& label) {
  cam::Program program;
  program.source = label;
  State s;
  std::istringstream in(text);
  int line = 0;
  for (std::string raw; std::getline(in, raw);) {
    ++line;
    const std::string where = label + ": line " + std::to_string(line);
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    const std::string code = code_of(raw, where);
    if (code.empty() || code == "%") continue;
    const Block b = parse_block(code, where);
    int motion = s.motion;
    for (int g : b.g) {
      if (g <= 3) motion = g;
      if (g >= 17 && g <= 19) s.plane = g;
      if (g == 20 || g == 21) s.unit = g == 20 ? 25.4 : 1.0;
      if (g == 90 || g == 91) s.incremental = g == 91;
      if (g == 93 || g == 94) {
        if ((g == 93) != s.inverse_time) s.feed = 0;
        s.inverse_time = g == 93;
      }
    }
    if (const auto f = b.words.find('F'); f != b.words.end()) {
      if (!(f->second >= 0)) refuse(where, "a negative feed rate");
      s.feed = s.inverse_time ? f->second : f->second * s.unit;
    }
    const bool axes = std::any_of(b.words.begin(), b.words.end(),
                                  [](const auto& w) { return std::strchr("XYZABC", w.first); });
    if (axes && motion < 0) refuse(where, "axis words with no motion mode (G0 to G3) in force");
    s.motion = motion;
    cam::Move m;
    if (motion >= 0 && block_move(b, s, motion, line, where, m)) program.moves.push_back(m);
    if (s.inverse_time && motion >= 1) s.feed = 0;  // G93: each block gives its own F
    if (b.end) break;
  }
  if (program.moves.empty()) refuse(label, "no move (G0 to G3 with an axis word)");
  return program;
}

cam::Program read_gcode(const std::string& path) { return parse_gcode(read_text_file(path), path); }

bool is_gcode_path(const std::string& path) {
  const std::string e = lower_extension(path);
  return e == ".ngc" || e == ".nc" || e == ".gcode" || e == ".tap" || e == ".cnc";
}

}  // namespace qmotion::io
