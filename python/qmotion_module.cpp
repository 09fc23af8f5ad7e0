// python/qmotion_module.cpp: the Python module `qmotion` (pybind11). Thin, like the CLI:
// every function converts its arguments, calls the library and converts the result.
// qmotion::Error becomes ValueError (bad input, exit 2), ArithmeticError (numerical
// failure, exit 3) or RuntimeError, with the CLI's message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fstream>
#include <qmotion/qmotion.hpp>
#include <sstream>

namespace py = pybind11;
namespace qm = qmotion;
using json = nlohmann::json;

namespace {

/// nlohmann::json -> Python objects, through Python's own json module.
py::object to_python(const json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

/// Python dict/list -> nlohmann::json.
json from_python(const py::handle& o) {
  return json::parse(py::module_::import("json").attr("dumps")(o).cast<std::string>());
}

Eigen::Vector3d vec3(const py::handle& o, const std::string& what) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(o);
  if (!a || a.size() != 3)
    throw qm::Error(qm::Errc::invalid_input, what + ": expected three numbers x, y, z");
  return Eigen::Vector3d(a.at(0), a.at(1), a.at(2));
}

py::array_t<double> points_array(const std::vector<Eigen::Vector3d>& pts) {
  py::array_t<double> a({static_cast<py::ssize_t>(pts.size()), py::ssize_t(3)});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (int c = 0; c < 3; ++c) m(static_cast<py::ssize_t>(i), c) = pts[i](c);
  return a;
}

/// A motion: the value (curve, factors, provenance, units), its file as parsed (for the
/// exact reports of info) and its document (what save writes).
struct PyMotion {
  qm::io::MotionFile file;
  qm::kernel::Motion<double> motion;
  json document;
  std::string text;  ///< the file as `qmotion interpolate` writes it; empty: document.dump(1)
};

PyMotion make_motion(json document, const std::string& source, std::string text = {}) {
  qm::io::MotionFile file = qm::io::parse_motion(document, source);
  qm::kernel::Motion<double> motion = qm::io::to_motion(file);
  return PyMotion{std::move(file), std::move(motion), std::move(document), std::move(text)};
}

/// The provenance as a dict (None for a hand-written motion).
py::object provenance_dict(const qm::kernel::Motion<double>& m) {
  if (!m.provenance) return py::none();
  const auto& p = *m.provenance;
  py::dict d;
  d["form"] = qm::kernel::to_string(p.form);
  d["rotation"] = qm::kernel::to_string(p.rotation);
  d["translation"] = qm::kernel::to_string(p.translation);
  d["rotation_degree"] = p.rotation_degree;
  d["translation_degree"] = p.translation_degree;
  if (p.translation_degree2 >= 0) d["translation_degree2"] = p.translation_degree2;
  d["param"] = p.param;
  d["parameters"] =
      py::array_t<double>(static_cast<py::ssize_t>(p.parameters.size()), p.parameters.data());
  d["residuals"] =
      py::array_t<double>(static_cast<py::ssize_t>(p.residuals.size()), p.residuals.data());
  d["poses"] = to_python(qm::io::poses_to_json(p.poses, m.units));
  return std::move(d);
}

/// Poses from a file name, a pose-JSON dict, or rows [t, x, y, z, qw, qx, qy, qz] (or
/// without t: 7 columns) as a list or numpy array.
qm::io::PoseSet to_poses(const py::handle& p, const std::string& units) {
  if (py::isinstance<qm::io::PoseSet>(p)) return p.cast<qm::io::PoseSet>();
  if (py::isinstance<py::str>(p)) return qm::io::read_poses(p.cast<std::string>());
  if (py::isinstance<py::dict>(p))
    return qm::io::parse_poses_json_value(from_python(p), "poses (dict)");
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(p);
  if (!a || a.ndim() != 2 || (a.shape(1) != 7 && a.shape(1) != 8))
    throw qm::Error(qm::Errc::invalid_input,
                    "poses: expected a file name, a pose dict, or rows of 8 numbers t, x, y, z, "
                    "qw, qx, qy, qz (7 without t)");
  const bool has_t = a.shape(1) == 8;
  json doc{{"units", units}, {"poses", json::array()}};
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    const int o = has_t ? 1 : 0;
    json pose{{"position", {a.at(i, o), a.at(i, o + 1), a.at(i, o + 2)}},
              {"rotation",
               {{"quaternion", {a.at(i, o + 3), a.at(i, o + 4), a.at(i, o + 5), a.at(i, o + 6)}}}}};
    if (has_t) pose["t"] = a.at(i, 0);
    doc["poses"].push_back(pose);
  }
  return qm::io::parse_poses_json_value(doc, "poses (array)");
}

