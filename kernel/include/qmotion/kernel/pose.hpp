// <qmotion/kernel/pose.hpp>
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>
#include <qmotion/kernel/dual_quaternion.hpp>

namespace qmotion::kernel {

/// A given position (14): P = (2 + eps s) * r with position s and rotation r (non-zero,
/// not necessarily unit), at parameter t when the input gives one.
template <typename Scalar>
struct Pose {
  std::optional<Scalar> t;
  Eigen::Matrix<Scalar, 3, 1> position;
  Quaternion<Scalar> rotation;

  DualQuaternion<Scalar> dual_quaternion() const {
    return DualQuaternion<Scalar>::pose(position, rotation);
  }
};

/// Scale-free distance between the displacements Q and P (docs/formats.md: proportional dual
/// quaternions are one pose): both are divided by the norm of their real part, the sign
/// that brings them closer is taken, and the largest component difference is divided by
/// max(1, largest component of P) (positions in mm make the dual part large).
inline double pose_residual(const DualQuaternion<double>& q, const DualQuaternion<double>& p) {
  const double nq = std::sqrt(q.real().norm2()), np = std::sqrt(p.real().norm2());
  if (!(nq > 0)) return std::numeric_limits<double>::infinity();
  double plus = 0, minus = 0, ref = 1;
  for (int i = 0; i < 8; ++i) {
    plus = std::max(plus, std::abs(q[i] / nq - p[i] / np));
    minus = std::max(minus, std::abs(q[i] / nq + p[i] / np));
    ref = std::max(ref, std::abs(p[i] / np));
  }
  return std::min(plus, minus) / ref;
}

}  // namespace qmotion::kernel
