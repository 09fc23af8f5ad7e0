// api/src/view.cpp: `qmotion view` (docs/guide/view.md).
#include <filesystem>
#include <qmotion/api/view.hpp>
#include <qmotion/api/volume.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/bodies.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/profiles.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/render/view.hpp>
#include <qmotion/sweep/body.hpp>
#include <qmotion/sweep/trajectory.hpp>

#include "volume_preview.hpp"

namespace qmotion {
namespace {

using json = nlohmann::json;

json quat(const Eigen::Quaterniond& q) { return {q.w(), q.x(), q.y(), q.z()}; }
json quat(const kernel::Quaternion<double>& q) { return {q.w(), q.x(), q.y(), q.z()}; }

/// The options that make the motion again from edited poses, by `interpolate`'s names; null
/// when the file does not record them (hand-written) or records a fit.
json method_of(const kernel::Provenance<double>* p) {
  if (!p || p->form == kernel::Form::fit || p->poses.size() < 2) return nullptr;
  return {{"form", kernel::to_string(p->form)},
          {"rotation", kernel::to_string(p->rotation)},
          {"translation", kernel::to_string(p->translation)},
          {"param", p->param.empty() ? "given" : p->param},
          {"k", p->rotation_degree},
          {"l", p->translation_degree},
          {"l2", std::max(p->translation_degree2, 0)}};
}

/// The poses the table shows: the interpolated poses when the page can edit them, else the
/// motion's frames at its breakpoints (a fit's dense stream would be thousands of rows).
json poses_of(const Motion& motion, bool editable) {
  json out = json::array();
  if (const auto* p = motion.provenance(); editable) {
    for (std::size_t i = 0; i < p->poses.size(); ++i) {
      const auto& x = p->poses[i];
      const auto& q = x.rotation;
      // Without a rule's name the parameters were given: they travel as the poses' t.
      const bool given = p->param.empty() || p->param == "given";
      json t = x.t ? json(*x.t) : given ? json(p->parameters.at(i)) : json(nullptr);
      out.push_back({{"t", t}, {"position", io::point_json(x.position)}, {"quaternion", quat(q)}});
    }
    return out;
  }
  for (const double t : motion.breakpoints()) {
    const Eigen::Matrix4d f = motion.frame(t);
    const Eigen::Quaterniond q(Eigen::Matrix3d(f.block<3, 3>(1, 1)));
    out.push_back(
        {{"t", t}, {"position", io::point_json(f.block<3, 1>(1, 0))}, {"quaternion", quat(q)}});
  }
  return out;
}

json curve_of(const Motion::Rational& m) {
  const auto& c = m.curve.curve;
  json points = json::array();
  for (const auto& q : c.ctrl()) {
    json p = json::array();
    for (int j = 0; j < 8; ++j) p.push_back(q[j]);
    points.push_back(std::move(p));
  }
  return {{"kind", "q-motion"},
          {"basis", m.curve.basis == kernel::Basis::bezier ? "bezier" : "bspline"},
          {"degree", c.degree()},
          {"knots", c.knots()},
          {"control_points", std::move(points)}};
}

/// A quaternion spline as the page's kernel reads it (loadSpline): what its file holds.
json spline_of(const kernel::QuaternionSpline& s) {
  json keys = json::array(), positions = json::array(), ctrl = json::array(), pctrl = json::array();
  for (const auto& q : s.keys) keys.push_back(quat(q));
  for (const auto& p : s.positions) positions.push_back(io::point_json(p));
  for (const auto& q : s.ctrl) ctrl.push_back(quat(q));
  for (const auto& p : s.pctrl) pctrl.push_back(io::point_json(p));
  return {{"kind", "quaternion-spline"},
          {"scheme", kernel::to_string(s.scheme)},
          {"knots", s.knots},
          {"keys", std::move(keys)},
          {"positions", std::move(positions)},
          {"tension", s.tension},
          {"control_quaternions", std::move(ctrl)},
          {"control_positions", std::move(pctrl)}};
}

/// A quaternion spline's keys are its poses, at its knots: the page fits them again at
/// those knots (`given`), with the scheme and the tensions the file records.
json spline_poses(const kernel::QuaternionSpline& s) {
  json out = json::array();
  for (std::size_t i = 0; i < s.keys.size(); ++i)
    out.push_back({{"t", s.knots[i]},
                   {"position", io::point_json(s.positions[i])},
                   {"quaternion", quat(s.keys[i])}});
  return out;
}

}  // namespace

json View::report() const {
  return {{"output", path},
          {"bytes", bytes},
          {"wasm_bytes", wasm_bytes},
          {"poses", poses},
          {"editable", editable},
          {"method", method},
          {"profile_edges", profile_edges},
          {"body_triangles", body_triangles},
          {"points", points},
          {"volume_triangles", volume_triangles},
          {"volume_distance_bound", volume_distance_bound}};
}

/// The body's swept volume as the page draws it: positions, indices and its certificate.
json volume_data(const Motion& motion, const ViewOptions& o) {
  if (o.body.empty())
    throw Error(Errc::invalid_input, "--volume: the swept volume is the body's: give --body");
  const SweptVolume v = detail::preview_volume(motion, o.body, o.volume_tol, nullptr);
  json positions = json::array(), indices = json::array();
  for (const auto& p : v.vertices) positions.insert(positions.end(), {p.x(), p.y(), p.z()});
  for (const auto& t : v.triangles) indices.insert(indices.end(), {t[0], t[1], t[2]});
  return {{"positions", std::move(positions)},
          {"indices", std::move(indices)},
          {"distance_bound", v.distance_bound},
          {"tolerance", v.tolerance}};
}

json view_data(const Motion& motion, const ViewOptions& o) {
  json curve, method, poses;
  if (motion.is_rational()) {
    const auto& m = motion.rational();
    sweep::refuse_poles(m);  // its trajectories would run to infinity
    curve = curve_of(m);
    method = method_of(motion.provenance());
    poses = poses_of(motion, !method.is_null());
  } else {
    const auto& s = motion.spline();
    curve = spline_of(s);
    method = {{"scheme", kernel::to_string(s.scheme)}, {"param", "given"}, {"tension", s.tension}};
    poses = spline_poses(s);
  }
  json data = {{"name", motion.label()},
               {"units", motion.units()},
               {"motion", std::move(curve)},
               {"method", std::move(method)},
               {"poses", std::move(poses)},
               {"profile", nullptr},
               {"body", nullptr},
               {"points", json::array()}};
  if (!o.profile.empty()) {
    json edges = json::array();
    for (const auto& e : io::read_profile(o.profile, motion.units()).edges) {
      json points = json::array();
      for (const auto& p : e.points) points.push_back(io::point_json(p));
      edges.push_back({{"degree", e.degree},
                       {"knots", e.knots},
                       {"control_points", std::move(points)},
                       {"weights", e.weights}});
    }
    data["profile"] = std::move(edges);
  }
  if (!o.body.empty()) {
    const sweep::Body body = io::read_body(o.body);
    const auto mesh = sweep::triangulate(body, 1e-3 * sweep::radius(body));
    json positions = json::array(), indices = json::array();
    for (const auto& v : mesh.vertices) positions.insert(positions.end(), {v.x(), v.y(), v.z()});
    for (const auto& t : mesh.triangles) indices.insert(indices.end(), {t[0], t[1], t[2]});
    data["body"] = {{"positions", std::move(positions)}, {"indices", std::move(indices)}};
  }
  for (const auto& p : o.points) {
    if (!p.allFinite()) throw Error(Errc::invalid_input, "--point: expected finite x,y,z");
    data["points"].push_back(io::point_json(p));
  }
  if (o.volume) data["volume"] = volume_data(motion, o);
  return data;
}

View view(const Motion& motion, const ViewOptions& o) {
  const std::string ext = io::lower_extension(o.output);
  if (ext != ".html" && ext != ".htm")
    throw Error(Errc::invalid_input,
                o.output + ": view writes an .html page (found '" + ext + "')");
  const json data = view_data(motion, o);
  // The title is the file's name; the data keep the path as given.
  const std::string title = std::filesystem::path(motion.label()).filename().string();
  const std::string page = render::viewer_page(title, motion.summary(), data);
  io::write_file_atomic(o.output, page);
  View v;
  v.path = o.output;
  v.bytes = page.size();
  v.wasm_bytes = render::viewer_wasm_bytes();
  v.poses = data["poses"].size();
  v.method = data["method"];
  v.editable = !v.method.is_null();
  v.profile_edges = data["profile"].is_null() ? 0 : data["profile"].size();
  v.body_triangles = data["body"].is_null() ? 0 : data["body"]["indices"].size() / 3;
  v.points = o.points.size();
  if (data.contains("volume")) {
    v.volume_triangles = data["volume"]["indices"].size() / 3;
    v.volume_distance_bound = data["volume"]["distance_bound"].get<double>();
  }
  return v;
}

}  // namespace qmotion