qm::sweep::Profile<double> to_profile(const py::handle& p, const std::string& units) {
  if (py::isinstance<qm::sweep::Profile<double>>(p)) return p.cast<qm::sweep::Profile<double>>();
  if (py::isinstance<qm::sweep::NurbsCurve<double>>(p))
    return qm::sweep::single_edge(p.cast<qm::sweep::NurbsCurve<double>>());
  return qm::io::read_profile(p.cast<std::string>(), units);
}

/// The point or profile of an export or check call (both or neither: the library refuses).
qm::Geometry to_geometry(const std::string& units, const py::object& profile,
                         const py::object& point) {
  qm::Geometry g;
  if (!point.is_none()) g.point = vec3(point, "point");
  if (!profile.is_none()) {
    g.profile = to_profile(profile, units);
    if (py::isinstance<py::str>(profile)) g.profile_name = profile.cast<std::string>();
  }
  return g;
}

qm::ExportOptions export_options(const std::string& output, int max_degree, double tol,
                                 const std::string& units, bool single_face, bool solid) {
  qm::ExportOptions o;
  o.output = output;
  o.max_degree = max_degree;
  o.tol = tol;
  o.units = units;
  o.single_face = single_face;
  o.solid = solid;
  return o;
}

json result_json(const qm::ExportResult& r) {
  json j{{"path", r.path},
         {"degree_u", r.degree_u},
         {"degree_v", r.degree_v},
         {"faces", r.faces},
         {"poles", r.poles},
         {"units", r.units},
         {"continuity_u", r.continuity_u},
         {"continuity_v", r.continuity_v}};
  if (r.approx_deviation) j["approximation_deviation"] = *r.approx_deviation;
  if (r.approx_tolerance) j["approximation_tolerance"] = *r.approx_tolerance;
  if (r.volume) j["volume"] = *r.volume;
  if (r.mesh)
    j["mesh"] = json{{"triangles", r.mesh->triangles.size()},
                     {"vertices", r.mesh->vertices.size()},
                     {"deflection", r.mesh->deflection},
                     {"max_deviation", r.mesh->max_deviation},
                     {"deviation_samples", r.mesh->deviation_samples},
                     {"closed", r.mesh->closed},
                     {"oriented", r.mesh->oriented}};
  if (r.self_intersection) {
    j["self_intersecting"] = r.self_intersection->found();
    if (r.self_intersection->found()) j["self_intersection"] = r.self_intersection->ranges();
  }
  return j;
}

/// `qmotion toolpath` for either kind of motion: the report dict.
/// A Motion or a QSpline as the library's either-kind motion; TypeError otherwise.
qm::io::AnyMotion any_motion(const py::handle& o) {
  if (py::isinstance<PyMotion>(o)) return qm::io::AnyMotion(o.cast<const PyMotion&>().motion);
  if (py::isinstance<qm::io::QSplineMotion>(o))
    return qm::io::AnyMotion(o.cast<const qm::io::QSplineMotion&>());
  throw py::type_error("expected a qmotion.Motion or a qmotion.QSpline");
}

/// `qmotion render` as a call; the dict of what was drawn.
py::object render_call(const py::handle& motion, const std::string& path, const py::object& points,
                       const py::object& profile, const std::string& view,
                       const std::pair<int, int>& size, int frames, const std::string& object,
                       double object_size, const std::string& title) {
  const qm::io::AnyMotion m = any_motion(motion);
  qm::render::RenderOptions o;
  o.output = path;
  if (!points.is_none())
    for (const auto& p : points) o.points.push_back(vec3(p, "points"));
  if (!profile.is_none()) o.profile = to_profile(profile, qm::io::units_of(m));
  o.view = view;
  std::tie(o.width, o.height) = size;
  o.frames = frames;
  o.object = object;
  o.object_size = object_size;
  o.title = title;
  const auto r = qm::render::render(m, o);
  py::dict d;
  d["path"] = r.path;
  d["width"] = r.width;
  d["height"] = r.height;
  d["trajectories"] = r.trajectories;
  d["object_poses"] = r.object_poses;
  d["key_poses"] = r.key_poses;
  d["key_markers"] = r.key_markers;
  d["surface_quads"] = r.surface_quads;
  d["scale"] = r.scale;
  d["origin"] = std::vector<double>{r.origin.x(), r.origin.y()};
  d["object_size"] = r.object_size;
  return std::move(d);
}

