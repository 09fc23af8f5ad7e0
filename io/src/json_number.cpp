// io/src/json_number.cpp
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <qmotion/io/json_number.hpp>
#include <qmotion/kernel/error.hpp>
#include <sstream>
#include <vector>

#include "json_simd.hpp"

#ifdef QMOTION_WITH_CGAL
#include <qmotion/io/exact_number.hpp>
#endif

namespace qmotion::io {
namespace {

using json = nlohmann::json;

/// SAX handler that builds the DOM like nlohmann's own, except that float literals are kept
/// as their source text (strings), so no digit of the input is lost.
class TextPreservingSax : public nlohmann::json_sax<json> {
 public:
  explicit TextPreservingSax(json& root) : root_(root) {}

  bool null() override { return put(json(nullptr)); }
  bool boolean(bool v) override { return put(json(v)); }
  bool number_integer(number_integer_t v) override { return put(json(v)); }
  bool number_unsigned(number_unsigned_t v) override { return put(json(v)); }
  bool number_float(number_float_t, const string_t& s) override { return put(json(s)); }
  bool string(string_t& v) override { return put(json(v)); }
  bool binary(binary_t& v) override { return put(json::binary(v)); }
  bool start_object(std::size_t) override { return open(json::object()); }
  bool key(string_t& k) override {
    key_ = k;
    return true;
  }
  bool end_object() override {
    stack_.pop_back();
    return true;
  }
  bool start_array(std::size_t) override { return open(json::array()); }
  bool end_array() override {
    stack_.pop_back();
    return true;
  }
  bool parse_error(std::size_t pos, const std::string& last_token,
                   const nlohmann::detail::exception& ex) override {
    error_pos_ = pos;
    last_token_ = last_token;
    error_ = ex.what();
    return false;
  }

  std::size_t error_pos_ = 0;
  std::string last_token_, error_;
  bool too_deep_ = false;  ///< stopped at an array or object kMaxJsonDepth levels deep

