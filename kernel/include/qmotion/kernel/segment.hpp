// <qmotion/kernel/segment.hpp>: the distance from a point to a segment, which the toolpath's
// chords and the fit's polyline both measure.
#pragma once
#include <Eigen/Core>
#include <algorithm>

namespace qmotion::kernel {

/// Distance from x to the segment [a, b] (to a when they coincide).
inline double point_segment_distance(const Eigen::Vector3d& x, const Eigen::Vector3d& a,
                                     const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double l2 = ab.squaredNorm();
  const double s = l2 > 0 ? std::clamp((x - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (x - (a + s * ab)).norm();
}

}  // namespace qmotion::kernel
