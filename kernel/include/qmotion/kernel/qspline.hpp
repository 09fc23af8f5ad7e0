// <qmotion/kernel/qspline.hpp>: the non-rational mode (docs/geometry.md): unit-quaternion
// interpolation splines in cumulative form, with the matching R³ spline for the positions.
//   quartic: Xing, Fan, Tan, Xu 2017 (seed 003), (1)-(4), uniform knots;
//   quintic: Tan et al. (seed 002), (3.1)-(3.7), a tension per key and arbitrary knots;
//   kks: Kim, Kim, Shin (seed 000), the cumulative cubic B-spline quaternion curve whose
//        control quaternions solve (11) by the iteration (12)-(13), natural ends.
// Segment s of n keys (s = 0, ..., n-2) runs from key s to key s+1 with local parameter t
// in [0, 1] and reads the control quaternions E_{s-1}, E_s, E_{s+1}, E_{s+2}. For the quartic
// and the quintic they are the keys with the ends repeated (E_{-1} = E_0, E_n = E_{n-1}, as
// both papers define them); for KKS the B-spline's control quaternions q_{-1}, ..., q_n:
//   q_s(t) = E_{s-1} exp(C~_1(t) w_{s-1}) exp(C~_2(t) w_s) exp(C~_3(t) w_{s+1}),
//   w_k = log(E_k^{-1} E_{k+1}),  C~_j = sum_{k>=j} C_k,
//   p_s(t) = sum_k C_k(t) P_{s-1+k},
// with C_k the scheme's blending functions; C~_0 = 1 for both schemes.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/quaternion.hpp>
#include <string>
#include <vector>

namespace qmotion::kernel {

enum class QSplineScheme { kks, quintic, quartic };

inline const char* to_string(QSplineScheme s) {
  switch (s) {
    case QSplineScheme::kks:
      return "kks";
    case QSplineScheme::quintic:
      return "quintic";
    case QSplineScheme::quartic:
      return "quartic";
  }
  return "";
}

/// The scheme of a name as to_string spells it (the one place scheme names are parsed).
inline std::optional<QSplineScheme> qspline_scheme_from_string(const std::string& s) {
  for (auto k : {QSplineScheme::kks, QSplineScheme::quintic, QSplineScheme::quartic})
    if (s == to_string(k)) return k;
  return std::nullopt;
}

/// Keys closer than this to a half-turn apart (|E_k . E_k+1| below it) leave the shorter
/// arc undefined: which way the spline turns is not determined by the keys.
inline constexpr double kHalfTurnDot = 1e-12;

/// A unit-quaternion interpolation spline with its position spline, evaluable at any u in
/// [knots.front(), knots.back()].
struct QuaternionSpline {
  QSplineScheme scheme = QSplineScheme::quartic;
  std::vector<double> knots;               ///< u of every key, strictly increasing
  std::vector<Quaternion<double>> keys;    ///< unit keys, signs aligned (E_k . E_k+1 > 0)
  std::vector<Eigen::Vector3d> positions;  ///< one per key
  std::vector<double> tension;             ///< quintic: alpha per key
  std::vector<Quaternion<double>> ctrl;    ///< E_{-1} .. E_n (n keys): ctrl[k + 1] = E_k
  std::vector<Eigen::Vector3d> pctrl;      ///< the position spline's P_{-1} .. P_n
  std::vector<Quaternion<double>> omega;   ///< omega[k] = log(ctrl[k]^-1 ctrl[k+1])
  /// KKS: fixed-point iterations, the last observed contraction ratio, and the largest
  /// interpolation residual |log(Q_i^-1 q(u_i))| after them and after the Gauss-Newton
  /// refinement (with its step count).
  int iterations = 0;
  double contraction = 0;
  double fixed_point_residual = 0;
  int newton_steps = 0;
  double residual = 0;

  double a() const { return knots.front(); }
  double b() const { return knots.back(); }
  int segments() const { return static_cast<int>(knots.size()) - 1; }

