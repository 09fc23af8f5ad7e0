// <qmotion/sweep/keyframes.hpp>: keyframes of a motion for players that blend poses between
// keys (glTF: linear translation, spherical-linear rotation; Blender: component-wise linear
// quaternions), placed so that every point of a body stays within a tolerance of the exact
// motion at every time, certified (docs/geometry.md, "Keyframes").
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <qmotion/kernel/bernstein.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/kernel/qspline_bounds.hpp>
#include <qmotion/motion.hpp>
#include <qmotion/sweep/trajectory.hpp>
#include <string>
#include <vector>

namespace qmotion::sweep {

/// A key as a player reads it: the motion's parameter t of the key, and the pose there as
/// written (translation in the motion's unit, unit rotation quaternion).
struct Keyframe {
  double t = 0;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
};

struct KeyframeOptions {
  double tol = 0;     ///< > 0, in the motion's length unit
  double radius = 0;  ///< >= 0: the largest |x| of the body's points in the moving space
  /// The parameter a key asked for at t gets (a time the file can hold, say); the key is the
  /// exact pose there. None: t itself. It must not decrease.
  std::function<double(double)> time;
  /// What is written for the exact pose of a key (rounded, say to 32-bit floats); the
  /// bounds hold for what it returns. None: as is.
  std::function<Keyframe(const Keyframe& exact)> write;
  int subdivisions = 4;            ///< parts per piece of a rational motion for the bound
  std::size_t max_keys = 1 << 22;  ///< Errc::numerical_failure beyond
};

struct Keyframes {
  std::vector<Keyframe> keys;
  double max_bound = 0;  ///< the largest certified deviation between two keys
  std::size_t bound_evaluations = 0;
};

namespace detail {

/// The rigid map (3 x 4: translation, rotation) of a key.
inline Eigen::Matrix<double, 3, 4> key_matrix(const Keyframe& k) {
  Eigen::Matrix<double, 3, 4> m;
  m.col(0) = k.translation;
  m.rightCols<3>() = k.rotation.normalized().toRotationMatrix();
  return m;
}

/// A bound of |(A(1, x))| over |x| <= rho for a 3 x 4 block A: |a0| + rho |A'|_F.
inline double lever_norm(const Eigen::Matrix<double, 3, 4>& a, double rho) {
  return a.col(0).norm() + rho * a.rightCols<3>().norm();
}

/// How far the rotation that a player makes between two unit quaternions (shortest arc,
/// q0 . q1 >= 0) leaves the linear blend of their matrices, in operator norm: at most
/// phi^2 / 8 for spherical-linear interpolation (phi the rotation angle between them; the
/// blend and the arc differ by (1 - s) + s e^{i phi} - e^{i s phi} in the plane of the
/// rotation, whose second derivative is phi^2), plus 2 (tan b - b), b = phi / 4, for the
/// component-wise blend of the quaternions normalised, whose angle differs from the
/// spherical one by atan(u tan b) - u b (u = 2 s - 1) in the quaternion, twice that in the
/// rotation. Infinite from phi >= pi / 2.
inline double blend_bound(const Eigen::Quaterniond& k0, const Eigen::Quaterniond& k1) {
  const Eigen::Vector4d q0 = k0.coeffs().normalized(), q1 = k1.coeffs().normalized();
  if (q0.dot(q1) < 0) return HUGE_VAL;    // written on opposite hemispheres: never here
  const double chord = (q1 - q0).norm();  // 2 sin(phi / 4)
  if (!(chord < 2 * std::sin(3.14159265358979323846 / 8))) return HUGE_VAL;
  const double phi = 4 * std::asin(chord / 2) * (1 + 1e-12);
  const double b = phi / 4;
  // tan b - b without cancellation: its series has positive terms, b^3/3 + 2 b^5/15 + ...,
  // bounded by b^3/3 + b^5 below b = 0.1.
  const double tb = b < 0.1 ? b * b * b / 3 + std::pow(b, 5) : (std::tan(b) - b) * (1 + 1e-12);
  return phi * phi / 8 + 2 * tb;
}

}  // namespace detail

/// Certified deviation bounds of a motion from the poses a player blends between two keys.
/// With L(t) the linear blend of the written keys' maps [p | R] over [t0, t1] and S(t) what
/// plays (L's translation, the rotation blended between the keys), for every x with
/// |x| <= radius: |M(t)(1,x) - S(t)(1,x)| <= |(M(t) - L(t))(1,x)| + radius |L_R(t) - S_R(t)|.
/// The second term is detail::blend_bound. The first:
/// - rational motion: M = N / w with N the matrix polynomial of the motion (degree 2n) and w
///   its weight, so w (M - L) = N - w L is a polynomial of degree 2n + 1; on every piece of
///   [t0, t1] (split at the breakpoints and into `subdivisions` parts) its Bernstein
///   coefficients D_k bound it (convex hull), so |(M - L)(1,x)| <= max_k lever_norm(D_k) /
///   min_k w_k, where w_k > 0 are the weight's coefficients there;
/// - quaternion spline: (M - L)(1,x) is within the larger of its ends (the keys' rounding)
///   plus h^2 / 8 max |M''(1,x)| (linear interpolation's Peano kernel), and |M''(1,x)| <=
///   |p''| + radius |R''| (kernel::second_derivative_bound).
class KeyframeBound {
 public:
  KeyframeBound(const qmotion::Motion& m, double radius, int subdivisions)
      : motion_(m), radius_(radius), parts_(std::max(1, subdivisions)) {
    if (m.is_rational()) {
      const auto& q = m.rational();
      refuse_poles(q);
      pieces_ = kernel::bezier_pieces(kernel::matrix_spline(q.curve));
    }
    breaks_ = m.breakpoints();
  }

