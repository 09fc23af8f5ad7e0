// <qmotion/io/exact_number.hpp>
#pragma once
// Exact conversion of number text to CGAL::Exact_rational (exact mode).
#include <cstdlib>
#include <qmotion/kernel/cgal_scalar.hpp>
#include <qmotion/kernel/error.hpp>
#include <sstream>
#include <string>

namespace qmotion::io {

/// Largest decimal exponent of an exact number (10^1000 is far beyond any length in a
/// CAD file; the bound keeps the big-number work per number small).
inline constexpr long kMaxExponent = 1000;

/// The exact rational value of an integer, decimal ("-1.25e-3") or "p/q" text, as
/// produced by parse_number_text. Throws Errc::invalid_input on other text.
inline kernel::Rational exact_from_text(const std::string& text) {
  using kernel::Rational;
  const auto slash = text.find('/');
  // Sign and digits only, without leading zeros: gmpxx reads a leading 0 as octal.
  auto integer = [&](std::string s) {
    bool negative = false;
    if (!s.empty() && (s[0] == '+' || s[0] == '-')) {
      negative = s[0] == '-';
      s.erase(0, 1);
    }
    if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos)
      throw Error(Errc::invalid_input, "'" + text + "' is not an exact number");
    const auto first = s.find_first_not_of('0');
    s = first == std::string::npos ? "0" : s.substr(first);
    return Rational((negative ? "-" : "") + s);
  };
  if (slash != std::string::npos) {
    const Rational p = integer(text.substr(0, slash)), q = integer(text.substr(slash + 1));
    if (q == Rational(0)) throw Error(Errc::invalid_input, "'" + text + "' has a zero denominator");
    return Rational(p / q);
  }
  // Decimal: mantissa digits with the point removed, scaled by a power of ten.
  std::string s = text;
  long exp10 = 0;
  const auto e = s.find_first_of("eE");
  if (e != std::string::npos) {
    const std::string digits = s.substr(e + 1);
    const auto first = digits.find_first_not_of("+-0");
    if (first != std::string::npos && digits.size() - first > 6)
      throw Error(Errc::invalid_input, "'" + text + "' has an exponent out of range");
    exp10 = first == std::string::npos ? 0 : std::strtol(digits.c_str(), nullptr, 10);
    s.erase(e);
  }
  const auto dot = s.find('.');
  if (dot != std::string::npos) {
    exp10 -= static_cast<long>(s.size() - dot - 1);
    s.erase(dot, 1);
  }
  if (s.empty() || s == "-" || s == "+") s += "0";
  if (exp10 < -kMaxExponent || exp10 > kMaxExponent)
    throw Error(Errc::invalid_input, "'" + text + "' has an exponent out of range (at most " +
                                         std::to_string(kMaxExponent) + " in magnitude)");
  Rational value = integer(s);
  const Rational scale("1" +
                       std::string(static_cast<std::size_t>(exp10 < 0 ? -exp10 : exp10), '0'));
  if (exp10 < 0) return Rational(value / scale);
  return Rational(value * scale);
}

/// Text of an exact rational for files: "p/q", or "p" when integral.
inline std::string exact_to_text(const kernel::Rational& r) {
  std::ostringstream os;
  os << r;
  return os.str();
}

}  // namespace qmotion::io
