// python/values.cpp: values that travel between Python and the library as numpy arrays:
// a motion's frames and points at many times in one call, and a swept volume's mesh, handed
// to Python without a copy (docs/library.md, "Arrays in and out").
#include <cstdint>
#include <memory>
#include <qmotion/io/bodies.hpp>

#include "convert.hpp"

namespace qmotion::python {
namespace {

// The mesh's vectors are handed over as they lie in memory: rows of three packed numbers.
static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double));
static_assert(sizeof(std::array<int, 3>) == 3 * sizeof(int));

using kernel::detail::format_double;
using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// The times of a frames() or places() call: a number or a 1-d array (read in place when it
/// is already a contiguous float64 array), each on the motion's interval.
Doubles times(const PyMotion& p, const py::handle& t) {
  Doubles a = Doubles::ensure(t);
  if (!a || a.ndim() > 1)
    throw Error(Errc::invalid_input, "t: expected a number or a 1-d array of parameters");
  const double* in = a.data();
  for (py::ssize_t i = 0; i < a.size(); ++i)
    if (!(in[i] >= p.motion.a() && in[i] <= p.motion.b()))
      throw Error(Errc::invalid_input, "t[" + std::to_string(i) + "] = " + format_double(in[i]) +
                                           " is outside the motion's interval [" +
                                           format_double(p.motion.a()) + ", " +
                                           format_double(p.motion.b()) + "]");
  return a;
}

py::array_t<double> frames(const PyMotion& p, const py::handle& t) {
  const Doubles ts = times(p, t);
  const auto n = static_cast<py::ssize_t>(ts.size());
  py::array_t<double> out({n, py::ssize_t(4), py::ssize_t(4)});
  auto w = out.mutable_unchecked<3>();
  const double* in = ts.data();
  for (py::ssize_t i = 0; i < n; ++i) {
    const Eigen::Matrix4d f = p.motion.frame(in[i]);
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) w(i, r, c) = f(r, c);
  }
  return out;
}

py::array_t<double> places(const PyMotion& p, const py::handle& t, const py::object& point) {
  const Doubles ts = times(p, t);
  const Eigen::Vector3d x = point.is_none() ? Eigen::Vector3d::Zero() : vec3(point, "point");
  const auto n = static_cast<py::ssize_t>(ts.size());
  py::array_t<double> out({n, py::ssize_t(3)});
  auto w = out.mutable_unchecked<2>();
  const double* in = ts.data();
  for (py::ssize_t i = 0; i < n; ++i) {
    const Eigen::Vector3d y = p.motion.place(in[i], x);
    for (int c = 0; c < 3; ++c) w(i, c) = y(c);
  }
  return out;
}

/// A triangle mesh from (vertices n x 3, triangles m x 3 of integers).
sweep::TriangleMesh mesh_of(const py::handle& vertices, const py::handle& triangles) {
  const Doubles v = Doubles::ensure(vertices);
  if (!v || v.ndim() != 2 || v.shape(1) != 3)
    throw Error(Errc::invalid_input, "body: the vertices must be an n x 3 array of numbers");
  const py::array raw = py::array::ensure(triangles);
  if (!raw || (raw.dtype().kind() != 'i' && raw.dtype().kind() != 'u'))
    throw Error(Errc::invalid_input, "body: the triangles must be an m x 3 array of integers");
  using Ints = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;
  const Ints f = Ints::ensure(raw);
  if (!f || f.ndim() != 2 || f.shape(1) != 3)
    throw Error(Errc::invalid_input, "body: the triangles must be an m x 3 array of integers");
  sweep::TriangleMesh m;
  const double* pv = v.data();
  for (py::ssize_t i = 0; i < v.shape(0); ++i)
    m.vertices.emplace_back(pv[3 * i], pv[3 * i + 1], pv[3 * i + 2]);
  const std::int64_t* pf = f.data();
  const auto n = static_cast<std::int64_t>(m.vertices.size());
  for (py::ssize_t i = 0; i < f.shape(0); ++i) {
    std::array<int, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      const std::int64_t x = pf[3 * i + k];
      if (x < 0 || x >= n)
        throw Error(Errc::invalid_input, "body (arrays): triangle " + std::to_string(i) +
                                             " (counted from 0) names vertex " + std::to_string(x) +
                                             ", outside 0.." + std::to_string(n - 1));
      tri[static_cast<std::size_t>(k)] = static_cast<int>(x);
    }
    m.triangles.push_back(tri);
  }
  return m;
}

