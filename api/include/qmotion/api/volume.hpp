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
#include <qmotion/sweep/volume_mesh.hpp>
#include <string>
#include <vector>

namespace qmotion {

using sweep::swept_volume;
using sweep::SweptVolume;
using sweep::VolumeRounding;

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