 private:
  bool put(json v) {
    if (stack_.empty()) {
      root_ = std::move(v);
    } else if (stack_.back()->is_array()) {
      stack_.back()->push_back(std::move(v));
    } else {
      (*stack_.back())[key_] = std::move(v);
    }
    return true;
  }
  bool open(json v) {
    if (stack_.size() >= kMaxJsonDepth) {
      too_deep_ = true;
      return false;
    }
    if (stack_.empty()) {
      root_ = std::move(v);
      stack_.push_back(&root_);
    } else if (stack_.back()->is_array()) {
      stack_.back()->push_back(std::move(v));
      stack_.push_back(&stack_.back()->back());
    } else {
      json& slot = (*stack_.back())[key_];
      slot = std::move(v);
      stack_.push_back(&slot);
    }
    return true;
  }
  json& root_;
  std::vector<json*> stack_;
  std::string key_;
};

std::string line_column(const std::string& text, std::size_t pos) {
  std::size_t line = 1, col = 1;
  for (std::size_t i = 0; i + 1 < pos && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(col);
}

/// The fast path: simdjson's on-demand parser for documents that are an object or an array
/// (every file qmotion reads). False when simdjson refuses anything, so that the caller
/// falls back to nlohmann for the verdict and the message.
bool parse_json_simd(const std::string& text, std::string_view plain_member, json& root) {
  std::size_t first = 0;
  while (first < text.size() &&
         (text[first] == ' ' || text[first] == '\t' || text[first] == '\n' || text[first] == '\r'))
    ++first;
  if (first == text.size() || (text[first] != '{' && text[first] != '[')) return false;
  simd::Document d(text);
  if (!d.ok) return false;
  if (text[first] == '[' || plain_member.empty()) {
    simd::sj::value v;
    if (d.doc.get_value().get(v) || !simd::build(v, root, false)) return false;
  } else {
    simd::sj::object obj;
    if (d.doc.get_object().get(obj)) return false;
    root = json::object();
    for (auto field : obj) {
      std::string_view key;
      if (field.unescaped_key().get(key)) return false;
      if (!simd::build(field.value(), root[std::string(key)], key == plain_member, 1)) return false;
    }
  }
  return d.at_end();
}

/// The nlohmann parser: the reference for what is accepted and for the messages.
json parse_json_checked(const std::string& text, const std::string& source) {
  json root;
  TextPreservingSax sax(root);
  const bool ok = json::sax_parse(text, &sax, json::input_format_t::json, /*strict=*/true);
  if (!ok && sax.too_deep_)
    throw Error(Errc::invalid_input, source + ": arrays and objects nested more than " +
                                         std::to_string(kMaxJsonDepth) + " levels deep");
  if (!ok) {
    std::string msg = source + ": invalid JSON at " + line_column(text, sax.error_pos_);
    const std::string& tok = sax.last_token_;
    if (tok.find("NaN") != std::string::npos || tok.find("nan") != std::string::npos ||
        tok.find("Inf") != std::string::npos || tok.find("inf") != std::string::npos ||
        (!tok.empty() && (tok.back() == 'N' || tok.back() == 'I'))) {
      msg +=
          ": NaN and Infinity are not numbers (JSON has no such literals; every number must be "
          "finite)";
    } else if (sax.error_.find("number overflow") != std::string::npos) {
      msg += ": number " + tok + " is out of the range of double";
    } else {
      msg += ": " + sax.error_;
    }
    throw Error(Errc::invalid_input, msg);
  }
  return root;
}

}  // namespace

Number Number::from_double(double v) {
  // The shortest text that reads back as v (often the very text of the file it came from).
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return Number{std::string(buf, r.ptr), v};
}

json parse_json(const std::string& text, const std::string& source) {
  return parse_json(text, source, {});
}

json parse_json_reference(const std::string& text, const std::string& source) {
  return parse_json_checked(text, source);
}

json parse_json(const std::string& text, const std::string& source, std::string_view plain_member) {
  json root;
  if (parse_json_simd(text, plain_member, root)) return root;
  root = parse_json_checked(text, source);
  if (!plain_member.empty() && root.is_object()) {
    const auto it = root.find(plain_member);
    if (it != root.end()) *it = json::parse(text)[std::string(plain_member)];
  }
  return root;
}

std::string read_text_file(const std::string& path, std::uintmax_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(Errc::invalid_input, path + ": cannot open file for reading");
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > max_bytes)
    throw Error(Errc::invalid_input, path + ": a file of " + std::to_string(size) +
                                         " bytes (at most " + std::to_string(max_bytes) + ")");
  // Read in chunks up to the limit: a device or pipe (/dev/zero, a FIFO) has no size.
  // The spare capacity lets the JSON reader parse the text in place (simdjson reads up to
  // 64 bytes past the end).
  std::string text;
  if (!ec && size <= max_bytes) text.reserve(static_cast<std::size_t>(size) + kReadPadding);
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes)
      throw Error(Errc::invalid_input,
                  path + ": more than " + std::to_string(max_bytes) + " bytes (the limit)");
  }
  if (in.bad()) throw Error(Errc::invalid_input, path + ": read error");
  return text;
}

json read_json_file(const std::string& path) { return parse_json(read_text_file(path), path); }

namespace {

/// The common case of every number read, without allocation or message: a decimal literal
/// [+-]? (digits [. digits*] | . digits) ([eE] [+-]? digits)? with nothing around it, and its
/// nearest double (std::from_chars rounds correctly). False for anything else, which
/// parse_number_text then reads or refuses with a message.
bool fast_decimal(std::string_view t, double& v) {
  if (t.empty() || t.size() > kMaxNumberChars) return false;
  const char* p = t.data();
  const char* const e = p + t.size();
  const bool plus = *p == '+';
  if (*p == '+' || *p == '-') ++p;
  const char* const mantissa = plus ? p : t.data();
  const auto digits = [e](const char*& q) {
    const char* s = q;
    while (q < e && *q >= '0' && *q <= '9') ++q;
    return q > s;
  };
  bool ok = digits(p);
  if (p < e && *p == '.') {
    ++p;
    ok = digits(p) || ok;
  }
  if (!ok) return false;
  if (p < e && (*p == 'e' || *p == 'E')) {
    ++p;
    if (p < e && (*p == '+' || *p == '-')) ++p;
    if (!digits(p)) return false;
  }
  if (p != e) return false;
  const auto r = std::from_chars(mantissa, e, v);
  return r.ec == std::errc() && r.ptr == e && std::isfinite(v);
}

}  // namespace