/// A body: a spec string as for the CLI, or a closed mesh as (vertices, triangles).
sweep::Body body_of(const py::handle& body) {
  if (py::isinstance<py::str>(body)) return io::read_body(body.cast<std::string>());
  if (py::isinstance<py::sequence>(body) && py::len(body) == 2) {
    const auto s = body.cast<py::sequence>();
    return io::mesh_body(mesh_of(s[0], s[1]), "body (arrays)");
  }
  throw Error(Errc::invalid_input,
              "body: expected a body spec such as 'cutter:ball,6,20', a mesh file name, or "
              "(vertices, triangles) arrays");
}

py::dict swept_volume_arrays(const PyMotion& p, const py::handle& body, const py::object& tol) {
  const sweep::Body b = body_of(body);
  std::optional<double> t;
  if (!tol.is_none()) t = tol.cast<double>();
  std::unique_ptr<SweptVolume> v;
  {
    py::gil_scoped_release free;  // the mesher runs on its own threads; Python may go on
    v = std::make_unique<SweptVolume>(swept_volume(p.motion, b, t));
  }
  SweptVolume* owned = v.get();
  py::capsule owner(owned, [](void* q) { delete static_cast<SweptVolume*>(q); });
  v.release();  // the capsule owns it now, and frees it with the arrays' last view
  const auto nv = static_cast<py::ssize_t>(owned->vertices.size());
  const auto nt = static_cast<py::ssize_t>(owned->triangles.size());
  py::dict d;
  d["vertices"] = py::array_t<double>(
      {nv, py::ssize_t(3)}, {py::ssize_t(3 * sizeof(double)), py::ssize_t(sizeof(double))},
      owned->vertices.front().data(), owner);
  d["triangles"] = py::array_t<int>({nt, py::ssize_t(3)},
                                    {py::ssize_t(3 * sizeof(int)), py::ssize_t(sizeof(int))},
                                    owned->triangles.front().data(), owner);
  d["units"] = p.motion.units();
  d["tolerance"] = owned->tolerance;
  d["distance_bound"] = owned->distance_bound;
  d["measured_distance"] = owned->measured_distance;
  d["volume_bounds"] = py::make_tuple(owned->volume_lower, owned->volume_upper);
  d["closed"] = owned->closed;
  return d;
}

}  // namespace

void bind_values(py::module_& m) {
  auto motion = py::reinterpret_borrow<py::class_<PyMotion>>(m.attr("Motion"));
  motion.def("frames", &frames, py::arg("t"),
             "The rigid maps at every parameter of t (a number or a 1-d array) as an n x 4 x 4 "
             "array, each as frame(t) gives it. ValueError outside the interval.");
  motion.def("places", &places, py::arg("t"), py::arg("point") = py::none(),
             "The images of a point of the moving space (default the origin) at every "
             "parameter of t, as an n x 3 array.");
  m.def("swept_volume", &swept_volume_arrays, py::arg("motion"), py::arg("body"),
        py::arg("tol") = py::none(),
        "The certified enclosing mesh of `qmotion volume`, in memory: a dict with vertices "
        "(n x 3 float64) and triangles (m x 3 int32, counter-clockwise from outside), both "
        "views of the library's own arrays (no copy), and tolerance, distance_bound, "
        "measured_distance, volume_bounds and closed, in the motion's unit. body: a spec "
        "string as for the command line, a mesh file, or a closed mesh as (vertices, "
        "triangles) arrays in the moving space.");
}

}  // namespace qmotion::python