  /// The parametric continuity in u at interior key k (0 < k < n - 1): C2 for uniform
  /// knots; the quintic between spans of different lengths is G2 but only C0 in u (its
  /// segments run on local parameters of unit length).
  int continuity(std::size_t k) const {
    if (scheme != QSplineScheme::quintic) return 2;
    const double h0 = knots[k] - knots[k - 1], h1 = knots[k + 1] - knots[k];
    return std::abs(h1 - h0) <= 1e-12 * std::max(h0, h1) ? 2 : 0;
  }

  /// The segment holding u (the last one for u = b) and u's local parameter in it.
  std::pair<int, double> locate(double u) const {
    const int n = segments();
    int s = 0;
    if (scheme == QSplineScheme::quintic) {
      while (s + 1 < n && u >= knots[static_cast<std::size_t>(s + 1)]) ++s;
      const double u0 = knots[static_cast<std::size_t>(s)];
      const double u1 = knots[static_cast<std::size_t>(s + 1)];
      return {s, (u - u0) / (u1 - u0)};
    }
    // Uniform constructions: the keys sit at uniform knots mapped linearly onto [a, b].
    const double g = (u - a()) / (b() - a()) * n;
    // (comparisons first: a NaN or huge g must not reach the integer conversion)
    s = g >= n ? n - 1 : g > 0 ? static_cast<int>(std::floor(g)) : 0;
    return {s, g - s};
  }

  /// Quintic segment s: its Bezier points V_0..V_5 of (3.3), solved from (3.4), as weights
  /// of E_{s-1}, ..., E_{s+2}.
  std::array<std::array<double, 4>, 6> quintic_points(int s) const {
    const double al = tension[static_cast<std::size_t>(s)];
    const double be = tension[static_cast<std::size_t>(s + 1)];
    return {{{0, 1, 0, 0},
             {-al / 5, 1, al / 5, 0},
             {-7 * al / 20, 1 - al / 10, 9 * al / 20, 0},
             {0, 9 * be / 20, 1 - be / 10, -7 * be / 20},
             {0, be / 5, 1, -be / 5},
             {0, 0, 1, 0}}};
  }

  /// The four blending functions C_0..C_3 of segment s at local parameter t.
  std::array<double, 4> blend(int s, double t) const {
    const double t2 = t * t, t3 = t2 * t;
    if (scheme == QSplineScheme::kks) {  // the uniform cubic B-spline basis
      const double u = 1 - t;
      return {u * u * u / 6, (3 * t3 - 6 * t2 + 4) / 6, (-3 * t3 + 3 * t2 + 3 * t + 1) / 6, t3 / 6};
    }
    if (scheme == QSplineScheme::quintic) {
      const auto V = quintic_points(s);
      const double u = 1 - t;
      const double B[6] = {u * u * u * u * u,      5 * t * u * u * u * u, 10 * t * t * u * u * u,
                           10 * t * t * t * u * u, 5 * t * t * t * t * u, t * t * t * t * t};
      std::array<double, 4> c{0, 0, 0, 0};
      for (int k = 0; k < 6; ++k)
        for (int j = 0; j < 4; ++j)
          c[static_cast<std::size_t>(j)] +=
              B[k] * V[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)];
      return c;
    }
    // (4) of seed 003.
    const double t4 = t3 * t;
    return {0.5 * t4 - 1.5 * t3 + 1.5 * t2 - 0.5 * t, -0.5 * t4 + 2.5 * t3 - 3 * t2 + 1,
            -0.5 * t4 - 0.5 * t3 + 1.5 * t2 + 0.5 * t, 0.5 * t4 - 0.5 * t3};
  }

