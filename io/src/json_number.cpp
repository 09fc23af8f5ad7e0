// io/src/json_number.cpp: JSON text read whole and checked (every float literal keeps its
// source text), and numbers read from text or a tree, with the message naming the field.
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
  if (!ec && size > max_bytes) refuse_file_size(path, max_bytes);
  // Read in chunks up to the limit: a device or pipe (/dev/zero, a FIFO) has no size.
  // The spare capacity lets the JSON reader parse the text in place (simdjson reads up to
  // 64 bytes past the end).
  std::string text;
  if (!ec && size <= max_bytes) text.reserve(static_cast<std::size_t>(size) + kReadPadding);
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes) refuse_file_size(path, max_bytes);
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
