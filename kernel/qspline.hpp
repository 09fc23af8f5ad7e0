// kernel/qspline.hpp: the non-rational mode (SPEC §3): unit-quaternion interpolation splines
// in cumulative form, with the matching R³ spline for the positions.
//   quartic: Xing, Fan, Tan, Xu 2017 (seed 003), (1)-(4), uniform knots;
//   quintic: Tan et al. (seed 002), (3.1)-(3.7), a tension per key and arbitrary knots.
// Both are explicit. Segment s of n keys (s = 0, ..., n-2) runs from key s to key s+1 with
// local parameter t in [0, 1] and reads the keys E_{s-1}, E_s, E_{s+1}, E_{s+2}, where the
// ends repeat (E_{-1} = E_0, E_n = E_{n-1}, as both papers define them):
//   q_s(t) = E_{s-1} exp(C~_1(t) w_{s-1}) exp(C~_2(t) w_s) exp(C~_3(t) w_{s+1}),
//   w_k = log(E_k^{-1} E_{k+1}),  C~_j = sum_{k>=j} C_k,
//   p_s(t) = sum_k C_k(t) P_{s-1+k},
// with C_k the scheme's blending functions; C~_0 = 1 for both schemes.
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
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
  std::vector<Quaternion<double>> omega;   ///< w_k = log(E_k^-1 E_k+1), k = -1 .. n-1

  double a() const { return knots.front(); }
  double b() const { return knots.back(); }
  int segments() const { return static_cast<int>(knots.size()) - 1; }

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
    s = std::min(n - 1, std::max(0, static_cast<int>(std::floor(g))));
    return {s, g - s};
  }

  /// The four blending functions C_0..C_3 of segment s at local parameter t.
  std::array<double, 4> blend(int s, double t) const {
    if (scheme == QSplineScheme::quintic) {
      const double al = tension[static_cast<std::size_t>(s)];
      const double be = tension[static_cast<std::size_t>(s + 1)];
      // Bezier points V_0..V_5 of (3.3) solved from (3.4), as weights of E_{s-1..s+2}.
      const double V[6][4] = {{0, 1, 0, 0},
                              {-al / 5, 1, al / 5, 0},
                              {-7 * al / 20, 1 - al / 10, 9 * al / 20, 0},
                              {0, 9 * be / 20, 1 - be / 10, -7 * be / 20},
                              {0, be / 5, 1, -be / 5},
                              {0, 0, 1, 0}};
      const double u = 1 - t;
      const double B[6] = {u * u * u * u * u,      5 * t * u * u * u * u, 10 * t * t * u * u * u,
                           10 * t * t * t * u * u, 5 * t * t * t * t * u, t * t * t * t * t};
      std::array<double, 4> c{0, 0, 0, 0};
      for (int k = 0; k < 6; ++k)
        for (int j = 0; j < 4; ++j) c[static_cast<std::size_t>(j)] += B[k] * V[k][j];
      return c;
    }
    // (4) of seed 003.
    const double t2 = t * t, t3 = t2 * t, t4 = t3 * t;
    return {0.5 * t4 - 1.5 * t3 + 1.5 * t2 - 0.5 * t, -0.5 * t4 + 2.5 * t3 - 3 * t2 + 1,
            -0.5 * t4 - 0.5 * t3 + 1.5 * t2 + 0.5 * t, 0.5 * t4 - 0.5 * t3};
  }

  /// The unit rotation at u.
  Quaternion<double> rotation(double u) const {
    const auto [s, t] = locate(u);
    const auto c = blend(s, t);
    const double c3 = c[3], c2 = c[2] + c3, c1 = c[1] + c2;  // cumulative C~_j
    const auto& w = omega;                                   // w[k + 1] is w_k
    Quaternion<double> q = key(s - 1);
    q = q * exp_pure(w[static_cast<std::size_t>(s)] * c1);
    q = q * exp_pure(w[static_cast<std::size_t>(s + 1)] * c2);
    q = q * exp_pure(w[static_cast<std::size_t>(s + 2)] * c3);
    return q;
  }

  /// The position (image of the moving origin) at u.
  Eigen::Vector3d position(double u) const {
    const auto [s, t] = locate(u);
    const auto c = blend(s, t);
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int j = 0; j < 4; ++j) p += c[static_cast<std::size_t>(j)] * point(s - 1 + j);
    return p;
  }

  /// Key k with the ends repeated (k = -1 .. n).
  const Quaternion<double>& key(int k) const {
    const int n = static_cast<int>(keys.size());
    return keys[static_cast<std::size_t>(std::min(n - 1, std::max(0, k)))];
  }
  const Eigen::Vector3d& point(int k) const {
    const int n = static_cast<int>(positions.size());
    return positions[static_cast<std::size_t>(std::min(n - 1, std::max(0, k)))];
  }
};

namespace detail {

/// Checks and prepares keys: unit, signs aligned along the sequence, no half-turn between
/// neighbours; the logarithms w_k with the ends repeated.
inline void prepare_keys(QuaternionSpline& s) {
  const std::size_t n = s.keys.size();
  if (n < 2 || s.positions.size() != n || s.knots.size() != n)
    throw Error(Errc::invalid_input, std::string(to_string(s.scheme)) +
                                         ": needs at least two keys, with one position and "
                                         "one parameter each");
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
  s.omega.clear();
  for (int k = -1; k < static_cast<int>(n); ++k)
    s.omega.push_back(log_unit(inverse(s.key(k)) * s.key(k + 1)));
}

}  // namespace detail

/// Xing et al.'s quartic spline through the keys (seed 003, (1)-(4)): C² at the keys, the
/// keys at uniform knots mapped linearly onto [a, b] (`knots` records where each key is).
inline QuaternionSpline quartic_spline(std::vector<Quaternion<double>> keys,
                                       std::vector<Eigen::Vector3d> positions, double a, double b) {
  QuaternionSpline s;
  s.scheme = QSplineScheme::quartic;
  s.keys = std::move(keys);
  s.positions = std::move(positions);
  const std::size_t n = s.keys.size();
  for (std::size_t i = 0; i < n; ++i)
    s.knots.push_back(n > 1 ? a + (b - a) * static_cast<double>(i) / static_cast<double>(n - 1)
                            : a);
  if (n > 1) s.knots.back() = b;
  detail::prepare_keys(s);
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
  return s;
}

}  // namespace qmotion::kernel
