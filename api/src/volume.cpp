// api/src/volume.cpp: `qmotion volume`, its report and its outputs, the exact pipe faces of a
// sphere or ball cutter, and `render --body` (docs/guide/volume.md). The enclosing mesh itself
// is sweep::swept_volume (sweep/src/volume_mesh.cpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <qmotion/api/volume.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/bodies.hpp>
#include <qmotion/io/mesh.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/io/units.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/sweep/pipe_approx.hpp>
#include <qmotion/sweep/pipe_reach.hpp>
#include <qmotion/sweep/trajectory.hpp>

#include "volume_preview.hpp"

namespace qmotion {

SweptVolume detail::preview_volume(const Motion& motion, const std::string& body_spec,
                                   std::optional<double> tol, sweep::Body* body_out) {
  if (tol && (!(*tol > 0) || !std::isfinite(*tol)))
    throw Error(Errc::invalid_input, "--body-tol: the tolerance must be a positive length, got " +
                                         kernel::detail::format_double(*tol));
  sweep::Body body = io::read_body(body_spec);
  sweep::validate(body);
  SweptVolume v = swept_volume(
      motion, body, tol ? *tol : 1e-2 * sweep::sampled_swept_box(motion, body).diagonal().norm());
  if (body_out) *body_out = std::move(body);
  return v;
}

render::RenderResult render_volume(const Motion& motion, render::RenderOptions options,
                                   const std::string& body_spec, std::optional<double> tol) {
  sweep::Body body;
  SweptVolume v = detail::preview_volume(motion, body_spec, tol, &body);
  options.volume_vertices = std::move(v.vertices);
  options.volume_triangles = std::move(v.triangles);
  options.volume_label = "swept volume of " + body.spec + " (encloses it, within " +
                         kernel::detail::format_double(v.distance_bound) + " " + motion.units() +
                         ")";
  return render::render(motion, options);
}

bool has_exact_swept_volume(const sweep::Body& body) {
  return body.kind == sweep::Body::Kind::sphere || body.kind == sweep::Body::Kind::ball_cutter;
}

sweep::PipeShell exact_swept_volume(const Motion& motion, const sweep::Body& body) {
  sweep::validate(body);
  if (!has_exact_swept_volume(body))
    throw Error(Errc::invalid_input,
                body.spec + ": exact faces exist for sphere:r and cutter:ball (its ball) only");
  if (!motion.is_rational())
    throw Error(Errc::invalid_input,
                motion.label() +
                    ": a quaternion-spline motion's trajectories are not rational: no exact faces");
  sweep::refuse_poles(motion.rational());
  const bool sphere = body.kind == sweep::Body::Kind::sphere;
  const double r = sphere ? body.r : body.D / 2;
  const Eigen::Vector3d centre = sphere ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0, 0, r);
  const auto path = sweep::point_trajectory(motion.rational(), centre);
  sweep::PipeShell pipe = sweep::pipe_shell(path, r, motion.label());
  // The faces bound the swept volume only where the pipe does not overlap itself.
  pipe.reach = sweep::pipe_overlap_free(path, r, motion.label());
  return pipe;
}

nlohmann::json VolumeReport::report() const {
  const auto& v = volume;
  if (exact)
    return {{"output", path},
            {"body", body},
            {"units", units},
            {"exact", true},
            {"route",
             approximated
                 ? "faces of degree 9 within approximation_bound of the exact pipe around the "
                   "sphere centre's rational trajectory (of exact_degree), its end circles and "
                   "half-sphere caps exact (docs/geometry.md, Pipes of a low degree)"
                 : "exact faces: the pipe around the sphere centre's rational trajectory and its "
                   "two half-sphere caps (docs/geometry.md, Exact pipe surfaces)"},
            {"approximation", approximated ? nlohmann::json{{"bound", approximation_bound},
                                                            {"degree", degree},
                                                            {"exact_degree", exact_degree}}
                                           : nlohmann::json(nullptr)},
            {"exact_part", exact_part},
            {"radius", radius},
            {"faces", faces},
            {"pipe_faces", pipe_faces},
            {"pieces", pieces},
            {"degree", degree},
            {"distance_bound", approximation_bound},
            {"measured_distance", radius_deviation * radius},
            {"orthogonality", orthogonality},
            {"overlap_free",
             {{"curvature_radius_bound", curvature_radius},
              {"radius", radius},
              {"pieces", reach_pieces},
              {"pairs", reach_pairs}}},
            {"volume", exact_volume},
            {"volume_bounds",
             has_bounds ? nlohmann::json{v.volume_lower, v.volume_upper} : nlohmann::json(nullptr)},
            {"tolerance", has_bounds ? nlohmann::json(v.tolerance) : nlohmann::json(nullptr)},
            {"triangles", 0},
            {"vertices", 0},
            {"closed", true},
            {"seconds", seconds}};
  return {{"output", path},
          {"body", body},
          {"units", units},
          {"tolerance", v.tolerance},
          {"distance_bound", v.distance_bound},
          {"measured_distance", v.measured_distance},
          {"measured_vertices", v.measured_vertices},
          {"volume_bounds", {v.volume_lower, v.volume_upper}},
          {"triangles", triangles},
          {"vertices", vertices},
          {"closed", closed},
          {"float32_rounding", v.rounding},
          {"route",
           "an octree refined until every triangle is certified clear of the swept volume "
           "(docs/geometry.md, Swept volumes)"},
          {"grid_step", v.grid_step},
          {"largest_cell", v.largest_cell},
          {"surface_cells", v.surface_cells},
          {"hull_pieces", v.hull_pieces},
          {"level", v.level},
          {"time_pieces", v.time_pieces},
          {"piece_radius", v.piece_delta},
          {"distance_queries", v.distance_queries},
          {"rounds", v.rounds},
          {"seconds", seconds}};
}

