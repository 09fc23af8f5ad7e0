// sweep/src/volume_detail.hpp: what the mesher's files (volume_mesh.cpp, volume_adaptive.cpp,
// volume_tets.cpp and volume_written.cpp) share.
#pragma once
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <qmotion/kernel/outward.hpp>
#include <qmotion/motion.hpp>
#include <qmotion/sweep/body.hpp>
#include <qmotion/sweep/swept_volume.hpp>
#include <qmotion/sweep/volume_mesh.hpp>
#include <string>
#include <vector>

namespace qmotion::sweep {
class HullPieces;
}

namespace qmotion::sweep::mesher {

/// A certified enclosing mesh as it will be written (rounded when float32), from either
/// route: V inside, closed, embedded, each vertex within distance_bound (<= T) of V.
struct EnclosingMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  /// Each vertex's bound: the placement the tree's search found for it (signed_upper).
  std::vector<sweep::VolumeDistance> at;
  double distance_bound = 0;
  kernel::Interval enclosed;  ///< the volume inside the mesh before rounding
  double inside_volume = 0;   ///< of cells or tetrahedra certified inside V (rounded down)
  double rounding = 0, level = 0;
  double smallest_cell = 0, largest_cell = 0;  ///< edges of the cells the surface crosses
  bool closed = false;
  int rounds = 0;
  std::size_t queries = 0, cells = 0, pieces = 0;
};

/// The adaptive route (volume_adaptive.cpp), for every body: an octree refined where a
/// triangle or a vertex is not certified.
EnclosingMesh adaptive_mesh(const qmotion::Motion& motion, const sweep::SweptVolumeTree& tree,
                            const sweep::HullPieces& hulls, double T,
                            const VolumeRounding& rounding);

/// Errc::numerical_failure when T is too fine for the octree about box (checked before any
/// work, on the sampled box).
void refuse_octree(const qmotion::Motion& motion, const Eigen::AlignedBox3d& box, double T);

/// The volume inside a closed, outward-oriented mesh (the divergence theorem about `o`),
/// rounded outward: the exact volume of the mesh with these vertices lies in it.
kernel::Interval enclosed_volume(const std::vector<Eigen::Vector3d>& vertices,
                                 const std::vector<std::array<int, 3>>& triangles,
                                 const Eigen::Vector3d& o);

/// Errc::invalid_input: float32 rounding by e is too coarse for the tolerance T.
[[noreturn]] void refuse_float32(const qmotion::Motion& motion, double e, double T,
                                 const VolumeRounding& rounding);
/// Errc::numerical_failure beyond 10^7 triangles.
void refuse_size(const qmotion::Motion& motion, double T, std::size_t triangles);

/// The largest distance float32 rounding moves a point whose coordinates are at most
/// `largest` in magnitude: sqrt(3) 2^-24 largest (round to nearest, normal floats), with a
/// relative 1e-6 for the scaling into the output unit and back.
double float32_rounding(double largest);

/// float32_rounding for the vertices of a mesh within T of box, in the motion's unit.
/// Errc::invalid_input when the coordinates do not fit a float.
double float32_written(const Eigen::AlignedBox3d& box, double T, const VolumeRounding& rounding);

/// Each vertex x replaced by float32(scale x) / scale: the point a binary STL holds, in the
/// motion's unit.
void round_to_float32(std::vector<Eigen::Vector3d>& vertices, double scale);

/// Whether the mesh, welded by its vertices' coordinates as a reader of the written file
/// welds them, has every directed edge once and its reverse once: closed, 2-manifold along
/// its edges and consistently oriented. Measured, on the coordinates as given.
bool closed_as_written(const std::vector<Eigen::Vector3d>& vertices,
                       const std::vector<std::array<int, 3>>& triangles);

}  // namespace qmotion::sweep::mesher