  /// The bound on [k0.t, k1.t].
  double operator()(const Keyframe& k0, const Keyframe& k1) const {
    const double blend = radius_ * detail::blend_bound(k0.rotation, k1.rotation);
    if (!std::isfinite(blend)) return blend;
    return blend + linear(k0, k1);
  }

  /// The first term alone: |M(t)(1,x) - L(t)(1,x)| <= linear(k0, k1) for t in [k0.t, k1.t]
  /// and |x| <= radius, L the linear blend of the keys' maps (detail::key_matrix). So the
  /// body's piece of the swept volume there lies in the convex hull of the two placed bodies
  /// grown by it (sweep::HullPieces).
  double linear(const Keyframe& k0, const Keyframe& k1) const {
    const Eigen::Matrix<double, 3, 4> L0 = detail::key_matrix(k0), L1 = detail::key_matrix(k1);
    const double t0 = k0.t, t1 = k1.t;
    auto lerp = [&](double t) -> Eigen::Matrix<double, 3, 4> {
      const double s = (t - t0) / (t1 - t0);
      return (1 - s) * L0 + s * L1;
    };
    return motion_.is_rational() ? rational_part(t0, t1, lerp) : spline_part(k0, k1);
  }

 private:
  template <typename Lerp>
  double rational_part(double t0, double t1, const Lerp& lerp) const {
    double worst = 0;
    auto it = std::upper_bound(breaks_.begin(), breaks_.end(), t0);
    double u = t0;
    while (u < t1) {
      const std::size_t span = static_cast<std::size_t>(it - breaks_.begin()) - 1;
      const double next = it != breaks_.end() ? std::min(*it, t1) : t1;
      for (int k = 0; k < parts_; ++k) {
        const double u0 = u + (next - u) * k / parts_;
        const double u1 = k + 1 == parts_ ? next : u + (next - u) * (k + 1) / parts_;
        if (!(u0 < u1)) continue;
        worst = std::max(worst, part_bound(pieces_[std::min(span, pieces_.size() - 1)], u0, u1,
                                           lerp(u0), lerp(u1)));
      }
      u = next;
      if (it != breaks_.end()) ++it;
    }
    return worst;
  }

