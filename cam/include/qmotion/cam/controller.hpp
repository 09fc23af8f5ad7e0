// <qmotion/cam/controller.hpp>: what a G-code program tells the controller so that the
// certificate holds on the machine: the dialect's words for units, comments and the path
// mode, and the time a block takes under the axes' velocity and acceleration limits.
// docs/cam.md ("The controller's contract") gives the reasons.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <qmotion/kernel/error.hpp>
#include <string>

namespace qmotion::cam {

/// The controllers whose words a program uses.
enum class Dialect { linuxcnc, fanuc, siemens };

/// "linuxcnc", "fanuc" or "siemens" (`--dialect`); Errc::invalid_input naming `where` else.
inline Dialect parse_dialect(const std::string& name, const std::string& where) {
  if (name == "linuxcnc") return Dialect::linuxcnc;
  if (name == "fanuc") return Dialect::fanuc;
  if (name == "siemens") return Dialect::siemens;
  throw Error(Errc::invalid_input, where + " " + name + ": expected linuxcnc, fanuc or siemens");
}

inline std::string dialect_name(Dialect d) {
  switch (d) {
    case Dialect::fanuc:
      return "fanuc";
    case Dialect::siemens:
      return "siemens";
    default:
      return "linuxcnc";
  }
}

/// A comment line: "(text)" (LinuxCNC, Fanuc; parentheses inside become brackets) or
/// "; text" (Siemens).
inline std::string comment(Dialect d, std::string text) {
  if (d == Dialect::siemens) return "; " + text;
  for (char& c : text)
    if (c == '(') {
      c = '[';
    } else if (c == ')') {
      c = ']';
    }
  return "(" + text + ")";
}

/// The metric or inch word: G21/G20, or G71/G70 for Siemens.
inline std::string units_word(Dialect d, bool inch) {
  if (d == Dialect::siemens) return inch ? "G70" : "G71";
  return inch ? "G20" : "G21";
}

/// The path mode a program commands before its first feed move, and the one-line
/// assumption its header states.
struct PathMode {
  std::string words;       ///< e.g. "G61", "G64 P0.0025 Q0.0025", "G60 G601"
  std::string assumption;  ///< for the header comment
};

/// The path mode under which the certificate holds with `controller_tol` (>= 0, the
/// program's length unit) of the tolerance left to the controller:
/// - 0: the controller follows the programmed polyline: LinuxCNC G61 (exact path), Fanuc
///   G61 (exact stop), Siemens G60 G601 (exact stop, fine window);
/// - > 0: LinuxCNC G64 P<p/2> Q<p/2> (its naive-CAM merging keeps the path within Q of the
///   polyline and the blending within P of that), Siemens G642 with CTOL=<p>. Fanuc's
///   smoothing tolerance is a machine parameter, not a program word: Errc::invalid_input.
inline PathMode path_mode(Dialect d, double controller_tol, const std::string& units) {
  auto num = [](double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%.6f", x);
    return std::string(b);
  };
  if (!(controller_tol > 0)) {
    const std::string w = d == Dialect::siemens ? "G60 G601" : "G61";
    return {w, "path mode " + w +
                   ": the certificate assumes the controller follows the "
                   "programmed polyline exactly"};
  }
  const std::string share = ": the certificate leaves the controller " + num(controller_tol) + " " +
                            units + " of the tolerance";
  switch (d) {
    case Dialect::linuxcnc: {
      const std::string w = "G64 P" + num(controller_tol / 2) + " Q" + num(controller_tol / 2);
      return {w, "path mode " + w + share};
    }
    case Dialect::siemens: {
      const std::string w = "G642 CTOL=" + num(controller_tol);
      return {w, "path mode " + w + share};
    }
    default:
      throw Error(Errc::invalid_input,
                  "--controller-tol with --dialect fanuc: Fanuc's smoothing tolerance is a "
                  "machine parameter, not a program word, so the program cannot state it; use "
                  "--controller-tol 0 (G61)");
  }
}

/// The minutes a block takes from rest to rest when its axes move linearly and together
/// (one parameter s from 0 to 1): `minutes` at the velocity the feed and the velocity limits
/// allow (1 / minutes is the top rate of s), `delta` the axes' displacements and `accel` their
/// acceleration limits (per s^2, infinite: none). The rate of s accelerates at
/// a = min accel_j / |delta_j| (per minute^2) on a trapezoidal profile: 1/v + v/a when the
/// top rate v is reached, 2/sqrt(a) when it is not. Never less than `minutes`; equal to it
/// with no acceleration limit.
inline double block_minutes(double minutes, const std::array<double, 5>& delta,
                            const std::array<double, 5>& accel) {
  double a = HUGE_VAL;
  for (std::size_t j = 0; j < 5; ++j)
    if (std::abs(delta[j]) > 0) a = std::min(a, accel[j] * 3600 / std::abs(delta[j]));
  if (!std::isfinite(a) || !(minutes > 0)) return minutes;
  const double v = 1 / minutes;
  return v * v <= a ? minutes + v / a : 2 / std::sqrt(a);
}

}  // namespace qmotion::cam
