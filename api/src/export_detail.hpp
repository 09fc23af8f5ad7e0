// api/src/export_detail.hpp: what the export calls share (private to api/): the output
// formats, the checks of options and degrees, unit handling, and the two routes from a motion
// to NURBS: exact for a rational motion (export_exact.cpp), fitted for a quaternion spline
// (export_fitted.cpp).
#pragma once
#include <Eigen/Core>
#include <functional>
#include <nlohmann/json.hpp>
#include <qmotion/api/export.hpp>
#include <qmotion/motion.hpp>
#include <qmotion/sweep/solid.hpp>
#include <string>
#include <vector>

namespace qmotion::detail {

enum class Format { json, step, iges, mesh };

/// The format of a file name: .json, .step/.stp, .igs/.iges, and with allow_stl a mesh.
Format output_format(const std::string& path, bool allow_stl);
/// A surface's output format, with the mesh options checked before any work.
Format surface_format(const ExportOptions& opt);
/// Refuses a --max-degree below 1 (-1 means none) or, for STEP/IGES, above what
/// OpenCASCADE stores.
void check_max_degree(const ExportOptions& opt, Format f);
/// Refuses degrees above what the target stores, unless an approximation was asked for.
void check_degree(int degree, const std::string& what, Format f, const ExportOptions& opt);
/// The bounding-box diagonal of the points.
double diagonal(const std::vector<Eigen::Vector3d>& pts);
/// n + 1 Cartesian points of a homogeneous curve at uniform parameters.
std::vector<Eigen::Vector3d> curve_samples(const kernel::BSpline<Eigen::Vector4d>& h, int n);
double min_weight(const std::vector<double>& w);
/// Scales Cartesian poles into another unit (weights and knots unchanged).
void scale_points(sweep::NurbsCurve<double>& c, double k);
void scale_points(sweep::NurbsSurface<double>& s, double k);
/// The declared unit and the factor from the motion's unit into it (--units converts).
void resolve_units(const std::string& motion_units, const ExportOptions& opt, ExportResult& r);
/// Degrees, lowest continuities and smallest weight of the surfaces, into r.
void summarize_surfaces(const std::vector<sweep::NurbsSurface<double>>& surfaces, ExportResult& r);
/// What a sweep is checked for before it is built: with opt.solid a closed planar profile
/// whose region never sweeps back (`backsweep`) and its volume (`volume`, in the motion's
/// unit); the self-intersection check (`self_intersection`) unless switched off, refused
/// with --fail-on-self-intersection or --solid.
void sweep_checks(
    const sweep::Profile<double>& profile, const std::string& profile_name,
    const ExportOptions& opt, ExportResult& r,
    const std::function<sweep::BacksweepResult(const sweep::PlanarRegion&)>& backsweep,
    const std::function<double(const sweep::PlanarRegion&)>& volume,
    const std::function<SelfIntersection()>& self_intersection);

/// The self-intersection check of the sweep of `profile` (CGAL); none in a build without it.
inline std::function<SelfIntersection()> self_intersection_check(
    const Motion& m, const sweep::Profile<double>& profile) {
#ifdef QMOTION_WITH_CGAL
  return [&m, &profile] { return sweep_self_intersections(m, profile); };
#else
  (void)m;
  (void)profile;
  return {};
#endif
}

/// Geometry in the declared unit and its file's approximation record (null when exact).
template <typename Geometry>
struct Computed {
  Geometry geometry;
  nlohmann::json approximation;
};

/// A rational motion's trajectory: exact at its minimal degree with positive weights, or
/// approximated above opt.max_degree; fills r; f decides the degree limit.
Computed<sweep::NurbsCurve<double>> exact_trajectory(const kernel::Motion<double>& lm,
                                                     const Eigen::Vector3d& point,
                                                     const ExportOptions& opt, Format f,
                                                     ExportResult& r);
/// A rational motion's surfaces of the profile's edges, filling r (with the solid's checks
/// and volume for opt.solid).
Computed<std::vector<sweep::NurbsSurface<double>>> exact_surfaces(
    const Motion& m, const sweep::Profile<double>& profile, const std::string& profile_name,
    const ExportOptions& opt, Format f, ExportResult& r);
/// A quaternion spline's trajectory and surfaces: its rigid maps fitted once on one knot
/// vector (sweep::fit_frames), the geometry that matrix spline applied to points.
Computed<sweep::NurbsCurve<double>> fitted_trajectory(const Motion& m, const Eigen::Vector3d& point,
                                                      const ExportOptions& opt, Format f,
                                                      ExportResult& r);
Computed<std::vector<sweep::NurbsSurface<double>>> fitted_surfaces(
    const Motion& m, const sweep::Profile<double>& profile, const std::string& profile_name,
    const ExportOptions& opt, Format f, ExportResult& r);

}  // namespace qmotion::detail
