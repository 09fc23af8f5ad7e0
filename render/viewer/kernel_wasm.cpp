// render/viewer/kernel_wasm.cpp: the kernel the viewer page runs, compiled to WebAssembly by
// Debian's emscripten (render/viewer/CMakeLists.txt). It holds one current motion of either
// kind: a rational Q-motion read from its file's curve, or a quaternion spline read from its
// keys and control points; or either made again from edited poses with the file's method.
// The page evaluates it, its trajectories and its sweep through the calls bound at the end
// (docs/guide/view.md). Every call returns an object with `error` set instead of throwing.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <optional>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/kernel/parametrization.hpp>
#include <qmotion/kernel/qspline.hpp>
#include <qmotion/kernel/spline_interpolation.hpp>
#include <qmotion/sweep/surface.hpp>
#include <qmotion/sweep/surface_eval.hpp>
#include <string>
#include <vector>

namespace {

using emscripten::val;
using qmotion::Errc;
using qmotion::Error;
using qmotion::kernel::Motion;
using qmotion::kernel::Quaternion;
using qmotion::kernel::QuaternionSpline;

// The motion the page shows: exactly one of the two is set once a motion is loaded.
std::optional<Motion<double>> rational;
std::optional<QuaternionSpline> spline;

std::vector<double> numbers(const val& array) { return emscripten::vecFromJSArray<double>(array); }

val float64_array(const std::vector<double>& v) {
  return val::global("Float64Array")
      .new_(emscripten::typed_memory_view(v.size(), v.data()))
      .call<val>("slice");
}

std::vector<Quaternion<double>> quaternions(const val& flat_js) {
  const auto flat = numbers(flat_js);
  std::vector<Quaternion<double>> out;
  for (std::size_t i = 0; i + 3 < flat.size(); i += 4)
    out.emplace_back(flat[i], flat[i + 1], flat[i + 2], flat[i + 3]);
  return out;
}

std::vector<Eigen::Vector3d> points(const val& flat_js) {
  const auto flat = numbers(flat_js);
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i + 2 < flat.size(); i += 3)
    out.emplace_back(flat[i], flat[i + 1], flat[i + 2]);
  return out;
}

/// `count` >= 2 parameters evenly spread over [a, b], the last exactly b.
std::vector<double> spread(double a, double b, int count) {
  if (count < 2) throw Error(Errc::invalid_input, "at least 2 parameters are needed");
  std::vector<double> out(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) out[static_cast<std::size_t>(i)] = a + (b - a) * i / (count - 1);
  out.back() = b;
  return out;
}

void require_motion() {
  if (!rational && !spline) throw Error(Errc::invalid_input, "no motion");
}
double start() { return rational ? rational->a() : spline->a(); }
double end() { return rational ? rational->b() : spline->b(); }

/// The pose at t as `qmotion eval` computes it: the origin's image and the unit rotation.
std::pair<Eigen::Vector3d, Quaternion<double>> pose(double t) {
  using namespace qmotion::kernel;
  if (spline) return {spline->position(t), spline->rotation(t)};
  const auto q = evaluate(rational->curve, t);
  if (q.real().norm2() <= 1e-300)
    throw Error(Errc::numerical_failure, "the motion has a pole at t = " + std::to_string(t));
  return {translation_vector(q), normalized(q.real())};
}

val failure(const std::string& message) {
  val out = val::object();
  out.set("error", message);
  return out;
}

val success() {
  val out = val::object();
  out.set("kind", rational ? "q-motion" : "quaternion-spline");
  out.set("degree", rational ? rational->degree() : 0);
  out.set("segments", rational ? rational->segments() : spline->segments());
  out.set("a", start());
  out.set("b", end());
  return out;
}

/// Runs `f`; a kernel error (or any exception) becomes {error: message}.
template <typename F>
val guarded(F&& f) {
  try {
    return f();
  } catch (const std::exception& e) {
    return failure(e.what());
  }
}

/// The motion of a q-motion file's curve: basis "bezier" or "bspline", the degree, the
/// full clamped knot vector and 8 numbers per control point (real part first).
val load_curve(std::string basis, int degree, val knots_js, val points_js) {
  return guarded([&] {
    const auto knots = numbers(knots_js), flat = numbers(points_js);
    std::vector<qmotion::kernel::DualQuaternion<double>> ctrl(flat.size() / 8);
    for (std::size_t i = 0; i < ctrl.size(); ++i)
      for (int j = 0; j < 8; ++j) ctrl[i][j] = flat[8 * i + static_cast<std::size_t>(j)];
    const auto b =
        basis == "bezier" ? qmotion::kernel::Basis::bezier : qmotion::kernel::Basis::bspline;
    rational.emplace(qmotion::kernel::QMotion<double>{
        b, qmotion::kernel::BSpline<qmotion::kernel::DualQuaternion<double>>::make(
               degree, knots, std::move(ctrl))});
    spline.reset();
    return success();
  });
}