  /// d/dt of the four blending functions of segment s at local parameter t.
  std::array<double, 4> blend_derivative(int s, double t) const {
    const double t2 = t * t, t3 = t2 * t;
    if (scheme == QSplineScheme::kks) {
      const double u = 1 - t;
      return {-u * u / 2, (9 * t2 - 12 * t) / 6, (-9 * t2 + 6 * t + 3) / 6, t2 / 2};
    }
    if (scheme ==
        QSplineScheme::quintic) {  // numerically, as in blend(): dB^5_k = 5 (B^4_{k-1} - B^4_k)
      const double u = 1 - t;
      const double B4[5] = {u * u * u * u, 4 * t * u * u * u, 6 * t2 * u * u, 4 * t3 * u, t3 * t};
      std::array<double, 4> c{0, 0, 0, 0};
      const auto V = quintic_points(s);
      for (int k = 0; k < 6; ++k) {
        const double dB = 5 * ((k > 0 ? B4[k - 1] : 0.0) - (k < 5 ? B4[k] : 0.0));
        for (int j = 0; j < 4; ++j)
          c[static_cast<std::size_t>(j)] +=
              dB * V[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)];
      }
      return c;
    }
    return {2 * t3 - 4.5 * t2 + 3 * t - 0.5, -2 * t3 + 7.5 * t2 - 6 * t,
            -2 * t3 - 1.5 * t2 + 3 * t + 0.5, 2 * t3 - 1.5 * t2};
  }

  /// dt/du: the local parameter's rate in segment s.
  double local_rate(int s) const {
    if (scheme == QSplineScheme::quintic)
      return 1 / (knots[static_cast<std::size_t>(s + 1)] - knots[static_cast<std::size_t>(s)]);
    return segments() / (b() - a());
  }

  /// The angular velocity at u in the fixed frame, 2 q'(u) q(u)^-1 (radians per unit of u).
  Eigen::Vector3d angular_velocity(double u) const {
    const auto [s, t] = locate(u);
    const auto c = blend(s, t);
    const auto d = blend_derivative(s, t);
    const double c3 = c[3], c2 = c[2] + c3, c1 = c[1] + c2;
    const double d3 = d[3], d2 = d[2] + d3, d1 = d[1] + d2;
    const auto k = static_cast<std::size_t>(s);
    const auto e1 = exp_pure(omega[k] * c1), e2 = exp_pure(omega[k + 1] * c2),
               e3 = exp_pure(omega[k + 2] * c3);
    // d/dt exp(c w) = exp(c w) c' w (w commutes with itself).
    const Quaternion<double> dq =
        ctrl[k] * (e1 * omega[k] * d1 * e2 * e3 + e1 * e2 * omega[k + 1] * d2 * e3 +
                   e1 * e2 * e3 * omega[k + 2] * d3);
    const Quaternion<double> q = ctrl[k] * e1 * e2 * e3;
    return (2 * local_rate(s)) * (dq * q.conj()).vec();
  }

  /// The unit rotation at u.
  Quaternion<double> rotation(double u) const {
    const auto [s, t] = locate(u);
    return rotation_in(s, t);
  }
  /// The unit rotation at local parameter t of segment s.
  Quaternion<double> rotation_in(int s, double t) const {
    const auto c = blend(s, t);
    const double c3 = c[3], c2 = c[2] + c3, c1 = c[1] + c2;  // cumulative C~_j
    const auto k = static_cast<std::size_t>(s);
    return ctrl[k] * exp_pure(omega[k] * c1) * exp_pure(omega[k + 1] * c2) *
           exp_pure(omega[k + 2] * c3);
  }

  /// The image at u of the point x of the moving space.
  Eigen::Vector3d place(double u, const Eigen::Vector3d& x) const {
    return rotate(rotation(u), x) + position(u);
  }

  /// The velocity at u of the point x of the moving space: omega x (R x) + d position / du.
  Eigen::Vector3d point_velocity(double u, const Eigen::Vector3d& x) const {
    return angular_velocity(u).cross(rotate(rotation(u), x)) + velocity(u);
  }

  /// continuity(k) for every interior key, in order (what a fit of the motion keeps).
  std::vector<int> interior_continuity() const {
    std::vector<int> c;
    for (std::size_t k = 1; k + 1 < knots.size(); ++k) c.push_back(continuity(k));
    return c;
  }

  /// The velocity of the moving origin at u, d position / du.
  Eigen::Vector3d velocity(double u) const {
    const auto [s, t] = locate(u);
    const auto d = blend_derivative(s, t);
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    for (int j = 0; j < 4; ++j)
      v += d[static_cast<std::size_t>(j)] * pctrl[static_cast<std::size_t>(s + j)];
    return local_rate(s) * v;
  }

  /// The rigid map at u as a 4x4 matrix acting on homogeneous points (x0, x):
  /// (x0, x) -> (x0, R x + x0 p), the convention of sweep's matrix splines.
  Eigen::Matrix4d frame(double u) const {
    Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
    m(0, 0) = 1;
    m.block<3, 1>(1, 0) = position(u);
    m.block<3, 3>(1, 1) = rotation_matrix(rotation(u));
    return m;
  }

  /// The position (image of the moving origin) at u.
  Eigen::Vector3d position(double u) const {
    const auto [s, t] = locate(u);
    const auto c = blend(s, t);
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int j = 0; j < 4; ++j)
      p += c[static_cast<std::size_t>(j)] * pctrl[static_cast<std::size_t>(s + j)];
    return p;
  }
};

