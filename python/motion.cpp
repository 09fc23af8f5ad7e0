// python/motion.cpp: qmotion.Motion, one class for both kinds of motion, and the calls that
// make one: load, interpolate, qspline.
#include <qmotion/api/fit.hpp>
#include <sstream>

#include "convert.hpp"

namespace qmotion::python {
namespace {

/// The provenance as a dict (None for a hand-written motion).
py::object provenance_dict(const Motion& m) {
  if (!m.provenance()) return py::none();
  const auto& p = *m.provenance();
  py::dict d;
  d["form"] = kernel::to_string(p.form);
  d["rotation"] = kernel::to_string(p.rotation);
  d["translation"] = kernel::to_string(p.translation);
  d["rotation_degree"] = p.rotation_degree;
  d["translation_degree"] = p.translation_degree;
  if (p.translation_degree2 >= 0) d["translation_degree2"] = p.translation_degree2;
  d["param"] = p.param;
  d["parameters"] =
      py::array_t<double>(static_cast<py::ssize_t>(p.parameters.size()), p.parameters.data());
  d["residuals"] =
      py::array_t<double>(static_cast<py::ssize_t>(p.residuals.size()), p.residuals.data());
  d["poses"] = to_python(io::poses_to_json(p.poses, m.units()));
  return std::move(d);
}

py::array_t<double> vector_array(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

py::array_t<double> matrix_array(const Eigen::Matrix4d& f) {
  py::array_t<double> a({py::ssize_t(4), py::ssize_t(4)});
  auto w = a.mutable_unchecked<2>();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) w(i, j) = f(i, j);
  return a;
}

py::tuple vec_tuple(const Eigen::Vector3d& v) { return py::make_tuple(v(0), v(1), v(2)); }

Eigen::Vector3d point_or_origin(const py::object& point) {
  return point.is_none() ? Eigen::Vector3d::Zero() : vec3(point, "point");
}

/// The rational motion's control points B_i as an n x 8 array (real part first).
py::array_t<double> control_points(const Motion& m) {
  const auto& ctrl = m.rational().curve.curve.ctrl();
  py::array_t<double> a({static_cast<py::ssize_t>(ctrl.size()), py::ssize_t(8)});
  auto w = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < ctrl.size(); ++i)
    for (int k = 0; k < 8; ++k) w(static_cast<py::ssize_t>(i), k) = ctrl[i][k];
  return a;
}

/// A motion from its file's text, named `source`: its tree as written (numbers as numbers,
/// for to_dict) and the motion, refusals naming the source and field.
PyMotion from_text(std::string text, const std::string& source) {
  json document = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (io::is_qspline_document(document)) {
    Motion motion = io::qspline_motion(document, source);
    return PyMotion{std::move(motion), std::nullopt, std::move(document), std::move(text)};
  }
  io::MotionFile file = io::parse_motion_text(text, source);  // the digits, for info --exact
  Motion motion(io::to_motion(file));
  return PyMotion{std::move(motion), std::move(file), std::move(document), std::move(text)};
}

/// Read once: save() writes the text back as it was read.
PyMotion load(const std::string& path) { return from_text(io::read_text_file(path), path); }

/// The pickled state: the motion file's text, which both kinds are rebuilt from by the
/// parse that load() runs, and whether the text was the motion's own (save() writes it) or
/// its document dumped. The rebuilt motion evaluates bit for bit as the original
/// (tests/python/test_values.py): a rational motion is always built from its file's text,
/// and a quaternion spline's document holds its keys and controls in shortest round-trip
/// decimals.
std::string motion_text(const PyMotion& p) {
  return p.text.empty() ? p.document.dump(1) + "\n" : p.text;
}

py::tuple pickle_state(const PyMotion& p) {
  return py::make_tuple(motion_text(p), !p.text.empty());
}

PyMotion unpickle(const py::tuple& state) {
  if (state.size() != 2)
    throw Error(Errc::invalid_input, "Motion pickle: expected (text, own), got " +
                                         std::to_string(state.size()) + " items");
  PyMotion p = from_text(state[0].cast<std::string>(), "<pickled motion>");
  if (!state[1].cast<bool>()) p.text.clear();
  return p;
}

void bind_motion_class(py::module_& m) {
  py::class_<PyMotion>(
      m, "Motion",
      "A rigid-body motion of either kind (docs/geometry.md): a rational Q-motion (its "
      "trajectories and sweeps are exact NURBS) or a unit-quaternion spline (kks, quintic, "
      "quartic; its geometry is fitted within a tolerance). Both answer the same calls.")
      .def_property_readonly(
          "kind",
          [](const PyMotion& p) {
            return p.motion.is_rational() ? "q-motion" : "quaternion-spline";
          },
          "'q-motion' (rational) or 'quaternion-spline'")
      .def(py::pickle(&pickle_state, &unpickle))
      .def_property_readonly(
          "rational", [](const PyMotion& p) { return p.motion.is_rational(); },
          "True for a rational Q-motion")
      .def_property_readonly(
          "scheme",
          [](const PyMotion& p) -> py::object {
            if (p.motion.is_rational()) return py::none();
            return py::str(kernel::to_string(p.motion.spline().scheme));
          },
          "A quaternion spline's scheme (kks, quintic, quartic); None for a Q-motion")
      .def_property_readonly("units", [](const PyMotion& p) { return p.motion.units(); })
      .def_property_readonly(
          "param_range",
          [](const PyMotion& p) { return std::make_pair(p.motion.a(), p.motion.b()); })
      .def_property_readonly("segments", [](const PyMotion& p) { return p.motion.segments(); })
      .def_property_readonly(
          "degree",
          [](const PyMotion& p) -> py::object {
            if (!p.motion.is_rational()) return py::none();
            return py::int_(p.motion.rational().degree());
          },
          "The Q-motion's degree; None for a quaternion spline (not polynomial)")
      .def_property_readonly(
          "knots",
          [](const PyMotion& p) {
            return p.motion.is_rational() ? vector_array(p.motion.rational().curve.curve.knots())
                                          : vector_array(p.motion.spline().knots);
          },
          "A Q-motion's full knot vector; a quaternion spline's key knots")
      .def_property_readonly(
          "control_points", [](const PyMotion& p) { return control_points(p.motion); },
          "A Q-motion's control points B_i as an n x 8 array (real part first, "
          "docs/formats.md); ValueError for a quaternion spline")
      .def_property_readonly(
          "has_factors",
          [](const PyMotion& p) {
            return p.motion.is_rational() && p.motion.rational().factors.has_value();
          },
          "True when the factors the motion is the product of are known (trajectories at their "
          "minimal degree)")
      .def_property_readonly(
          "provenance", [](const PyMotion& p) { return provenance_dict(p.motion); },
          "How an interpolated Q-motion was made, as a dict (form, rotation, translation, "
          "degrees, param, parameters, residuals at the poses, poses); None otherwise")
      .def_property_readonly(
          "breakpoints", [](const PyMotion& p) { return vector_array(p.motion.breakpoints()); },
          "Where the pieces meet, a = x_0 < ... < x_r = b")
      .def_property_readonly(
          "continuity", [](const PyMotion& p) { return p.motion.continuity(); },
          "The order of continuity at every interior breakpoint")
      .def_property_readonly(
          "key_parameters",
          [](const PyMotion& p) { return vector_array(p.motion.key_parameters()); },
          "Where the motion interpolates its poses")
      .def(
          "frame", [](const PyMotion& p, double t) { return matrix_array(p.motion.frame(t)); },
          py::arg("t"),
          "The rigid map at t as a 4 x 4 array on homogeneous points (x0, x): "
          "[[1, 0], [p, R]]. ArithmeticError at a pole.")
      .def(
          "place",
          [](const PyMotion& p, double t, const py::object& point) {
            return vec_tuple(p.motion.place(t, point_or_origin(point)));
          },
          py::arg("t"), py::arg("point") = py::none(),
          "The image at t of a point of the moving space")
      .def(
          "angular_velocity",
          [](const PyMotion& p, double t) { return vec_tuple(p.motion.angular_velocity(t)); },
          py::arg("t"), "The angular velocity at t, fixed frame, radians per unit of t")
      .def(
          "point_velocity",
          [](const PyMotion& p, double t, const py::object& point) {
            return vec_tuple(p.motion.point_velocity(t, point_or_origin(point)));
          },
          py::arg("t"), py::arg("point") = py::none(),
          "The velocity at t of a point of the moving space, units per unit of t")
      .def(
          "eval",
          [](const PyMotion& p, double t, const py::object& point) {
            const Eigen::Vector3d x = point_or_origin(point);
            if (p.file) return to_python(motion_eval(*p.file, t, x));
            return to_python(qspline_eval(p.motion.spline(), t, x, std::to_string(t)));
          },
          py::arg("t"), py::arg("point") = py::none(),
          "`qmotion eval` at t: dict with position (image of the moving origin), quaternion "
          "(unit, w >= 0) and point (image of `point`); a quaternion spline adds its "
          "angular_velocity. ValueError outside the interval, ArithmeticError at a pole.")
      .def(
          "info",
          [](const PyMotion& p, bool exact) {
            if (p.file) return to_python(motion_info(*p.file, exact));
            if (exact)
              throw Error(Errc::invalid_input, p.motion.label() +
                                                   ": exact is for rational motions; a "
                                                   "quaternion spline is not rational");
            return to_python(qspline_info(p.document, p.motion.spline()));
          },
          py::arg("exact") = false,
          "The `qmotion info` report as a dict: type, basis, degree, order, segments, "
          "param_range, units, plucker_residual, interpolation_residual, poles, method (for a "
          "quaternion spline: scheme, knots, residuals and, for kks, the iteration's figures).")
      .def(
          "to_dict", [](const PyMotion& p) { return to_python(p.document); },
          "The motion file's document (docs/formats.md) as a dict")
      .def("dumps", &motion_text,
           "The motion file's text, what save writes; qmotion.loads(text) gives the motion back "
           "bit for bit")
      .def(
          "save",
          [](const PyMotion& p, const std::string& path) {
            io::write_file_atomic(path, p.text.empty() ? p.document.dump(1) + "\n" : p.text);
          },
          py::arg("path"),
          "Writes the motion file: byte for byte what `qmotion interpolate` or `qmotion "
          "qspline` writes, or, for a loaded motion, the file as it was read");
}

}  // namespace