/// The quaternion spline of a file, as `qmotion` reads it (io/src/qspline_file.cpp): the
/// scheme, the knots, 4 numbers per key, 3 per position, the quintic's tensions, and KKS's
/// recorded control quaternions and points (its solution, not a new solve).
val load_spline(std::string scheme_name, val knots_js, val keys_js, val positions_js,
                val tension_js, val ctrl_js, val pctrl_js) {
  return guarded([&] {
    using namespace qmotion::kernel;
    const auto scheme = qspline_scheme_from_string(scheme_name);
    if (!scheme) throw Error(Errc::invalid_input, "unknown scheme '" + scheme_name + "'");
    const auto knots = numbers(knots_js);
    if (knots.size() < 2) throw Error(Errc::invalid_input, "a spline needs two knots or more");
    if (*scheme == QSplineScheme::kks)
      spline = kks_from_control(quaternions(keys_js), points(positions_js), knots.front(),
                                knots.back(), quaternions(ctrl_js), points(pctrl_js));
    else
      spline =
          qspline(*scheme, quaternions(keys_js), points(positions_js), knots, numbers(tension_js));
    rational.reset();
    return success();
  });
}

/// Interpolates the poses (8 numbers each: t, x, y, z, w, qx, qy, qz; t NaN when absent)
/// with a method as the page's data records it: for a rational motion {form, rotation,
/// translation, param, k, l, l2}; for a quaternion spline {scheme, param, tension}.
val interpolate(val poses_js, val method) {
  return guarded([&] {
    using namespace qmotion::kernel;
    const auto flat = numbers(poses_js);
    std::vector<Pose<double>> poses(flat.size() / 8);
    for (std::size_t i = 0; i < poses.size(); ++i) {
      const double* p = &flat[8 * i];
      if (!std::isnan(p[0])) poses[i].t = p[0];
      poses[i].position = Eigen::Vector3d(p[1], p[2], p[3]);
      poses[i].rotation = normalized(Quaternion<double>(p[4], p[5], p[6], p[7]));
    }
    const auto name = [&](const char* key) { return method[key].as<std::string>(); };
    const auto rule = param_rule_from_string(name("param"));
    if (!rule) throw Error(Errc::invalid_input, "the page's method names an unknown rule");
    const std::vector<double> t = parametrize(poses, *rule);
    if (method.hasOwnProperty("scheme")) {
      const auto scheme = qspline_scheme_from_string(name("scheme"));
      if (!scheme) throw Error(Errc::invalid_input, "the page's method names an unknown scheme");
      std::vector<Quaternion<double>> keys;
      std::vector<Eigen::Vector3d> positions;
      for (const auto& p : poses) {
        keys.push_back(p.rotation);
        positions.push_back(p.position);
      }
      spline =
          qspline(*scheme, std::move(keys), std::move(positions), t, numbers(method["tension"]));
      rational.reset();
      return success();
    }
    const auto form = form_from_string(name("form"));
    const auto rotation = rotation_method_from_string(name("rotation"));
    const auto translation = translation_method_from_string(name("translation"));
    if (!form || !rotation || !translation)
      throw Error(Errc::invalid_input, "the page's method names an unknown option");
    InterpolationOptions bezier;
    bezier.rotation = *rotation;
    bezier.translation = *translation;
    const int k = method["k"].as<int>(), l = method["l"].as<int>(), l2 = method["l2"].as<int>();
    if (*translation == TranslationMethod::trt) bezier.trt_degrees = std::make_pair(l, l2);
    SplineOptions options;
    options.translation = *translation;
    options.k = k;
    options.l = l;
    rational.emplace(qmotion::kernel::interpolate(poses, t, *form, bezier, options));
    spline.reset();
    return success();
  });
}

/// The motion the page holds, for its "Save motion" (docs/guide/view.md): the fields of a
/// motion file (docs/formats.md) with every array flat (8 numbers a control point of a
/// Q-motion; 4 a key or control quaternion and 3 a position of a spline), the numbers as the
/// kernel holds them. The page shapes the arrays and adds the units.
val motion_document() {
  return guarded([&] {
    using namespace qmotion::kernel;
    require_motion();
    val doc = val::object();
    doc.set("param_range", float64_array({start(), end()}));
    const auto flat = [](const auto& list, int n) {
      std::vector<double> out;
      for (const auto& x : list)
        for (int k = 0; k < n; ++k) out.push_back(x[k]);
      return float64_array(out);
    };
    if (rational) {
      doc.set("type", std::string("q-motion"));
      doc.set("basis", std::string(rational->curve.basis == Basis::bezier ? "bezier" : "bspline"));
      doc.set("degree", rational->degree());
      doc.set("knots", float64_array(rational->curve.curve.knots()));
      doc.set("control_points", flat(rational->curve.curve.ctrl(), 8));
      return doc;
    }
    const auto quats = [](const std::vector<Quaternion<double>>& list) {
      std::vector<double> out;
      for (const auto& q : list) out.insert(out.end(), {q.w(), q.x(), q.y(), q.z()});
      return float64_array(out);
    };
    doc.set("type", std::string("quaternion-spline"));
    doc.set("scheme", to_string(spline->scheme));
    doc.set("knots", float64_array(spline->knots));
    doc.set("keys", quats(spline->keys));
    doc.set("positions", flat(spline->positions, 3));
    doc.set("tension", float64_array(spline->tension));
    doc.set("control_quaternions", quats(spline->ctrl));
    doc.set("control_positions", flat(spline->pctrl, 3));
    return doc;
  });
}