Number parse_number_text(const std::string& raw, const std::string& where) {
  if (double v = 0; fast_decimal(raw, v)) return Number{raw, v};
  if (raw.size() > kMaxNumberChars)
    throw Error(Errc::invalid_input, where + ": a number of " + std::to_string(raw.size()) +
                                         " characters (at most " + std::to_string(kMaxNumberChars) +
                                         ")");
  // The grammar, scanned by hand (this runs for every number of every file):
  //   decimal: ws [+-]? (digits [. digits*] | . digits) ([eE] [+-]? digits)? ws
  //   ratio:   ws [+-]? digits ws / ws [+-]? digits ws
  const char* const b = raw.data();
  const char* const e = b + raw.size();
  const auto space = [](char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
  };
  const auto digits = [e](const char*& p) {
    const char* s = p;
    while (p < e && *p >= '0' && *p <= '9') ++p;
    return p > s;
  };
  const char* p = b;
  while (p < e && space(*p)) ++p;
  const char* const start = p;
  if (p < e && (*p == '+' || *p == '-')) ++p;
  const char* q = p;
  const bool integral = digits(q);
  // decimal
  {
    const char* d = q;
    bool ok = integral;
    if (d < e && *d == '.') {
      ++d;
      ok = digits(d) || integral;
    }
    if (ok && d < e && (*d == 'e' || *d == 'E')) {
      const char* x = d + 1;
      if (x < e && (*x == '+' || *x == '-')) ++x;
      ok = digits(x);
      d = x;
    }
    const char* const end = d;
    while (d < e && space(*d)) ++d;
    if (ok && d == e) {
      const std::string t(start, end);
      const double v = std::strtod(t.c_str(), nullptr);
      if (!std::isfinite(v))
        throw Error(Errc::invalid_input,
                    where + ": number '" + raw + "' is out of the range of double");
      return Number{t, v};
    }
  }
  // ratio
  if (integral) {
    const std::string num(start, q);
    const char* d = q;
    while (d < e && space(*d)) ++d;
    if (d < e && *d == '/') {
      ++d;
      while (d < e && space(*d)) ++d;
      const char* const den0 = d;
      if (d < e && (*d == '+' || *d == '-')) ++d;
      const bool den_digits = digits(d);
      const std::string den(den0, d);
      while (d < e && space(*d)) ++d;
      if (den_digits && d == e) {
        if (den.find_first_not_of("+-0") == std::string::npos)
          throw Error(Errc::invalid_input,
                      where + ": rational '" + raw + "' has a zero denominator");
        Number n{num + "/" + den, 0.0};
#ifdef QMOTION_WITH_CGAL
        n.value = kernel::to_double(exact_from_text(n.text.str()));
#else
        n.value = std::strtod(num.c_str(), nullptr) / std::strtod(den.c_str(), nullptr);
#endif
        if (!std::isfinite(n.value))
          throw Error(Errc::invalid_input,
                      where + ": number '" + raw + "' is out of the range of double");
        return n;
      }
    }
  }
  std::string lower = raw;
  for (auto& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos)
    throw Error(Errc::invalid_input, where + ": '" + raw + "' is not a finite number");
  throw Error(Errc::invalid_input,
              where + ": '" + raw + "' is not a number (expected e.g. 1.5, -2e3 or \"3/4\")");
}

Number read_number(const json& j, const std::string& where) {
  if (j.is_number_integer()) return Number{j.dump(), static_cast<double>(j.get<std::int64_t>())};
  if (j.is_number_unsigned()) return Number{j.dump(), static_cast<double>(j.get<std::uint64_t>())};
  if (j.is_number_float()) {  // only from JSON built in memory, not from parse_json
    const double v = j.get<double>();
    if (!std::isfinite(v)) throw Error(Errc::invalid_input, where + ": not a finite number");
    return Number::from_double(v);
  }
  if (j.is_string()) return parse_number_text(j.get<std::string>(), where);
  throw Error(Errc::invalid_input,
              where + ": expected a number, found " + std::string(j.type_name()));
}