namespace {

/// A pipe above STEP/IGES's degree is written at this degree (every CAD system reads it)...
constexpr int kLowDegree = 9;
/// ... within this fraction of its bounding-box diagonal of the exact pipe.
constexpr double kApproximation = 1e-6;

/// The volume's figures (without its mesh) scaled by f, lengths and volumes.
SweptVolume in_unit(SweptVolume v, double f) {
  for (double* x : {&v.tolerance, &v.distance_bound, &v.measured_distance, &v.grid_step,
                    &v.largest_cell, &v.level, &v.piece_delta, &v.rounding})
    *x *= f;
  v.volume_lower *= f * f * f;
  v.volume_upper *= f * f * f;
  return v;
}

/// The exact faces written (STEP, IGES or a nurbs_shell), with the certified volume bounds of
/// the enclosing mesh beside them for the sphere.
void write_exact(const Motion& motion, const sweep::Body& body, const VolumeOptions& o,
                 const std::string& ext, double f, VolumeReport& r) {
  sweep::PipeShell pipe = exact_swept_volume(motion, body);
  const bool cad = ext != ".json";
  if (cad && pipe.degree_t > io::occt_max_degree()) {
    // Above what STEP/IGES store: faces of degree kLowDegree within a proven distance of the
    // exact ones (sweep/pipe_approx.hpp); the end circles and the caps stay exact.
    const double target = kApproximation * sweep::diagonal(pipe.shell);
    sweep::LowDegreePipe low = sweep::pipe_to_degree(pipe, kLowDegree, target, o.output);
    r.approximated = true;
    r.approximation_bound = f * low.bound;
    r.exact_degree = pipe.degree_t;
    pipe = std::move(low.pipe);
  }
  for (auto& face : pipe.shell.faces)
    for (auto& row : face.points)
      for (auto& x : row) x *= f;
  r.exact = true;
  r.radius = f * (body.kind == sweep::Body::Kind::sphere ? body.r : body.D / 2);
  r.exact_part = body.kind == sweep::Body::Kind::sphere
                     ? "the sphere"
                     : "the ball: centre (0, 0, " + kernel::detail::format_double(body.D / 2) +
                           ") of the moving frame, radius " +
                           kernel::detail::format_double(body.D / 2) +
                           "; the shank is not in these faces (a mesh of the whole cutter: "
                           ".stl, .obj, .ply)";
  r.faces = pipe.shell.faces.size();
  r.pipe_faces = pipe.pipe_faces;
  r.pieces = pipe.pieces;
  r.degree = pipe.degree_t;
  r.orthogonality = pipe.orthogonality;
  r.curvature_radius = f * pipe.reach.curvature_radius;
  r.reach_pieces = pipe.reach.pieces;
  r.reach_pairs = pipe.reach.pairs;
  r.radius_deviation = pipe.radius_deviation;
  r.exact_volume = pipe.volume * f * f * f;
  r.closed = true;
  r.has_bounds = body.kind == sweep::Body::Kind::sphere;
  if (r.has_bounds) {
    // Default: 1e-2 of the size, and at most a quarter of the radius (the bounds' gap is
    // about the tolerance times the area).
    const double T =
        o.tol ? *o.tol / f : std::min(1e-2 * sweep::diagonal(pipe.shell) / f, 0.25 * body.r);
    SweptVolume v = swept_volume(motion, body, T);
    v.vertices.clear();
    v.triangles.clear();
    r.volume = in_unit(std::move(v), f);
  }
  io::ExportInfo info;
  info.units = r.units;
  info.description = motion.label() + " swept by " + body.spec;
  if (r.approximated)
    info.description +=
        ": an approximation of degree " + std::to_string(r.degree) +
        " of the exact pipe of degree " + std::to_string(r.exact_degree) + ", every point within " +
        kernel::detail::format_double(r.approximation_bound) + " " + r.units + " of it (proven)";
  if (ext == ".json") {
    nlohmann::json extra{{"units", r.units}, {"body", r.body}, {"volume", r.exact_volume}};
    io::write_shell_json(o.output, pipe.shell.faces, true, extra);
  } else if (ext == ".step" || ext == ".stp") {
    io::write_step(o.output, pipe.shell, info);
  } else {
    io::write_iges(o.output, pipe.shell, info);
  }
}

}  // namespace