/// The pose at t: [x, y, z, w, qx, qy, qz] with w >= 0, as `qmotion eval` gives it.
val evaluate(double t) {
  return guarded([&] {
    require_motion();
    auto [p, r] = pose(t);
    if (r.w() < 0) r = -r;
    return float64_array({p.x(), p.y(), p.z(), r.w(), r.x(), r.y(), r.z()});
  });
}

/// The point (x, y, z) of the moving space at `count` parameters evenly spread over the
/// interval, 3 numbers each: on its exact trajectory (a NURBS curve) for a rational motion,
/// R(t) x + p(t) for a quaternion spline.
val trajectory(double x, double y, double z, int count) {
  return guarded([&] {
    using namespace qmotion;
    require_motion();
    const Eigen::Vector3d X(x, y, z);
    std::optional<sweep::NurbsCurve<double>> curve;
    if (rational) curve = sweep::trajectory_curve(*rational, X);
    std::vector<double> out;
    for (const double t : spread(start(), end(), count)) {
      const Eigen::Vector3d p =
          curve ? sweep::evaluate(*curve, t)
                : Eigen::Vector3d(kernel::rotate(spline->rotation(t), X) + spline->position(t));
      out.insert(out.end(), {p.x(), p.y(), p.z()});
    }
    return float64_array(out);
  });
}

/// The profile edge (degree, full knots, 3 numbers per pole, weights) read into a curve.
qmotion::sweep::NurbsCurve<double> edge_of(int degree, const val& knots, const val& poles,
                                           const val& weights) {
  qmotion::sweep::NurbsCurve<double> edge;
  edge.degree = degree;
  edge.knots = numbers(knots);
  edge.weights = numbers(weights);
  edge.points = points(poles);
  if (edge.knots.size() != edge.points.size() + static_cast<std::size_t>(degree) + 1 ||
      edge.weights.size() != edge.points.size())
    throw Error(Errc::invalid_input, "a profile edge's knots, poles and weights disagree");
  return edge;
}

/// `count` points of a profile edge at parameters evenly spread over its knots.
val curve_points(int degree, val knots, val poles, val weights, int count) {
  return guarded([&] {
    const auto edge = edge_of(degree, knots, poles, weights);
    std::vector<double> out;
    for (const double v : spread(edge.knots.front(), edge.knots.back(), count)) {
      const Eigen::Vector3d p = qmotion::sweep::evaluate(edge, v);
      out.insert(out.end(), {p.x(), p.y(), p.z()});
    }
    return float64_array(out);
  });
}

/// The sweep of a profile edge (degree, full knots, 3 numbers per pole, weights) on `nt` x
/// `nv` parameters (t major), 3 numbers each. A rational motion's is its exact NURBS surface
/// (sweep::kinematic_nurbs), built and evaluated here; a quaternion spline's is
/// R(t) x(v) + p(t), evaluated directly (it has no NURBS form).
val sweep_edge(int degree, val knots_js, val poles_js, val weights_js, int nt, int nv) {
  return guarded([&] {
    using namespace qmotion;
    require_motion();
    const auto edge = edge_of(degree, knots_js, poles_js, weights_js);
    const auto ts = spread(start(), end(), nt);
    const auto vs = spread(edge.knots.front(), edge.knots.back(), nv);
    std::vector<Eigen::Vector3d> grid(ts.size() * vs.size());
    if (rational) {
      const sweep::SurfaceEvaluator surface(sweep::kinematic_nurbs(*rational, edge));
      surface.grid(ts, vs, grid.data(), 0, ts.size());  // per row the u basis once
    } else {
      std::vector<Eigen::Vector3d> profile;
      for (const double v : vs) profile.push_back(sweep::evaluate(edge, v));
      for (std::size_t i = 0; i < ts.size(); ++i) {
        const Eigen::Matrix3d R = kernel::rotation_matrix(spline->rotation(ts[i]));
        const Eigen::Vector3d p = spline->position(ts[i]);
        for (std::size_t j = 0; j < vs.size(); ++j) grid[i * vs.size() + j] = R * profile[j] + p;
      }
    }
    std::vector<double> out;
    out.reserve(3 * grid.size());
    for (const auto& p : grid) out.insert(out.end(), {p.x(), p.y(), p.z()});
    return float64_array(out);
  });
}

}  // namespace

EMSCRIPTEN_BINDINGS(qmotion_kernel) {
  emscripten::function("loadCurve", &load_curve);
  emscripten::function("loadSpline", &load_spline);
  emscripten::function("interpolate", &interpolate);
  emscripten::function("evaluate", &evaluate);
  emscripten::function("motionDocument", &motion_document);
  emscripten::function("trajectory", &trajectory);
  emscripten::function("sweepEdge", &sweep_edge);
  emscripten::function("curvePoints", &curve_points);
}