namespace detail {

/// Checks and prepares keys: unit, signs aligned along the sequence, no half-turn between
/// neighbours.
inline void prepare_keys(QuaternionSpline& s) {
  const std::size_t n = s.keys.size();
  if (n < 2 || s.positions.size() != n || s.knots.size() != n)
    throw Error(Errc::invalid_input, std::string(to_string(s.scheme)) +
                                         ": needs at least two keys, with one position and "
                                         "one parameter each");
  if (!std::isfinite(s.knots.back() - s.knots.front()))
    throw Error(Errc::invalid_input,
                std::string(to_string(s.scheme)) + ": the parameter interval is not finite");
  for (std::size_t i = 1; i < n; ++i)
    if (!(s.knots[i - 1] < s.knots[i]))
      throw Error(Errc::invalid_input, std::string(to_string(s.scheme)) +
                                           ": parameters must increase strictly (key " +
                                           std::to_string(i) + ")");
  for (auto& q : s.keys) q = normalized(q);
  for (std::size_t i = 1; i < n; ++i) {
    const double d = s.keys[i - 1].dot(s.keys[i]);
    if (std::abs(d) <= kHalfTurnDot)
      throw Error(Errc::invalid_input,
                  std::string(to_string(s.scheme)) + ": keys " + std::to_string(i - 1) + " and " +
                      std::to_string(i) +
                      " are a half-turn apart: the shorter arc between them is not defined, so "
                      "the spline cannot choose which way to turn (insert a key between them)");
    if (d < 0) s.keys[i] = -s.keys[i];
  }
}

/// The logarithms omega of consecutive control quaternions.
inline void finish(QuaternionSpline& s) {
  s.omega.clear();
  s.omega.reserve(s.ctrl.size());
  for (std::size_t k = 0; k + 1 < s.ctrl.size(); ++k)
    s.omega.push_back(log_unit(inverse(s.ctrl[k]) * s.ctrl[k + 1]));
}

/// Control quaternions and points for the schemes that repeat the end keys.
inline void repeat_ends(QuaternionSpline& s) {
  s.ctrl.reserve(s.keys.size() + 2);
  s.ctrl.assign(1, s.keys.front());
  s.ctrl.insert(s.ctrl.end(), s.keys.begin(), s.keys.end());
  s.ctrl.push_back(s.keys.back());
  s.pctrl.reserve(s.positions.size() + 2);
  s.pctrl.assign(1, s.positions.front());
  s.pctrl.insert(s.pctrl.end(), s.positions.begin(), s.positions.end());
  s.pctrl.push_back(s.positions.back());
  finish(s);
}

/// n keys at uniform knots on [a, b] (the last exactly b).
inline std::vector<double> uniform_knots(std::size_t n, double a, double b) {
  std::vector<double> u;
  for (std::size_t i = 0; i < n; ++i)
    u.push_back(n > 1 ? a + (b - a) * static_cast<double>(i) / static_cast<double>(n - 1) : a);
  if (n > 1) u.back() = b;
  return u;
}

/// q with w >= 0 (the same rotation; its powers take the shorter arc).
inline Quaternion<double> short_arc(const Quaternion<double>& q) { return q.w() < 0 ? -q : q; }

}  // namespace detail

