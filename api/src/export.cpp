// api/src/export.cpp: the export calls (docs/guide/commands.md): a motion of either kind to
// trajectories and kinematic surfaces, written as JSON, STEP, IGES or a mesh; the helpers the
// exact and the fitted routes share.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <qmotion/api/export.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/mesh.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/io/units.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/shell.hpp>
#include <qmotion/sweep/span_faces.hpp>
#include <sstream>

#include "export_detail.hpp"

namespace qmotion {
using namespace io;  // NOLINT: the formats this call reads and writes
using json = nlohmann::json;

namespace detail {

Format output_format(const std::string& path, bool allow_stl) {
  const std::string e = lower_extension(path);
  if (e == ".json") return Format::json;
  if (e == ".step" || e == ".stp") return Format::step;
  if (e == ".igs" || e == ".iges") return Format::iges;
  if (allow_stl && is_mesh_path(path)) return Format::mesh;
  throw Error(Errc::invalid_input,
              "-o " + path + ": expected a .json, .step, .stp, .igs or .iges file name" +
                  std::string(allow_stl ? " (or a .stl, .obj or .ply mesh)" : ""));
}

/// A surface's output format, with the mesh options checked before any work.
Format surface_format(const ExportOptions& opt) {
  const Format f = output_format(opt.output, true);
  const bool mesh_option = opt.deflection != 0 || opt.angle_deg != 20 || opt.ascii;
  if (f != Format::mesh && mesh_option)
    throw Error(Errc::invalid_input,
                "--deflection, --angle and --ascii are for mesh output (.stl, .obj, .ply)");
  if (f == Format::mesh && (!(opt.deflection >= 0) || !std::isfinite(opt.deflection) ||
                            (opt.deflection == 0 && std::signbit(opt.deflection))))
    throw Error(Errc::invalid_input, "--deflection: expected a positive length");
  if (f == Format::mesh && !(opt.angle_deg > 0 && opt.angle_deg <= 90))
    throw Error(Errc::invalid_input, "--angle: expected degrees in (0, 90]");
  return f;
}

std::string fmt(double x) {
  std::ostringstream os;
  os.precision(3);
  os << x;
  return os.str();
}

/// Refuses a --max-degree below 1 (-1 means none) or, for STEP/IGES, above what
/// OpenCASCADE stores.
void check_max_degree(const ExportOptions& opt, Format f) {
  if (opt.max_degree == -1) return;
  if (opt.max_degree < 1)
    throw Error(Errc::invalid_input, "--max-degree " + std::to_string(opt.max_degree) +
                                         ": expected a degree of at least 1");
  if (f != Format::step && f != Format::iges) return;  // OpenCASCADE loads only for them
  const int limit = occt_max_degree();
  if (opt.max_degree > limit)
    throw Error(Errc::invalid_input, "--max-degree " + std::to_string(opt.max_degree) +
                                         ": STEP and IGES (OpenCASCADE) store degrees up to " +
                                         std::to_string(limit));
}

/// Refuses degrees above what the target stores, unless an approximation was asked for.
void check_degree(int degree, const std::string& what, Format f, const ExportOptions& opt) {
  if (f != Format::step && f != Format::iges) return;  // OpenCASCADE loads only for them
  const int limit = occt_max_degree();
  if (degree > limit && opt.max_degree < 0)
    throw Error(Errc::numerical_failure,
                what + " has degree " + std::to_string(degree) + ", above the " +
                    std::to_string(limit) +
                    " that OpenCASCADE (and so STEP/IGES export) stores; many CAD systems accept "
                    "less (Rhino 11, AutoCAD 10). "
                    "Use a spline motion (interpolate --form bspline) to keep degrees low, or "
                    "--max-degree D for an approximation "
                    "within --tol");
}

double diagonal(const std::vector<Eigen::Vector3d>& pts) {
  Eigen::Vector3d lo = pts.front(), hi = pts.front();
  for (const auto& p : pts) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

std::vector<Eigen::Vector3d> curve_samples(const kernel::BSpline<Eigen::Vector4d>& h, int n) {
  std::vector<Eigen::Vector3d> s;
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector4d y = kernel::evaluate(h, h.a() + (h.b() - h.a()) * i / n);
    s.push_back(y.tail<3>() / y(0));
  }
  return s;
}

/// The file header of an export; `units` is the declared unit.
ExportInfo export_info(const std::string& label, const std::string& units,
                       const std::string& what) {
  ExportInfo info;
  info.units = units;
  info.product = "qmotion " + what;
  info.description = what + " of motion " + std::filesystem::path(label).filename().string();
  return info;
}

double min_weight(const std::vector<double>& w) { return *std::min_element(w.begin(), w.end()); }

/// Scales Cartesian poles into another unit (weights and knots unchanged).
void scale_points(sweep::NurbsCurve<double>& c, double k) {
  if (k != 1.0)
    for (auto& p : c.points) p *= k;
}
void scale_points(sweep::NurbsSurface<double>& s, double k) {
  if (k != 1.0)
    for (auto& row : s.points)
      for (auto& p : row) p *= k;
}

/// The declared unit and the factor from the motion's unit into it (--units converts).
void resolve_units(const std::string& motion_units, const ExportOptions& opt, ExportResult& r) {
  r.units = opt.units.empty() ? motion_units : canonical_unit(opt.units, "--units");
  r.unit_factor = unit_factor(motion_units, r.units);
}

/// Degrees, lowest continuities and smallest weight of the surfaces, into r.
void summarize_surfaces(const std::vector<sweep::NurbsSurface<double>>& surfaces, ExportResult& r) {
  r.degree_u = surfaces.front().degree_u;
  r.degree_v = surfaces.front().degree_v;
  r.continuity_u = r.degree_u;
  r.continuity_v = r.degree_v;
  r.min_weight = 1.0;
  for (const auto& s : surfaces) {
    r.degree_v = std::max(r.degree_v, s.degree_v);
    r.continuity_u = std::min(r.continuity_u, sweep::min_continuity(s.knots_u, s.degree_u));
    r.continuity_v = std::min(r.continuity_v, sweep::min_continuity(s.knots_v, s.degree_v));
    for (const auto& row : s.weights) r.min_weight = std::min(r.min_weight, min_weight(row));
  }
  if (surfaces.size() > 1) r.continuity_v = std::min(r.continuity_v, 0);  // edges meet at C0
}

/// What a sweep is checked for before it is built: with opt.solid a closed planar profile
/// whose region never sweeps back (`backsweep`) and its volume (`volume`, in the motion's
/// unit); the self-intersection check (`self_intersection`) unless switched off, refused
/// with --fail-on-self-intersection or --solid.
void sweep_checks(
    const sweep::Profile<double>& profile, const std::string& profile_name,
    const ExportOptions& opt, ExportResult& r,
    const std::function<sweep::BacksweepResult(const sweep::PlanarRegion&)>& backsweep,
    const std::function<double(const sweep::PlanarRegion&)>& volume,
    [[maybe_unused]] const std::function<SelfIntersection()>& self_intersection) {
  if (opt.solid) {
    if (!profile.closed)
      throw Error(Errc::invalid_input, "--solid: the profile " + profile_name +
                                           " is open (its last edge does not end where the "
                                           "first starts); a solid needs a closed planar profile");
    const sweep::PlanarRegion region = sweep::planar_region(profile);
    const auto back = backsweep(region);
    if (back.t) {
      std::ostringstream os;
      os.precision(12);
      os << "--solid: the profile's region sweeps back over itself near t = " << *back.t
         << " (a point of the region has zero or reversed normal velocity there), so the capped "
            "sweep is not a solid; sweep a shorter interval or drop --solid for the open shell";
      throw Error(Errc::numerical_failure, os.str());
    }
    r.volume = volume(region) * std::pow(r.unit_factor, 3);
  }
#ifdef QMOTION_WITH_CGAL
  if (opt.self_intersection_check) {
    r.self_intersection = self_intersection();
    const auto& si = *r.self_intersection;
    if (si.found() && (opt.fail_on_self_intersection || opt.solid))
      throw Error(Errc::numerical_failure,
                  std::string(opt.solid ? "--solid" : "--fail-on-self-intersection") +
                      ": the sweep of " + profile_name + " intersects itself (" +
                      std::to_string(si.pairs) + " crossing triangle pairs of a " +
                      std::to_string(si.samples_t) + " x " + std::to_string(si.samples_v) +
                      " tessellation; " + si.ranges() + ")" +
                      (opt.solid ? ": a self-intersecting shell bounds no solid" : ""));
  }
#endif
}

}  // namespace detail

using namespace detail;  // NOLINT: this file's own helpers
namespace {

int count_poles(const std::vector<sweep::NurbsSurface<double>>& faces) {
  int n = 0;
  for (const auto& f : faces) n += static_cast<int>(f.points.size() * f.points.front().size());
  return n;
}

std::string trajectory_what(const Eigen::Vector3d& point) {
  return "trajectory of (" + fmt(point(0)) + "," + fmt(point(1)) + "," + fmt(point(2)) + ")";
}

/// Writes a trajectory in the format f (JSON with units, continuity and any approximation
/// record; STEP or IGES with the header `info`).
void write_curve(const sweep::NurbsCurve<double>& c, Format f, const std::string& path,
                 const ExportResult& r, const ExportInfo& info, const json& approximation) {
  switch (f) {
    case Format::json: {
      json extra{{"units", r.units}, {"continuity", r.continuity_u}};
      if (!approximation.is_null()) extra["approximation"] = approximation;
      write_curve_json(path, c, extra);
      break;
    }
    case Format::step:
      write_step(path, c, info);
      break;
    case Format::iges:
      write_iges(path, c, info);
      break;
    case Format::mesh:
      break;
  }
}

/// Writes the surfaces in the format f: JSON (one surface, or a shell of one face per edge,
/// with units, continuity and any approximation record), STEP or IGES (a shell of C1 faces,
/// or one face per edge with opt.single_face; caps and one solid with opt.solid), or an STL
/// mesh. Sets r.faces and r.poles to what was written.
void write_surfaces(const std::vector<sweep::NurbsSurface<double>>& surfaces, Format f,
                    const ExportOptions& opt, ExportResult& r, const ExportInfo& info,
                    const json& approximation) {
  const bool one_surface = surfaces.size() == 1 && !opt.solid;
  if (f == Format::json) {  // exact surfaces per edge (JSON readers handle C0 knots)
    json extra{{"units", r.units}, {"continuity", {r.continuity_u, r.continuity_v}}};
    if (!approximation.is_null()) extra["approximation"] = approximation;
    if (!one_surface && opt.solid) extra["volume"] = *r.volume;
    if (one_surface)
      write_surface_json(opt.output, surfaces.front(), extra);
    else
      write_shell_json(opt.output, surfaces, opt.solid, extra);
    r.faces = static_cast<int>(surfaces.size());
    r.poles = count_poles(surfaces);
    return;
  }
  // The other formats write a shell of C1 faces: split copies, made only for them (for a
  // 10^4-span surface they are megabytes).
  sweep::NurbsShell<double> shell;
  for (const auto& s : surfaces) {
    if (opt.single_face) {
      shell.faces.push_back(s);
    } else if (opt.solid && f != Format::mesh) {  // one face a u span: FreeCAD's volume
      for (auto& piece : sweep::split_u_spans(s)) shell.faces.push_back(std::move(piece));
    } else {
      for (auto& piece : sweep::split_c0(s)) shell.faces.push_back(std::move(piece));
    }
    if (opt.solid) {
      shell.cap_start.push_back(sweep::boundary_v_curve(s, false));
      shell.cap_end.push_back(sweep::boundary_v_curve(s, true));
    }
  }
  shell.closed = opt.solid;
  switch (f) {
    case Format::json:  // written above
      break;
    case Format::step:
      write_step(opt.output, shell, info);
      break;
    case Format::iges:
      write_iges(opt.output, shell, info);
      break;
    case Format::mesh: {
      MeshOptions mo;
      mo.deflection = opt.deflection > 0 ? opt.deflection : 1e-3 * sweep::diagonal(shell);
      mo.angle_deg = opt.angle_deg;
      mo.ascii = opt.ascii;
      Mesh mesh = mesh_shell_within(shell, mo, opt.output);
      write_mesh(opt.output, mesh, opt.ascii);
      r.mesh = std::move(mesh);
      break;
    }
  }
  r.faces = static_cast<int>(shell.faces.size()) + (opt.solid ? 2 : 0);
  r.poles = count_poles(shell.faces);
}

/// The trajectory of either kind: exact (rational) or fitted (quaternion spline).
Computed<sweep::NurbsCurve<double>> compute_trajectory(const Motion& m,
                                                       const Eigen::Vector3d& point,
                                                       const ExportOptions& opt, Format f,
                                                       ExportResult& r) {
  if (m.is_rational()) return exact_trajectory(m.rational(), point, opt, f, r);
  return fitted_trajectory(m, point, opt, f, r);
}

/// Under --solid or --fail-on-self-intersection, the proof that the surfaces about to be
/// written (and a solid's caps) do not meet themselves: both refuse anything not proven, a
/// crossing, a contact, a singular point or a budget that ran out (docs/geometry.md).
void prove_surfaces(const std::vector<sweep::NurbsSurface<double>>& surfaces,
                    const sweep::Profile<double>& profile, const std::string& profile_name,
                    const ExportOptions& opt, ExportResult& r) {
  if (!opt.self_intersection_check || !(opt.solid || opt.fail_on_self_intersection)) return;
  r.self_intersection_proof = sweep::prove_no_self_intersection(surfaces, profile.closed, opt.solid,
                                                                opt.self_intersection_budget);
  const auto& p = *r.self_intersection_proof;
  if (!p.proven())
    throw Error(Errc::numerical_failure,
                std::string(opt.solid ? "--solid" : "--fail-on-self-intersection") +
                    ": the sweep of " + profile_name + " " + p.describe() +
                    (opt.solid ? ": a shell that is not proven free of self-intersection bounds "
                                 "no solid"
                               : ""));
}

/// The surfaces of either kind: exact (rational) or fitted (quaternion spline).
Computed<std::vector<sweep::NurbsSurface<double>>> compute_surfaces(
    const Motion& m, const sweep::Profile<double>& profile, const std::string& profile_name,
    const ExportOptions& opt, Format f, ExportResult& r) {
  auto s = m.is_rational() ? exact_surfaces(m, profile, profile_name, opt, f, r)
                           : fitted_surfaces(m, profile, profile_name, opt, f, r);
  prove_surfaces(s.geometry, profile, profile_name, opt, r);
  return s;
}

void require_one(const Geometry& g, const char* what) {
  if (g.point.has_value() == g.profile.has_value())
    throw Error(Errc::invalid_input, std::string(what) + ": give exactly one of profile and point");
}
}  // namespace

sweep::NurbsCurve<double> trajectory_nurbs(const Motion& m, const Eigen::Vector3d& point,
                                           const ExportOptions& opt, ExportResult* result) {
  ExportResult r;
  auto c = compute_trajectory(m, point, opt, Format::json, r);
  if (result) *result = r;
  return std::move(c.geometry);
}

std::vector<sweep::NurbsSurface<double>> sweep_nurbs(const Motion& m,
                                                     const sweep::Profile<double>& profile,
                                                     const ExportOptions& opt,
                                                     ExportResult* result) {
  ExportResult r;
  auto s = compute_surfaces(m, profile, "the profile", opt, Format::json, r);
  r.faces = static_cast<int>(s.geometry.size());
  r.poles = count_poles(s.geometry);
  if (result) *result = r;
  return std::move(s.geometry);
}

ExportResult export_trajectory(const Motion& m, const Eigen::Vector3d& point,
                               const ExportOptions& opt) {
  const Format f = output_format(opt.output, false);
  ExportResult r;
  r.path = opt.output;
  const auto c = compute_trajectory(m, point, opt, f, r);
  write_curve(c.geometry, f, opt.output, r, export_info(m.label(), r.units, trajectory_what(point)),
              c.approximation);
  return r;
}

ExportResult export_surface(const Motion& m, const sweep::Profile<double>& profile,
                            const std::string& profile_name, const ExportOptions& opt) {
  const Format f = surface_format(opt);
  ExportResult r;
  r.path = opt.output;
  const auto s = compute_surfaces(m, profile, profile_name, opt, f, r);
  write_surfaces(s.geometry, f, opt, r,
                 export_info(m.label(), r.units, "kinematic surface of " + profile_name),
                 s.approximation);
  return r;
}

ExportResult export_geometry(const Motion& motion, const Geometry& geometry,
                             const ExportOptions& opt) {
  require_one(geometry, "export");
  if (geometry.point) return export_trajectory(motion, *geometry.point, opt);
  return export_surface(motion, *geometry.profile, geometry.profile_name, opt);
}

json check(const std::string& file, const Motion& motion, const Geometry& geometry, int grid) {
  require_one(geometry, "check");
  return check_geometry(file, motion, geometry.profile, geometry.point, grid);
}

}  // namespace qmotion