VolumeReport volume(const Motion& motion, const VolumeOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const std::string ext = io::lower_extension(o.output);
  const bool cad = ext == ".step" || ext == ".stp" || ext == ".igs" || ext == ".iges";
  if (!cad && !io::is_mesh_path(o.output) && ext != ".json")
    throw Error(
        Errc::invalid_input,
        o.output + ": unknown volume format (expected .stl, .obj, .ply, .json, .step or .igs)");
  if (o.body.empty())
    throw Error(Errc::invalid_input, "volume: --body is required (sphere:r, box:a,b,c, ...)");
  VolumeReport r;
  r.path = o.output;
  r.units = o.units.empty() ? motion.units() : io::canonical_unit(o.units, "--units");
  const double f = io::unit_factor(motion.units(), r.units);  // motion unit -> output unit
  if (o.tol && (!(*o.tol > 0) || !std::isfinite(*o.tol)))
    throw Error(Errc::invalid_input, "--tol: the tolerance must be a positive length, got " +
                                         kernel::detail::format_double(*o.tol));
  const sweep::Body body = io::read_body(o.body);
  r.body = body.spec;
  if (cad && !has_exact_swept_volume(body))
    throw Error(Errc::invalid_input,
                o.output +
                    ": exact STEP/IGES faces exist for sphere:r and cutter:ball (its ball's "
                    "sweep); the swept volume of " +
                    body.spec + " is written as a mesh (.stl, .obj, .ply) or .json");
  if (cad && !motion.is_rational())
    throw Error(Errc::invalid_input,
                o.output + ": " + motion.label() +
                    " is a quaternion spline, whose trajectories are not rational: no exact "
                    "faces; write a mesh (.stl, .obj, .ply) or .json");
  if (cad || (ext == ".json" && has_exact_swept_volume(body) && motion.is_rational())) {
    write_exact(motion, body, o, ext, f, r);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
  }
  std::optional<double> tol;
  if (o.tol) tol = *o.tol / f;
  // What is written is what was certified: a binary STL's float32 vertices are the ones
  // bounded, and closedness is measured on them.
  VolumeRounding rounding;
  rounding.float32 = ext == ".stl" && !o.ascii;
  rounding.scale = f;
  SweptVolume v = swept_volume(motion, body, tol, rounding);
  io::Mesh mesh;
  mesh.vertices.reserve(v.vertices.size());
  for (const auto& x : v.vertices) mesh.vertices.push_back(f * x);
  mesh.triangles = std::move(v.triangles);
  v.vertices.clear();
  r.volume = in_unit(std::move(v), f);
  r.triangles = mesh.triangles.size();
  r.vertices = mesh.vertices.size();
  r.closed = v.closed;  // measured on the coordinates as written
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (ext == ".json") {
    nlohmann::json j = {{"kind", "swept_volume_mesh"}, {"units", r.units}, {"body", r.body}};
    j["report"] = r.report();
    nlohmann::json verts = nlohmann::json::array(), tris = nlohmann::json::array();
    for (const auto& x : mesh.vertices) verts.push_back({x.x(), x.y(), x.z()});
    for (const auto& t : mesh.triangles) tris.push_back({t[0], t[1], t[2]});
    j["vertices"] = std::move(verts);
    j["triangles"] = std::move(tris);
    io::write_file_atomic(o.output, j.dump() + "\n");
  } else {
    io::write_mesh(o.output, mesh, o.ascii);
  }
  return r;
}

}  // namespace qmotion
