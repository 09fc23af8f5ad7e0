// <qmotion/kernel/motion_value.hpp>
#pragma once
#include <algorithm>
#include <optional>
#include <qmotion/kernel/methods.hpp>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/kernel/motion_factors.hpp>
#include <qmotion/kernel/pose.hpp>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace qmotion::kernel {

/// How an interpolated motion was made: the method, its degrees, and the input it
/// interpolates (the poses at their parameters).
template <typename Scalar>
struct Provenance {
  Form form = Form::bezier;
  RotationMethod rotation = RotationMethod::elliptic;
  TranslationMethod translation = TranslationMethod::tr;
  int rotation_degree = 0;       ///< k: degree of Q_rot
  int translation_degree = 0;    ///< l: degree of the translational factor (TRT: l1)
  int translation_degree2 = -1;  ///< TRT: l2; -1 for the other methods
  /// The parametrisation rule's name (docs/interpolation.md), e.g. "uniform"; empty when the caller
  /// gave the parameters directly.
  std::string param;
  std::vector<Scalar> parameters;  ///< t_i, strictly increasing
  std::vector<Pose<Scalar>> poses;
  std::vector<double> residuals;  ///< pose_residual at every pose
  /// Form::fit: the tolerances the fit met (position, length unit; rotation, degrees).
  double tolerance = 0, angle_tolerance_deg = 0;
  /// Bezier motions: poses where |Q_rot(t_i)| is below 1% of Q_rot's largest coefficient
  /// (near-inaccessible; rounding is amplified there).
  std::vector<int> near_inaccessible;

  double max_residual() const {
    double r = 0;
    for (double x : residuals) r = std::max(r, x);
    return r;
  }
};

/// A rational rigid-body motion as a value: the Q-motion (the curve every evaluation and
/// export uses), the factors it is the product of when known (they give trajectories at
/// their minimal degree), how it was made when known, and its length unit. Every
/// interpolator returns one; io/ reads and writes it (docs/formats.md).
template <typename Scalar>
struct Motion {
  explicit Motion(QMotion<Scalar> q, std::optional<MotionFactors<Scalar>> f = std::nullopt,
                  std::optional<Provenance<Scalar>> p = std::nullopt, std::string u = "mm",
                  std::string n = {})
      : curve(std::move(q)),
        factors(std::move(f)),
        provenance(std::move(p)),
        units(std::move(u)),
        name(std::move(n)) {}

  QMotion<Scalar> curve;
  std::optional<MotionFactors<Scalar>> factors;  ///< absent for hand-written motions
  std::optional<Provenance<Scalar>> provenance;  ///< absent for hand-written motions
  std::string units = "mm";                      ///< length unit of the translations
  std::string name;  ///< where it came from (a file name), for messages; may be empty

  int degree() const { return curve.degree(); }
  const Scalar& a() const { return curve.a(); }
  const Scalar& b() const { return curve.b(); }
  int segments() const { return curve.segments(); }
  /// The name for messages: the file name, or "motion" for one built in memory.
  std::string label() const { return name.empty() ? std::string("motion") : name; }
};

/// Q(t).
template <typename Scalar>
DualQuaternion<Scalar> evaluate(const Motion<Scalar>& m, const Scalar& t) {
  return evaluate(m.curve, t);
}

/// A pose in double precision.
template <typename Scalar>
Pose<double> pose_to_double(const Pose<Scalar>& x) {
  Pose<double> y;
  y.rotation = Quaternion<double>(to_double(x.rotation.w()), to_double(x.rotation.x()),
                                  to_double(x.rotation.y()), to_double(x.rotation.z()));
  y.position =
      Eigen::Vector3d(to_double(x.position(0)), to_double(x.position(1)), to_double(x.position(2)));
  if (x.t) y.t = to_double(*x.t);
  return y;
}

/// The same motion in double precision (factors and provenance converted too).
template <typename Scalar>
Motion<double> to_double(const Motion<Scalar>& m) {
  if constexpr (std::is_same_v<Scalar, double>) {
    return m;
  } else {
    auto dq = [](const DualQuaternion<Scalar>& q) {
      DualQuaternion<double> r;
      for (int i = 0; i < 8; ++i) r[i] = to_double(q[i]);
      return r;
    };
    auto qd = [](const Quaternion<Scalar>& q) {
      return Quaternion<double>(to_double(q.w()), to_double(q.x()), to_double(q.y()),
                                to_double(q.z()));
    };
    auto vd = [](const Eigen::Matrix<Scalar, 3, 1>& v) {
      return Eigen::Vector3d(to_double(v(0)), to_double(v(1)), to_double(v(2)));
    };
    auto sd = [](const Scalar& s) { return to_double(s); };
    auto spline = [&](const auto& s, auto conv) {
      std::vector<double> knots;
      for (const auto& k : s.knots()) knots.push_back(to_double(k));
      std::vector<decltype(conv(s.ctrl().front()))> c;
      for (const auto& p : s.ctrl()) c.push_back(conv(p));
      return BSpline<decltype(conv(s.ctrl().front()))>::make(s.degree(), std::move(knots),
                                                             std::move(c));
    };
    Motion<double> out(QMotion<double>{m.curve.basis, spline(m.curve.curve, dq)}, std::nullopt,
                       std::nullopt, m.units, m.name);
    if (m.factors) {
      const auto& f = *m.factors;
      out.factors = MotionFactors<double>{f.method, spline(f.rotation, qd),
                                          spline(f.translation, vd), std::nullopt};
      if (f.translation2) out.factors->translation2 = spline(*f.translation2, vd);
    }
    if (m.provenance) {
      const auto& p = *m.provenance;
      Provenance<double> q;
      q.form = p.form;
      q.rotation = p.rotation;
      q.translation = p.translation;
      q.rotation_degree = p.rotation_degree;
      q.translation_degree = p.translation_degree;
      q.translation_degree2 = p.translation_degree2;
      q.param = p.param;
      for (const auto& t : p.parameters) q.parameters.push_back(sd(t));
      for (const auto& x : p.poses) q.poses.push_back(pose_to_double(x));
      q.residuals = p.residuals;
      q.tolerance = p.tolerance;
      q.angle_tolerance_deg = p.angle_tolerance_deg;
      q.near_inaccessible = p.near_inaccessible;
      out.provenance = std::move(q);
    }
    return out;
  }
}

}  // namespace qmotion::kernel
