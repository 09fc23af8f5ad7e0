// python/convert.cpp: Python <-> C++ conversions shared by the bindings.
#include "convert.hpp"

namespace qmotion::python {

py::object to_python(const json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

json from_python(const py::handle& o) {
  return json::parse(py::module_::import("json").attr("dumps")(o).cast<std::string>());
}

Eigen::Vector3d vec3(const py::handle& o, const std::string& what) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(o);
  if (!a || a.size() != 3)
    throw Error(Errc::invalid_input, what + ": expected three numbers x, y, z");
  return Eigen::Vector3d(a.at(0), a.at(1), a.at(2));
}

py::array_t<double> points_array(const std::vector<Eigen::Vector3d>& pts) {
  py::array_t<double> a({static_cast<py::ssize_t>(pts.size()), py::ssize_t(3)});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (int c = 0; c < 3; ++c) m(static_cast<py::ssize_t>(i), c) = pts[i](c);
  return a;
}

io::PoseSet to_poses(const py::handle& p, const std::string& units) {
  if (py::isinstance<io::PoseSet>(p)) return p.cast<io::PoseSet>();
  if (py::isinstance<py::str>(p)) return io::read_poses(p.cast<std::string>());
  if (py::isinstance<py::dict>(p))
    return io::parse_poses_json_value(from_python(p), "poses (dict)");
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(p);
  if (!a || a.ndim() != 2 || (a.shape(1) != 7 && a.shape(1) != 8))
    throw Error(Errc::invalid_input,
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
  return io::parse_poses_json_value(doc, "poses (array)");
}

sweep::Profile<double> to_profile(const py::handle& p, const std::string& units) {
  if (py::isinstance<sweep::Profile<double>>(p)) return p.cast<sweep::Profile<double>>();
  if (py::isinstance<sweep::NurbsCurve<double>>(p))
    return sweep::single_edge(p.cast<sweep::NurbsCurve<double>>());
  if (py::isinstance<py::dict>(p)) return io::profile_from_json(from_python(p), "profile (dict)");
  if (py::isinstance<py::list>(p)) return io::profile_from_json(from_python(p), "profile (list)");
  return io::read_profile(p.cast<std::string>(), units);
}

Geometry to_geometry(const std::string& units, const py::object& profile, const py::object& point) {
  Geometry g;
  if (!point.is_none()) g.point = vec3(point, "point");
  if (!profile.is_none()) {
    g.profile = to_profile(profile, units);
    if (py::isinstance<py::str>(profile)) g.profile_name = profile.cast<std::string>();
  }
  return g;
}

ExportOptions export_options(const std::string& output, int max_degree, double tol,
                             const std::string& units, bool single_face, bool solid) {
  ExportOptions o;
  o.output = output;
  o.max_degree = max_degree;
  o.tol = tol;
  o.units = units;
  o.single_face = single_face;
  o.solid = solid;
  return o;
}

json result_json(const ExportResult& r) {
  json j{{"path", r.path},
         {"degree_u", r.degree_u},
         {"degree_v", r.degree_v},
         {"faces", r.faces},
         {"poles", r.poles},
         {"units", r.units},
         {"continuity_u", r.continuity_u},
         {"continuity_v", r.continuity_v}};
  if (r.approx_deviation) j["approximation_deviation"] = *r.approx_deviation;
  if (r.approx_bound) j["approximation_bound"] = *r.approx_bound;
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
  if (r.self_intersection_proof) {
    const auto& p = *r.self_intersection_proof;
    j["self_intersection_proof"] = json{{"status", sweep::SelfIntersectionProof::name(p.status)},
                                        {"proven", p.proven()},
                                        {"patches", p.patches},
                                        {"pairs", p.pairs},
                                        {"depth", p.depth},
                                        {"message", p.describe()}};
  }
  return j;
}

PyMotion rational_motion(json document, const std::string& source, std::string text) {
  io::MotionFile file = io::parse_motion(document, source);
  Motion motion(io::to_motion(file));
  return PyMotion{std::move(motion), std::move(file), std::move(document), std::move(text)};
}

}  // namespace qmotion::python
