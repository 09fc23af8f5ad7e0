// api/src/volume_detail.hpp: what volume.cpp and volume_mesh.cpp share.
#pragma once
#include <Eigen/Geometry>
#include <qmotion/motion.hpp>
#include <qmotion/sweep/body.hpp>

namespace qmotion::detail {

/// The bounding box of V, sampled: the body's triangulation at 64 times a segment.
Eigen::AlignedBox3d sampled_box(const Motion& m, const sweep::Body& body);

}  // namespace qmotion::detail
