// <qmotion/motion.hpp>: the one motion value every module takes (docs/architecture.md).
//
// A qmotion::Motion holds either kind of motion qmotion makes:
//   - a rational Q-motion (kernel::Motion<double>: interpolate, a hand-written file), whose
//     trajectories and sweeps are exact NURBS;
//   - a unit-quaternion spline (kernel::QuaternionSpline: qspline's kks, quintic, quartic),
//     whose geometry is fitted within a tolerance.
// Both answer the same questions (interval, breakpoints and continuity, key parameters, the
// rigid map at t and its velocities, units, name); the calls that need the kind (exact NURBS
// or a fit) ask for it with rational() or spline(). Copies share the motion: it is immutable.
// Exact work keeps the Scalar-generic kernel::Motion<Scalar>.
#pragma once
#include <Eigen/Core>
#include <memory>
#include <mutex>
#include <optional>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/motion_value.hpp>
#include <qmotion/kernel/qspline.hpp>
#include <string>
#include <utility>
#include <vector>

namespace qmotion {

class Motion {
 public:
  using Rational = kernel::Motion<double>;
  using Spline = kernel::QuaternionSpline;

  /// A rational motion; its units and name are the motion's.
  Motion(Rational m)  // NOLINT(google-explicit-constructor): every Q-motion is a Motion
      : units_(m.units), name_(m.name), rational_(std::make_shared<Rational>(std::move(m))) {}
  /// A quaternion-spline motion with its length unit and name (a file name, or empty).
  explicit Motion(Spline s, std::string units = "mm", std::string name = {})
      : units_(std::move(units)),
        name_(std::move(name)),
        spline_(std::make_shared<const Spline>(std::move(s))) {}

  /// True for a rational Q-motion, false for a quaternion spline.
  bool is_rational() const noexcept { return rational_ != nullptr; }
  /// The rational motion; Errc::invalid_input naming the motion for a quaternion spline.
  const Rational& rational() const {
    if (!rational_)
      throw Error(Errc::invalid_input,
                  label() + ": a quaternion-spline motion is not rational (no control points)");
    return *rational_;
  }
  /// The quaternion spline; Errc::invalid_input naming the motion for a rational motion.
  const Spline& spline() const {
    if (!spline_)
      throw Error(Errc::invalid_input, label() + ": a rational motion is not a quaternion spline");
    return *spline_;
  }

  double a() const { return rational_ ? rational_->a() : spline_->a(); }
  double b() const { return rational_ ? rational_->b() : spline_->b(); }
  int segments() const { return rational_ ? rational_->segments() : spline_->segments(); }
  /// a = x_0 < ... < x_r = b: where the pieces meet.
  std::vector<double> breakpoints() const {
    return rational_ ? rational_->curve.curve.breakpoints() : spline_->knots;
  }
  /// The order of continuity at every interior breakpoint, in order.
  std::vector<int> continuity() const {
    if (!rational_) return spline_->interior_continuity();
    const std::vector<double> x = breakpoints();
    std::vector<int> c;
    for (std::size_t i = 1; i + 1 < x.size(); ++i)
      c.push_back(kernel::continuity_at(rational_->curve.curve, x[i]));
    return c;
  }
  /// Where the motion interpolates its poses: the rule's parameters of an interpolated
  /// motion, a spline's knots; the breakpoints of a hand-written rational motion.
  std::vector<double> key_parameters() const {
    if (!rational_) return spline_->knots;
    return rational_->provenance ? rational_->provenance->parameters : breakpoints();
  }
  /// How it was made, when it was interpolated here (rational motions only).
  const kernel::Provenance<double>* provenance() const {
    return rational_ && rational_->provenance ? &*rational_->provenance : nullptr;
  }

