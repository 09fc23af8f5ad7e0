// <qmotion/io/units.hpp>: the length units qmotion reads, declares and converts between
// (docs/formats.md).
#pragma once
#include <qmotion/kernel/error.hpp>
#include <string>

namespace qmotion::io {

/// The canonical name of a length unit: mm, cm, m, in, ft, um ("µm" is read as um). Throws
/// Errc::invalid_input naming `where` for anything else.
inline std::string canonical_unit(const std::string& u, const std::string& where) {
  if (u == "mm" || u == "cm" || u == "m" || u == "in" || u == "ft" || u == "um") return u;
  if (u == "\xC2\xB5m" || u == "\xCE\xBCm") return "um";  // micro sign, Greek mu
  throw Error(Errc::invalid_input,
              where + ": unknown length unit '" + u + "' (expected mm, cm, m, in, ft, um or µm)");
}

/// The size of the unit in millimetres (exact decimal definitions: 1 in = 25.4 mm).
inline double unit_in_mm(const std::string& u) {
  const std::string c = canonical_unit(u, "unit");
  if (c == "mm") return 1.0;
  if (c == "cm") return 10.0;
  if (c == "m") return 1000.0;
  if (c == "in") return 25.4;
  if (c == "ft") return 304.8;
  return 0.001;
}

/// The factor that converts a length in `from` into `to`: 1 when they are the same unit
/// (no rounding at all), else from/to in millimetres.
inline double unit_factor(const std::string& from, const std::string& to) {
  if (canonical_unit(from, "unit") == canonical_unit(to, "unit")) return 1.0;
  return unit_in_mm(from) / unit_in_mm(to);
}

}  // namespace qmotion::io