namespace simd {

Document::Document(const std::string& text) {
  thread_local sj::parser shared;
  if (text.size() > kOwnParserChars) own = std::make_unique<sj::parser>();
  sj::parser& parser = own ? *own : shared;
  // read_text_file leaves the padding simdjson reads past the end; other text is copied.
  if (text.capacity() - text.size() >= simdjson::SIMDJSON_PADDING) {
    ok = !parser.iterate(text).get(doc);
  } else {
    padded = simdjson::padded_string(text);
    ok = !parser.iterate(padded).get(doc);
  }
}

bool Document::at_end() {
  // Past the root value, the location is an out-of-bounds error.
  const char* rest = nullptr;
  return doc.current_location().get(rest) == simdjson::OUT_OF_BOUNDS;
}

namespace {

/// Whether raw is the shortest round-trip text of d (the number then keeps no text: the value
/// gives it back).
bool is_shortest_text(double d, std::string_view raw) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, d);
  return std::string_view(buf, static_cast<std::size_t>(r.ptr - buf)) == raw;
}

/// The trailing white space the raw token of a number carries.
std::string_view trimmed(std::string_view raw) {
  while (!raw.empty() &&
         (raw.back() == ' ' || raw.back() == '\t' || raw.back() == '\n' || raw.back() == '\r'))
    raw.remove_suffix(1);
  return raw;
}

/// Reads v whole (simdjson validates what is read, not what is skipped) into *out, or
/// only validates it when out is null.
bool walk(sj::value v, json* out, bool plain, std::size_t depth = 0) {
  sj::json_type type;
  if (v.type().get(type)) return false;
  switch (type) {
    case sj::json_type::array: {
      if (depth >= kMaxJsonDepth) return false;  // nlohmann's reader words the refusal
      sj::array arr;
      if (v.get_array().get(arr)) return false;
      if (out) *out = json::array();
      for (auto child : arr) {
        sj::value cv;
        if (child.get(cv)) return false;
        if (out) out->push_back(nullptr);
        if (!walk(cv, out ? &out->back() : nullptr, plain, depth + 1)) return false;
      }
      return true;
    }
    case sj::json_type::object: {
      if (depth >= kMaxJsonDepth) return false;
      sj::object obj;
      if (v.get_object().get(obj)) return false;
      if (out) *out = json::object();
      for (auto field : obj) {
        std::string_view key;
        if (field.unescaped_key().get(key)) return false;
        if (!walk(field.value(), out ? &(*out)[std::string(key)] : nullptr, plain, depth + 1))
          return false;
      }
      return true;
    }
    case sj::json_type::number: {
      // get_number validates the literal (the raw token alone is not checked) and tells
      // integers from floats; floats keep their text, as in TextPreservingSax.
      sj::number n;
      if (v.get_number().get(n)) return false;
      if (!out) return true;
      switch (n.get_number_type()) {
        case sj::number_type::signed_integer:
          *out = n.get_int64();
          return true;
        case sj::number_type::unsigned_integer:
          *out = n.get_uint64();
          return true;
        default:
          if (plain) {
            *out = n.get_double();
          } else {
            *out = std::string(trimmed(v.raw_json_token()));
          }
          return true;
      }
    }
    case sj::json_type::string: {
      std::string_view s;
      if (v.get_string().get(s)) return false;
      if (out) *out = std::string(s);
      return true;
    }
    case sj::json_type::boolean: {
      bool b = false;
      if (v.get_bool().get(b)) return false;
      if (out) *out = b;
      return true;
    }
    case sj::json_type::null: {
      bool null = false;
      if (v.is_null().get(null) || !null) return false;
      if (out) *out = nullptr;
      return true;
    }
  }
  return false;
}

}  // namespace

bool build(sj::value v, json& out, bool plain, std::size_t depth) {
  return walk(v, &out, plain, depth);
}

bool check(sj::value v) { return walk(v, nullptr, false); }

