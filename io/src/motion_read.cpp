// io/src/motion_read.cpp: motion files read (docs/formats.md): a fast reader of the common
// layout that keeps no tree, the tree reader that words every refusal, and the checks both
// share once the fields are read.
#include <functional>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <variant>

#include "json_simd.hpp"

namespace qmotion::io {
using json = nlohmann::json;
namespace {

/// The checks that need the whole file, once its fields are read (by either reader):
/// default Bezier knots, control point count, the knot vector, the parameter range's
/// agreement with it, a non-zero rotational part.
void finish_motion(MotionFile& f, bool knots_given) {
  const std::string& source = f.source;
  const std::size_t n = f.ctrl.size();
  const auto& range = f.range;
  if (!knots_given && f.basis == kernel::Basis::bspline)
    throw Error(Errc::invalid_input,
                source + ": missing field 'knots' (required for a bspline motion)");
  if (!knots_given) {
    f.knots.assign(static_cast<std::size_t>(f.degree + 1), f.range[0]);
    f.knots.insert(f.knots.end(), static_cast<std::size_t>(f.degree + 1), f.range[1]);
  }
  if (f.basis == kernel::Basis::bezier && n != static_cast<std::size_t>(f.degree + 1))
    throw Error(Errc::invalid_input,
                source + ": a Bezier motion of degree " + std::to_string(f.degree) + " needs " +
                    std::to_string(f.degree + 1) + " control points, found " + std::to_string(n));
  std::vector<double> kv;
  for (const auto& k : f.knots) kv.push_back(k.value);
  const auto issues = kernel::BSpline<double>::validate(f.degree, kv, n);
  if (!issues.empty()) throw Error(Errc::invalid_input, source + ": knots: " + issues.front());
  if (f.basis == kernel::Basis::bezier && (kv.size() != 2 * n || kv[n - 1] != kv.front()))
    throw Error(Errc::invalid_input, source + ": knots: a Bezier motion has no interior knots");
  for (std::size_t i = f.degree + 1; i + f.degree + 1 < kv.size(); ++i)
    if (kv[i] == kv[i + f.degree])
      throw Error(Errc::invalid_input,
                  source + ": knots: knot " + f.knots[i].source() +
                      " has multiplicity above the degree (the motion would be discontinuous)");
  if (kv.front() != range[0].value || kv.back() != range[1].value)
    throw Error(Errc::invalid_input, source + ": param_range [" + range[0].source() + ", " +
                                         range[1].source() +
                                         "] differs from the knot vector's ends");
  bool real_nonzero = false;
  for (const auto& c : f.ctrl)
    for (std::size_t k = 0; k < 4; ++k) real_nonzero = real_nonzero || c[k].value != 0.0;
  if (!real_nonzero)
    throw Error(Errc::invalid_input,
                source + ": control_points: the rotational (real) part is zero everywhere");
}

}  // namespace

namespace {

/// A method block's control points as rows of one width, read lean (the scanner on every
/// core, or simdjson when the scanner declines); false for anything else (no rows, an empty
/// row, rows of different widths, not numbers): the tree reader then reads and words it.
bool control_rows(std::string_view raw, MotionFile::Rows& out) {
  const bool scanned = simd::number_rows(
      raw, 0,
      [&](std::size_t n, std::size_t w) {
        out.width = w;
        out.values.assign(n * w, Number());
        return true;
      },
      [&](std::size_t i) { return out.values.data() + i * out.width; }, /*lean=*/true);
  if (scanned) return out.width != 0 && !out.values.empty();
  return simd::read_value(raw, [&](simd::sj::value rv) {
    simd::sj::array ra;
    if (rv.get_array().get(ra)) return false;
    out.width = 0;
    out.values.clear();
    for (auto e : ra) {
      simd::sj::value row;
      if (e.get(row)) return false;
      const std::size_t before = out.values.size();
      if (!simd::numbers(row, out.values, /*lean=*/true)) return false;
      const std::size_t width = out.values.size() - before;
      if (out.width == 0) out.width = width;
      if (width == 0 || width != out.width) return false;
    }
    return out.width != 0;
  });
}

/// The motion's control points, rows of 8 numbers read lean (the scanner on every core, or
/// simdjson when the scanner declines); false for anything else, or more than
/// kMaxMotionControlPoints.
bool control_points(std::string_view raw, std::vector<std::array<Number, 8>>& ctrl) {
  const bool scanned = simd::number_rows(
      raw, 8,
      [&](std::size_t n, std::size_t) {
        if (n > kMaxMotionControlPoints) return false;
        ctrl.assign(n, {});
        return true;
      },
      [&](std::size_t i) { return ctrl[i].data(); }, /*lean=*/true);
  if (scanned) return true;
  return simd::read_value(raw, [&](simd::sj::value v) {
    simd::sj::array rows;
    std::size_t count = 0;
    if (v.get_array().get(rows) || rows.count_elements().get(count) ||
        count > kMaxMotionControlPoints)
      return false;
    ctrl.clear();
    ctrl.reserve(count);  // no regrowth: the rows' numbers are moved, not copied twice
    for (auto r : rows) {
      simd::sj::array row;
      if (r.get_array().get(row)) return false;
      auto& c = ctrl.emplace_back();
      std::size_t k = 0;
      for (auto e : row) {
        simd::sj::value ev;
        if (k == 8 || e.get(ev) || !simd::number(ev, c[k++], /*lean=*/true)) return false;
      }
      if (k != 8) return false;
    }
    return true;
  });
}

/// The method block's text: null, or an object whose members are read one by one (the input
/// poses straight into a pose set, rows of numbers by the scanner, the rest into a tree), or
/// only validated, member by member, when the caller does not want it. False for anything
/// else: the tree reader then reads and words it.
bool method_block(std::string_view raw, MotionFile& f, bool with_method,
                  const std::function<void(const char*)>& read_to) {
  namespace sj = simd::sj;
  if (raw == "null") {
    if (with_method) f.method = nullptr;
    return true;
  }
  std::vector<simd::Member> members;
  if (!simd::members(raw, members)) return false;
  constexpr std::size_t depth = 2;  // the method's members lie two levels deep
  if (!with_method) {
    for (const auto& m : members) {
      if (!simd::check_slice(m.value, depth)) return false;
      read_to(m.value.data() + m.value.size());
    }
    return true;
  }
  f.method = json::object();
  f.input_poses.reset();
  f.factor_rows.clear();
  for (const auto& [key, value] : members) {
    bool ok = true;
    if (key == "input_poses") {
      if (f.input_poses) return false;  // given twice: the tree reader decides
      try {
        f.input_poses = simd::poses_text(value, f.source + ": method.input_poses");
      } catch (const Error&) {
        return false;  // refused where the tree reader refuses it, in its words
      }
      ok = f.input_poses.has_value();
    } else if (key == "rotation_control_points" || key == "translation_control_points" ||
               key == "translation2_control_points") {
      // Rows of equal width, read lean; anything else (or a repeat) the tree reader words.
      ok = !f.factor_rows.count(key) && value.front() == '[' &&
           control_rows(value, f.factor_rows[std::string(key)]);
    } else {
      nlohmann::json& out = f.method[std::string(key)];  // (a lambda cannot name a binding)
      ok = simd::read_member(
          value, [&](sj::value v) { return simd::build(v, out, /*plain=*/true, depth); });
    }
    if (!ok) return false;
    read_to(value.data() + value.size());
  }
  return true;
}

/// The motion file read straight from the text: members() cuts the object into its members
/// without indexing the text, the rows of numbers go to the scanner, and each other member is
/// read by simdjson on its own (the index then covers one member, not the file). No DOM for
/// the control points and knots (a 10^4-pose motion is 10^5 numbers). std::nullopt as soon as
/// anything is unusual (a field of the wrong kind, an exact "p/q" number, invalid JSON):
/// parse_motion then reads the file and words the message. Throws only finish_motion's
/// errors, which both readers share. `text` has simdjson's padding past its end; read_to(p)
/// is told that nothing before p will be read again (parse_motion_fast's two forms).
std::optional<MotionFile> parse_motion_view(std::string_view text, const std::string& source,
                                            bool with_method,
                                            const std::function<void(const char*)>& read_to) {
  namespace sj = simd::sj;
  std::vector<simd::Member> root;
  if (!simd::members(text, root)) return std::nullopt;
  MotionFile f;
  f.source = source;
  bool type = false, basis = false, degree = false, range = false, ctrl = false,
       knots_given = false;
  const auto numbers = [](std::string_view raw, std::vector<Number>& out, bool lean = false) {
    out.clear();
    return simd::read_member(raw, [&](sj::value v) { return simd::numbers(v, out, lean); });
  };
  for (const auto& [key, raw] : root) {
    bool ok = true;
    if (key == "type") {
      std::string t;
      ok = simd::string_value(raw, t) && t == "q-motion";
      type = true;
    } else if (key == "basis") {
      std::string b;
      ok = simd::string_value(raw, b) && (b == "bezier" || b == "bspline");
      f.basis = b == "bezier" ? kernel::Basis::bezier : kernel::Basis::bspline;
      basis = true;
    } else if (key == "degree") {
      ok = simd::integer_value(raw, 0, 200, f.degree);
      degree = true;
    } else if (key == "param_range") {
      std::vector<Number> r;
      ok = numbers(raw, r) && r.size() == 2 && r[0].value < r[1].value;
      if (ok) f.range = {r[0], r[1]};
      range = true;
    } else if (key == "units") {
      ok = simd::string_value(raw, f.units) && is_known_unit(f.units);
    } else if (key == "control_points") {
      ok = raw.front() == '[' && control_points(raw, f.ctrl);
      ctrl = true;
    } else if (key == "knots") {
      knots_given = raw != "null";
      if (knots_given) ok = numbers(raw, f.knots, /*lean=*/true);
    } else if (key == "method") {
      ok = method_block(raw, f, with_method, read_to);
    } else {
      ok = simd::check_slice(raw, 1);
    }
    if (!ok) return std::nullopt;
    read_to(raw.data() + raw.size());
  }
  if (!type || !basis || !degree || !range || !ctrl) return std::nullopt;
  finish_motion(f, knots_given);
  return f;
}

}  // namespace

std::optional<MotionFile> parse_motion_fast(const std::string& text, const std::string& source,
                                            bool with_method) {
  const simd::Padded padded(text);
  return parse_motion_view(padded.view(), source, with_method, [](const char*) {});
}

std::optional<MotionFile> parse_motion_fast(PagedText& text, const std::string& source,
                                            bool with_method) {
  const char* const base = text.view().data();
  return parse_motion_view(text.view(), source, with_method, [&](const char* p) {
    text.release_before(static_cast<std::size_t>(p - base));
  });
}

namespace {

/// The file's fields, the method block checked but left to the caller to copy or move in.
MotionFile parse_motion_fields(const json& doc, const std::string& source) {
  MotionFile f;
  f.source = source;
  if (!doc.is_object())
    throw Error(Errc::invalid_input, source + ": expected a JSON object (a motion file)");
  const json& type = require(doc, "type", source);
  if (type == "quaternion-spline")
    throw Error(
        Errc::invalid_input,
        source +
            ": type \"quaternion-spline\" is a non-rational motion and this needs a rational "
            "q-motion (info, eval, trajectory, sweep and check read both kinds; check --exact "
            "verifies rational motions only)");
  if (type != "q-motion")
    throw Error(Errc::invalid_input,
                source + ": type: expected \"q-motion\", found " + type.dump());
  const json& basis = require(doc, "basis", source);
  if (basis == "bezier") {
    f.basis = kernel::Basis::bezier;
  } else if (basis == "bspline") {
    f.basis = kernel::Basis::bspline;
  } else {
    throw Error(Errc::invalid_input,
                source + ": basis: expected \"bezier\" or \"bspline\", found " + basis.dump());
  }
  const json& degree = require(doc, "degree", source);
  if (!degree.is_number_integer())
    throw Error(Errc::invalid_input,
                source + ": degree: expected an integer from 0 to 200, found " + degree.dump());
  check_motion_limits(degree.get<long long>(), 0, source);
  f.degree = degree.get<int>();
  const auto range = read_numbers(require(doc, "param_range", source), source + ": param_range");
  if (range.size() != 2)
    throw Error(Errc::invalid_input, source + ": param_range: expected [a, b]");
  if (!(range[0].value < range[1].value))
    throw Error(Errc::invalid_input, source + ": param_range: expected a < b");
  f.range = {range[0], range[1]};
  if (doc.contains("units")) {
    if (!doc["units"].is_string() || !is_known_unit(doc["units"].get<std::string>()))
      throw Error(Errc::invalid_input, source + ": units: expected one of mm, cm, m, in, ft, um");
    f.units = doc["units"].get<std::string>();
  }
  const json& ctrl = require(doc, "control_points", source);
  if (!ctrl.is_array())
    throw Error(Errc::invalid_input, source + ": control_points: expected an array");
  check_motion_limits(f.degree, ctrl.size(), source);
  f.ctrl.resize(ctrl.size());
  for (std::size_t i = 0; i < ctrl.size(); ++i) {
    // Messages are built only when a row is refused: this loop reads every number.
    const auto w = [&] { return source + ": control_points[" + std::to_string(i) + "]"; };
    const json& row = ctrl[i];
    if (!row.is_array()) throw Error(Errc::invalid_input, w() + ": expected an array of numbers");
    if (row.size() != 8)
      throw Error(Errc::invalid_input,
                  w() + ": expected 8 numbers (w,x,y,z, eps w,eps x,eps y,eps z), found " +
                      std::to_string(row.size()));
    std::array<Number, 8>& c = f.ctrl[i];
    for (std::size_t k = 0; k < 8; ++k)
      c[k] = read_number_lazy(row[k], [&] { return w() + "[" + std::to_string(k) + "]"; });
  }
  const bool knots_given = doc.contains("knots") && !doc["knots"].is_null();
  if (knots_given) f.knots = read_numbers(doc["knots"], source + ": knots");
  finish_motion(f, knots_given);
  if (doc.contains("method")) {
    if (!doc["method"].is_object() && !doc["method"].is_null())
      throw Error(Errc::invalid_input, source +
                                           ": method: expected an object (how the motion "
                                           "was made), found " +
                                           std::string(doc["method"].type_name()));
  }
  return f;
}

}  // namespace

void check_motion_limits(long long degree, std::size_t control_points, const std::string& source) {
  if (degree < 0 || degree > kMaxMotionDegree)
    throw Error(Errc::invalid_input, source + ": degree: expected an integer from 0 to " +
                                         std::to_string(kMaxMotionDegree) + ", found " +
                                         std::to_string(degree));
  if (control_points > kMaxMotionControlPoints)
    throw Error(Errc::invalid_input, source + ": control_points: more than " +
                                         std::to_string(kMaxMotionControlPoints) +
                                         " (the limit keeps memory bounded)");
}

MotionFile parse_motion(const json& doc, const std::string& source) {
  MotionFile f = parse_motion_fields(doc, source);
  if (doc.contains("method")) f.method = doc["method"];
  return f;
}

MotionFile parse_motion(json&& doc, const std::string& source) {
  MotionFile f = parse_motion_fields(doc, source);
  if (doc.contains("method")) f.method = std::move(doc["method"]);
  return f;
}

std::variant<MotionFile, std::string> read_motion_or_text(const std::string& path,
                                                          bool with_method) {
  PagedText paged = PagedText::read(path);  // given back as it is read, freed on return
  if (auto f = parse_motion_fast(paged, path, with_method)) return std::move(*f);
  return paged.whole(path);
}

MotionFile read_motion(const std::string& path) {
  auto read = read_motion_or_text(path);
  if (auto* f = std::get_if<MotionFile>(&read)) return std::move(*f);
  return parse_motion(parse_json(std::get<std::string>(read), path, "method"), path);
}

MotionFile parse_motion_text(const std::string& text, const std::string& path) {
  if (auto f = parse_motion_fast(text, path)) return std::move(*f);
  // The method block is metadata echoed back to users: its numbers stay numbers (the
  // text-preserving parse turns float literals into strings).
  return parse_motion(parse_json(text, path, "method"), path);
}

}  // namespace qmotion::io
