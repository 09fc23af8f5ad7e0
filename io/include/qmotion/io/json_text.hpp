// <qmotion/io/json_text.hpp>: a streaming JSON writer for the large documents (NURBS, motion
// files): no tree, members in the sorted order nlohmann's tree writes them, shortest round-trip
// numbers. Small values (names, method records) go through nlohmann. Long arrays are
// formatted in blocks on every core and joined in order, so the bytes never depend on the
// number of cores.
#pragma once
#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <qmotion/kernel/error.hpp>
#include <string>
#include <utility>
#include <vector>

namespace qmotion::io {

class JsonText {
 public:
  std::string out;
  /// Where finished text goes while it is made (a file being written), when set: blocks()
  /// hands `out` and its blocks over as they are ready, so a long document is never held
  /// whole, and finish() hands over the rest. Unset: everything stays in `out`.
  std::function<void(const std::string&)> sink;
  void finish() {
    if (sink && !out.empty()) {
      sink(out);
      out.clear();
    }
  }

  /// Shortest text that reads back as `v` (std::to_chars); -0 as "-0.0" ("-0" would read
  /// back as the integer 0); null for non-finite numbers, as nlohmann writes them.
  void number(double v) {
    if (!std::isfinite(v)) {
      out += "null";
      return;
    }
    if (v == 0 && std::signbit(v)) {
      out += "-0.0";
      return;
    }
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
  }
  void integer(long long v) { out += std::to_string(v); }
  void boolean(bool v) { out += v ? "true" : "false"; }
  /// A JSON string; plain printable ASCII (number texts, names) is written as it is.
  void string(const std::string& s) {
    const bool plain = std::all_of(
        s.begin(), s.end(), [](char c) { return c >= 0x20 && c < 0x7f && c != '"' && c != '\\'; });
    if (!plain) {
      out += nlohmann::json(s).dump();
      return;
    }
    out += '"';
    out += s;
    out += '"';
  }
  /// A small value, compact.
  void value(const nlohmann::json& v) { out += v.dump(); }
  void numbers(const std::vector<double>& v) {
    out += '[';
    blocks(v.size(), 1, [&v](JsonText& t, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        if (i) t.out += ',';
        t.number(v[i]);
      }
    });
    out += ']';
  }
  template <typename Vec>
  void point(const Vec& p, int n) {
    out += '[';
    for (int i = 0; i < n; ++i) {
      if (i) out += ',';
      number(p[i]);
    }
    out += ']';
  }
  void indent(int depth) { out.append(static_cast<std::size_t>(depth), ' '); }
  /// An array of `n` items, each on its own line at depth + 1: item(t, i) writes item i
  /// into t, which is this text or one of its blocks (see blocks); an item has about
  /// `numbers_each` numbers.
  template <typename F>
  void lines(std::size_t n, int depth, std::size_t numbers_each, F item) {
    if (n == 0) {
      out += "[]";
      return;
    }
    out += "[\n";
    blocks(n, numbers_each, [&](JsonText& t, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        t.indent(depth + 1);
        item(t, i);
        t.out += i + 1 < n ? ",\n" : "\n";
      }
    });
    indent(depth);
    out += ']';
  }

  /// Appends what emit(t, begin, end) writes for items [begin, end) of `n`, as emit(*this,
  /// 0, n) would. When there are enough numbers to pay (`numbers_each` an item), the items
  /// are cut into blocks formatted in parallel (oneTBB) into texts of their own, a wave of
  /// blocks at a time; each wave is then appended (or handed to the sink) in order.
  using Emit = std::function<void(JsonText&, std::size_t, std::size_t)>;
  void blocks(std::size_t n, std::size_t numbers_each, const Emit& emit);

  using Members = std::vector<std::pair<std::string, std::function<void(int)>>>;
  /// An object whose members are written by the functions (given the depth), in sorted key
  /// order; `extra`'s members join them. A key given twice is refused (Errc::internal).
  void object(Members members, const nlohmann::json& extra, int depth) {
    for (const auto& [k, v] : extra.items()) {
      nlohmann::json copy = v;
      members.emplace_back(k, [this, copy](int) { value(copy); });
    }
    std::sort(members.begin(), members.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 1; i < members.size(); ++i)
      if (members[i].first == members[i - 1].first)
        throw Error(Errc::internal, "JSON text: member '" + members[i].first + "' twice");
    out += "{\n";
    for (std::size_t i = 0; i < members.size(); ++i) {
      indent(depth + 1);
      string(members[i].first);
      out += ": ";
      members[i].second(depth + 1);
      out += i + 1 < members.size() ? ",\n" : "\n";
    }
    indent(depth);
    out += '}';
  }
  void object(Members members, int depth) {
    object(std::move(members), nlohmann::json::object(), depth);
  }
};

/// Writes the JSON document write(t) makes, and a final newline, to `path` atomically as it
/// is made (JsonText::sink): the text is never held whole. Throws Errc::invalid_input naming
/// the path when the file cannot be written; nothing is left behind then.
void write_json_atomic(const std::string& path, const std::function<void(JsonText&)>& write);

}  // namespace qmotion::io