bool number(sj::value v, Number& out, bool lean) {
  sj::json_type type;
  if (v.type().get(type)) return false;
  if (type == sj::json_type::string) {
    std::string_view s;
    if (v.get_string().get(s)) return false;
    auto n = try_number_text(s);
    if (!n) return false;
    out = std::move(*n);
    return true;
  }
  if (type != sj::json_type::number) return false;
  sj::number n;
  if (v.get_number().get(n)) return false;
  switch (n.get_number_type()) {
    case sj::number_type::signed_integer:
      out = Number{std::to_string(n.get_int64()), static_cast<double>(n.get_int64())};
      return true;
    case sj::number_type::unsigned_integer:
      out = Number{std::to_string(n.get_uint64()), static_cast<double>(n.get_uint64())};
      return true;
    default: {
      const std::string_view raw = trimmed(v.raw_json_token());
      const double d = n.get_double();
      if (lean && is_shortest_text(d, raw)) {
        out.text.clear();
        out.value = d;
        return true;
      }
      out = Number{std::string(raw), d};
      return true;
    }
  }
}

namespace {

bool json_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

const char* skip_space(const char* p, const char* e) {
  while (p < e && json_space(*p)) ++p;
  return p;
}

bool digit(const char* p, const char* e) { return p < e && *p >= '0' && *p <= '9'; }

/// The JSON number token at p into out, as number() reads it (integers keep their text,
/// decimals too unless `lean` finds it the shortest round-trip text); p is left after it.
bool scan_number(const char*& p, const char* e, Number& out, bool lean) {
  const char* const s = p;
  if (p < e && *p == '-') ++p;
  if (p < e && *p == '0') {
    ++p;
  } else if (p < e && *p >= '1' && *p <= '9') {
    while (digit(p, e)) ++p;
  } else {
    return false;
  }
  bool real = false;
  if (p < e && *p == '.') {
    if (!digit(++p, e)) return false;
    while (digit(p, e)) ++p;
    real = true;
  }
  if (p < e && (*p == 'e' || *p == 'E')) {
    ++p;
    if (p < e && (*p == '+' || *p == '-')) ++p;
    if (!digit(p, e)) return false;
    while (digit(p, e)) ++p;
    real = true;
  }
  if (!real) {
    if (p - s > 18) return false;  // 18 characters always fit int64; longer ones simdjson decides
    std::int64_t i = 0;
    std::from_chars(s, p, i);
    out.text = std::to_string(i);
    out.value = static_cast<double>(i);
    return true;
  }
  double d = 0;
  const auto r = std::from_chars(s, p, d);
  if (r.ec != std::errc() || r.ptr != p || !std::isfinite(d)) return false;
  const std::string_view raw(s, static_cast<std::size_t>(p - s));
  out.value = d;
  out.text = lean && is_shortest_text(d, raw) ? NumberText() : NumberText(raw);
  return true;
}

/// `count` rows of `width` numbers, "[n, ...], [n, ...]", filling [p, e) exactly.
bool scan_rows(const char* p, const char* e, std::size_t first, std::size_t count,
               std::size_t width, const std::function<Number*(std::size_t)>& row, bool lean) {
  for (std::size_t i = 0; i < count; ++i) {
    p = skip_space(p, e);
    if (i > 0) {
      if (p == e || *p != ',') return false;
      p = skip_space(p + 1, e);
    }
    if (p == e || *p != '[') return false;
    Number* const out = row(first + i);
    for (std::size_t k = 0; k < width; ++k) {
      p = skip_space(p + 1, e);  // past '[' or ','
      if (!scan_number(p, e, out[k], lean)) return false;
      p = skip_space(p, e);
      if (p == e || *p != (k + 1 < width ? ',' : ']')) return false;
    }
    ++p;
  }
  return skip_space(p, e) == e;
}

}  // namespace

