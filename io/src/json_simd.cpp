// io/src/json_simd.cpp: the simdjson layer of the JSON readers (json_simd.hpp): documents,
// trees whose float literals keep their text, and numbers and rows of numbers read in place.
#include "json_simd.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <charconv>
#include <functional>
#include <qmotion/io/json_number.hpp>
#include <string_view>
#include <vector>

namespace qmotion::io {
using json = nlohmann::json;

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

}  // namespace qmotion::io
