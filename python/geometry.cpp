// python/geometry.cpp: poses and NURBS as Python objects.
#include <qmotion/io/robot_programs.hpp>

#include "convert.hpp"

namespace qmotion::python {

void bind_geometry(py::module_& m) {
  py::class_<io::PoseSet>(m, "Poses", "A validated set of poses (docs/formats.md)")
      .def_property_readonly("units", [](const io::PoseSet& s) { return s.units; })
      .def("__len__", [](const io::PoseSet& s) { return s.poses.size(); })
      .def(
          "to_dict", [](const io::PoseSet& s) { return to_python(io::poses_to_json(s)); },
          "The poses as pose JSON (docs/formats.md), as a dict");
  m.def(
      "read_poses",
      [](const std::string& path, const std::string& robot_config, const std::string& tool,
         const std::string& base, bool skip_unknown) {
        io::RobotOptions o;
        o.config_path = robot_config;
        o.tool = tool;
        o.base = base;
        o.skip_unknown = skip_unknown;
        io::PoseSet set = io::read_poses(path, o);
        const py::object warn = py::module_::import("warnings").attr("warn");
        for (const std::string& w : set.warnings) warn(w);
        return set;
      },
      py::arg("path"), py::kw_only(), py::arg("robot_config") = "", py::arg("tool") = "",
      py::arg("base") = "", py::arg("skip_unknown") = false,
      "Reads and validates a pose file (.json, .csv) or robot program (KUKA .src, ABB .mod/.prg, "
      "URScript .script; docs/fitting.md). robot_config, tool, base and skip_unknown are the "
      "CLI's --robot-config, --tool, --base and --skip-unknown; skipped statements are "
      "reported with warnings.warn. ValueError names the file, the line or pose, and the "
      "field that is wrong.");
  m.def("poses", &to_poses, py::arg("poses"), py::arg("units") = "mm",
        "Poses from a file name, a pose dict, or rows [t, x, y, z, qw, qx, qy, qz] (7 columns "
        "without t) as a list or numpy array, validated as the CLI validates files.");

  py::class_<sweep::NurbsCurve<double>>(m, "NurbsCurve",
                                        "A NURBS curve: degree, full clamped knots, "
                                        "Cartesian poles (n x 3) and weights")
      .def_readonly("degree", &sweep::NurbsCurve<double>::degree)
      .def_property_readonly("knots",
                             [](const sweep::NurbsCurve<double>& c) {
                               return py::array_t<double>(static_cast<py::ssize_t>(c.knots.size()),
                                                          c.knots.data());
                             })
      .def_property_readonly(
          "poles", [](const sweep::NurbsCurve<double>& c) { return points_array(c.points); })
      .def_property_readonly("weights",
                             [](const sweep::NurbsCurve<double>& c) {
                               return py::array_t<double>(
                                   static_cast<py::ssize_t>(c.weights.size()), c.weights.data());
                             })
      .def(
          "__call__",
          [](const sweep::NurbsCurve<double>& c, double t) {
            const Eigen::Vector3d p = sweep::evaluate(c, t);
            return std::vector<double>{p(0), p(1), p(2)};
          },
          py::arg("t"), "The point at parameter t");

  py::class_<sweep::NurbsSurface<double>>(
      m, "NurbsSurface",
      "A tensor-product NURBS surface: degrees, full clamped knots in u (the motion parameter "
      "t) and v (the profile's), poles (nu x nv x 3) and weights (nu x nv)")
      .def_readonly("degree_u", &sweep::NurbsSurface<double>::degree_u)
      .def_readonly("degree_v", &sweep::NurbsSurface<double>::degree_v)
      .def_property_readonly("knots_u",
                             [](const sweep::NurbsSurface<double>& s) {
                               return py::array_t<double>(
                                   static_cast<py::ssize_t>(s.knots_u.size()), s.knots_u.data());
                             })
      .def_property_readonly("knots_v",
                             [](const sweep::NurbsSurface<double>& s) {
                               return py::array_t<double>(
                                   static_cast<py::ssize_t>(s.knots_v.size()), s.knots_v.data());
                             })
      .def_property_readonly(
          "poles",
          [](const sweep::NurbsSurface<double>& s) {
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
          [](const sweep::NurbsSurface<double>& s) {
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
          [](const sweep::NurbsSurface<double>& s, double u, double v) {
            const Eigen::Vector3d p = sweep::evaluate(s, u, v);
            return std::vector<double>{p(0), p(1), p(2)};
          },
          py::arg("u"), py::arg("v"), "The point at (u, v)")
      .def(
          "grid",
          [](const sweep::NurbsSurface<double>& s, const std::vector<double>& us,
             const std::vector<double>& vs) {
            std::vector<Eigen::Vector3d> pts;
            {
              py::gil_scoped_release release;
              pts = evaluate_grid(s, us, vs);
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
}

}  // namespace qmotion::python
