// render/viewer/kernel_wasm.cpp: the kernel the viewer page runs, compiled to WebAssembly by
// Debian's emscripten (render/viewer/CMakeLists.txt). It holds one current motion: read from
// the file's curve, or interpolated again from edited poses with the file's method; the page
// evaluates it, its trajectories and its exact sweep through the calls bound at the end
// (docs/guide/view.md). Every call returns an object with `error` set instead of throwing.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <optional>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/kernel/parametrization.hpp>
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

std::optional<Motion<double>> current;  // the motion the page shows

std::vector<double> numbers(const val& array) { return emscripten::vecFromJSArray<double>(array); }

val float64_array(const std::vector<double>& v) {
  return val::global("Float64Array")
      .new_(emscripten::typed_memory_view(v.size(), v.data()))
      .call<val>("slice");
}

/// `count` >= 2 parameters evenly spread over [a, b], the last exactly b.
std::vector<double> spread(double a, double b, int count) {
  if (count < 2) throw Error(Errc::invalid_input, "at least 2 parameters are needed");
  std::vector<double> out(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) out[static_cast<std::size_t>(i)] = a + (b - a) * i / (count - 1);
  out.back() = b;
  return out;
}

val failure(const std::string& message) {
  val out = val::object();
  out.set("error", message);
  return out;
}

val success() {
  val out = val::object();
  out.set("degree", current->degree());
  out.set("segments", current->segments());
  out.set("a", current->a());
  out.set("b", current->b());
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
    current.emplace(qmotion::kernel::QMotion<double>{
        b, qmotion::kernel::BSpline<qmotion::kernel::DualQuaternion<double>>::make(
               degree, knots, std::move(ctrl))});
    return success();
  });
}

/// Interpolates the poses (8 numbers each: t, x, y, z, w, qx, qy, qz; t NaN when absent)
/// with a method as the file records it: {form, rotation, translation, param, k, l, l2}.
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
    const auto form = form_from_string(name("form"));
    const auto rotation = rotation_method_from_string(name("rotation"));
    const auto translation = translation_method_from_string(name("translation"));
    const auto rule = param_rule_from_string(name("param"));
    if (!form || !rotation || !translation || !rule)
      throw Error(Errc::invalid_input, "the page's method names an unknown option");
    InterpolationOptions bezier;
    bezier.rotation = *rotation;
    bezier.translation = *translation;
    const int k = method["k"].as<int>(), l = method["l"].as<int>(), l2 = method["l2"].as<int>();
    if (*translation == TranslationMethod::trt) bezier.trt_degrees = std::make_pair(l, l2);
    SplineOptions spline;
    spline.translation = *translation;
    spline.k = k;
    spline.l = l;
    current.emplace(
        qmotion::kernel::interpolate(poses, parametrize(poses, *rule), *form, bezier, spline));
    return success();
  });
}

/// The pose at t: [x, y, z, w, qx, qy, qz] with w >= 0, as `qmotion eval` gives it.
val evaluate(double t) {
  return guarded([&] {
    using namespace qmotion::kernel;
    if (!current) throw Error(Errc::invalid_input, "no motion");
    const auto q = qmotion::kernel::evaluate(current->curve, t);
    if (q.real().norm2() <= 1e-300)
      throw Error(Errc::numerical_failure, "the motion has a pole at t = " + std::to_string(t));
    Quaternion<double> r = normalized(q.real());
    if (r.w() < 0) r = -r;
    const Eigen::Vector3d p = translation_vector(q);
    return float64_array({p.x(), p.y(), p.z(), r.w(), r.x(), r.y(), r.z()});
  });
}

/// The point (x, y, z) of the moving space on its exact trajectory (a NURBS curve) at
/// `count` parameters evenly spread over the interval: 3 numbers each.
val trajectory(double x, double y, double z, int count) {
  return guarded([&] {
    using namespace qmotion;
    if (!current) throw Error(Errc::invalid_input, "no motion");
    const auto curve = sweep::trajectory_curve(*current, Eigen::Vector3d(x, y, z));
    std::vector<double> out;
    for (const double t : spread(current->a(), current->b(), count)) {
      const Eigen::Vector3d p = sweep::evaluate(curve, t);
      out.insert(out.end(), {p.x(), p.y(), p.z()});
    }
    return float64_array(out);
  });
}

/// The profile edge (degree, full knots, 3 numbers per pole, weights) read into a curve.
qmotion::sweep::NurbsCurve<double> edge_of(int degree, const val& knots, const val& points,
                                           const val& weights) {
  qmotion::sweep::NurbsCurve<double> edge;
  edge.degree = degree;
  edge.knots = numbers(knots);
  edge.weights = numbers(weights);
  const auto flat = numbers(points);
  for (std::size_t i = 0; i + 2 < flat.size(); i += 3)
    edge.points.emplace_back(flat[i], flat[i + 1], flat[i + 2]);
  if (edge.knots.size() != edge.points.size() + static_cast<std::size_t>(degree) + 1 ||
      edge.weights.size() != edge.points.size())
    throw Error(Errc::invalid_input, "a profile edge's knots, poles and weights disagree");
  return edge;
}

/// `count` points of a profile edge at parameters evenly spread over its knots.
val curve_points(int degree, val knots, val points, val weights, int count) {
  return guarded([&] {
    const auto edge = edge_of(degree, knots, points, weights);
    std::vector<double> out;
    for (const double v : spread(edge.knots.front(), edge.knots.back(), count)) {
      const Eigen::Vector3d p = qmotion::sweep::evaluate(edge, v);
      out.insert(out.end(), {p.x(), p.y(), p.z()});
    }
    return float64_array(out);
  });
}

/// The exact sweep of a profile edge (degree, full knots, 3 numbers per pole, weights):
/// its NURBS surface evaluated on `nt` x `nv` parameters (t major), 3 numbers each.
val sweep_edge(int degree, val knots_js, val points_js, val weights_js, int nt, int nv) {
  return guarded([&] {
    using namespace qmotion;
    if (!current) throw Error(Errc::invalid_input, "no motion");
    const auto edge = edge_of(degree, knots_js, points_js, weights_js);
    const sweep::SurfaceEvaluator surface(sweep::kinematic_nurbs(*current, edge));
    const auto ts = spread(current->a(), current->b(), nt);
    const auto vs = spread(edge.knots.front(), edge.knots.back(), nv);
    std::vector<Eigen::Vector3d> grid(ts.size() * vs.size());
    surface.grid(ts, vs, grid.data(), 0, ts.size());  // per row the u basis once
    std::vector<double> out;
    out.reserve(3 * grid.size());
    for (const auto& p : grid) out.insert(out.end(), {p.x(), p.y(), p.z()});
    return float64_array(out);
  });
}

}  // namespace

EMSCRIPTEN_BINDINGS(qmotion_kernel) {
  emscripten::function("loadCurve", &load_curve);
  emscripten::function("interpolate", &interpolate);
  emscripten::function("evaluate", &evaluate);
  emscripten::function("trajectory", &trajectory);
  emscripten::function("sweepEdge", &sweep_edge);
  emscripten::function("curvePoints", &curve_points);
}