bool number_rows(std::string_view text, std::size_t width,
                 const std::function<bool(std::size_t, std::size_t)>& rows,
                 const std::function<Number*(std::size_t)>& row, bool lean) {
  const char* b = skip_space(text.data(), text.data() + text.size());
  const char* e = text.data() + text.size();
  while (e > b && json_space(e[-1])) --e;
  if (e - b < 2 || *b != '[' || e[-1] != ']') return false;
  ++b;
  --e;  // the rows, between the brackets
  if (skip_space(b, e) == e) return rows(0, width);
  if (width == 0) {  // the first row's: its commas and one
    const char* const end = std::find(b, e, ']');
    if (end == e) return false;
    width = static_cast<std::size_t>(std::count(b, end, ',')) + 1;
  }
  // Parts of about equal length, each ending at a row's ']' and the next starting after the
  // comma that follows it; rows are counted by their '['.
  constexpr std::size_t kPartChars = std::size_t(1) << 16;
  const auto length = static_cast<std::size_t>(e - b);
  const std::size_t parts_wanted =
      std::min<std::size_t>(4 * static_cast<std::size_t>(tbb::this_task_arena::max_concurrency()),
                            1 + length / kPartChars);
  struct Part {
    const char* b;
    const char* e;
    std::size_t first = 0, count = 0;
  };
  std::vector<Part> parts;
  const char* start = b;
  for (std::size_t j = 1; j < parts_wanted && start < e; ++j) {
    const char* cut = std::max(start, b + j * length / parts_wanted);
    const char* close = std::find(cut, e, ']');
    if (close == e) break;
    const char* comma = skip_space(close + 1, e);
    if (comma == e) break;  // the last row
    if (*comma != ',') return false;
    parts.push_back({start, close + 1});
    start = comma + 1;
  }
  parts.push_back({start, e});
  std::size_t total = 0;
  for (auto& part : parts) {
    part.first = total;
    part.count = static_cast<std::size_t>(std::count(part.b, part.e, '['));
    total += part.count;
  }
  if (!rows(total, width)) return false;
  std::atomic<bool> ok{true};
  const auto read = [&](std::size_t j) {
    const Part& part = parts[j];
    if (ok.load(std::memory_order_relaxed) &&
        !scan_rows(part.b, part.e, part.first, part.count, width, row, lean))
      ok = false;
  };
  if (parts.size() == 1) {
    read(0);
  } else {
    tbb::parallel_for(std::size_t(0), parts.size(), read);
  }
  return ok;
}

bool read_value(std::string_view text, const std::function<bool(sj::value)>& read) {
  const simdjson::padded_string copy(text);
  sj::parser parser;
  sj::document doc;
  sj::value v;
  if (parser.iterate(copy).get(doc) || doc.get_value().get(v)) return false;
  return read(v);
}

bool numbers(sj::value v, std::vector<Number>& out, bool lean) {
  sj::array a;
  if (v.get_array().get(a)) return false;
  for (auto e : a) {
    sj::value ev;
    if (e.get(ev) || !number(ev, out.emplace_back(), lean)) return false;
  }
  return true;
}

}  // namespace simd

std::optional<Number> try_number_text(std::string_view t) {
  if (double v = 0; fast_decimal(t, v)) return Number{std::string(t), v};
  return std::nullopt;
}

std::optional<Number> try_read_number(const json& j) {
  if (j.is_string()) {
    return try_number_text(j.get_ref<const std::string&>());
  } else if (j.is_number_integer()) {
    return read_number(j, std::string());  // cannot fail
  }
  return std::nullopt;
}

Number read_number(const json& j, const std::string& where, std::size_t index) {
  return read_number_lazy(j, [&] { return where + "[" + std::to_string(index) + "]"; });
}

std::vector<Number> read_numbers(const json& j, const std::string& where) {
  if (!j.is_array()) throw Error(Errc::invalid_input, where + ": expected an array of numbers");
  std::vector<Number> v;
  v.reserve(j.size());
  for (std::size_t i = 0; i < j.size(); ++i) v.push_back(read_number(j[i], where, i));
  return v;
}

const json& require(const json& j, const std::string& key, const std::string& where) {
  if (!j.is_object())
    throw Error(Errc::invalid_input,
                where + ": expected an object, found " + std::string(j.type_name()));
  const auto it = j.find(key);
  if (it == j.end()) throw Error(Errc::invalid_input, where + ": missing field '" + key + "'");
  return *it;
}

}  // namespace qmotion::io
