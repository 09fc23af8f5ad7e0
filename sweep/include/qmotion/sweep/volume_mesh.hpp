// <qmotion/sweep/volume_mesh.hpp>: the certified enclosing mesh of a swept volume, the mesh
// `qmotion volume` writes (docs/guide/volume.md; the constructions and their proofs are in
// docs/geometry.md, "Swept volumes"). Its code is in sweep/src, compiled into libqmotion.
#pragma once
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <optional>
#include <qmotion/motion.hpp>
#include <qmotion/sweep/body.hpp>
#include <vector>

namespace qmotion::sweep {

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
SweptVolume swept_volume(const qmotion::Motion& motion, const Body& body,
                         std::optional<double> tol = std::nullopt,
                         const VolumeRounding& rounding = {});

/// The bounding box of V, sampled: the body's triangulation at 64 times a segment of the
/// motion (not an enclosure; the default tolerances are fractions of its diagonal).
Eigen::AlignedBox3d sampled_swept_box(const qmotion::Motion& motion, const Body& body);

}  // namespace qmotion::sweep
