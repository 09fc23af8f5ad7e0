// sweep/factors.hpp
#pragma once
#include <Eigen/Core>
#include <optional>
#include <qmotion/kernel/motion_factors.hpp>

namespace qmotion::sweep {

using kernel::factors_match;
using kernel::MotionFactors;

/// The factors of an interpolation result (Bezier factors on the motion's interval).
template <typename Scalar>
MotionFactors<Scalar> factors_of(const kernel::Interpolation<Scalar>& r,
                                 kernel::TranslationMethod method) {
  using V3 = Eigen::Matrix<Scalar, 3, 1>;
  auto rows = [&](const kernel::MatX<Scalar>& P) {
    std::vector<V3> c;
    for (Eigen::Index j = 0; j < P.rows(); ++j) c.emplace_back(P(j, 0), P(j, 1), P(j, 2));
    return kernel::BSpline<V3>::from_bezier(
        kernel::Bernstein<V3>(std::move(c), r.rotation.a(), r.rotation.b()));
  };
  MotionFactors<Scalar> f{method,
                          kernel::BSpline<kernel::Quaternion<Scalar>>::from_bezier(r.rotation),
                          rows(r.translation), std::nullopt};
  if (method == kernel::TranslationMethod::trt) f.translation2 = rows(r.translation2);
  return f;
}

}  // namespace qmotion::sweep