py::object toolpath_call(const qm::io::AnyMotion& motion, const std::string& path,
                         const py::object& point, const py::object& axis, double chord_tol,
                         double angle_tol, double max_step, double feed, bool arc_length,
                         const std::string& rotary, bool c_hold, const std::string& units,
                         bool nurbs) {
  qm::ToolpathOptions o;
  o.nurbs = nurbs;
  o.units = units;
  o.output = path;
  o.point = vec3(point, "point");
  o.axis = vec3(axis, "axis");
  o.chord_tol = chord_tol;
  o.angle_tol_deg = angle_tol;
  o.max_step = max_step;
  o.feed = feed;
  o.arc_length = arc_length;
  o.rotary = rotary;
  o.c_hold = c_hold;
  return to_python(qm::toolpath(motion, o).report());
}

}  // namespace

PYBIND11_MODULE(qmotion, m) {
  m.doc() =
      "qmotion: rational rigid-body motions (Juttler's dual-quaternion Bezier and B-spline "
      "motions) and their exact NURBS trajectories and kinematic sweep surfaces, written as "
      "STEP, IGES and JSON.\n\n"
      "    import qmotion\n"
      "    m = qmotion.interpolate('poses.json')          # elliptic + TR, like the CLI\n"
      "    s = qmotion.sweep(m, 'circle:3')[0]            # NurbsSurface, numpy arrays\n"
      "    qmotion.export(m, 'tube.step', profile='circle:3', solid=True)\n"
      "    qmotion.check('tube.step', m, profile='circle:3')['relative_deviation']\n\n"
      "Bad input raises ValueError, a numerical failure ArithmeticError, with the messages "
      "of the qmotion command line.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const qm::Error& e) {
      switch (e.code()) {
        case qm::Errc::invalid_input:
          PyErr_SetString(PyExc_ValueError, e.what());
          return;
        case qm::Errc::numerical_failure:
          PyErr_SetString(PyExc_ArithmeticError, e.what());
          return;
        default:
          PyErr_SetString(PyExc_RuntimeError, e.what());
          return;
      }
    }
  });

  py::class_<qm::io::PoseSet>(m, "Poses", "A validated set of poses (docs/formats.md)")
      .def_property_readonly("units", [](const qm::io::PoseSet& s) { return s.units; })
      .def("__len__", [](const qm::io::PoseSet& s) { return s.poses.size(); })
      .def(
          "to_dict", [](const qm::io::PoseSet& s) { return to_python(qm::io::poses_to_json(s)); },
          "The poses as pose JSON (docs/formats.md), as a dict");
  m.def(
      "read_poses", [](const std::string& path) { return qm::io::read_poses(path); },
      py::arg("path"),
      "Reads and validates a pose file (.json or .csv). ValueError names the "
      "file, the pose and the field that is wrong.");
  m.def("poses", &to_poses, py::arg("poses"), py::arg("units") = "mm",
        "Poses from a file name, a pose dict, or rows [t, x, y, z, qw, qx, qy, qz] (7 columns "
        "without t) as a list or numpy array, validated as the CLI validates files.");

  py::class_<qm::sweep::NurbsCurve<double>>(m, "NurbsCurve",
                                            "A NURBS curve: degree, full clamped knots, "
                                            "Cartesian poles (n x 3) and weights")
      .def_readonly("degree", &qm::sweep::NurbsCurve<double>::degree)
      .def_property_readonly("knots",
                             [](const qm::sweep::NurbsCurve<double>& c) {
                               return py::array_t<double>(static_cast<py::ssize_t>(c.knots.size()),
                                                          c.knots.data());
                             })
      .def_property_readonly(
          "poles", [](const qm::sweep::NurbsCurve<double>& c) { return points_array(c.points); })
      .def_property_readonly("weights",
                             [](const qm::sweep::NurbsCurve<double>& c) {
                               return py::array_t<double>(
                                   static_cast<py::ssize_t>(c.weights.size()), c.weights.data());
                             })
      .def(
          "__call__",
          [](const qm::sweep::NurbsCurve<double>& c, double t) {
            const Eigen::Vector3d p = qm::sweep::evaluate(c, t);
            return std::vector<double>{p(0), p(1), p(2)};
          },
          py::arg("t"), "The point at parameter t");

  py::class_<qm::sweep::NurbsSurface<double>>(
      m, "NurbsSurface",
      "A tensor-product NURBS surface: degrees, full clamped knots in u (the motion parameter "
      "t) and v (the profile's), poles (nu x nv x 3) and weights (nu x nv)")
      .def_readonly("degree_u", &qm::sweep::NurbsSurface<double>::degree_u)
      .def_readonly("degree_v", &qm::sweep::NurbsSurface<double>::degree_v)
      .def_property_readonly("knots_u",
                             [](const qm::sweep::NurbsSurface<double>& s) {
                               return py::array_t<double>(
                                   static_cast<py::ssize_t>(s.knots_u.size()), s.knots_u.data());
                             })
      .def_property_readonly("knots_v",
                             [](const qm::sweep::NurbsSurface<double>& s) {
                               return py::array_t<double>(
                                   static_cast<py::ssize_t>(s.knots_v.size()), s.knots_v.data());
                             })
      .def_property_readonly(
          "poles",
          [](const qm::sweep::NurbsSurface<double>& s) {
            const auto nu = static_cast<py::ssize_t>(s.points.size());
            const auto nv = static_cast<py::ssize_t>(s.points.front().size());
            py::array_t<double> a({nu, nv, py::ssize_t(3)});
            auto w = a.mutable_unchecked<3>();
            for (py::ssize_t i = 0; i < nu; ++i)
              for (py::ssize_t j = 0; j < nv; ++j)
                for (int c = 0; c < 3; ++c)
                  w(i, j, c) =
                      s.points[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)](c);
            return a;
          })
      .def_property_readonly(
          "weights",
          [](const qm::sweep::NurbsSurface<double>& s) {
            const auto nu = static_cast<py::ssize_t>(s.weights.size());
            const auto nv = static_cast<py::ssize_t>(s.weights.front().size());
            py::array_t<double> a({nu, nv});
            auto w = a.mutable_unchecked<2>();
            for (py::ssize_t i = 0; i < nu; ++i)
              for (py::ssize_t j = 0; j < nv; ++j)
                w(i, j) = s.weights[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
            return a;
          })
      .def(
          "__call__",
          [](const qm::sweep::NurbsSurface<double>& s, double u, double v) {
            const Eigen::Vector3d p = qm::sweep::evaluate(s, u, v);
            return std::vector<double>{p(0), p(1), p(2)};
          },
          py::arg("u"), py::arg("v"), "The point at (u, v)")
      .def(
          "grid",
          [](const qm::sweep::NurbsSurface<double>& s, const std::vector<double>& us,
             const std::vector<double>& vs) {
            std::vector<Eigen::Vector3d> pts;
            {
              py::gil_scoped_release release;
              pts = qm::evaluate_grid(s, us, vs);
            }
            py::array_t<double> a({static_cast<py::ssize_t>(us.size()),
                                   static_cast<py::ssize_t>(vs.size()), py::ssize_t(3)});
            auto w = a.mutable_unchecked<3>();
            for (std::size_t i = 0; i < us.size(); ++i)
              for (std::size_t j = 0; j < vs.size(); ++j)
                for (int c = 0; c < 3; ++c)
                  w(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(j), c) =
                      pts[i * vs.size() + j](c);
            return a;
          },
          py::arg("us"), py::arg("vs"),
          "The points at every (us[i], vs[j]): an array of shape (len(us), len(vs), 3), on all "
          "cores");

  py::class_<PyMotion>(m, "Motion",
                       "A rational motion: its dual-quaternion curve, the factors it is the "
                       "product of, how it was made, and its units")
      .def_property_readonly("units", [](const PyMotion& p) { return p.motion.units; })
      .def_property_readonly(
          "param_range",
          [](const PyMotion& p) { return std::make_pair(p.motion.curve.a(), p.motion.curve.b()); })
      .def_property_readonly("degree", [](const PyMotion& p) { return p.motion.curve.degree(); })
      .def_property_readonly("segments", [](const PyMotion& p) { return p.motion.segments(); })
      .def_property_readonly(
          "has_factors", [](const PyMotion& p) { return p.motion.factors.has_value(); },
          "True when the factors the motion is the product of are known (trajectories at their "
          "minimal degree)")
      .def_property_readonly(
          "provenance", [](const PyMotion& p) { return provenance_dict(p.motion); },
          "How the motion was made, as a dict (form, rotation, translation, degrees, param, "
          "parameters, residuals at the poses, poses), or None for a hand-written motion")
      .def(
          "eval",
          [](const PyMotion& p, double t, const py::object& point) {
            const Eigen::Vector3d x =
                point.is_none() ? Eigen::Vector3d::Zero() : vec3(point, "point");
            return to_python(qm::motion_eval(p.file, t, x));
          },
          py::arg("t"), py::arg("point") = py::none(),
          "Where the motion is at t: dict with position (image of the moving origin), "
          "quaternion (unit, w >= 0) and point (image of `point`). ValueError outside the "
          "interval, ArithmeticError at a pole.")
      .def(
          "info",
          [](const PyMotion& p, bool exact) { return to_python(qm::motion_info(p.file, exact)); },
          py::arg("exact") = false,
          "The `qmotion info` report as a dict: type, basis, degree, order, segments, "
          "param_range, units, plucker_residual, interpolation_residual, poles, method.")
      .def(
          "to_dict", [](const PyMotion& p) { return to_python(p.document); },
          "The motion file's document (docs/formats.md) as a dict")
      .def(
          "save",
          [](const PyMotion& p, const std::string& path) {
            qm::io::write_file_atomic(path, p.text.empty() ? p.document.dump(1) + "\n" : p.text);
          },
          py::arg("path"),
          "Writes the motion file: byte for byte what `qmotion interpolate` writes, or, for a "
          "loaded motion, the file as it was read");

  m.def(
      "load",
      [](const std::string& path) -> py::object {
        {
          auto any = qm::io::load_any_motion(path);
          if (auto* q = std::get_if<qm::io::QSplineMotion>(&any)) return py::cast(std::move(*q));
        }
        qm::io::MotionFile file = qm::io::read_motion(path);
        qm::kernel::Motion<double> motion = qm::io::to_motion(file);
        std::ifstream in(path, std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        json document = json::parse(text.str());  // as written (numbers as numbers)
        // save() writes the file back as it was read.
        return py::cast(
            PyMotion{std::move(file), std::move(motion), std::move(document), text.str()});
      },
      py::arg("path"),
      "Reads a motion file written by `qmotion interpolate`, `qmotion qspline` or `save`: a "
      "Motion, or a QSpline for a quaternion-spline file.");

  m.def(
      "interpolate",
      [](const py::object& poses, const std::string& rotation, const std::string& translation,
         const std::string& form, const std::string& param, int degree, int translation_degree,
         const py::object& trt_degrees, bool exact, const std::string& units) {
        qm::InterpolateOptions o;
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
        auto r = qm::interpolate(to_poses(poses, units), o);
        return make_motion(r.document(), "interpolate()", r.text());
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
      "trajectory",
      [](const PyMotion& p, const py::object& point, int max_degree, double tol,
         const std::string& units) {
        return qm::trajectory_nurbs(p.motion, vec3(point, "point"),
                                    export_options("", max_degree, tol, units, false, false));
      },
      py::arg("motion"), py::arg("point"), py::arg("max_degree") = -1, py::arg("tol") = -1.0,
      py::arg("units") = "",
      "The exact rational trajectory of `point` (moving space) as a NurbsCurve parametrised "
      "by t, at its minimal degree with positive weights; above max_degree an approximation "
      "within tol (default 1e-6 of its size). units converts (mm, cm, m, um, in, ft).");

  m.def(
      "sweep",
      [](const PyMotion& p, const py::object& profile, int max_degree, double tol,
         const std::string& units) {
        return qm::sweep_nurbs(p.motion, to_profile(profile, p.motion.units),
                               export_options("", max_degree, tol, units, false, false));
      },
      py::arg("motion"), py::arg("profile"), py::arg("max_degree") = -1, py::arg("tol") = -1.0,
      py::arg("units") = "",
      "The kinematic surface M(t) x(v) of each profile edge: a list of NurbsSurface, u = t, v "
      "the edge's parameter, poles M_i X_j (exact, no fitting). profile: a NurbsCurve, or a "
      "spec as for the CLI: a .json/.step/.igs file, 'segment:x0,y0,z0:x1,y1,z1', "
      "'polyline:x,y,z:...', 'rect:w,h', 'circle:r', 'arc:r,a0,a1'.");

  m.def(
      "export",
      [](const PyMotion& p, const std::string& path, const py::object& profile,
         const py::object& point, int max_degree, double tol, const std::string& units,
         bool single_face, bool solid, double deflection, double angle, bool ascii) {
        auto opt = export_options(path, max_degree, tol, units, single_face, solid);
        opt.deflection = deflection;
        opt.angle_deg = angle;
        opt.ascii = ascii;
        return to_python(result_json(
            qm::export_geometry(p.motion, to_geometry(p.motion.units, profile, point), opt)));
      },
      py::arg("motion"), py::arg("path"), py::arg("profile") = py::none(),
      py::arg("point") = py::none(), py::arg("max_degree") = -1, py::arg("tol") = -1.0,
      py::arg("units") = "", py::arg("single_face") = false, py::arg("solid") = false,
      py::arg("deflection") = 0.0, py::arg("angle") = 20.0, py::arg("ascii") = false,
      "Writes the trajectory of `point` or the sweep of `profile` to path (.json, .step/.stp, "
      ".igs/.iges; sweeps also a .stl/.obj/.ply mesh within deflection, default 1e-3 of the "
      "size, angle in degrees, ascii STL/PLY), as `qmotion trajectory` / `qmotion sweep` do: "
      "STEP/IGES shells split at C0 knots (single_face: one face per edge), solid=True for a "
      "closed planar profile. Returns a dict: degrees, continuity, faces, poles, units, volume, "
      "and for a mesh its triangles and measured max_deviation.");

  m.def(
      "demo", [](const std::string& dir) { return to_python(qm::write_demo(dir)); },
      py::arg("dir") = "demo-out",
      "Runs `qmotion demo`: five embedded poses -> motion -> trajectories and the kinematic "
      "surface of a parabola as JSON/STEP/IGES, checked, with demo.svg and report.json, all "
      "written into dir or none of them. Returns the report as a dict.");

  m.def(
      "check",
      [](const std::string& path, const PyMotion& p, const py::object& profile,
         const py::object& point, int grid) {
        return to_python(
            qm::check(path, p.motion, to_geometry(p.motion.units, profile, point), grid));
      },
      py::arg("path"), py::arg("motion"), py::arg("profile") = py::none(),
      py::arg("point") = py::none(), py::arg("grid") = 41,
      "The exactness check of `qmotion check`: the file's NURBS (STEP/IGES read through "
      "OpenCASCADE) against the motion applied to the profile or point. A dict with "
      "max_deviation, relative_deviation, weights_positive, valid, faces, closed, volume, ...");

  py::class_<qm::io::QSplineMotion>(
      m, "QSpline",
      "A non-rational quaternion-spline motion (docs/geometry.md): kks, quintic or quartic. Its "
      "trajectories and sweeps are fitted within a tolerance (trajectory, sweep, export) and "
      "checked against the spline itself (check).")
      .def_property_readonly("scheme",
                             [](const qm::io::QSplineMotion& q) {
                               return std::string(qm::kernel::to_string(q.spline.scheme));
                             })
      .def_property_readonly("units", [](const qm::io::QSplineMotion& q) { return q.units; })
      .def_property_readonly(
          "param_range",
          [](const qm::io::QSplineMotion& q) { return std::make_pair(q.spline.a(), q.spline.b()); })
      .def_property_readonly("knots", [](const qm::io::QSplineMotion& q) { return q.spline.knots; })
      .def(
          "evaluate",
          [](const qm::io::QSplineMotion& q, double t, const py::object& point) {
            const Eigen::Vector3d x =
                point.is_none() ? Eigen::Vector3d::Zero() : vec3(point, "point");
            return to_python(qm::qspline_eval(q.spline, t, x, std::to_string(t)));
          },
          py::arg("t"), py::arg("point") = py::none(),
          "`qmotion eval`: position, quaternion, the image of point, angular velocity at t.")
      .def(
          "info",
          [](const qm::io::QSplineMotion& q) {
            return to_python(qm::qspline_info(q.document, q.spline));
          },
          "The `qmotion info` report: scheme, segments, knots, residuals, and for kks the "
          "iteration's figures.")
      .def(
          "to_dict", [](const qm::io::QSplineMotion& q) { return to_python(q.document); },
          "The quaternion-spline file's document as a dict")
      .def(
          "save",
          [](const qm::io::QSplineMotion& q, const std::string& path) {
            qm::io::write_file_atomic(path, q.document.dump(1) + "\n");
          },
          py::arg("path"), "Writes the motion file, as `qmotion qspline` does");

  m.def(
      "qspline",
      [](const py::object& poses, const std::string& scheme, const py::object& tension,
         const std::string& param, const std::string& units) {
        qm::QSplineOptions o;
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
        return qm::qspline(to_poses(poses, units), o);
      },
      py::arg("poses"), py::arg("scheme"), py::arg("tension") = py::none(), py::arg("param") = "",
      py::arg("units") = "mm",
      "A unit-quaternion spline motion through the poses, as `qmotion qspline`:\n"
      "  scheme: 'kks' (Kim-Kim-Shin C2, iterative) | 'quintic' (tension) | 'quartic'\n"
      "  tension: quintic only, a number for every key or one per key (default 0.5)\n"
      "  param: a rule of interpolate; kks and quartic put the keys at uniform knots.");

  m.def(
      "trajectory",
      [](const qm::io::QSplineMotion& q, const py::object& point, int max_degree, double tol,
         const std::string& units) {
        return qm::trajectory_nurbs(q, vec3(point, "point"),
                                    export_options("", max_degree, tol, units, false, false));
      },
      py::arg("motion"), py::arg("point"), py::arg("max_degree") = -1, py::arg("tol") = -1.0,
      py::arg("units") = "",
      "For a QSpline: the trajectory fitted within tol (default 1e-6 of its size) at degree "
      "max_degree (default 5), a polynomial NurbsCurve parametrised by t.");

  m.def(
      "sweep",
      [](const qm::io::QSplineMotion& q, const py::object& profile, int max_degree, double tol,
         const std::string& units) {
        return qm::sweep_nurbs(q, to_profile(profile, q.units),
                               export_options("", max_degree, tol, units, false, false));
      },
      py::arg("motion"), py::arg("profile"), py::arg("max_degree") = -1, py::arg("tol") = -1.0,
      py::arg("units") = "",
      "For a QSpline: the sweep of each profile edge fitted within tol (default 1e-6 of its "
      "size) at degree max_degree (default 5) along t.");

  m.def(
      "export",
      [](const qm::io::QSplineMotion& q, const std::string& path, const py::object& profile,
         const py::object& point, int max_degree, double tol, const std::string& units,
         bool single_face, bool solid, double deflection, double angle, bool ascii) {
        auto opt = export_options(path, max_degree, tol, units, single_face, solid);
        opt.deflection = deflection;
        opt.angle_deg = angle;
        opt.ascii = ascii;
        return to_python(
            result_json(qm::export_geometry(q, to_geometry(q.units, profile, point), opt)));
      },
      py::arg("motion"), py::arg("path"), py::arg("profile") = py::none(),
      py::arg("point") = py::none(), py::arg("max_degree") = -1, py::arg("tol") = -1.0,
      py::arg("units") = "", py::arg("single_face") = false, py::arg("solid") = false,
      py::arg("deflection") = 0.0, py::arg("angle") = 20.0, py::arg("ascii") = false,
      "For a QSpline: as for a Motion, the geometry fitted within tol; the dict adds "
      "approximation_deviation and approximation_tolerance.");

  m.def(
      "check",
      [](const std::string& path, const qm::io::QSplineMotion& q, const py::object& profile,
         const py::object& point, int grid) {
        return to_python(qm::check(path, q, to_geometry(q.units, profile, point), grid));
      },
      py::arg("path"), py::arg("motion"), py::arg("profile") = py::none(),
      py::arg("point") = py::none(), py::arg("grid") = 41,
      "For a QSpline: the file against the spline itself (exp and log), not the fit.");

  m.def(
      "compare",
      [](const py::object& poses, const std::string& param, const py::object& point,
         const std::string& profile, double tol, const std::string& units) {
        qm::CompareOptions o;
        o.param = param;
        if (!point.is_none()) o.point = vec3(point, "point");
        o.profile = profile;
        o.rel_tol = tol;
        return to_python(qm::to_json(qm::compare_schemes(to_poses(poses, units), o)));
      },
      py::arg("poses"), py::arg("param") = "", py::arg("point") = py::none(),
      py::arg("profile") = "", py::arg("tol") = 1e-6, py::arg("units") = "mm",
      "`qmotion compare`: for elliptic bspline, c1, kks, quintic and quartic through the "
      "poses, a list of dicts: max_angular_velocity, max_angular_acceleration, "
      "trajectory_length (of point), sweep_poles (exact, or fitted within tol of the sweep's "
      "size), sweep_deviation, max_key_residual; or error.");

  const char* toolpath_doc =
      "`qmotion toolpath`: cutter-location points along the trajectory of point with the tool "
      "axis R(t) axis, each chord within chord_tol of the exact trajectory and each axis within "
      "angle_tol degrees of the chord's blend (certified from control points), written to path "
      "(.apt/.cls, .csv, .nc/.ngc; rotary='ac' for a table-tilting A/C machine; nurbs=True for "
      "G06.2 NURBS blocks of degree <= 3 with a certified deviation). Returns the report dict: "
      "points, path_length, machining_time_min, max_chord_deviation_bound, ... (with nurbs: "
      "degree, control_points, spans, exact, max_deviation_bound, max_deviation_measured)";
  m.def(
      "toolpath",
      [](const PyMotion& p, const std::string& path, const py::object& point,
         const py::object& axis, double chord_tol, double angle_tol, double max_step, double feed,
         bool arc_length, const std::string& rotary, bool c_hold, const std::string& units,
         bool nurbs) {
        return toolpath_call(p.motion, path, point, axis, chord_tol, angle_tol, max_step, feed,
                             arc_length, rotary, c_hold, units, nurbs);
      },
      py::arg("motion"), py::arg("path"), py::arg("point"),
      py::arg("axis") = std::vector<double>{0, 0, 1}, py::arg("chord_tol"),
      py::arg("angle_tol") = 0.5, py::arg("max_step") = 0.0, py::arg("feed") = 1000.0,
      py::arg("arc_length") = false, py::arg("rotary") = "", py::arg("c_hold") = false,
      py::arg("units") = "", py::arg("nurbs") = false, toolpath_doc);
  m.def(
      "toolpath",
      [](const qm::io::QSplineMotion& q, const std::string& path, const py::object& point,
         const py::object& axis, double chord_tol, double angle_tol, double max_step, double feed,
         bool arc_length, const std::string& rotary, bool c_hold, const std::string& units,
         bool nurbs) {
        return toolpath_call(q, path, point, axis, chord_tol, angle_tol, max_step, feed, arc_length,
                             rotary, c_hold, units, nurbs);
      },
      py::arg("motion"), py::arg("path"), py::arg("point"),
      py::arg("axis") = std::vector<double>{0, 0, 1}, py::arg("chord_tol"),
      py::arg("angle_tol") = 0.5, py::arg("max_step") = 0.0, py::arg("feed") = 1000.0,
      py::arg("arc_length") = false, py::arg("rotary") = "", py::arg("c_hold") = false,
      py::arg("units") = "", py::arg("nurbs") = false, toolpath_doc);

  m.def("render", &render_call, py::arg("motion"), py::arg("path"), py::arg("points") = py::none(),
        py::arg("profile") = py::none(), py::arg("view") = "iso",
        py::arg("size") = std::pair<int, int>(960, 720), py::arg("frames") = 7,
        py::arg("object") = "cube", py::arg("object_size") = 0.0, py::arg("title") = "",
        "`qmotion render`: the motion (Motion or QSpline) drawn to path (.svg or .png): the "
        "object at frames evenly spaced times, the numbered key poses, the trajectories of "
        "points (default the origin), the swept surface of profile, axes and a scale bar, in "
        "the orthographic view (iso, top, front, side or a direction 'x,y,z'). Returns a dict "
        "of what was drawn and the projection (scale in pixels per unit, origin in pixels).");
  m.def(
      "plot",
      [](const py::object& motions, const std::string& path, const std::string& quantity,
         const py::object& point, const std::pair<int, int>& size, int samples,
         const std::string& title) {
        std::vector<qm::io::AnyMotion> ms;
        if (py::isinstance<py::list>(motions) || py::isinstance<py::tuple>(motions)) {
          for (const auto& m : motions) ms.push_back(any_motion(m));
        } else {
          ms.push_back(any_motion(motions));
        }
        qm::render::PlotOptions o;
        o.output = path;
        o.quantity = qm::render::parse_quantity(quantity);
        if (!point.is_none()) o.point = vec3(point, "point");
        std::tie(o.width, o.height) = size;
        o.samples = samples;
        o.title = title;
        py::list out;
        for (const auto& s : qm::render::plot(ms, o)) {
          py::dict d;
          d["name"] = s.name;
          d["t"] = py::array_t<double>(static_cast<py::ssize_t>(s.t.size()), s.t.data());
          d["value"] =
              py::array_t<double>(static_cast<py::ssize_t>(s.value.size()), s.value.data());
          d["keys"] = s.keys;
          d["min"] = s.min;
          d["max"] = s.max;
          d["t_min"] = s.t_min;
          d["t_max"] = s.t_max;
          out.append(d);
        }
        return out;
      },
      py::arg("motions"), py::arg("path"), py::arg("quantity") = "speed",
      py::arg("point") = py::none(), py::arg("size") = std::pair<int, int>(900, 500),
      py::arg("samples") = 600, py::arg("title") = "",
      "`qmotion plot`: speed, angular-speed, curvature or weights along t for one motion or a "
      "list of them (compared on one plot), written to path (.svg or .png). Returns one dict "
      "per motion: name, t and value (numpy), keys, min, max, t_min, t_max.");

#ifdef QMOTION_WITH_CGAL
  m.def(
      "check_exact",
      [](const std::string& motion_path, const py::object& point) {
        std::optional<Eigen::Vector3d> x;
        if (!point.is_none()) x = vec3(point, "point");
        return to_python(qm::check_exact(motion_path, x));
      },
      py::arg("motion_path"), py::arg("point") = py::none(),
      "`qmotion check --exact`: the motion file recomputed in exact rationals from the poses "
      "it records; a dict with the exact Plucker and interpolation residuals (plucker, "
      "interpolation), file_deviation, the trajectory order of point by an exact gcd beside "
      "the degree trajectory writes (order), and verified.");
#endif
}
