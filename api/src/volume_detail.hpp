// api/src/volume_detail.hpp: what volume.cpp, volume_mesh.cpp and volume_written.cpp share.
#pragma once
#include <Eigen/Geometry>
#include <array>
#include <qmotion/api/volume.hpp>
#include <qmotion/motion.hpp>
#include <qmotion/sweep/body.hpp>
#include <vector>

namespace qmotion::detail {

/// The bounding box of V, sampled: the body's triangulation at 64 times a segment.
Eigen::AlignedBox3d sampled_box(const Motion& m, const sweep::Body& body);

/// The largest distance float32 rounding moves a point whose coordinates are at most
/// `largest` in magnitude: sqrt(3) 2^-24 largest (round to nearest, normal floats), with a
/// relative 1e-6 for the scaling into the output unit and back.
double float32_rounding(double largest);

/// float32_rounding for the vertices of a lattice of step h about box at the tolerance T, in
/// the motion's unit. Errc::invalid_input when the coordinates do not fit a float.
double float32_written(const Eigen::AlignedBox3d& box, double T, double h,
                       const VolumeRounding& rounding);

/// Each vertex x replaced by float32(scale x) / scale: the point a binary STL holds, in the
/// motion's unit.
void round_to_float32(std::vector<Eigen::Vector3d>& vertices, double scale);

/// Whether the mesh, welded by its vertices' coordinates as a reader of the written file
/// welds them, has every directed edge once and its reverse once: closed, 2-manifold along
/// its edges and consistently oriented. Measured, on the coordinates as given.
bool closed_as_written(const std::vector<Eigen::Vector3d>& vertices,
                       const std::vector<std::array<int, 3>>& triangles);

}  // namespace qmotion::detail
