// <qmotion/api/volume.hpp>: `qmotion volume`: the space a moving solid occupies, as a closed
// mesh that encloses it for certain and whose vertices lie within a tolerance of it
// (docs/guide/volume.md).
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <qmotion/motion.hpp>
#include <qmotion/render/render.hpp>
#include <qmotion/sweep/body.hpp>
#include <qmotion/sweep/pipe.hpp>
#include <string>
#include <vector>

namespace qmotion {

/// The swept volume V = { M(t) x : t in [a, b], x in the body } enclosed by a triangle mesh,
/// in the motion's length unit. Certified (docs/geometry.md, "Swept volumes"):
/// - the mesh is closed, 2-manifold, outward-oriented and free of self-intersections, and
///   V lies inside it;
/// - every vertex lies within distance_bound <= tolerance of V;
/// - volume_lower <= vol(V) <= volume_upper.
struct SweptVolume {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;  ///< 0-based, counter-clockwise from outside
  double tolerance = 0;
  double distance_bound = 0;     ///< certified, over every vertex
  double measured_distance = 0;  ///< the vertices' distance refined by a search on t
  std::size_t measured_vertices = 0;
  double volume_lower = 0, volume_upper = 0;
  double grid_step = 0;           ///< the smallest edge of a cell the surface crosses
  double largest_cell = 0;        ///< and the largest
  std::size_t surface_cells = 0;  ///< the octree's leaves the surface crosses
  std::size_t hull_pieces = 0;    ///< the pieces of time that cover V (per part of a mesh)
  double level = 0;               ///< the level of the distance bound the surface follows
  std::size_t time_pieces = 0;    ///< leaves of the parameter tree
  double piece_delta = 0;         ///< their largest certified radius of motion
  std::size_t distance_queries = 0;
  int rounds = 0;  ///< the octree's rounds of refinement
  /// VolumeRounding::float32: the largest distance a vertex may move when its coordinates
  /// are rounded to float32; the mesh encloses V grown by it, and the vertices (and so
  /// distance_bound) are the rounded ones. 0 when the vertices are written as doubles.
  double rounding = 0;
  /// Measured on the vertices as written (welded by their written coordinates, as a reader
  /// of an STL file welds them): every directed edge once, and its reverse once.
  bool closed = false;
};

/// How the mesh's vertices will be written, so that what is certified is what is written
/// (docs/guide/volume.md, "What is written is what was certified").
struct VolumeRounding {
  bool float32 = false;  ///< coordinates rounded to float32 (binary STL)
  double scale = 1;      ///< output unit per motion unit: the file holds float32(scale * x)
};

/// The swept volume of body under the motion (either kind), every vertex within tol (motion
/// unit; unset: 1e-3 of the bounding-box diagonal of V, sampled). Errc::invalid_input for a
/// bad body or tolerance; Errc::numerical_failure for a rational motion with a pole on its
/// interval, or a tolerance too fine for the memory. With rounding.float32, the vertices are
/// float32(scale * x) / scale, certified as they are; Errc::invalid_input when float32 is too
/// coarse for the tolerance at the volume's coordinates.
SweptVolume swept_volume(const Motion& motion, const sweep::Body& body,
                         std::optional<double> tol = std::nullopt,
                         const VolumeRounding& rounding = {});

/// The exact faces of the volume a sphere sweeps: for `sphere:r` the body itself, for
/// `cutter:ball,D,L` its ball (centre (0, 0, D/2) of the moving frame, radius D/2; the shank
/// is not part of them). The pipe around the centre's trajectory and its two half-sphere
/// caps, as one closed shell of rational faces in the motion's unit (sweep::pipe_shell;
/// docs/geometry.md, "Exact pipe surfaces"). Errc::invalid_input for another body, a
/// quaternion-spline motion (its trajectories are not rational) or a path with a corner;
/// Errc::numerical_failure for a pole or a cusp.
sweep::PipeShell exact_swept_volume(const Motion& motion, const sweep::Body& body);

/// Whether exact_swept_volume takes the body (a sphere or a ball cutter).
bool has_exact_swept_volume(const sweep::Body& body);

struct VolumeOptions {
  /// .stl, .obj, .ply: the enclosing mesh; .step/.stp, .igs/.iges: the exact faces
  /// (exact_swept_volume's bodies); .json: the exact faces as a nurbs_shell for those bodies
  /// under a rational motion, otherwise the mesh and its report.
  std::string output;
  std::string body;  ///< io::read_body's forms (required)
  /// In the output unit; unset: 1e-3 of V's diagonal (a mesh); beside exact faces, the
  /// tolerance of the certified volume bounds, unset: 1e-2 of the diagonal, at most r / 4.
  std::optional<double> tol;
  std::string units;   ///< the output unit (default the motion's)
  bool ascii = false;  ///< STL and PLY as text
};

/// What `qmotion volume` prints: SweptVolume's figures in the output unit, and the file.
struct VolumeReport {
  std::string path, body, units;
  SweptVolume volume;  ///< scaled into units (without the mesh)
  std::size_t triangles = 0, vertices = 0;
  /// Exact faces written (exact_swept_volume), with their figures in `units`; their volume
  /// bounds come from the enclosing mesh at the tolerance (the sphere only).
  bool exact = false;
  std::size_t faces = 0, pipe_faces = 0, pieces = 0;
  int degree = 0;
  double radius = 0, orthogonality = 0, radius_deviation = 0, exact_volume = 0;
  std::string exact_part;  ///< "the sphere", or the ball of a ball cutter (its shank left out)
  /// The proof that the pipe does not overlap itself (sweep::pipe_overlap_free): a lower
  /// bound of the path's least radius of curvature, and the pieces and pairs it took.
  double curvature_radius = 0;
  std::size_t reach_pieces = 0, reach_pairs = 0;
  /// STEP/IGES of a pipe above the degree they store (a tilting ball cutter's): faces of
  /// degree 9 within approximation_bound (proven) of the exact ones of exact_degree.
  bool approximated = false;
  double approximation_bound = 0;
  int exact_degree = 0;
  bool has_bounds = true;
  bool closed = false;
  double seconds = 0;
  nlohmann::json report() const;
};

/// Writes the body's swept volume to options.output: the enclosing mesh, or the exact faces
/// (VolumeOptions::output). Errc::invalid_input (nothing written) for an unknown extension,
/// STEP or IGES for a body without exact faces or a quaternion-spline motion, a missing or
/// bad body, a bad tolerance or unit; Errc::numerical_failure for a pole, or exact faces of
/// a degree above what STEP/IGES (OpenCASCADE) store.
VolumeReport volume(const Motion& motion, const VolumeOptions& options);

/// `qmotion render --body B`: render::render's figure with the body's swept volume drawn
/// among it, as shaded triangles: swept_volume's enclosing mesh at tol (the motion's unit;
/// unset: 1e-2 of the volume's bounding-box diagonal). Errc::invalid_input for a bad body or
/// tolerance and render's own refusals; nothing is written then.
render::RenderResult render_volume(const Motion& motion, render::RenderOptions options,
                                   const std::string& body,
                                   std::optional<double> tol = std::nullopt);

/// `qmotion check VOLUME --motion M --body B`: a volume mesh checked by sampling of its own,
/// independent of how it was made (CGAL's point-in-mesh test, a search on t):
/// - `samples` points of the swept volume (at random t: on the body's boundary, vertices of
///   its triangulation within 1e-4 of its radius, and midpoints of two such inside it) and
///   how many lie outside the mesh (`outside`; `encloses` when none);
/// - the largest distance to the swept volume of up to 20 000 of its vertices, each by 256
///   times and golden sections (`vertex_distance`, an upper bound of each);
/// - triangles, vertices, its volume, closed and oriented (else refused as a body is).
/// The mesh is in the motion's unit (STL, OBJ, PLY) or declares it (`qmotion volume`'s
/// JSON). Errc::invalid_input for an open mesh or a bad body; needs CGAL.
nlohmann::json check_volume(const std::string& path, const Motion& motion, const std::string& body,
                            int samples = 20000);

}  // namespace qmotion
