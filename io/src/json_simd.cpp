// io/src/json_simd.cpp: the simdjson layer of the JSON readers (json_simd.hpp): documents,
// trees whose float literals keep their text, and numbers and rows of numbers read in place.
#include "json_simd.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <functional>
#include <qmotion/io/json_number.hpp>
#include <string_view>
#include <vector>

namespace qmotion::io {
using json = nlohmann::json;

namespace simd {

Document::Document(const std::string& text) : padded(text) {
  thread_local sj::parser shared;
  if (text.size() > kOwnParserChars) own = std::make_unique<sj::parser>();
  sj::parser& parser = own ? *own : shared;
  const std::string_view t = padded.view();
  ok = !parser.iterate(t.data(), t.size(), t.size() + simdjson::SIMDJSON_PADDING).get(doc);
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

bool check(sj::value v, std::size_t depth) { return walk(v, nullptr, false, depth); }

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

Padded::Padded(const std::string& text) : text_(text) {
  if (text.capacity() - text.size() < simdjson::SIMDJSON_PADDING) {
    copy_ = simdjson::padded_string(text);
    text_ = std::string_view(copy_.data(), copy_.size());
  }
}

namespace {

/// Past the string whose opening quote is at s[i]; npos when it does not close.
std::size_t skip_string(std::string_view s, std::size_t i) {
  for (++i; i < s.size(); ++i) {
    if (s[i] == '\\') {
      ++i;
    } else if (s[i] == '"') {
      return i + 1;
    }
  }
  return std::string_view::npos;
}

/// The index of the first bracket or quote from i on, stepping over the digits of the large
/// arrays sixteen bytes at a time with SSE2, else eight (SWAR: a byte equal to c shows as a
/// high bit of (y - 1...1) & ~y with y = x ^ c...c; false matches lie only above a true one,
/// so the lowest is exact). The last few bytes of s may come back unexamined (an index below
/// s.size()) for the caller's byte loop.
std::size_t next_special(std::string_view s, std::size_t i) {
#ifdef __SSE2__
  // Sixteen bytes a step where SSE2 is (every x86-64): one compare per character sought.
  const __m128i open = _mm_set1_epi8('['), close = _mm_set1_epi8(']'), brace = _mm_set1_epi8('{'),
                end = _mm_set1_epi8('}'), quote = _mm_set1_epi8('"');
  for (; i + 16 <= s.size(); i += 16) {
    const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(s.data() + i));
    const __m128i hit =
        _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi8(x, open), _mm_cmpeq_epi8(x, close)),
                     _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi8(x, brace), _mm_cmpeq_epi8(x, end)),
                                  _mm_cmpeq_epi8(x, quote)));
    if (const int mask = _mm_movemask_epi8(hit))
      return i + static_cast<std::size_t>(__builtin_ctz(static_cast<unsigned>(mask)));
  }
#endif
  constexpr std::uint64_t ones = 0x0101010101010101ULL, highs = 0x8080808080808080ULL;
  const auto has = [](std::uint64_t x, std::uint64_t c) {
    const std::uint64_t y = x ^ (ones * c);
    return (y - ones) & ~y & highs;
  };
  for (; i + 8 <= s.size(); i += 8) {
    std::uint64_t x = 0;
    std::memcpy(&x, s.data() + i, 8);
    const std::uint64_t folded = x | (ones * 0x20);  // '[' ']' fold onto '{' '}'
    const std::uint64_t hits = has(folded, '{') | has(folded, '}') | has(x, '"');
    if (hits) {
      // The first byte in memory is the word's lowest on a little-endian machine.
      constexpr bool little = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;
      return little ? i + static_cast<std::size_t>(__builtin_ctzll(hits) >> 3) : i;
    }
  }
  return i;
}

/// Past the value starting at s[i]: an array or object up to its closing bracket (strings
/// skipped), a string up to its closing quote, anything else up to the next delimiter.
/// npos when a bracket or quote does not close. The brackets' kinds are not matched: the
/// reader of the slice validates it.
std::size_t skip_value(std::string_view s, std::size_t i) {
  constexpr auto npos = std::string_view::npos;
  if (i >= s.size()) return npos;
  if (s[i] == '"') return skip_string(s, i);
  if (s[i] != '[' && s[i] != '{') {
    while (i < s.size() && !json_space(s[i]) && s[i] != ',' && s[i] != '}' && s[i] != ']') ++i;
    return i;
  }
  std::size_t depth = 0;
  for (; i < s.size(); ++i) {
    i = next_special(s, i);
    if (i == s.size()) break;
    const char c = s[i];
    if (c == '"') {
      i = skip_string(s, i);
      if (i == npos) return npos;
      --i;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if ((c == ']' || c == '}') && --depth == 0) {
      return i + 1;
    }
  }
  return npos;
}

/// skip_space on an index of s.
std::size_t skip_spaces(std::string_view s, std::size_t i) {
  return static_cast<std::size_t>(skip_space(s.data() + i, s.data() + s.size()) - s.data());
}

}  // namespace

