// api/src/export.cpp
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <qmotion/api/export.hpp>
#include <qmotion/api/self_intersection.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/mesh.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/io/units.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/approximate.hpp>
#include <qmotion/sweep/fit.hpp>
#include <qmotion/sweep/shell.hpp>
#include <qmotion/sweep/solid.hpp>
#include <qmotion/sweep/surface.hpp>
#include <random>
#include <sstream>

namespace qmotion {
using namespace io;  // NOLINT: the formats this call reads and writes
namespace {

using json = nlohmann::json;

enum class Format { json, step, iges, mesh };

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
  const int limit = occt_max_degree();
  if ((f == Format::step || f == Format::iges) && opt.max_degree > limit)
    throw Error(Errc::invalid_input, "--max-degree " + std::to_string(opt.max_degree) +
                                         ": STEP and IGES (OpenCASCADE) store degrees up to " +
                                         std::to_string(limit));
}

/// Refuses degrees above what the target stores, unless an approximation was asked for.
void check_degree(int degree, const std::string& what, Format f, const ExportOptions& opt) {
  const int limit = occt_max_degree();
  if ((f == Format::step || f == Format::iges) && degree > limit && opt.max_degree < 0)
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

/// The JSON record of an approximation (tolerance and deviation in the declared unit).
json approximation_json(const ExportOptions& opt, const ExportResult& r, double tol) {
  return json{{"max_degree", opt.max_degree},
              {"tolerance", tol * r.unit_factor},
              {"degree", r.degree_u},
              {"measured_deviation", *r.approx_deviation},
              {"max_deviation", *r.approx_deviation},
              {"continuity", r.continuity_u}};
}

/// The exact (or --max-degree approximated) surface of one profile edge, in the motion's
/// unit; `tol_used` receives the approximation tolerance.
sweep::NurbsSurface<double> edge_surface(const kernel::Motion<double>& lm,
                                         const sweep::NurbsCurve<double>& profile,
                                         const ExportOptions& opt, Format f, ExportResult& r,
                                         double& tol_used) {
  if (opt.max_degree > 0) {
    std::vector<sweep::Vec4<double>> X;
    for (std::size_t j = 0; j < profile.points.size(); ++j)
      X.emplace_back(profile.weights[j], profile.weights[j] * profile.points[j](0),
                     profile.weights[j] * profile.points[j](1),
                     profile.weights[j] * profile.points[j](2));
    const auto cols = sweep::trajectories(lm, X);
    if (cols.front().degree() > opt.max_degree) {
      double diag = 0;
      for (const auto& c : cols) diag = std::max(diag, diagonal(curve_samples(c, 100)));
      const double tol = opt.tol > 0 ? opt.tol : 1e-6 * diag;
      tol_used = tol;
      // The columns are fitted within a tolerance; the surface between them is measured at
      // 6 x 6 points in every span of its knots and held to 0.9 of the tolerance, like the
      // columns, tightening the columns' tolerance by halves up to five times.
      const auto params = [](const std::vector<double>& knots) {
        std::vector<double> x;
        for (std::size_t k = 0; k + 1 < knots.size(); ++k)
          if (knots[k + 1] > knots[k])
            for (int i = 0; i < 6; ++i) x.push_back(knots[k] + (knots[k + 1] - knots[k]) * i / 6);
        x.push_back(knots.back());
        return x;
      };
      const std::vector<double> vs = params(profile.knots);
      std::vector<Eigen::Vector3d> section(vs.size());
      for (std::size_t j = 0; j < vs.size(); ++j) section[j] = sweep::evaluate(profile, vs[j]);
      double dev = HUGE_VAL, col_tol = tol;
      sweep::NurbsSurface<double> s;
      for (int attempt = 0; attempt < 6 && !(dev <= 0.9 * tol); ++attempt, col_tol /= 2) {
        const auto approx = sweep::approximate_homogeneous(cols, opt.max_degree, col_tol);
        sweep::HomogeneousSurface<double> hs{approx.curves.front().degree(),
                                             profile.degree,
                                             approx.curves.front().knots(),
                                             profile.knots,
                                             {}};
        hs.poles.assign(approx.curves.front().ctrl().size(),
                        std::vector<sweep::Vec4<double>>(cols.size()));
        for (std::size_t j = 0; j < cols.size(); ++j)
          for (std::size_t i = 0; i < hs.poles.size(); ++i)
            hs.poles[i][j] = approx.curves[j].ctrl()[i];
        s = sweep::to_nurbs(hs);
        dev = 0;
        for (const double u : params(s.knots_u)) {
          const auto m = kernel::evaluate(lm.curve, u);
          for (std::size_t j = 0; j < vs.size(); ++j)
            dev = std::max(
                dev, (sweep::evaluate(s, u, vs[j]) - kernel::apply_point(m, section[j])).norm());
        }
      }
      if (!(dev <= tol))
        throw Error(Errc::numerical_failure,
                    "--max-degree " + std::to_string(opt.max_degree) +
                        ": the approximated surface deviates by " + std::to_string(dev) +
                        ", more than the tolerance " + std::to_string(tol));
      r.approx_deviation = std::max(r.approx_deviation.value_or(0.0), dev);
      return s;
    }
  }
  auto s = sweep::kinematic_nurbs(lm, profile);
  check_degree(s.degree_u, "the surface (along the motion)", f, opt);
  return s;
}

int count_poles(const std::vector<sweep::NurbsSurface<double>>& faces) {
  int n = 0;
  for (const auto& f : faces) n += static_cast<int>(f.points.size() * f.points.front().size());
  return n;
}

}  // namespace

namespace {

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

/// The trajectory NURBS in the declared unit, filling r; f decides the degree limit.
sweep::NurbsCurve<double> compute_trajectory(const kernel::Motion<double>& lm,
                                             const Eigen::Vector3d& point, const ExportOptions& opt,
                                             Format f, ExportResult& r, double& tol) {
  check_max_degree(opt, f);
  sweep::refuse_poles(lm);
  resolve_units(lm.units, opt, r);
  const auto h0 = sweep::point_trajectory(lm, point);
  auto h = h0;
  if (opt.max_degree > 0 && h.degree() > opt.max_degree) {
    tol = opt.tol > 0 ? opt.tol : 1e-6 * std::max(diagonal(curve_samples(h0, 200)), 1e-300);
    const auto approx = sweep::approximate_homogeneous({h0}, opt.max_degree, tol);
    h = approx.curves.front();
    r.approx_deviation = approx.max_deviation * r.unit_factor;
    r.approx_tolerance = tol * r.unit_factor;
  } else {
    check_degree(h.degree(), "the trajectory", f, opt);
    const auto extra = sweep::knots_for_positive_weights(h);
    r.inserted_knots = static_cast<int>(extra.size());
    h = sweep::insert_knots(h, extra);
  }
  sweep::NurbsCurve<double> c = sweep::to_nurbs(h);
  scale_points(c, r.unit_factor);
  r.degree_u = c.degree;
  r.continuity_u = sweep::min_continuity(c.knots, c.degree);
  r.poles = static_cast<int>(c.points.size());
  r.min_weight = min_weight(c.weights);
  return c;
}

}  // namespace

sweep::NurbsCurve<double> trajectory_nurbs(const kernel::Motion<double>& lm,
                                           const Eigen::Vector3d& point, const ExportOptions& opt,
                                           ExportResult* result) {
  ExportResult r;
  double tol = 0;
  auto c = compute_trajectory(lm, point, opt, Format::json, r, tol);
  if (result) *result = r;
  return c;
}

ExportResult export_trajectory(const kernel::Motion<double>& lm, const Eigen::Vector3d& point,
                               const ExportOptions& opt) {
  const Format f = output_format(opt.output, false);
  ExportResult r;
  r.path = opt.output;
  double tol = 0;
  const auto c = compute_trajectory(lm, point, opt, f, r, tol);
  write_curve(c, f, opt.output, r, export_info(lm.label(), r.units, trajectory_what(point)),
              r.approx_deviation ? approximation_json(opt, r, tol) : json());
  return r;
}

namespace {

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

/// Writes the surfaces in the format f: JSON (one surface, or a shell of one face per edge,
/// with units, continuity and any approximation record), STEP or IGES (a shell of C1 faces,
/// or one face per edge with opt.single_face; caps and one solid with opt.solid), or an STL
/// mesh. Sets r.faces and r.poles to what was written.
void write_surfaces(const std::vector<sweep::NurbsSurface<double>>& surfaces, Format f,
                    const ExportOptions& opt, ExportResult& r, const ExportInfo& info,
                    const json& approximation) {
  sweep::NurbsShell<double> shell;
  for (const auto& s : surfaces) {
    if (opt.single_face) {
      shell.faces.push_back(s);
    } else {
      for (auto& piece : sweep::split_c0(s)) shell.faces.push_back(std::move(piece));
    }
    if (opt.solid) {
      shell.cap_start.push_back(sweep::boundary_v_curve(s, false));
      shell.cap_end.push_back(sweep::boundary_v_curve(s, true));
    }
  }
  shell.closed = opt.solid;
  const bool one_surface = surfaces.size() == 1 && !opt.solid;
  switch (f) {
    case Format::json: {  // exact surfaces per edge (JSON readers handle C0 knots)
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

/// The surfaces of the profile's edges in the declared unit, filling r (with the solid's
/// checks and volume for opt.solid); f decides the degree limit.
std::vector<sweep::NurbsSurface<double>> compute_surfaces(const kernel::Motion<double>& lm,
                                                          const sweep::Profile<double>& profile,
                                                          const std::string& profile_name,
                                                          const ExportOptions& opt, Format f,
                                                          ExportResult& r, double& tol) {
  check_max_degree(opt, f);
  sweep::refuse_poles(lm);
  resolve_units(lm.units, opt, r);
  if (f == Format::step || f == Format::iges)
    for (const auto& e : profile.edges) check_degree(e.degree, "the profile", f, ExportOptions{});
  sweep_checks(
      profile, profile_name, opt, r,
      [&](const sweep::PlanarRegion& region) { return sweep::find_backsweep(lm, profile, region); },
      [&](const sweep::PlanarRegion& region) { return sweep::swept_volume(lm, region); },
      [&] { return sweep_self_intersections(lm, profile); });
  std::vector<sweep::NurbsSurface<double>> surfaces;
  for (const auto& e : profile.edges) {
    surfaces.push_back(edge_surface(lm, e, opt, f, r, tol));
    scale_points(surfaces.back(), r.unit_factor);
  }
  if (r.approx_deviation) {
    *r.approx_deviation *= r.unit_factor;
    r.approx_tolerance = tol * r.unit_factor;
  }
  summarize_surfaces(surfaces, r);
  return surfaces;
}

}  // namespace

std::vector<sweep::NurbsSurface<double>> sweep_nurbs(const kernel::Motion<double>& lm,
                                                     const sweep::Profile<double>& profile,
                                                     const ExportOptions& opt,
                                                     ExportResult* result) {
  ExportResult r;
  double tol = 0;
  auto s = compute_surfaces(lm, profile, "the profile", opt, Format::json, r, tol);
  r.faces = static_cast<int>(s.size());
  r.poles = count_poles(s);
  if (result) *result = r;
  return s;
}

ExportResult export_surface(const kernel::Motion<double>& lm, const sweep::Profile<double>& profile,
                            const std::string& profile_name, const ExportOptions& opt) {
  const Format f = surface_format(opt);
  ExportResult r;
  r.path = opt.output;
  double tol = 0;
  const auto surfaces = compute_surfaces(lm, profile, profile_name, opt, f, r, tol);
  write_surfaces(surfaces, f, opt, r,
                 export_info(lm.label(), r.units, "kinematic surface of " + profile_name),
                 r.approx_deviation ? approximation_json(opt, r, tol) : json());
  return r;
}

namespace {

/// Our name of the unit a STEP/IGES reader reports ("" or an unknown name: `fallback`).
std::string cad_unit(const std::string& name, const std::string& fallback) {
  if (name == "mm" || name == "millimetre" || name == "millimeter") return "mm";
  if (name == "cm" || name == "centimetre" || name == "centimeter") return "cm";
  if (name == "m" || name == "metre" || name == "meter") return "m";
  if (name == "in" || name == "inch") return "in";
  if (name == "ft" || name == "foot") return "ft";
  if (name == "um" || name == "micrometre" || name == "micrometer" || name == "micron") return "um";
  return fallback;
}

/// A face to check: its parameter box, how OpenCASCADE or our reader evaluates it, and
/// whether its weights are positive.
struct CheckFace {
  double u0, u1, v0, v1;
  std::function<Eigen::Vector3d(double, double)> value;
  bool weights_positive = true;
  int degree_u = 0, degree_v = 0;
};

CheckFace check_face(const sweep::NurbsSurface<double>& s,
                     std::function<Eigen::Vector3d(double, double)> value) {
  CheckFace c{s.knots_u.front(), s.knots_u.back(), s.knots_v.front(), s.knots_v.back(),
              std::move(value)};
  if (!c.value) c.value = [s](double u, double v) { return sweep::evaluate(s, u, v); };
  for (const auto& row : s.weights)
    for (double w : row) c.weights_positive = c.weights_positive && w > 0;
  c.degree_u = s.degree_u;
  c.degree_v = s.degree_v;
  return c;
}

/// A curve to check, as a face of one parameter.
CheckFace check_curve(const sweep::NurbsCurve<double>& c,
                      std::function<Eigen::Vector3d(double, double)> value) {
  CheckFace f{c.knots.front(), c.knots.back(), 0, 0, std::move(value)};
  for (double w : c.weights) f.weights_positive = f.weights_positive && w > 0;
  f.degree_u = c.degree;
  return f;
}

}  // namespace

namespace {

/// A motion as check_geometry sees it: its interval, unit and the image place(t, x).
struct Placement {
  double a, b;
  std::string units;
  std::function<Eigen::Vector3d(double, const Eigen::Vector3d&)> place;
};

json check_placement(const std::string& file, const Placement& lm,
                     const std::optional<sweep::Profile<double>>& profile,
                     const std::optional<Eigen::Vector3d>& point, int grid) {
  const bool surface = profile.has_value();
  const std::string e = lower_extension(file);
  std::vector<CheckFace> faces;
  int planar_faces = 0;
  std::string file_units = lm.units;
  json out{{"file", file}, {"kind", surface ? "surface" : "curve"}};
  if (e == ".json") {
    const json doc = read_json_file(file);
    if (doc.is_object() && doc.contains("units") && doc["units"].is_string())
      file_units = canonical_unit(doc["units"].get<std::string>(), file + ": units");
    if (surface) {
      if (doc.is_object() && doc.value("type", "") == "nurbs_shell") {
        if (!doc.contains("faces") || !doc["faces"].is_array() || doc["faces"].empty())
          throw Error(Errc::invalid_input, file + ": faces: expected an array of nurbs_surface");
        for (std::size_t k = 0; k < doc["faces"].size(); ++k)
          faces.push_back(check_face(
              surface_from_json(doc["faces"][k], file + ": face " + std::to_string(k + 1)),
              nullptr));
      } else {
        faces.push_back(check_face(surface_from_json(doc, file), nullptr));
      }
    } else {
      const auto c = curve_from_json(doc, file);
      faces.push_back(check_curve(c, [c](double t, double) { return sweep::evaluate(c, t); }));
    }
    out["reader"] = "qmotion JSON";
  } else {
    // Read in the motion's unit (OpenCASCADE converts); deviations are reported in the
    // unit the file declares.
    const CadGeometry g = read_cad(file, surface, lm.units);
    if (surface) {
      for (const auto& cf : g.face_list) {
        if (cf.is_plane) {
          ++planar_faces;
          continue;
        }
        faces.push_back(check_face(cf.surface, cf.value));
      }
    } else {
      faces.push_back(check_curve(g.curve, g.value));
    }
    out["reader"] = "OpenCASCADE " + std::string(e == ".igs" || e == ".iges" ? "IGES" : "STEP");
    out["valid"] = g.valid;
    out["faces"] = g.faces;
    out["edges"] = g.edges;
    out["shells"] = g.shells;
    out["solids"] = g.solids;
    out["closed"] = g.closed;
    out["file_units"] = g.file_units;
    file_units = cad_unit(g.file_units, lm.units);
    if (g.solids > 0) out["volume"] = g.volume * std::pow(unit_factor(lm.units, file_units), 3);
  }
  // The file's numbers are in file_units; the motion's in lm.units. For STEP/IGES the
  // reader already converted into the motion's unit: scale only the reported deviation.
  const bool cad = e != ".json";
  const double k = unit_factor(lm.units, file_units);
  const double a = lm.a, b = lm.b;
  std::mt19937 rng(20261122);
  double dev = 0, u_lo = faces.front().u0, u_hi = faces.front().u1;
  bool weights_positive = true;
  std::vector<Eigen::Vector3d> ref;
  std::size_t samples = 0;
  const std::vector<sweep::NurbsCurve<double>> edges =
      surface ? profile->edges : std::vector<sweep::NurbsCurve<double>>{};
  std::vector<double> covered(edges.size(), 0.0);  // parameter area matched per edge
  for (const auto& face : faces) {
    weights_positive = weights_positive && face.weights_positive;
    u_lo = std::min(u_lo, face.u0);
    u_hi = std::max(u_hi, face.u1);
    std::vector<std::pair<double, double>> params;
    for (int i = 0; i <= grid; ++i)
      for (int j = 0; j <= (surface ? grid : 0); ++j)
        params.emplace_back(face.u0 + (face.u1 - face.u0) * i / grid,
                            face.v0 + (face.v1 - face.v0) * j / std::max(grid, 1));
    std::uniform_real_distribution<double> uu(face.u0, face.u1),
        vv(face.v0, surface ? face.v1 : face.v0 + 1);
    for (int s = 0; s < 400; ++s) params.emplace_back(uu(rng), surface ? vv(rng) : face.v0);
    samples += params.size();
    std::vector<Eigen::Vector3d> got;
    for (const auto& [u, v] : params) got.push_back(face.value(u, v) * (cad ? 1.0 : 1.0 / k));
    // The profile edge this face sweeps: the one it matches best.
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_edge = 0;
    std::vector<Eigen::Vector3d> best_ref;
    for (std::size_t ed = 0; ed < (surface ? edges.size() : 1); ++ed) {
      if (surface && (face.v0 < edges[ed].knots.front() || face.v1 > edges[ed].knots.back()))
        continue;
      double worst = 0;
      std::vector<Eigen::Vector3d> r_ed;
      for (std::size_t s = 0; s < params.size(); ++s) {
        const double u = std::clamp(params[s].first, a, b);
        const Eigen::Vector3d exact =
            lm.place(u, surface ? sweep::evaluate(edges[ed], params[s].second) : *point);
        r_ed.push_back(exact);
        worst = std::max(worst, (got[s] - exact).norm());
        if (!(worst < best)) break;  // cannot beat the best edge
      }
      if (worst < best) {
        best = worst;
        best_edge = ed;
        best_ref = std::move(r_ed);
      }
    }
    if (best_ref.empty())
      throw Error(Errc::invalid_input, file + ": a face's v range [" + std::to_string(face.v0) +
                                           ", " + std::to_string(face.v1) +
                                           "] lies in no profile edge's parameter range");
    dev = std::max(dev, best);
    ref.insert(ref.end(), best_ref.begin(), best_ref.end());
    if (surface) covered[best_edge] += (face.u1 - face.u0) * (face.v1 - face.v0);
  }
  const double diag = diagonal(ref);
  out["samples"] = samples;
  out["max_deviation"] = dev * k;
  out["bbox_diagonal"] = diag * k;
  out["relative_deviation"] = diag > 0 ? dev / diag : dev;
  out["units"] = file_units;
  out["degree_u"] = faces.front().degree_u;
  if (surface) {
    out["degree_v"] = faces.front().degree_v;
    out["checked_faces"] = faces.size();
    out["planar_faces"] = planar_faces;
    bool cover = true;
    for (std::size_t ed = 0; ed < edges.size(); ++ed) {
      const double want = (b - a) * (edges[ed].knots.back() - edges[ed].knots.front());
      cover = cover && std::abs(covered[ed] - want) <= 1e-9 * want;
    }
    out["faces_cover_profile"] = cover;
  }
  out["weights_positive"] = weights_positive;
  out["param_range"] = {u_lo, u_hi};
  out["param_range_matches_motion"] =
      std::abs(u_lo - a) <= 1e-12 * (b - a) && std::abs(u_hi - b) <= 1e-12 * (b - a);
  return out;
}

}  // namespace

json check_geometry(const std::string& file, const kernel::Motion<double>& lm,
                    const std::optional<sweep::Profile<double>>& profile,
                    const std::optional<Eigen::Vector3d>& point, int grid) {
  json out =
      check_placement(file,
                      Placement{lm.a(), lm.b(), lm.units,
                                [&](double t, const Eigen::Vector3d& x) {
                                  return kernel::apply_point(kernel::evaluate(lm.curve, t), x);
                                }},
                      profile, point, grid);
  out["motion"] = "q-motion (rational, evaluated exactly in double)";
  return out;
}

json check_geometry(const std::string& file, const QSplineMotion& m,
                    const std::optional<sweep::Profile<double>>& profile,
                    const std::optional<Eigen::Vector3d>& point, int grid) {
  const kernel::QuaternionSpline& s = m.spline;
  json out =
      check_placement(file,
                      Placement{s.a(), s.b(), m.units,
                                [&](double t, const Eigen::Vector3d& x) { return s.place(t, x); }},
                      profile, point, grid);
  out["motion"] = std::string("quaternion-spline ") + kernel::to_string(s.scheme) +
                  " (the motion itself: exp and log of its quaternions, not the fit)";
  return out;
}

// ---------------------------------------------------------------------------------------
// Non-rational motions (docs/geometry.md): the rigid maps fitted once on one knot vector
// (sweep::fit_frames); trajectories and surfaces are that matrix spline applied to points.

namespace {

/// The fit for the given points (Cartesian, the motion's unit), with the tolerance used.
struct QSplineFit {
  sweep::FrameFit fit;
  double tol = 0;
};

QSplineFit fit_qspline(const QSplineMotion& m, const std::vector<Eigen::Vector3d>& pts,
                       const ExportOptions& opt, Format f) {
  check_max_degree(opt, f);
  const kernel::QuaternionSpline& s = m.spline;
  sweep::FrameFitOptions fo;
  fo.degree = opt.max_degree > 0 ? opt.max_degree : kQSplineFitDegree;
  if (opt.tol > 0) {
    fo.tol = opt.tol;
  } else {  // 1e-6 of the bounding-box diagonal of the points' trajectories
    std::vector<Eigen::Vector3d> samples;
    for (int i = 0; i <= 400; ++i) {
      const double t = s.a() + (s.b() - s.a()) * i / 400;
      const auto q = s.rotation(t);
      const Eigen::Vector3d p = s.position(t);
      for (const auto& x : pts) samples.push_back(kernel::rotate(q, x) + p);
    }
    fo.tol = 1e-6 * std::max(diagonal(samples), 1e-300);
  }
  try {
    return {sweep::fit_frames([&](double t) { return s.frame(t); }, s.knots,
                              s.interior_continuity(), pts, fo),
            fo.tol};
  } catch (const Error& e) {
    throw Error(e.code(), m.label() + ": " + e.what());
  }
}

/// The approximation record of a fitted export (tolerance and deviation in the declared
/// unit).
json fit_json(const QSplineFit& q, const ExportResult& r) {
  return json{{"method", "least-squares fit of the rigid maps on one knot vector (SPEC 3)"},
              {"tolerance", q.tol * r.unit_factor},
              {"measured_deviation", q.fit.max_deviation * r.unit_factor},
              {"max_deviation", q.fit.max_deviation * r.unit_factor},
              {"degree", q.fit.matrix.degree()},
              {"poles_per_curve", q.fit.matrix.ctrl().size()},
              {"spans", q.fit.spans},
              {"check_samples", q.fit.check_samples},
              {"continuity", r.continuity_u}};
}

void record_fit(const QSplineFit& q, ExportResult& r) {
  r.approx_deviation = q.fit.max_deviation * r.unit_factor;
  r.approx_tolerance = q.tol * r.unit_factor;
  r.approx_spans = q.fit.spans;
}

sweep::NurbsCurve<double> compute_trajectory(const QSplineMotion& m, const Eigen::Vector3d& point,
                                             const ExportOptions& opt, Format f, ExportResult& r,
                                             QSplineFit& q) {
  resolve_units(m.units, opt, r);
  q = fit_qspline(m, {point}, opt, f);
  sweep::NurbsCurve<double> c = sweep::to_nurbs(
      sweep::apply(q.fit.matrix, sweep::Vec4<double>(1, point(0), point(1), point(2))));
  scale_points(c, r.unit_factor);
  record_fit(q, r);
  r.degree_u = c.degree;
  r.continuity_u = sweep::min_continuity(c.knots, c.degree);
  r.poles = static_cast<int>(c.points.size());
  r.min_weight = min_weight(c.weights);
  return c;
}

std::vector<sweep::NurbsSurface<double>> compute_surfaces(const QSplineMotion& m,
                                                          const sweep::Profile<double>& profile,
                                                          const std::string& profile_name,
                                                          const ExportOptions& opt, Format f,
                                                          ExportResult& r, QSplineFit& q) {
  resolve_units(m.units, opt, r);
  if (f == Format::step || f == Format::iges)
    for (const auto& e : profile.edges) check_degree(e.degree, "the profile", f, ExportOptions{});
  std::vector<Eigen::Vector3d> pts;
  for (const auto& e : profile.edges) pts.insert(pts.end(), e.points.begin(), e.points.end());
  if (pts.empty())
    throw Error(Errc::invalid_input, "the profile " + profile_name + " has no edges");
  q = fit_qspline(m, pts, opt, f);
  const kernel::QuaternionSpline& s = m.spline;
  const auto& M = q.fit.matrix;
  sweep_checks(
      profile, profile_name, opt, r,
      [&](const sweep::PlanarRegion& region) {  // on the fitted surface that is written
        std::vector<kernel::BSpline<Eigen::Vector4d>> cols;
        for (const auto& X : sweep::homogeneous_points(profile)) cols.push_back(sweep::apply(M, X));
        return sweep::find_backsweep(
            cols, sweep::apply(
                      M, Eigen::Vector4d(0, region.normal(0), region.normal(1), region.normal(2))));
      },
      [&](const sweep::PlanarRegion& region) {  // of the motion itself: A |integral n . c'|
        return region.area * std::abs(sweep::detail::integrate(
                                 s.knots,
                                 [&](double t) {
                                   return kernel::rotate(s.rotation(t), region.normal)
                                       .dot(s.point_velocity(t, region.centroid));
                                 },
                                 64));
      },
      [&] { return sweep_self_intersections(s, profile); });
  std::vector<sweep::NurbsSurface<double>> surfaces;
  for (const auto& e : profile.edges) {
    sweep::HomogeneousSurface<double> hs{M.degree(), e.degree, M.knots(), e.knots, {}};
    hs.poles.assign(M.ctrl().size(), std::vector<sweep::Vec4<double>>(e.points.size()));
    for (std::size_t j = 0; j < e.points.size(); ++j) {
      const sweep::Vec4<double> X(e.weights[j], e.weights[j] * e.points[j](0),
                                  e.weights[j] * e.points[j](1), e.weights[j] * e.points[j](2));
      for (std::size_t i = 0; i < M.ctrl().size(); ++i) hs.poles[i][j] = M.ctrl()[i] * X;
    }
    surfaces.push_back(sweep::to_nurbs(hs));
    scale_points(surfaces.back(), r.unit_factor);
  }
  record_fit(q, r);
  summarize_surfaces(surfaces, r);
  return surfaces;
}

}  // namespace

sweep::NurbsCurve<double> trajectory_nurbs(const QSplineMotion& m, const Eigen::Vector3d& point,
                                           const ExportOptions& opt, ExportResult* result) {
  ExportResult r;
  QSplineFit q;
  auto c = compute_trajectory(m, point, opt, Format::json, r, q);
  if (result) *result = r;
  return c;
}

std::vector<sweep::NurbsSurface<double>> sweep_nurbs(const QSplineMotion& m,
                                                     const sweep::Profile<double>& profile,
                                                     const ExportOptions& opt,
                                                     ExportResult* result) {
  ExportResult r;
  QSplineFit q;
  auto s = compute_surfaces(m, profile, "the profile", opt, Format::json, r, q);
  r.faces = static_cast<int>(s.size());
  r.poles = count_poles(s);
  if (result) *result = r;
  return s;
}

ExportResult export_trajectory(const QSplineMotion& m, const Eigen::Vector3d& point,
                               const ExportOptions& opt) {
  const Format f = output_format(opt.output, false);
  ExportResult r;
  r.path = opt.output;
  QSplineFit q;
  const auto c = compute_trajectory(m, point, opt, f, r, q);
  write_curve(c, f, opt.output, r, export_info(m.label(), r.units, trajectory_what(point)),
              fit_json(q, r));
  return r;
}

ExportResult export_surface(const QSplineMotion& m, const sweep::Profile<double>& profile,
                            const std::string& profile_name, const ExportOptions& opt) {
  const Format f = surface_format(opt);
  ExportResult r;
  r.path = opt.output;
  QSplineFit q;
  const auto surfaces = compute_surfaces(m, profile, profile_name, opt, f, r, q);
  write_surfaces(surfaces, f, opt, r,
                 export_info(m.label(), r.units, "kinematic surface of " + profile_name),
                 fit_json(q, r));
  return r;
}

namespace {
void require_one(const Geometry& g, const char* what) {
  if (g.point.has_value() == g.profile.has_value())
    throw Error(Errc::invalid_input, std::string(what) + ": give exactly one of profile and point");
}
}  // namespace

ExportResult export_geometry(const kernel::Motion<double>& motion, const Geometry& geometry,
                             const ExportOptions& opt) {
  require_one(geometry, "export");
  if (geometry.point) return export_trajectory(motion, *geometry.point, opt);
  return export_surface(motion, *geometry.profile, geometry.profile_name, opt);
}

json check(const std::string& file, const kernel::Motion<double>& motion, const Geometry& geometry,
           int grid) {
  require_one(geometry, "check");
  return check_geometry(file, motion, geometry.profile, geometry.point, grid);
}

ExportResult export_geometry(const QSplineMotion& motion, const Geometry& geometry,
                             const ExportOptions& opt) {
  require_one(geometry, "export");
  if (geometry.point) return export_trajectory(motion, *geometry.point, opt);
  return export_surface(motion, *geometry.profile, geometry.profile_name, opt);
}

json check(const std::string& file, const QSplineMotion& motion, const Geometry& geometry,
           int grid) {
  require_one(geometry, "check");
  return check_geometry(file, motion, geometry.profile, geometry.point, grid);
}

ExportResult export_geometry(const AnyMotion& motion, const Geometry& geometry,
                             const ExportOptions& opt) {
  return std::visit([&](const auto& m) { return export_geometry(m, geometry, opt); }, motion);
}

json check(const std::string& file, const AnyMotion& motion, const Geometry& geometry, int grid) {
  return std::visit([&](const auto& m) { return check(file, m, geometry, grid); }, motion);
}

}  // namespace qmotion
