// python/convert.hpp: what the bindings share: Python <-> C++ conversions of poses, points,
// profiles and options, and the Python view of a motion.
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <qmotion/qmotion.hpp>
#include <string>
#include <vector>

namespace qmotion::python {

namespace py = pybind11;
using json = nlohmann::json;

/// nlohmann::json -> Python objects, through Python's own json module.
py::object to_python(const json& j);
/// Python dict/list -> nlohmann::json.
json from_python(const py::handle& o);
/// Three numbers (a list, tuple or array); Errc::invalid_input naming `what` otherwise.
Eigen::Vector3d vec3(const py::handle& o, const std::string& what);
/// Points as an n x 3 array.
py::array_t<double> points_array(const std::vector<Eigen::Vector3d>& pts);
/// Poses from a file name, a pose-JSON dict, or rows [t, x, y, z, qw, qx, qy, qz] (or
/// without t: 7 columns) as a list or numpy array.
io::PoseSet to_poses(const py::handle& p, const std::string& units);
/// A profile: a Profile, a NurbsCurve, or a spec string as for the CLI.
sweep::Profile<double> to_profile(const py::handle& p, const std::string& units);
/// The point or profile of an export or check call (both or neither: the library refuses).
Geometry to_geometry(const std::string& units, const py::object& profile, const py::object& point);
ExportOptions export_options(const std::string& output, int max_degree, double tol,
                             const std::string& units, bool single_face, bool solid);
/// An export's result as the dict the Python calls return.
json result_json(const ExportResult& r);

/// A motion of either kind as Python holds it: the value, and its file: as parsed (a
/// rational motion's, for the exact reports of info and eval), as a document (to_dict), and
/// as text (what save writes; empty: the document dumped as `qmotion` writes it).
struct PyMotion {
  Motion motion;
  std::optional<io::MotionFile> file;
  json document;
  std::string text;
};

/// A rational motion from its file's document, named `source`.
PyMotion rational_motion(json document, const std::string& source, std::string text = {});

void bind_geometry(py::module_& m);
void bind_motion(py::module_& m);
void bind_jobs(py::module_& m);
void bind_pictures(py::module_& m);
/// Needs bind_motion first (it adds to Motion).
void bind_values(py::module_& m);

}  // namespace qmotion::python
