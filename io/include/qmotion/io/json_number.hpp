// <qmotion/io/json_number.hpp>
#pragma once
#include <cstdint>
#include <cstring>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <qmotion/io/atomic_file.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace qmotion::io {

/// A number read from a file with its source text, so that exact mode can convert the text
/// itself ("0.1" is exactly 1/10 there, not the double nearest it).
/// Longest number text accepted (digits of an exact "p/q" included): bounds the work of
/// exact mode per number.
inline constexpr std::size_t kMaxNumberChars = 1000;

/// A number's kept source text, in one pointer: null (nothing allocated) when empty, the
/// common case, else one heap block holding the length and the characters. A Number is then
/// 16 bytes instead of 40 with a std::string (a 10^4-pose motion holds 6 x 10^5 of them).
/// The length takes one byte below 255 (else the byte 255 and the length in 8 bytes): a
/// 17-digit text such as "0.70710678118654757" then fits glibc's 32-byte chunk, not 48.
class NumberText {
 public:
  NumberText() = default;
  NumberText(std::string_view s) { assign(s); }  // NOLINT: implicit, like std::string
  NumberText(const std::string& s) : NumberText(std::string_view(s)) {}  // NOLINT
  NumberText(const char* s) : NumberText(std::string_view(s)) {}         // NOLINT
  NumberText(const NumberText& o) : NumberText(o.view()) {}
  NumberText(NumberText&&) noexcept = default;
  NumberText& operator=(const NumberText& o) {
    if (this != &o) assign(o.view());
    return *this;
  }
  NumberText& operator=(NumberText&&) noexcept = default;
  ~NumberText() = default;

  bool empty() const { return !block_; }
  std::size_t size() const { return view().size(); }
  std::string_view view() const {
    if (!block_) return {};
    const auto n = static_cast<unsigned char>(block_[0]);
    if (n < kLong) return std::string_view(block_.get() + 1, n);
    std::size_t m = 0;
    std::memcpy(&m, block_.get() + 1, sizeof m);
    return std::string_view(block_.get() + 1 + sizeof m, m);
  }
  operator std::string_view() const { return view(); }  // NOLINT: reads like a string
  std::string str() const { return std::string(view()); }
  const char* begin() const { return view().data(); }
  const char* end() const { return begin() + size(); }
  std::size_t find(char c) const { return view().find(c); }
  void clear() { block_.reset(); }

  friend bool operator==(const NumberText& a, const NumberText& b) { return a.view() == b.view(); }
  friend bool operator==(const NumberText& a, std::string_view b) { return a.view() == b; }
  friend bool operator==(const NumberText& a, const char* b) { return a.view() == b; }
  friend bool operator==(const NumberText& a, const std::string& b) { return a.view() == b; }
  friend bool operator!=(const NumberText& a, const NumberText& b) { return !(a == b); }
  friend std::ostream& operator<<(std::ostream& os, const NumberText& t) { return os << t.view(); }

 private:
  void assign(std::string_view s) {
    if (s.empty()) {
      block_.reset();
      return;
    }
    const std::size_t n = s.size();
    const std::size_t head = n < kLong ? 1 : 1 + sizeof n;
    std::unique_ptr<char[]> b(new char[head + n]);
    if (n < kLong) {
      b[0] = static_cast<char>(static_cast<unsigned char>(n));
    } else {
      b[0] = static_cast<char>(static_cast<unsigned char>(kLong));
      std::memcpy(b.get() + 1, &n, sizeof n);
    }
    std::memcpy(b.get() + head, s.data(), n);
    block_ = std::move(b);
  }
  static constexpr std::size_t kLong = 255;  ///< the length byte of a long text
  std::unique_ptr<char[]> block_;
};

struct Number {
  /// Canonical source text: integer, decimal or "p/q". Empty when the source text is the
  /// shortest round-trip text of `value` (the motion reader leaves it so for control
  /// points, 5.6 x 10^5 numbers in a 10^4-pose motion): read it through source().
  NumberText text;
  double value = 0;  ///< nearest double

  static Number from_double(double v);
  /// The source text: `text`, or the shortest round-trip text of `value` when it is empty.
  std::string source() const { return text.empty() ? from_double(value).text.str() : text.str(); }
};

/// Parses JSON text. Floating-point literals become JSON strings holding their exact source
/// text (read them with read_number); integers stay integers. Throws
/// Errc::invalid_input naming `source`, the line and the column on a syntax error.
nlohmann::json parse_json(const std::string& text, const std::string& source);
/// The reader parse_json falls back to, nlohmann's: the reference for what is accepted
/// and the one that words every message (line, column, NaN). Same document as parse_json.
nlohmann::json parse_json_reference(const std::string& text, const std::string& source);

/// The same, except that the root object's member `plain_member` (metadata echoed back to
/// users, such as a motion's "method") keeps float literals as JSON numbers (doubles).
nlohmann::json parse_json(const std::string& text, const std::string& source,
                          std::string_view plain_member);

/// Reads a whole file and parses it with parse_json. Throws Errc::invalid_input when the
/// file cannot be read.
nlohmann::json read_json_file(const std::string& path);

/// Deepest nesting of arrays and objects accepted in a JSON file (qmotion's own files nest
/// five deep at most): bounds the recursion that reads a document, whose stack a file of
/// nested brackets alone would otherwise exhaust.
inline constexpr std::size_t kMaxJsonDepth = 100;

/// Spare capacity read_text_file leaves after the text, so that JSON is parsed in place.
inline constexpr std::size_t kReadPadding = 64;

/// The whole file; Errc::invalid_input naming the path when it cannot be read or is larger
/// than max_bytes (refuse_file_size: the message a writer gives for the same file).
std::string read_text_file(const std::string& path, std::uintmax_t max_bytes = kMaxFileBytes);

/// Parses a number written as integer, decimal (with optional exponent) or "p/q".
/// Throws Errc::invalid_input with `where` in the message when the text is not a finite
/// number.
Number parse_number_text(const std::string& text, const std::string& where);

/// The finite number at j (a JSON number or a numeric string); `where` names the file and
/// field in the message of the Errc::invalid_input it throws otherwise.
Number read_number(const nlohmann::json& j, const std::string& where);

/// The number written as `text` when it is a plain decimal literal (the common case),
/// without building any message; std::nullopt otherwise.
std::optional<Number> try_number_text(std::string_view text);

/// The number at j when it is an integer or a plain decimal literal (the common case),
/// without building any message; std::nullopt otherwise (read_number then decides).
std::optional<Number> try_read_number(const nlohmann::json& j);

/// read_number, with the message's `where()` only called when the fast path declines (this
/// runs for every number of every file, and most of them are fine).
template <typename WhereFn>
Number read_number_lazy(const nlohmann::json& j, WhereFn&& where) {
  if (auto n = try_read_number(j)) return std::move(*n);
  return read_number(j, where());
}

/// The same for element `index` of an array named `where`: the message names where[index],
/// and that text is only built when the number is refused (this runs for every number).
Number read_number(const nlohmann::json& j, const std::string& where, std::size_t index);
/// The array of numbers j; Errc::invalid_input naming where[i] for a bad element.
std::vector<Number> read_numbers(const nlohmann::json& j, const std::string& where);

/// Member `key` of object j, or throws naming `where` and the key.
const nlohmann::json& require(const nlohmann::json& j, const std::string& key,
                              const std::string& where);

}  // namespace qmotion::io