/// Xing et al.'s quartic spline through the keys (seed 003, (1)-(4)): C² at the keys, the
/// keys at uniform knots mapped linearly onto [a, b] (`knots` records where each key is).
inline QuaternionSpline quartic_spline(std::vector<Quaternion<double>> keys,
                                       std::vector<Eigen::Vector3d> positions, double a, double b) {
  QuaternionSpline s;
  s.scheme = QSplineScheme::quartic;
  s.keys = std::move(keys);
  s.positions = std::move(positions);
  s.knots = detail::uniform_knots(s.keys.size(), a, b);
  detail::prepare_keys(s);
  detail::repeat_ends(s);
  return s;
}

/// Tan et al.'s quintic spline with tension (seed 002, (3.1)-(3.7)) through the keys at the
/// given knots: C² at the keys for uniform knots, G² otherwise (derivatives in the ratio of
/// the neighbouring spans, (3.14)). `tension` holds alpha per key.
inline QuaternionSpline quintic_spline(std::vector<Quaternion<double>> keys,
                                       std::vector<Eigen::Vector3d> positions,
                                       std::vector<double> knots, std::vector<double> tension) {
  QuaternionSpline s;
  s.scheme = QSplineScheme::quintic;
  s.keys = std::move(keys);
  s.positions = std::move(positions);
  s.knots = std::move(knots);
  if (tension.size() != s.keys.size())
    throw Error(Errc::invalid_input, "quintic: expected one tension per key (" +
                                         std::to_string(s.keys.size()) + "), found " +
                                         std::to_string(tension.size()));
  for (std::size_t i = 0; i < tension.size(); ++i)
    if (!std::isfinite(tension[i]))
      throw Error(Errc::invalid_input, "quintic: tension " + std::to_string(i) + " is not finite");
  s.tension = std::move(tension);
  detail::prepare_keys(s);
  detail::repeat_ends(s);
  return s;
}

/// Options of the Kim-Kim-Shin solve.
struct KksOptions {
  double tol = 1e-4;  ///< the fixed-point iteration stops when no key moves further
  int max_iterations = 1000;
  bool refine = true;  ///< Gauss-Newton on (11) after the fixed-point iteration
  double refine_tol = 1e-14;
  int max_refine_steps = 20;
};

namespace detail {

/// KKS control quaternions q_{-1} .. q_n of n keys from the interior ones q_0 .. q_{n-1}:
/// the natural ends q_{-1} = q_0 (q_0^-1 q_1)^-1, q_n = q_{n-1} (q_{n-2}^-1 q_{n-1}).
inline std::vector<Quaternion<double>> kks_with_ends(const std::vector<Quaternion<double>>& q) {
  const std::size_t n = q.size();
  std::vector<Quaternion<double>> c;
  c.reserve(n + 2);
  c.push_back(q[0] * inverse(inverse(q[0]) * q[1]));
  c.insert(c.end(), q.begin(), q.end());
  c.push_back(q[n - 1] * (inverse(q[n - 2]) * q[n - 1]));
  return c;
}

/// The KKS curve at key i (local t = 0 of segment i) from its control quaternions
/// q_{i-1}, q_i, q_{i+1}: q_{i-1} (q_{i-1}^-1 q_i)^{5/6} (q_i^-1 q_{i+1})^{1/6}.
inline Quaternion<double> kks_at_key(const Quaternion<double>& a, const Quaternion<double>& b,
                                     const Quaternion<double>& d) {
  return a * pow_unit(inverse(a) * b, 5.0 / 6) * pow_unit(inverse(b) * d, 1.0 / 6);
}

/// |log(Q^-1 q)|: the half-angle between two rotations (sign-free).
inline double rotation_distance(const Quaternion<double>& Q, const Quaternion<double>& q) {
  return log_unit(short_arc(inverse(Q) * q)).vec().norm();
}

/// The largest KKS interpolation residual |log(Q_i^-1 q(u_i))| over the keys, from the
/// control quaternions with ends c (c[k + 1] = q_k).
inline double kks_residual(const std::vector<Quaternion<double>>& keys,
                           const std::vector<Quaternion<double>>& c) {
  double r = 0;
  for (std::size_t i = 0; i < keys.size(); ++i)
    r = std::max(r, rotation_distance(keys[i], kks_at_key(c[i], c[i + 1], c[i + 2])));
  return r;
}

}  // namespace detail