  double part_bound(const kernel::Bernstein<Eigen::Matrix4d>& piece, double u0, double u1,
                    const Eigen::Matrix<double, 3, 4>& l0,
                    const Eigen::Matrix<double, 3, 4>& l1) const {
    // The piece on [u0, u1] by two de Casteljau splits (O(d^2); blossoms would take O(d^3)).
    auto n = piece;
    if (u0 > n.a()) n = kernel::subdivide(n, u0).second;
    if (u1 < n.b()) n = kernel::subdivide(n, u1).first;
    const int d = n.degree() + 1;  // of N elevated once, and of w L
    double wmin = HUGE_VAL, dmax = 0, scale = 0;
    for (int k = 0; k <= d; ++k) {
      // Coefficient k of N elevated, and of w (1 - s) l0 + w s l1 (formula (29) with degree 1).
      const double f = static_cast<double>(k) / d;
      Eigen::Matrix<double, 3, 4> e = Eigen::Matrix<double, 3, 4>::Zero();
      double we = 0;
      if (k > 0) {
        const auto& c = n[k - 1];
        e += f * (c.bottomRows<3>() - c(0, 0) * l1);
        we += f * c(0, 0);
        scale = std::max(scale, detail::lever_norm(c.bottomRows<3>(), radius_));
      }
      if (k < d) {
        const auto& c = n[k];
        e += (1 - f) * (c.bottomRows<3>() - c(0, 0) * l0);
        we += (1 - f) * c(0, 0);
      }
      wmin = std::min(wmin, we);
      dmax = std::max(dmax, detail::lever_norm(e, radius_));
    }
    if (!(wmin > 0)) return HUGE_VAL;  // no bound from this part: the caller takes a shorter step
    // Rounding of the de Casteljau blossoms and of the sums: relative 1e-12 of the terms.
    return (dmax + 1e-12 * (scale + dmax)) / wmin;
  }

  double spline_part(const Keyframe& k0, const Keyframe& k1) const {
    const auto& s = motion_.spline();
    auto end_error = [&](const Keyframe& k) {
      const Eigen::Matrix4d f = motion_.frame(k.t);
      Eigen::Matrix<double, 3, 4> e = f.bottomRows<3>() - detail::key_matrix(k);
      return detail::lever_norm(e, radius_);
    };
    const auto b = kernel::second_derivative_bound(s, k0.t, k1.t);
    const double h = k1.t - k0.t;
    return std::max(end_error(k0), end_error(k1)) * (1 + 1e-12) +
           h * h / 8 * (b.position + radius_ * b.rotation) * (1 + 1e-12);
  }

