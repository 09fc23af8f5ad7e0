// io/src/motion_json.cpp: motion files made from motions (trees and streamed text), and
// motion values made from what was read: the curve, its factors and its provenance.
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/json_text.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/interpolation.hpp>

#include "json_simd.hpp"

#ifdef QMOTION_WITH_CGAL
#include <qmotion/io/exact_number.hpp>
#endif

namespace qmotion::io {
namespace {
using json = nlohmann::json;

template <typename Scalar, typename Conv>
kernel::QMotion<Scalar> build_motion(const MotionFile& f, Conv conv) {
  std::vector<Scalar> knots;
  knots.reserve(f.knots.size());
  for (const auto& k : f.knots) knots.push_back(conv(k));
  std::vector<kernel::DualQuaternion<Scalar>> ctrl;
  ctrl.reserve(f.ctrl.size());
  for (const auto& c : f.ctrl) {
    kernel::DualQuaternion<Scalar> q;
    for (int i = 0; i < 8; ++i) q[i] = conv(c[static_cast<std::size_t>(i)]);
    ctrl.push_back(q);
  }
  return kernel::QMotion<Scalar>{f.basis, kernel::BSpline<kernel::DualQuaternion<Scalar>>::make(
                                              f.degree, std::move(knots), std::move(ctrl))};
}

template <typename Scalar, typename NumOut>
json motion_json(const kernel::QMotion<Scalar>& m, const json& method, const std::string& units,
                 NumOut num) {
  json ctrl = json::array();
  for (const auto& q : m.curve.ctrl()) {
    json c = json::array();
    for (int i = 0; i < 8; ++i) c.push_back(num(q[i]));
    ctrl.push_back(c);
  }
  json knots = json::array();
  for (const auto& k : m.curve.knots()) knots.push_back(num(k));
  json doc{{"type", "q-motion"},
           {"basis", m.basis == kernel::Basis::bezier ? "bezier" : "bspline"},
           {"degree", m.degree()},
           {"knots", knots},
           {"param_range", {num(m.a()), num(m.b())}},
           {"units", units},
           {"control_points", ctrl}};
  if (!method.is_null()) doc["method"] = method;
  return doc;
}

/// Reads the recorded factors with the number conversion `conv`; nullopt when absent.
template <typename Scalar, typename Conv>
std::optional<sweep::MotionFactors<Scalar>> read_factors(const MotionFile& f,
                                                         const kernel::QMotion<Scalar>& m,
                                                         Conv conv) {
  const json& me = f.method;
  const auto has = [&](const char* key) {  // (asked only of an object)
    return f.factor_rows.count(key) > 0 || me.contains(key);
  };
  if (!me.is_object() || !has("rotation_control_points") || !has("translation_control_points") ||
      !me.contains("translation"))
    return std::nullopt;
  const std::string where = f.source + ": method";
  const auto parsed = kernel::translation_method_from_string(
      me["translation"].is_string() ? me["translation"].get<std::string>() : "");
  if (!parsed)
    throw Error(Errc::invalid_input, where + ".translation: expected tr, trt or minimal");
  const kernel::TranslationMethod method = *parsed;
  auto knots_for = [&](const char* key, std::size_t poles) {
    std::vector<Scalar> k;
    if (me.contains(key)) {
      for (const auto& n : read_numbers(me[key], where + "." + key)) k.push_back(conv(n));
    } else {
      k.assign(poles, m.a());
      k.insert(k.end(), poles, m.b());
    }
    return k;
  };
  auto rows = [&](const char* key, std::size_t width) {
    std::vector<std::vector<Scalar>> r;
    if (const auto it = f.factor_rows.find(key); it != f.factor_rows.end()) {
      const MotionFile::Rows& fr = it->second;  // the fast reader's: non-empty, checked widths
      if (fr.width != width)
        throw Error(Errc::invalid_input,
                    where + "." + key + "[0]: expected " + std::to_string(width) + " numbers");
      r.reserve(fr.values.size() / width);
      for (std::size_t i = 0; i < fr.values.size(); i += width) {
        std::vector<Scalar>& row = r.emplace_back();
        for (std::size_t k = 0; k < width; ++k) row.push_back(conv(fr.values[i + k]));
      }
      return r;
    }
    // (const operator[] on a missing key is undefined: a TRT method without its second
    // translation factor read freed memory, found by tests/fuzz.)
    if (!me.contains(key))
      throw Error(Errc::invalid_input, where + "." + key +
                                           ": missing (expected an array of "
                                           "control points)");
    const json& a = me[key];
    if (!a.is_array() || a.empty())
      throw Error(Errc::invalid_input, where + "." + key + ": expected an array of control points");
    for (std::size_t i = 0; i < a.size(); ++i) {
      const auto v = read_numbers(a[i], where + "." + key + "[" + std::to_string(i) + "]");
      if (v.size() != width)
        throw Error(Errc::invalid_input, where + "." + key + "[" + std::to_string(i) +
                                             "]: expected " + std::to_string(width) + " numbers");
      std::vector<Scalar> row;
      for (const auto& n : v) row.push_back(conv(n));
      r.push_back(row);
    }
    return r;
  };
  using V3 = Eigen::Matrix<Scalar, 3, 1>;
  auto vec_spline = [&](const char* key, const char* knot_key) {
    std::vector<V3> c;
    for (const auto& r : rows(key, 3)) c.emplace_back(r[0], r[1], r[2]);
    const std::size_t n = c.size();
    std::vector<Scalar> k = knots_for(knot_key, n);
    const int deg = static_cast<int>(k.size() - n) - 1;
    return kernel::BSpline<V3>::make(deg, std::move(k), std::move(c));
  };
  std::vector<kernel::Quaternion<Scalar>> rc;
  for (const auto& r : rows("rotation_control_points", 4)) rc.emplace_back(r[0], r[1], r[2], r[3]);
  const std::size_t nr = rc.size();
  std::vector<Scalar> rk = knots_for("rotation_knots", nr);
  const int rdeg = static_cast<int>(rk.size() - nr) - 1;
  sweep::MotionFactors<Scalar> out{
      method, kernel::BSpline<kernel::Quaternion<Scalar>>::make(rdeg, std::move(rk), std::move(rc)),
      vec_spline("translation_control_points", "translation_knots"), std::nullopt};
  if (method == kernel::TranslationMethod::trt)
    out.translation2 = vec_spline("translation2_control_points", "translation2_knots");
  if (!sweep::factors_match(out, m))
    return std::nullopt;  // edited apart from the motion: not trusted
  return out;
}

/// The method block of a motion value: provenance, then the factors (with their knots for
/// spline motions). Null when the motion has neither.
template <typename Scalar, typename NumOut>
json method_json(const kernel::Motion<Scalar>& m, const json& input_poses, NumOut num) {
  if (!m.provenance && !m.factors) return nullptr;
  json method = json::object();
  auto numbers = [&](const std::vector<Scalar>& v) {
    json a = json::array();
    for (const auto& x : v) a.push_back(num(x));
    return a;
  };
  if (m.provenance) {
    const auto& p = *m.provenance;
    method["form"] = kernel::to_string(p.form);
    method["rotation"] = kernel::to_string(p.rotation);
    method["translation"] = kernel::to_string(p.translation);
    if (!p.param.empty()) method["param"] = p.param;
    method["exact"] = kernel::is_exact_v<Scalar>;
    if (!input_poses.is_null()) {
      method["input_poses"] = input_poses;
    } else {
      std::vector<kernel::Pose<double>> poses;
      for (const auto& x : p.poses) poses.push_back(kernel::pose_to_double(x));
      method["input_poses"] = poses_to_json(poses, m.units);
    }
    method["parameters"] = numbers(p.parameters);
    method["rotation_degree"] = p.rotation_degree;
    if (p.translation == kernel::TranslationMethod::trt) {
      method["translation_degree"] = {p.translation_degree, p.translation_degree2};
      method["trt_degrees"] = {p.translation_degree, p.translation_degree2};
    } else {
      method["translation_degree"] = p.translation_degree;
    }
    method["max_interpolation_residual"] = p.max_residual();
    if (p.form == kernel::Form::fit) {
      method["tolerance"] = p.tolerance;
      method["angle_tolerance_deg"] = p.angle_tolerance_deg;
    }
  }
  if (m.factors) {
    const auto& f = *m.factors;
    if (!m.provenance) method["translation"] = kernel::to_string(f.method);
    const bool spline = m.curve.basis == kernel::Basis::bspline;
    json rot = json::array();
    for (const auto& c : f.rotation.ctrl())
      rot.push_back(numbers(std::vector<Scalar>{c.w(), c.x(), c.y(), c.z()}));
    method["rotation_control_points"] = rot;
    if (spline) method["rotation_knots"] = numbers(f.rotation.knots());
    auto vec = [&](const char* name, const kernel::BSpline<Eigen::Matrix<Scalar, 3, 1>>& v) {
      json a = json::array();
      for (const auto& c : v.ctrl()) a.push_back(numbers(std::vector<Scalar>{c(0), c(1), c(2)}));
      method[std::string(name) + "_control_points"] = a;
      if (spline) method[std::string(name) + "_knots"] = numbers(v.knots());
    };
    vec("translation", f.translation);
    if (f.translation2) vec("translation2", *f.translation2);
  }
  return method;
}

/// method_json(m, input_poses) streamed for a double motion; `input`, when not null, is
/// written as the input poses (else the provenance's poses).
void method_text(JsonText& t, const kernel::Motion<double>& m, const PoseSet* input, int depth) {
  JsonText::Members members;
  auto add = [&](const char* key, std::function<void(int)> f) {
    members.emplace_back(key, std::move(f));
  };
  auto knots = [&](const std::vector<double>& k) { return [&t, &k](int) { t.numbers(k); }; };
  if (m.provenance) {
    const auto& p = *m.provenance;
    add("form", [&t, &p](int) { t.string(kernel::to_string(p.form)); });
    add("rotation", [&t, &p](int) { t.string(kernel::to_string(p.rotation)); });
    add("translation", [&t, &p](int) { t.string(kernel::to_string(p.translation)); });
    if (!p.param.empty()) add("param", [&t, &p](int) { t.string(p.param); });
    add("exact", [&t](int) { t.boolean(false); });
    add("input_poses", [&t, &p, &m, input](int d) {
      if (input) {
        poses_text(t, *input, d);
      } else {
        poses_text(t, p.poses, m.units, d);
      }
    });
    add("parameters", knots(p.parameters));
    add("rotation_degree", [&t, &p](int) { t.integer(p.rotation_degree); });
    if (p.translation == kernel::TranslationMethod::trt) {
      const auto pair = [&t, &p](int) {
        t.out += '[';
        t.integer(p.translation_degree);
        t.out += ',';
        t.integer(p.translation_degree2);
        t.out += ']';
      };
      add("translation_degree", pair);
      add("trt_degrees", pair);
    } else {
      add("translation_degree", [&t, &p](int) { t.integer(p.translation_degree); });
    }
    add("max_interpolation_residual", [&t, &p](int) { t.number(p.max_residual()); });
    if (p.form == kernel::Form::fit) {
      add("tolerance", [&t, &p](int) { t.number(p.tolerance); });
      add("angle_tolerance_deg", [&t, &p](int) { t.number(p.angle_tolerance_deg); });
    }
  }
  if (m.factors) {
    const auto& f = *m.factors;
    if (!m.provenance) add("translation", [&t, &f](int) { t.string(kernel::to_string(f.method)); });
    const bool spline = m.curve.basis == kernel::Basis::bspline;
    add("rotation_control_points", [&t, &f](int d) {
      const auto& c = f.rotation.ctrl();
      t.lines(c.size(), d, 4, [&](JsonText& b, std::size_t i) {
        b.point(std::array<double, 4>{c[i].w(), c[i].x(), c[i].y(), c[i].z()}, 4);
      });
    });
    if (spline) add("rotation_knots", knots(f.rotation.knots()));
    auto vec = [&](const std::string& name, const kernel::BSpline<Eigen::Vector3d>& v) {
      members.emplace_back(name + "_control_points", [&t, &v](int d) {
        t.lines(v.ctrl().size(), d, 3,
                [&](JsonText& b, std::size_t i) { b.point(v.ctrl()[i], 3); });
      });
      if (spline) members.emplace_back(name + "_knots", knots(v.knots()));
    };
    vec("translation", f.translation);
    if (f.translation2) vec("translation2", *f.translation2);
  }
  t.object(std::move(members), depth);
}

/// Refuses a recorded method field that is present but malformed.
[[noreturn]] void bad_method_field(const std::string& source, const std::string& field,
                                   const std::string& expected) {
  throw Error(Errc::invalid_input,
              source + ": method." + field + ": expected " + expected +
                  "; regenerate the file with `qmotion interpolate` from its poses, or delete "
                  "the method block to use the motion as hand-written");
}

/// The provenance a method block records, when it records one completely.
std::optional<kernel::Provenance<double>> read_provenance(
    const MotionFile& f, const kernel::QMotion<double>& curve,
    const std::optional<sweep::MotionFactors<double>>& fac) {
  const json& me = f.method;
  if (!me.is_object() || !(f.input_poses || me.contains("input_poses"))) return std::nullopt;
  for (const char* key :
       {"form", "rotation", "translation", "parameters", "rotation_degree", "translation_degree"})
    if (!me.contains(key)) return std::nullopt;
  kernel::Provenance<double> p;
  auto name = [&](const char* key) {
    return me[key].is_string() ? me[key].get<std::string>() : std::string();
  };
  const auto form = kernel::form_from_string(name("form"));
  if (!form) bad_method_field(f.source, "form", "bezier, bspline, c1 or fit");
  p.form = *form;
  if (p.form == kernel::Form::fit)  // the tolerances the fit met (docs/fitting.md)
    for (auto [key, field] : {std::pair{"tolerance", &p.tolerance},
                              std::pair{"angle_tolerance_deg", &p.angle_tolerance_deg}}) {
      if (!me.contains(key) || !me[key].is_number() || !(me[key].get<double>() > 0))
        bad_method_field(f.source, key, "a positive number (the tolerance the fit met)");
      *field = me[key].get<double>();
    }
  const auto rot = kernel::rotation_method_from_string(name("rotation"));
  if (!rot) bad_method_field(f.source, "rotation", "elliptic, affine or projective");
  p.rotation = *rot;
  const auto tr = kernel::translation_method_from_string(name("translation"));
  if (!tr) bad_method_field(f.source, "translation", "tr, trt or minimal");
  p.translation = *tr;
  if (me.contains("param")) p.param = name("param");
  // A recorded degree: an integer from 0 to 200, else the field is refused as `expected`.
  auto degree = [&](const json& j, const char* field, const char* expected) {
    if (!j.is_number_integer() || j.get<long long>() < 0 || j.get<long long>() > 200)
      bad_method_field(f.source, field, expected);
    return j.get<int>();
  };
  p.rotation_degree = degree(me["rotation_degree"], "rotation_degree", "an integer from 0 to 200");
  const json& td = me["translation_degree"];
  if (p.translation == kernel::TranslationMethod::trt) {
    const char* pair = "[L1, L2], integers from 0 to 200";
    if (!td.is_array() || td.size() != 2) bad_method_field(f.source, "translation_degree", pair);
    p.translation_degree = degree(td[0], "translation_degree", pair);
    p.translation_degree2 = degree(td[1], "translation_degree", pair);
  } else {
    p.translation_degree = degree(td, "translation_degree", "an integer from 0 to 200");
  }
  if (!me["parameters"].is_array()) bad_method_field(f.source, "parameters", "an array of numbers");
  for (std::size_t i = 0; i < me["parameters"].size(); ++i)
    p.parameters.push_back(read_number(me["parameters"][i],
                                       f.source + ": method.parameters[" + std::to_string(i) + "]")
                               .value);
  std::optional<PoseSet> parsed;
  const PoseSet& set = f.input_poses ? *f.input_poses : *(parsed = recorded_input_poses(f));
  p.poses = to_poses_double(set);
  if (p.parameters.size() != p.poses.size())
    bad_method_field(f.source, "parameters",
                     "one parameter per input pose (" + std::to_string(p.poses.size()) + ")");
  for (std::size_t i = 1; i < p.parameters.size(); ++i)
    if (!(p.parameters[i - 1] < p.parameters[i]))
      bad_method_field(f.source, "parameters", "strictly increasing numbers");
  p.residuals = kernel::pose_residuals(curve, p.poses, p.parameters);
  if (p.form == kernel::Form::bezier && fac)
    p.near_inaccessible = kernel::near_inaccessible(fac->rotation, p.parameters);
  return p;
}

}  // namespace

std::optional<sweep::MotionFactors<double>> factors_double(const MotionFile& f,
                                                           const kernel::QMotion<double>& m) {
  return read_factors<double>(f, m, [](const Number& n) { return n.value; });
}

#ifdef QMOTION_WITH_CGAL
std::optional<sweep::MotionFactors<kernel::Rational>> factors_exact(
    const MotionFile& f, const kernel::QMotion<kernel::Rational>& m) {
  return read_factors<kernel::Rational>(
      f, m, [](const Number& n) { return exact_from_text(n.source()); });
}
#endif

std::optional<PoseSet> recorded_input_poses(const MotionFile& f) {
  if (f.input_poses) return f.input_poses;
  if (!f.method.is_object() || !f.method.contains("input_poses")) return std::nullopt;
  return parse_poses_json_value(f.method["input_poses"], f.source + ": method.input_poses");
}

kernel::QMotion<double> to_motion_double(const MotionFile& f) {
  return build_motion<double>(f, [](const Number& n) { return n.value; });
}

json motion_to_json(const kernel::QMotion<double>& m, const json& method,
                    const std::string& units) {
  return motion_json(m, method, units, [](double v) { return json(v); });
}

namespace {
/// The motion of f; with `spent` (f itself), each part of f goes as soon as it is read: of a
/// 10^4-pose motion, the control points' numbers are 5 MB and the factors' 1 MB.
kernel::Motion<double> motion_value(const MotionFile& f, MotionFile* spent) {
  kernel::Motion<double> m(to_motion_double(f), std::nullopt, std::nullopt, f.units, f.source);
  if (spent) std::vector<std::array<Number, 8>>().swap(spent->ctrl);
  m.factors = factors_double(f, m.curve);
  if (spent) decltype(spent->factor_rows)().swap(spent->factor_rows);
  m.provenance = read_provenance(f, m.curve, m.factors);
  return m;
}
}  // namespace

kernel::Motion<double> to_motion(const MotionFile& f) { return motion_value(f, nullptr); }

kernel::Motion<double> to_motion(MotionFile&& f) { return motion_value(f, &f); }

json motion_document(const kernel::Motion<double>& m, const json& input_poses) {
  return motion_to_json(m.curve, method_json(m, input_poses, [](double v) { return json(v); }),
                        m.units);
}

namespace {
void motion_text(JsonText& t, const kernel::Motion<double>& m, const PoseSet* input_poses) {
  const auto& ctrl = m.curve.curve.ctrl();
  const auto& knots = m.curve.curve.knots();
  JsonText::Members members{
      {"type", [&t](int) { t.string("q-motion"); }},
      {"basis",
       [&t, &m](int) { t.string(m.curve.basis == kernel::Basis::bezier ? "bezier" : "bspline"); }},
      {"degree", [&t, &m](int) { t.integer(m.degree()); }},
      {"knots", [&t, &knots](int) { t.numbers(knots); }},
      {"param_range",
       [&t, &m](int) {
         t.point(std::array<double, 2>{m.a(), m.b()}, 2);
       }},
      {"units", [&t, &m](int) { t.string(m.units); }},
      {"control_points", [&t, &ctrl](int d) {
         t.lines(ctrl.size(), d, 8, [&](JsonText& b, std::size_t i) { b.point(ctrl[i], 8); });
       }}};
  if (m.provenance || m.factors)
    members.emplace_back("method", [&](int d) { method_text(t, m, input_poses, d); });
  t.object(std::move(members), 0);
}
}  // namespace

std::string motion_json_text(const kernel::Motion<double>& m, const PoseSet* input_poses) {
  JsonText t;
  t.out.reserve(4096 + m.curve.curve.ctrl().size() * 200 +
                (input_poses ? input_poses->poses.size() * 200 : 0));
  motion_text(t, m, input_poses);
  t.out += '\n';
  return std::move(t.out);
}

void write_motion_json(const std::string& path, const kernel::Motion<double>& m,
                       const PoseSet* input_poses) {
  check_motion_limits(m.degree(), m.curve.curve.ctrl().size(), path);
  write_json_atomic(path, [&](JsonText& t) { motion_text(t, m, input_poses); });
}

void save_motion(const kernel::Motion<double>& m, const std::string& path) {
  write_motion_json(path, m);
}

#ifdef QMOTION_WITH_CGAL
kernel::QMotion<kernel::Rational> to_motion_exact(const MotionFile& f) {
  return build_motion<kernel::Rational>(
      f, [](const Number& n) { return exact_from_text(n.source()); });
}

json motion_to_json(const kernel::QMotion<kernel::Rational>& m, const json& method,
                    const std::string& units) {
  return motion_json(m, method, units,
                     [](const kernel::Rational& v) { return json(exact_to_text(v)); });
}

json motion_document(const kernel::Motion<kernel::Rational>& m, const json& input_poses) {
  const auto num = [](const kernel::Rational& v) { return json(exact_to_text(v)); };
  return motion_json(m.curve, method_json(m, input_poses, num), m.units, num);
}
#endif

}  // namespace qmotion::io