/// Kim, Kim and Shin's C² B-spline quaternion curve through the keys (seed 000): the
/// cumulative-form uniform cubic B-spline whose control quaternions solve (11) with natural
/// ends, by the fixed-point iteration (13) until no control quaternion moves more than
/// options.tol (the map F of the paper: every q_i from the previous iterate), then
/// (options.refine) Gauss-Newton on (11) to options.refine_tol. Keys at
/// uniform knots mapped linearly onto [a, b]. Positions: the interpolating uniform cubic
/// B-spline with natural ends. Throws Errc::numerical_failure, naming the largest key
/// distance, when the iteration does not converge or converges to control quaternions that
/// miss a key by more than 1e-10 rad (10 x options.tol without refinement). The paper's
/// bound is 1.4 rad at an axis difference of pi/2; tests/bench/kks_convergence measures
/// convergence up to the half-turn limit there, and failure once the axis nearly reverses
/// between keys.
inline QuaternionSpline kks_spline(std::vector<Quaternion<double>> keys,
                                   std::vector<Eigen::Vector3d> positions, double a, double b,
                                   const KksOptions& options = {}) {
  QuaternionSpline s;
  s.scheme = QSplineScheme::kks;
  s.keys = std::move(keys);
  s.positions = std::move(positions);
  const std::size_t n = s.keys.size();
  s.knots = detail::uniform_knots(n, a, b);
  detail::prepare_keys(s);
  const auto& Q = s.keys;

  double theta = 0;  // the largest key distance |log(Q_{i-1}^-1 Q_i)|
  for (std::size_t i = 1; i < n; ++i)
    theta = std::max(theta, detail::rotation_distance(Q[i - 1], Q[i]));
  auto diverged = [&](const std::string& how) {
    return Error(Errc::numerical_failure,
                 "kks: the iteration for the control quaternions " + how +
                     "; the largest key distance |log(Q_i-1^-1 Q_i)| is " + std::to_string(theta) +
                     " rad (Kim, Kim and Shin converge below about 1.4 rad; insert keys between "
                     "distant ones, or use --scheme quintic or quartic, which need no iteration)");
  };

  // Fixed-point iteration (13), all q_i from the previous iterate; q_0, q_{n-1} are the keys.
  std::vector<Quaternion<double>> q = Q;
  double last = 0, best = std::numeric_limits<double>::infinity();
  int best_at = 0;  // a contraction improves; 100 steps without a new best is a cycle
  for (int it = 1; n > 2; ++it) {
    std::vector<Quaternion<double>> next = q;
    double moved = 0;
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const auto inner = inverse(q[i - 1]) * Q[i] * pow_unit(inverse(q[i]) * q[i + 1], -1.0 / 6);
      next[i] = q[i - 1] * pow_unit(inner, 6.0 / 5);
      if (next[i].dot(q[i]) < 0) next[i] = -next[i];
      moved = std::max(moved, detail::rotation_distance(q[i], next[i]));
    }
    q = std::move(next);
    s.iterations = it;
    if (!std::isfinite(moved)) throw diverged("produced non-numbers");
    if (last > 0) s.contraction = moved / last;
    last = moved;
    if (moved < options.tol) break;
    if (moved < best) {
      best = moved;
      best_at = it;
    }
    if (it >= options.max_iterations || moved > 10 || it - best_at > 100)
      throw diverged("did not converge in " + std::to_string(it) + " iterations (last step " +
                     std::to_string(moved) + " rad)");
  }
  s.fixed_point_residual = detail::kks_residual(Q, detail::kks_with_ends(q));

  // Gauss-Newton on the interior equations r_i = log(Q_i^-1 q(i)) = 0, i = 1..n-2, in the
  // unknowns q_i exp(d_i): block tridiagonal (r_i reads q_{i-1}, q_i, q_{i+1}; the natural
  // ends make q(0) = q_0 and q(n-1) = q_{n-1} hold identically), forward-difference blocks.
  if (options.refine && n > 2) {
    using M3 = Eigen::Matrix3d;
    const std::size_t m = n - 2;  // unknowns d_1 .. d_{n-2}
    auto r_at = [&](const std::vector<Quaternion<double>>& x, std::size_t i) {
      const auto at = detail::kks_at_key(x[i - 1], x[i], x[i + 1]);
      return Eigen::Vector3d(log_unit(detail::short_arc(inverse(Q[i]) * at)).vec());
    };
    for (int step = 0; step < options.max_refine_steps; ++step) {
      std::vector<Eigen::Vector3d> r(m);
      double rmax = 0;
      for (std::size_t j = 0; j < m; ++j) {
        r[j] = r_at(q, j + 1);
        rmax = std::max(rmax, r[j].norm());
      }
      if (rmax <= options.refine_tol) break;
      std::vector<M3> L(m, M3::Zero()), D(m, M3::Zero()), U(m, M3::Zero());
      const double h = 1e-7;
      for (std::size_t j = 0; j < m; ++j)
        for (int k = 0; k < 3; ++k) {
          const Quaternion<double> saved = q[j + 1];
          Eigen::Vector3d e = Eigen::Vector3d::Zero();
          e(k) = h;
          q[j + 1] = saved * exp_pure(Quaternion<double>::pure(e));
          for (std::size_t row = (j == 0 ? 0 : j - 1); row <= std::min(m - 1, j + 1); ++row) {
            const Eigen::Vector3d col = (r_at(q, row + 1) - r[row]) / h;
            if (row + 1 == j) U[row].col(k) = col;
            if (row == j) D[row].col(k) = col;
            if (row == j + 1) L[row].col(k) = col;
          }
          q[j + 1] = saved;
        }
      // Block Thomas: J d = -r.
      std::vector<M3> Dp(m);
      std::vector<Eigen::Vector3d> rp(m), d(m);
      Dp[0] = D[0];
      rp[0] = -r[0];
      for (std::size_t j = 1; j < m; ++j) {
        const M3 f = L[j] * Dp[j - 1].inverse();
        Dp[j] = D[j] - f * U[j - 1];
        rp[j] = -r[j] - f * rp[j - 1];
      }
      d[m - 1] = Dp[m - 1].inverse() * rp[m - 1];
      for (std::size_t j = m - 1; j-- > 0;) d[j] = Dp[j].inverse() * (rp[j] - U[j] * d[j + 1]);
      for (std::size_t j = 0; j < m; ++j) {
        if (!d[j].allFinite()) throw diverged("refinement met a singular Jacobian");
        q[j + 1] = normalized(q[j + 1] * exp_pure(Quaternion<double>::pure(d[j])));
      }
      s.newton_steps = step + 1;
    }
  }
  s.ctrl = detail::kks_with_ends(q);
  s.residual = detail::kks_residual(Q, s.ctrl);
  // A fixed point far from (11) (seen with axes turning by more than pi/2 between keys)
  // or a refinement that did not reach its goal is no interpolation.
  const double accept = options.refine ? 1e-10 : 10 * options.tol;
  if (!(s.residual <= accept))
    throw diverged("stopped at control quaternions that miss a key by " +
                   std::to_string(s.residual) + " rad");
  detail::finish(s);

  // Positions: p_{i-1} + 4 p_i + p_{i+1} = 6 P_i inside, p_0 = P_0, p_{n-1} = P_{n-1}
  // (natural ends), by the tridiagonal (Thomas) solve; then p_{-1}, p_n.
  std::vector<Eigen::Vector3d> p = s.positions;
  if (n > 2) {
    const std::size_t m = n - 2;
    std::vector<double> cp(m);
    std::vector<Eigen::Vector3d> dp(m);
    for (std::size_t j = 0; j < m; ++j) {
      Eigen::Vector3d rhs = 6 * s.positions[j + 1];
      if (j == 0) rhs -= s.positions[0];
      if (j + 1 == m) rhs -= s.positions[n - 1];
      const double denom = 4 - (j ? cp[j - 1] : 0.0);
      cp[j] = 1 / denom;
      dp[j] = (rhs - (j ? dp[j - 1] : Eigen::Vector3d::Zero().eval())) / denom;
    }
    for (std::size_t j = m; j-- > 0;)
      p[j + 1] = dp[j] - (j + 1 < m ? cp[j] * p[j + 2] : Eigen::Vector3d::Zero().eval());
  }
  s.pctrl.assign(1, 2 * p[0] - p[1]);
  s.pctrl.insert(s.pctrl.end(), p.begin(), p.end());
  s.pctrl.push_back(2 * p[n - 1] - p[n - 2]);
  return s;
}

