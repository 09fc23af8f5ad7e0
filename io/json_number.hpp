// io/json_number.hpp
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

namespace qmotion::io {

/// A number read from a file with its source text, so that exact mode can convert the text
/// itself ("0.1" is exactly 1/10 there, not the double nearest it).
/// Longest number text accepted (digits of an exact "p/q" included): bounds the work of
/// exact mode per number.
inline constexpr std::size_t kMaxNumberChars = 1000;

struct Number {
  std::string text;  ///< canonical source text: integer, decimal or "p/q"
  double value = 0;  ///< nearest double

  static Number from_double(double v);
};

/// Parses JSON text. Floating-point literals become JSON strings holding their exact source
/// text (read them with read_number); integers stay integers. Throws
/// Errc::invalid_input naming `source`, the line and the column on a syntax error.
nlohmann::json parse_json(const std::string& text, const std::string& source);

/// Reads a whole file and parses it with parse_json. Throws Errc::invalid_input when the
/// file cannot be read.
nlohmann::json read_json_file(const std::string& path);

/// Largest file read (bounded memory: a 10^5-pose motion file is about 130 MB).
inline constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t(512) << 20;

/// The whole file; Errc::invalid_input naming the path when it cannot be read or is larger
/// than max_bytes.
std::string read_text_file(const std::string& path, std::uintmax_t max_bytes = kMaxFileBytes);

/// Parses a number written as integer, decimal (with optional exponent) or "p/q".
/// Throws Errc::invalid_input with `where` in the message when the text is not a finite
/// number.
Number parse_number_text(const std::string& text, const std::string& where);

/// The finite number at j (a JSON number or a numeric string); `where` names the file and
/// field in the message of the Errc::invalid_input it throws otherwise.
Number read_number(const nlohmann::json& j, const std::string& where);

/// Member `key` of object j, or throws naming `where` and the key.
const nlohmann::json& require(const nlohmann::json& j, const std::string& key,
                              const std::string& where);

}  // namespace qmotion::io