void bind_motion(py::module_& m) {
  bind_motion_class(m);
  m.def("load", &load, py::arg("path"),
        "Reads a motion file of either kind, written by `qmotion interpolate`, `qmotion "
        "qspline` or `save`, as a Motion.");
  m.def(
      "loads",
      [](const std::string& text, const std::string& name) { return from_text(text, name); },
      py::arg("text"), py::arg("name") = "<text>",
      "A Motion from a motion file's text (Motion.dumps), refusals naming `name`.");

  m.def(
      "interpolate",
      [](const py::object& poses, const std::string& rotation, const std::string& translation,
         const std::string& form, const std::string& param, int degree, int translation_degree,
         const py::object& trt_degrees, bool exact, const std::string& units) {
        InterpolateOptions o;
        o.rotation = rotation;
        o.translation = translation;
        o.form = form;
        o.param = param;
        o.degree = degree;
        o.translation_degree = translation_degree;
        if (!trt_degrees.is_none()) {
          const auto d = trt_degrees.cast<std::pair<int, int>>();
          o.trt_degrees = std::to_string(d.first) + "," + std::to_string(d.second);
        }
        o.exact = exact;
        auto r = interpolate(to_poses(poses, units), o);
        return rational_motion(r.document(), "interpolate()", r.text());
      },
      py::arg("poses"), py::arg("rotation") = "elliptic", py::arg("translation") = "tr",
      py::arg("form") = "", py::arg("param") = "", py::arg("degree") = -1,
      py::arg("translation_degree") = -1, py::arg("trt_degrees") = py::none(),
      py::arg("exact") = false, py::arg("units") = "mm",
      "A Q-motion through the poses (Juttler 1994), with the options of `qmotion interpolate`:\n"
      "  rotation: 'elliptic' | 'affine' | 'projective'\n"
      "  translation: 'tr' | 'trt' | 'minimal'; trt_degrees=(L1, L2)\n"
      "  form: 'bezier' (default up to six poses) | 'bspline' (beyond) | 'c1'\n"
      "  param: 'given' (default when every pose has t) | 'uniform' | 'chordal' | "
      "'star-chordal' | 'centripetal' | 'angular' | 'angular-chordal'\n"
      "  degree, translation_degree: the B-spline factors' degrees K and L (default 3)\n"
      "  exact: CGAL exact rationals (quaternion rotations, 'p/q' strings kept exactly)\n"
      "poses: a file name, a pose dict, or rows [t,x,y,z,qw,qx,qy,qz] (units for arrays).");

  m.def(
      "fit",
      [](const py::object& poses, double tol, double angle_tol, int degree, int translation_degree,
         const std::string& param, const std::string& units, bool between) {
        FitOptions o;
        o.tol = tol;
        o.between = between;
        o.angle_tol_deg = angle_tol;
        o.degree = degree;
        o.translation_degree = translation_degree;
        o.param = param;
        const FitResult r = fit(to_poses(poses, units), o);
        return py::make_tuple(rational_motion(r.document(), "fit()", r.text()),
                              to_python(r.report_json()));
      },
      py::arg("poses"), py::arg("tol"), py::arg("angle_tol") = 0.1, py::arg("degree") = -1,
      py::arg("translation_degree") = -1, py::arg("param") = "", py::arg("units") = "mm",
      py::arg("between") = false,
      "A lean B-spline Q-motion within tol (the poses' unit) of every pose's position and\n"
      "angle_tol degrees of its rotation, as `qmotion fit`; returns (Motion, report) where the\n"
      "report dict gives control_points, spans, the worst deviations and where, and the\n"
      "deviation at every pose. between=True (`fit --between`) holds both along the whole\n"
      "motion, proven (the report's 'between'). poses: as for interpolate (also robot\n"
      "programs: .src KRL, .mod/.prg RAPID, .script URScript).");

  m.def(
      "qspline",
      [](const py::object& poses, const std::string& scheme, const py::object& tension,
         const std::string& param, const std::string& units) {
        QSplineOptions o;
        o.scheme = scheme;
        o.param = param;
        if (!tension.is_none()) {
          std::ostringstream os;
          os.precision(17);
          if (py::isinstance<py::float_>(tension) || py::isinstance<py::int_>(tension)) {
            os << tension.cast<double>();
          } else {
            const auto a = tension.cast<std::vector<double>>();
            for (std::size_t i = 0; i < a.size(); ++i) os << (i ? "," : "") << a[i];
          }
          o.tension = os.str();
        }
        const QSplineResult r = qspline(to_poses(poses, units), o);
        // Built from its document, as load() and unpickling build it: the same motion bit
        // for bit whichever way it arrives (a KKS spline's solve leaves its controls a last
        // bit from unit, which the document's reading normalizes).
        return PyMotion{io::qspline_motion(r.document, "qspline()"), std::nullopt, r.document, {}};
      },
      py::arg("poses"), py::arg("scheme"), py::arg("tension") = py::none(), py::arg("param") = "",
      py::arg("units") = "mm",
      "A unit-quaternion spline motion through the poses, as `qmotion qspline`:\n"
      "  scheme: 'kks' (Kim-Kim-Shin C2, iterative) | 'quintic' (tension) | 'quartic'\n"
      "  tension: quintic only, a number for every key or one per key (default 0.5)\n"
      "  param: a rule of interpolate; kks and quartic put the keys at uniform knots.");
}

}  // namespace qmotion::python