/// A KKS spline from a recorded solution (no solve): the keys at uniform knots on [a, b],
/// the control quaternions q_{-1} .. q_n and the position spline's control points
/// p_{-1} .. p_n (two more than keys each). `residual` is recomputed from them; the solve's
/// other figures are left for the caller to restore.
inline QuaternionSpline kks_from_control(std::vector<Quaternion<double>> keys,
                                         std::vector<Eigen::Vector3d> positions, double a, double b,
                                         std::vector<Quaternion<double>> ctrl,
                                         std::vector<Eigen::Vector3d> pctrl) {
  QuaternionSpline s;
  s.scheme = QSplineScheme::kks;
  s.keys = std::move(keys);
  s.positions = std::move(positions);
  s.knots = detail::uniform_knots(s.keys.size(), a, b);
  detail::prepare_keys(s);
  if (ctrl.size() != s.keys.size() + 2 || pctrl.size() != s.keys.size() + 2)
    throw Error(Errc::invalid_input,
                "kks: expected two more control quaternions and points than keys");
  for (auto& q : ctrl) q = normalized(q);
  s.ctrl = std::move(ctrl);
  s.pctrl = std::move(pctrl);
  detail::finish(s);
  s.residual = detail::kks_residual(s.keys, s.ctrl);
  return s;
}

/// The spline of `scheme` through the keys and positions at the parameters t: the quintic
/// takes t as its knots and `tension` as its alpha per key; KKS and the quartic place the
/// keys at uniform knots on [t_0, t_n]. The one dispatch `qmotion qspline` and the viewer's
/// kernel share.
inline QuaternionSpline qspline(QSplineScheme scheme, std::vector<Quaternion<double>> keys,
                                std::vector<Eigen::Vector3d> positions,
                                const std::vector<double>& t, std::vector<double> tension = {}) {
  if (t.size() != keys.size() || t.size() < 2)
    throw Error(Errc::invalid_input, "qspline: expected a parameter for each of two or more keys");
  if (scheme == QSplineScheme::quintic)
    return quintic_spline(std::move(keys), std::move(positions), t, std::move(tension));
  if (scheme == QSplineScheme::quartic)
    return quartic_spline(std::move(keys), std::move(positions), t.front(), t.back());
  return kks_spline(std::move(keys), std::move(positions), t.front(), t.back());
}

}  // namespace qmotion::kernel