bool members(std::string_view s, std::vector<Member>& out) {
  out.clear();
  std::size_t i = skip_spaces(s, 0);
  if (i == s.size() || s[i] != '{') return false;
  i = skip_spaces(s, i + 1);
  if (i < s.size() && s[i] == '}') return skip_spaces(s, i + 1) == s.size();
  while (true) {
    if (i == s.size() || s[i] != '"') return false;
    const std::size_t close = s.find_first_of("\\\"", i + 1);
    if (close == std::string_view::npos || s[close] != '"') return false;  // an escape: decline
    const std::string_view key = s.substr(i + 1, close - i - 1);
    // No parser reads the keys: what JSON forbids in a string (a control character, bytes
    // that are not UTF-8) declines here, and the full parser words it.
    if (std::any_of(key.begin(), key.end(),
                    [](char c) { return static_cast<unsigned char>(c) < 0x20; }) ||
        !simdjson::validate_utf8(key.data(), key.size()))
      return false;
    i = skip_spaces(s, close + 1);
    if (i == s.size() || s[i] != ':') return false;
    i = skip_spaces(s, i + 1);
    const std::size_t end = skip_value(s, i);
    if (end == std::string_view::npos || end == i) return false;
    out.push_back({key, s.substr(i, end - i)});
    i = skip_spaces(s, end);
    if (i == s.size()) return false;
    if (s[i] == '}') return skip_spaces(s, i + 1) == s.size();
    if (s[i] != ',') return false;
    i = skip_spaces(s, i + 1);
  }
}

bool elements(std::string_view s, const std::function<bool(std::string_view)>& each) {
  std::size_t i = skip_spaces(s, 0);
  if (i == s.size() || s[i] != '[') return false;
  i = skip_spaces(s, i + 1);
  if (i < s.size() && s[i] == ']') return skip_spaces(s, i + 1) == s.size();
  while (true) {
    const std::size_t end = skip_value(s, i);
    if (end == std::string_view::npos || end == i || !each(s.substr(i, end - i))) return false;
    i = skip_spaces(s, end);
    if (i == s.size()) return false;
    if (s[i] == ']') return skip_spaces(s, i + 1) == s.size();
    if (s[i] != ',') return false;
    i = skip_spaces(s, i + 1);
  }
}

bool check_slice(std::string_view slice, std::size_t depth) {
  const auto whole = [&] {
    return read_member(slice, [&](sj::value v) { return check(v, depth); });
  };
  if (slice.size() <= kSharedParserChars || depth >= kMaxJsonDepth) return whole();
  if (slice.front() == '[')
    return elements(slice, [&](std::string_view e) { return check_slice(e, depth + 1); });
  if (slice.front() != '{') return whole();
  std::vector<Member> parts;
  if (!members(slice, parts)) return whole();  // an escaped key: simdjson reads it whole
  for (const auto& m : parts)
    if (!check_slice(m.value, depth + 1)) return false;
  return true;
}

bool read_member(std::string_view slice, const std::function<bool(sj::value)>& read) {
  if (slice.empty()) return false;
  if (slice.front() != '[' && slice.front() != '{') {
    // A scalar root is not a value in simdjson's on-demand API: read it as [slice].
    std::string wrapped;
    wrapped.reserve(slice.size() + 2);
    wrapped.append("[").append(slice).append("]");
    return read_value(wrapped, [&](sj::value v) {
      sj::array a;
      if (v.get_array().get(a)) return false;
      std::size_t n = 0;
      for (auto e : a) {
        sj::value ev;
        if (n++ > 0 || e.get(ev) || !read(ev)) return false;
      }
      return n == 1;
    });
  }
  // A parser of its own above 64 KiB, freed after: the thread's parser keeps the buffers of
  // the longest text it ever read (5 bytes a character reserved).
  thread_local sj::parser shared;
  std::unique_ptr<sj::parser> own;
  if (slice.size() > kSharedParserChars) own = std::make_unique<sj::parser>();
  sj::parser& parser = own ? *own : shared;
  sj::document doc;
  sj::value v;
  // The slice lies in a Padded text: the padding's bytes past its end are readable.
  if (parser.iterate(slice.data(), slice.size(), slice.size() + simdjson::SIMDJSON_PADDING)
          .get(doc) ||
      doc.get_value().get(v) || !read(v))
    return false;
  const char* rest = nullptr;
  return doc.current_location().get(rest) == simdjson::OUT_OF_BOUNDS;
}

bool string_value(std::string_view slice, std::string& out) {
  return read_member(slice, [&](sj::value v) {
    std::string_view s;
    if (v.get_string().get(s)) return false;
    out = std::string(s);
    return true;
  });
}

bool integer_value(std::string_view slice, std::int64_t lo, std::int64_t hi, int& out) {
  return read_member(slice, [&](sj::value v) {
    sj::json_type t;
    std::int64_t g = 0;
    if (v.type().get(t) || t != sj::json_type::number || v.get_int64().get(g) || g < lo || g > hi)
      return false;
    out = static_cast<int>(g);
    return true;
  });
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