  const qmotion::Motion& motion_;
  double radius_;
  int parts_;
  std::vector<kernel::Bernstein<Eigen::Matrix4d>> pieces_;
  std::vector<double> breaks_;
};

/// The exact pose of the motion at t as a key (the rotation with w >= 0 for the first, the
/// sign nearest the previous key's after).
inline Keyframe exact_key(const qmotion::Motion& m, double t, const Keyframe* prev) {
  const Eigen::Matrix4d f = m.frame(t);
  Keyframe k;
  k.t = t;
  k.translation = f.block<3, 1>(1, 0);
  k.rotation = Eigen::Quaterniond(Eigen::Matrix3d(f.block<3, 3>(1, 1))).normalized();
  const double dir = prev ? prev->rotation.coeffs().dot(k.rotation.coeffs()) : k.rotation.w();
  if (dir < 0) k.rotation.coeffs() = -k.rotation.coeffs();
  return k;
}

/// What a player shows at t between two keys: translation blended linearly, rotation by
/// spherical-linear interpolation (glTF) or by blending the quaternions' components and
/// normalising (Blender's f-curves).
inline Keyframe play(const Keyframe& k0, const Keyframe& k1, double t, bool spherical = true) {
  const double s = (t - k0.t) / (k1.t - k0.t);
  Keyframe k;
  k.t = t;
  k.translation = (1 - s) * k0.translation + s * k1.translation;
  const Eigen::Quaterniond q0 = k0.rotation.normalized(), q1 = k1.rotation.normalized();
  if (spherical) {
    k.rotation = q0.slerp(s, q1);
  } else {
    k.rotation.coeffs() = ((1 - s) * q0.coeffs() + s * q1.coeffs()).normalized();
  }
  return k;
}

/// Keys from a to b, each as far from the one before as the certified bound (KeyframeBound)
/// allows within opt.tol: a greedy search on t, doubling then bisecting the step. The keys
/// of a quaternion spline include its breakpoints below C1 (the Peano bound needs C1).
/// Errc::invalid_input for a tolerance that is not positive or a negative radius;
/// Errc::numerical_failure when a step below 1e-12 of the interval is needed, or more
/// than opt.max_keys keys, naming the motion and t.
inline Keyframes place_keyframes(const qmotion::Motion& m, const KeyframeOptions& opt) {
  if (!(opt.tol > 0) || !std::isfinite(opt.tol))
    throw Error(Errc::invalid_input, "keyframes: the tolerance must be positive, got " +
                                         kernel::detail::format_double(opt.tol));
  if (!(opt.radius >= 0) || !std::isfinite(opt.radius))
    throw Error(Errc::invalid_input, "keyframes: the body's radius must be finite and >= 0");
  const KeyframeBound bound(m, opt.radius, opt.subdivisions);
  const double a = m.a(), b = m.b(), range = b - a;
  std::vector<double> stops;  // forced keys
  if (!m.is_rational()) {
    const auto x = m.breakpoints();
    const auto c = m.continuity();
    for (std::size_t i = 0; i < c.size(); ++i)
      if (c[i] < 1) stops.push_back(x[i + 1]);
  }
  stops.push_back(b);
  auto write = [&](double t, const Keyframe* prev) {
    const Keyframe e = exact_key(m, opt.time ? std::clamp(opt.time(t), a, b) : t, prev);
    return opt.write ? opt.write(e) : e;
  };
  Keyframes out;
  out.keys.push_back(write(a, nullptr));
  double h = range / std::max(1, 4 * m.segments());
  double at = a;  // the parameter asked for the last key (a written key may move it)
  std::size_t stop = 0;
  while (at < b) {
    const Keyframe k0 = out.keys.back();
    while (stops[stop] <= at) ++stop;
    const double limit = stops[stop];
    auto attempt = [&](double step, Keyframe& k1, double& asked) {
      asked = step >= limit - at ? limit : at + step;
      k1 = write(asked, &k0);
      if (!(k1.t > k0.t)) return HUGE_VAL;
      ++out.bound_evaluations;
      return bound(k0, k1);
    };
    Keyframe best, trial;
    double best_at = at, trial_at = at, best_e = 0;
    double e = attempt(h, trial, trial_at);
    double fail = 0;     // a step that failed, above h (0: none yet)
    if (e <= opt.tol) {  // grow while it holds
      while (true) {
        best = trial;
        best_at = trial_at;
        best_e = e;
        if (best_at >= limit) break;
        if (!((e = attempt(2 * h, trial, trial_at)) <= opt.tol)) {
          fail = 2 * h;
          break;
        }
        h *= 2;
      }
    } else {  // shrink until it holds
      do {
        fail = h;
        h /= 2;
        if (h < 1e-12 * range)
          throw Error(Errc::numerical_failure,
                      m.label() + ": no keyframe step within the tolerance " +
                          kernel::detail::format_double(opt.tol) +
                          " after t = " + kernel::detail::format_double(k0.t) +
                          " (below what the written numbers' rounding allows?)");
        e = attempt(h, trial, trial_at);
      } while (!(e <= opt.tol));
      best = trial;
      best_at = trial_at;
      best_e = e;
    }
    // Between the step that holds and the one that failed: three bisections (the bound
    // grows as the step squared, so this takes most of what is left).
    for (int i = 0; i < 3 && fail > 0 && best_at < limit; ++i) {
      const double mid = 0.5 * (h + fail);
      if ((e = attempt(mid, trial, trial_at)) <= opt.tol) {
        h = mid;
        best = trial;
        best_at = trial_at;
        best_e = e;
      } else {
        fail = mid;
      }
    }
    out.max_bound = std::max(out.max_bound, best_e);
    out.keys.push_back(best);
    at = best_at;
    if (out.keys.size() > opt.max_keys)
      throw Error(Errc::numerical_failure,
                  m.label() + ": more than " + std::to_string(opt.max_keys) +
                      " keyframes for the tolerance " + kernel::detail::format_double(opt.tol));
  }
  return out;
}

}  // namespace qmotion::sweep
