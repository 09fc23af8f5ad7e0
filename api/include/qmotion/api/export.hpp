// <qmotion/api/export.hpp>: the main job as library calls: exact (or degree-limited) trajectories
// and kinematic surfaces written as JSON, STEP, IGES or STL, and the exactness check that reads
// them back. The CLI commands and the demo call these.
#pragma once
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <qmotion/api/self_intersection.hpp>
#include <qmotion/io/mesh.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/point_text.hpp>
#include <qmotion/motion.hpp>
#include <qmotion/sweep/factors.hpp>
#include <qmotion/sweep/nurbs.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <qmotion/sweep/self_intersection.hpp>
#include <string>

namespace qmotion {

/// The degree of the fitted geometry of a quaternion-spline motion unless --max-degree
/// gives one: error O(h^6), C4 between the motion's keys.
inline constexpr int kQSplineFitDegree = 5;

struct ExportOptions {
  std::string output;  ///< .json, .step/.stp, .igs/.iges (surfaces also .stl, .obj, .ply)
  /// Approximate above this degree (-1: exact only); for a quaternion-spline motion, the
  /// degree of the fit (default kQSplineFitDegree).
  int max_degree = -1;
  double tol = -1;           ///< approximation tolerance (absolute; default 1e-6 x diagonal)
  std::string units;         ///< the unit to convert into and declare (default: the motion's)
  bool single_face = false;  ///< surfaces: one face per profile edge, not split at C0 knots
  bool solid = false;        ///< surfaces: closed planar profile, add caps, one solid
  /// Surfaces: tessellate and look for self-intersections (CGAL); the result says where.
  /// With `solid` or `fail_on_self_intersection`, also the proof on the exact surfaces
  /// (sweep::prove_no_self_intersection).
  bool self_intersection_check = true;
  /// Surfaces: a sweep not proven free of self-intersection (crossing, touching, singular,
  /// or undecided when the budget runs out) is refused (Errc::numerical_failure), and so
  /// with --solid.
  bool fail_on_self_intersection = false;
  /// The patch pairs the proof may examine before it gives up (undecided).
  std::size_t self_intersection_budget = 2'000'000;
  /// Meshes: the largest deviation from the surfaces (absolute; 0: 1e-3 of the size), the
  /// mesher's angular deflection in degrees, ASCII STL/PLY instead of binary.
  double deflection = 0;
  double angle_deg = 20;
  bool ascii = false;
};

/// What was written, for messages and the demo's report.
struct ExportResult {
  std::string path;
  int degree_u = 0, degree_v = 0;
  int inserted_knots = 0;                  ///< for positive weights
  std::optional<double> approx_deviation;  ///< set when approximated (--max-degree, qspline)
  /// Quaternion splines: the proven bound of the fit's deviation (docs/geometry.md).
  std::optional<double> approx_bound;
  std::optional<double> approx_tolerance;  ///< the tolerance it was held to
  int approx_spans = 0;                    ///< quaternion splines: knot spans of the fit
  double min_weight = 0;
  int continuity_u = 0, continuity_v = 0;  ///< lowest continuity the knots declare
  int faces = 1;                           ///< faces written (STEP/IGES shells)
  int poles = 0;                           ///< control points written, all faces
  std::string units;                       ///< the declared unit of the numbers
  double unit_factor = 1;                  ///< motion's unit -> declared unit
  std::optional<double> volume;            ///< --solid: the independent swept volume
  /// Surfaces: what the self-intersection check found (absent when not run).
  std::optional<SelfIntersection> self_intersection;
  /// Surfaces under --solid or --fail-on-self-intersection: the proof on the surfaces
  /// written, their caps included for a solid.
  std::optional<sweep::SelfIntersectionProof> self_intersection_proof;
  /// Meshes: what was written, with its measured deviation.
  std::optional<io::Mesh> mesh;
};

/// Both kinds of motion go through the same calls. A rational motion's geometry is exact;
/// a quaternion spline's (docs/geometry.md) is approximated: its rigid maps [R(t) | p(t)] are
/// fitted once by a matrix B-spline of degree opt.max_degree (default kQSplineFitDegree) on
/// one knot vector holding the keys' knots (sweep::fit_frames), until the trajectories of the
/// point, or of every control point of the profile, are within opt.tol (default 1e-6 of
/// their bounding-box diagonal) on a dense grid; the surfaces, convex combinations of those,
/// are within it too. ExportResult and the JSON's "approximation" record the tolerance, the
/// measured deviation, the degree, the poles and the spans. --solid checks the fitted surface
/// for back-sweep and takes the volume from the motion itself. Errc::numerical_failure when
/// the fit cannot reach the tolerance (65536 spans).

/// The trajectory of the point as NURBS, exact at its minimal degree with positive weights
/// (or approximated above opt.max_degree within opt.tol), in opt.units (default the
/// motion's); nothing is written (opt.output is ignored). `result`, when given, receives
/// degree, continuity, pole count, units and any measured deviation.
sweep::NurbsCurve<double> trajectory_nurbs(const Motion& motion, const Eigen::Vector3d& point,
                                           const ExportOptions& opt = {},
                                           ExportResult* result = nullptr);

/// The kinematic surface of each profile edge as NURBS (u = t, v the edge's parameter;
/// exact, or approximated above opt.max_degree), in opt.units; with opt.solid the profile
/// is checked as for export (closed, planar, no back-sweep) and result->volume is set.
/// Nothing is written.
std::vector<sweep::NurbsSurface<double>> sweep_nurbs(const Motion& motion,
                                                     const sweep::Profile<double>& profile,
                                                     const ExportOptions& opt = {},
                                                     ExportResult* result = nullptr);

ExportResult export_trajectory(const Motion& motion, const Eigen::Vector3d& point,
                               const ExportOptions& opt);
ExportResult export_surface(const Motion& motion, const sweep::Profile<double>& profile,
                            const std::string& profile_name, const ExportOptions& opt);

/// The exactness check: the file's NURBS (read back through OpenCASCADE for STEP/IGES)
/// against the motion applied to the profile (surfaces) or to the point (curves), on a
/// grid x grid lattice plus 400 random parameters per face. Every face is matched to the
/// profile edge it sweeps; planar faces (a solid's caps) are counted. Deviations are in
/// the unit the file declares. A quaternion spline is checked against the spline itself (exp
/// and log of its quaternions), not against the fit. JSON report.
nlohmann::json check_geometry(const std::string& file, const Motion& motion,
                              const std::optional<sweep::Profile<double>>& profile,
                              const std::optional<Eigen::Vector3d>& point, int grid = 41);

/// What a motion makes: the trajectory of a point of the moving space, or the kinematic
/// surface of a profile (named in file headers and messages by profile_name).
struct Geometry {
  std::optional<Eigen::Vector3d> point;
  std::optional<sweep::Profile<double>> profile;
  std::string profile_name = "a profile";

  static Geometry trajectory(const Eigen::Vector3d& p) { return Geometry{p, std::nullopt, {}}; }
  static Geometry sweep(sweep::Profile<double> p, std::string name = "a profile") {
    return Geometry{std::nullopt, std::move(p), std::move(name)};
  }
};

/// export_trajectory or export_surface, as the geometry says; Errc::invalid_input unless
/// exactly one of point and profile is set.
ExportResult export_geometry(const Motion& motion, const Geometry& geometry,
                             const ExportOptions& opt);
/// check_geometry for the geometry's point or profile.
nlohmann::json check(const std::string& file, const Motion& motion, const Geometry& geometry,
                     int grid = 41);

}  // namespace qmotion