  /// The rigid map at t as a 4x4 matrix on homogeneous points (x0, x) -> (x0, R x + x0 p),
  /// as sweep's matrix splines. Errc::numerical_failure at a pole of a rational motion.
  Eigen::Matrix4d frame(double t) const {
    if (!rational_) return spline_->frame(t);
    const Eigen::Matrix4d m = kernel::to_matrix4(kernel::evaluate(rational_->curve, t));
    if (!(std::abs(m(0, 0)) > 0)) throw pole(t);
    Eigen::Matrix4d f = Eigen::Matrix4d::Zero();
    f(0, 0) = 1;
    f.block<3, 1>(1, 0) = m.block<3, 1>(1, 0) / m(0, 0);
    f.block<3, 3>(1, 1) = m.block<3, 3>(1, 1) / m(0, 0);
    return f;
  }
  /// The image at t of the point x of the moving space.
  Eigen::Vector3d place(double t, const Eigen::Vector3d& x) const {
    if (!rational_) return spline_->place(t, x);
    return apply(t, x, kernel::evaluate(*rational_, t));
  }
  /// The angular velocity at t in the fixed frame (radians per unit of t): for a rational
  /// motion 2 A' conj(A) / |A|^2, A its rotational part; for a spline 2 q' q^-1.
  Eigen::Vector3d angular_velocity(double t) const {
    if (!rational_) return spline_->angular_velocity(t);
    const auto A = kernel::evaluate(rational_->curve.curve, t).real();
    const auto dA = kernel::evaluate(derivative(), t).real();
    return Eigen::Vector3d(2 * (dA * A.conj()).vec() / A.norm2());
  }
  /// The velocity at t of the point x of the moving space (units per unit of t).
  Eigen::Vector3d point_velocity(double t, const Eigen::Vector3d& x) const {
    if (!rational_) return spline_->point_velocity(t, x);
    // y = apply(Q, (1, x)) is quadratic in Q, so y' = apply(Q + Q') - apply(Q) - apply(Q').
    const kernel::DualQuaternion<double> q = kernel::evaluate(rational_->curve.curve, t);
    const kernel::DualQuaternion<double> dq = kernel::evaluate(derivative(), t);
    Eigen::Vector4d h;
    h << 1, x;
    const Eigen::Vector4d y = kernel::apply(q, h);
    if (!(std::abs(y(0)) > 0)) throw pole(t);
    const Eigen::Vector4d dy =
        kernel::apply(kernel::DualQuaternion<double>(q + dq), h) - y - kernel::apply(dq, h);
    return (dy.tail<3>() * y(0) - y.tail<3>() * dy(0)) / (y(0) * y(0));
  }

  /// The length unit of positions (docs/formats.md).
  const std::string& units() const noexcept { return units_; }
  /// Where it came from (a file name), for messages; may be empty.
  const std::string& name() const noexcept { return name_; }
  /// The name for messages: the file name, or "motion" for one built in memory.
  std::string label() const { return name_.empty() ? std::string("motion") : name_; }
  /// How it was made in one line, e.g. "bspline, elliptic + tr, degree 6, 4 segments, 5 key
  /// poses" or "kks, 4 segments".
  std::string summary() const {
    const int s = segments();
    const std::string segs = std::to_string(s) + (s == 1 ? " segment" : " segments");
    if (!rational_) return std::string(kernel::to_string(spline_->scheme)) + ", " + segs;
    std::string how;
    if (const auto* p = provenance())
      how = std::string(kernel::to_string(p->form)) + ", " + kernel::to_string(p->rotation) +
            " + " + kernel::to_string(p->translation) + ", ";
    return how + "degree " + std::to_string(rational_->degree()) + ", " + segs + ", " +
           std::to_string(key_parameters().size()) + " key poses";
  }

 private:
  Error pole(double t) const {
    return Error(Errc::numerical_failure,
                 label() + ": the motion has a pole at t = " + std::to_string(t));
  }
  Eigen::Vector3d apply(double t, const Eigen::Vector3d& x,
                        const kernel::DualQuaternion<double>& q) const {
    Eigen::Vector4d h;
    h << 1, x;
    const Eigen::Vector4d y = kernel::apply(q, h);
    if (!(std::abs(y(0)) > 0)) throw pole(t);
    return y.tail<3>() / y(0);
  }
  /// Q', made on first use and shared by the copies.
  const kernel::BSpline<kernel::DualQuaternion<double>>& derivative() const {
    std::call_once(cache_->once,
                   [this] { cache_->d.emplace(kernel::derivative(rational_->curve.curve)); });
    return *cache_->d;
  }
  struct Cache {
    std::once_flag once;
    std::optional<kernel::BSpline<kernel::DualQuaternion<double>>> d;
  };

  std::string units_, name_;
  std::shared_ptr<const Rational> rational_;
  std::shared_ptr<const Spline> spline_;
  std::shared_ptr<Cache> cache_ = std::make_shared<Cache>();
};

}  // namespace qmotion
