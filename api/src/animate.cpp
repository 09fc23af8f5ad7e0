// api/src/animate.cpp: `qmotion animate` (docs/guide/animate.md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <qmotion/api/animate.hpp>
#include <qmotion/io/bodies.hpp>
#include <qmotion/io/gltf.hpp>
#include <qmotion/io/units.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/sweep/body.hpp>
#include <qmotion/sweep/keyframes.hpp>

namespace qmotion {
namespace {

/// The bounding box of the origin's trajectory at 64 points per segment (a size for
/// defaults, not a bound), and the largest |p| among them.
std::pair<Eigen::AlignedBox3d, double> sampled_extent(const Motion& m) {
  Eigen::AlignedBox3d box;
  double far = 0;
  const int n = 64 * std::max(1, m.segments());
  for (int i = 0; i <= n; ++i) {
    const double t = m.a() + (m.b() - m.a()) * i / n;
    const Eigen::Vector3d p = m.place(t, Eigen::Vector3d::Zero());
    box.extend(p);
    far = std::max(far, p.norm());
  }
  return {box, far};
}

std::array<float, 3> to_float(const Eigen::Vector3d& v, double scale) {
  return {static_cast<float>(v.x() * scale), static_cast<float>(v.y() * scale),
          static_cast<float>(v.z() * scale)};
}

/// The largest distance, over the points, between the exact motion and what plays between
/// consecutive keys (both blends), at 16 times inside every interval.
double measure(const Motion& m, const std::vector<sweep::Keyframe>& keys,
               const std::vector<Eigen::Vector3d>& points) {
  double worst = 0;
  for (std::size_t i = 0; i + 1 < keys.size(); ++i)
    for (int j = 1; j < 16; ++j) {
      const double t = keys[i].t + (keys[i + 1].t - keys[i].t) * j / 16;
      const Eigen::Matrix4d f = m.frame(t);
      for (bool spherical : {true, false}) {
        const sweep::Keyframe k = sweep::play(keys[i], keys[i + 1], t, spherical);
        const Eigen::Matrix3d R = k.rotation.toRotationMatrix();
        for (const auto& x : points) {
          const Eigen::Vector3d exact = f.block<3, 1>(1, 0) + f.block<3, 3>(1, 1) * x;
          worst = std::max(worst, (exact - (k.translation + R * x)).norm());
        }
      }
    }
  return worst;
}

}  // namespace

nlohmann::json Animation::report() const {
  return {{"output", path},
          {"keyframes", keyframes},
          {"tolerance", tolerance},
          {"distance_bound", bound},
          {"measured_distance", measured},
          {"units", units},
          {"gltf_units", "m"},
          {"metres_per_unit", metres_per_unit},
          {"seconds_per_unit", seconds_per_unit},
          {"duration", duration},
          {"interval", {a, b}},
          {"body", body},
          {"body_radius", radius},
          {"triangles", triangles},
          {"vertices", vertices},
          {"interpolation",
           "translation linear; rotation spherical-linear (glTF) or "
           "component-wise normalised (Blender), both certified"},
          {"bound_evaluations", bound_evaluations},
          {"seconds", seconds}};
}

Animation animate(const Motion& motion, const AnimateOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  if (!io::is_gltf_path(o.output))
    throw Error(Errc::invalid_input,
                o.output + ": unknown animation format (expected .glb or .gltf)");
  if (o.tol && (!(*o.tol > 0) || !std::isfinite(*o.tol)))
    throw Error(Errc::invalid_input, "--tol: the tolerance must be a positive length, got " +
                                         kernel::detail::format_double(*o.tol));
  if (!(o.duration >= 0) || !std::isfinite(o.duration))
    throw Error(Errc::invalid_input, "--duration: expected seconds >= 0, got " +
                                         kernel::detail::format_double(o.duration));
  if (motion.is_rational()) sweep::refuse_poles(motion.rational());
  Animation out;
  out.path = o.output;
  out.units = motion.units();
  out.metres_per_unit = io::unit_in_mm(motion.units()) / 1000;
  const double mpu = out.metres_per_unit;
  const auto [box, far] = sampled_extent(motion);
  const double extent = box.diagonal().norm();

  const double side = extent > 0 ? extent / 10 : 1;  // of the default cube
  const sweep::Body body =
      o.body.empty() ? sweep::Body::box(side, side, side) : io::read_body(o.body);
  out.body = body.spec;
  const sweep::TriangleMesh mesh = sweep::triangulate(body, 1e-3 * sweep::radius(body));

  // The mesh as the file holds it (floats, metres), and its points back in the motion's unit:
  // the body that plays, which the bounds are for.
  io::GltfAnimation g;
  g.name = motion.name().empty() ? "qmotion" : motion.name();
  std::vector<Eigen::Vector3d> played;
  for (const auto& v : mesh.vertices) {
    g.positions.push_back(to_float(v, mpu));
    const auto& f = g.positions.back();
    played.emplace_back(f[0] / mpu, f[1] / mpu, f[2] / mpu);
    out.radius = std::max(out.radius, played.back().norm());
  }
  for (const auto& t : mesh.triangles)
    g.triangles.push_back({static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]),
                           static_cast<std::uint32_t>(t[2])});
  out.radius *= 1 + 1e-12;
  out.tolerance = o.tol ? *o.tol : 1e-3 * (extent + 2 * out.radius);  // radius > 0: positive

  // 32-bit floats hold a position to 2^-24 of its size and a unit quaternion to 2^-24: below
  // a few of those no key can be certified.
  const double floor = 8 * std::ldexp(far + out.radius, -24);
  if (out.tolerance < floor)
    throw Error(Errc::invalid_input, "--tol " + kernel::detail::format_double(out.tolerance) +
                                         " is below what glTF's 32-bit floats "
                                         "hold for this motion (positions up to " +
                                         kernel::detail::format_double(far) + " " + motion.units() +
                                         "; at least " + kernel::detail::format_double(floor) +
                                         ")");

  const double a = motion.a(), b = motion.b();
  out.a = a;
  out.b = b;
  out.seconds_per_unit = o.duration > 0 ? o.duration / (b - a) : 1.0;
  const double k = out.seconds_per_unit;
  sweep::KeyframeOptions ko;
  ko.tol = out.tolerance;
  ko.radius = out.radius;
  // A key's time is the float the file holds; its pose is the exact one at that time.
  ko.time = [a, b, k](double t) {
    float s = static_cast<float>((t - a) * k);
    while (s > 0 && a + static_cast<double>(s) / k > b) s = std::nextafter(s, 0.0f);  // not past b
    return a + static_cast<double>(s) / k;
  };
  ko.write = [mpu](const sweep::Keyframe& e) {
    sweep::Keyframe w = e;
    const auto p = to_float(e.translation, mpu);
    w.translation = Eigen::Vector3d(p[0], p[1], p[2]) / mpu;
    // The floats themselves (x, y, z, w): players normalise them, and so do the bounds.
    w.rotation.coeffs() = e.rotation.coeffs().cast<float>().cast<double>();
    return w;
  };
  const sweep::Keyframes keys = sweep::place_keyframes(motion, ko);
  out.keyframes = keys.keys.size();
  out.bound = keys.max_bound;
  out.bound_evaluations = keys.bound_evaluations;
  for (const auto& key : keys.keys) {
    g.times.push_back(static_cast<float>((key.t - a) * k));
    g.translations.push_back(to_float(key.translation, mpu));
    const Eigen::Vector4f q = key.rotation.coeffs().cast<float>();
    g.rotations.push_back({q.x(), q.y(), q.z(), q.w()});
  }
  out.duration = static_cast<double>(g.times.back());
  // The measurement at up to 256 of the mesh's vertices.
  std::vector<Eigen::Vector3d> sample;
  const std::size_t stride = std::max<std::size_t>(1, played.size() / 256);
  for (std::size_t i = 0; i < played.size(); i += stride) sample.push_back(played[i]);
  out.measured = measure(motion, keys.keys, sample);
  out.triangles = g.triangles.size();
  out.vertices = g.positions.size();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  g.extras = out.report();
  g.extras.erase("seconds");
  io::write_gltf(o.output, g);
  return out;
}

}  // namespace qmotion
