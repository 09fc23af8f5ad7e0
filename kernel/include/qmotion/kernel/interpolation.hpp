// <qmotion/kernel/interpolation.hpp>
#pragma once
#include <cmath>
#include <optional>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/linear_solve.hpp>
#include <qmotion/kernel/methods.hpp>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/kernel/motion_value.hpp>
#include <qmotion/kernel/pose.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace qmotion::kernel {

struct InterpolationOptions {
  RotationMethod rotation = RotationMethod::elliptic;
  TranslationMethod translation = TranslationMethod::tr;
  /// TRT degrees (l1, l2) with l1 + l2 = m - 1; default (m - 1, 0).
  std::optional<std::pair<int, int>> trt_degrees;
  /// Largest accepted relative interpolation residual (double); above it the solve is
  /// refused as ill-conditioned.
  double max_residual = 1e-9;
};

/// Order (degree of a general point's trajectory) that the construction guarantees for
/// rotational degree k and translational degree l1 (TRT: l1, l2): TR 2k + l (Proposition 4),
/// TRT 2k + max(l1, l2), minimal order max(2k, l) (Theorem 6, (36)-(39)). Special data can
/// lower it further.
inline int construction_order(TranslationMethod method, int k, int l1, int l2 = 0) {
  switch (method) {
    case TranslationMethod::tr:
      return 2 * k + l1;
    case TranslationMethod::trt:
      return 2 * k + std::max(l1, l2);
    case TranslationMethod::minimal:
      return std::max(2 * k, l1);
  }
  return 0;
}

/// Rotation degree k for m + 1 poses: m, or ceil(3m/4) for the projective method.
inline int rotation_degree(RotationMethod method, int m) {
  return method == RotationMethod::projective ? (3 * m + 3) / 4 : m;
}

/// The rotations R_i normalised (23) with the signs of (24): each R_{i+1} on the side of
/// R_i (non-negative inner product). Exact Scalar: the factor 1/|r_i| is the double
/// nearest it, used exactly (exactly 1/|r_i| whenever that is a double); interpolation
/// stays exact because any non-zero factor lambda_i is allowed in (18).
template <typename Scalar>
std::vector<Quaternion<Scalar>> normalized_rotations(const std::vector<Pose<Scalar>>& poses) {
  std::vector<Quaternion<Scalar>> R;
  for (const auto& p : poses) {
    const double n = std::sqrt(to_double(p.rotation.norm2()));
    Quaternion<Scalar> r = p.rotation * Scalar(1.0 / n);
    if (!R.empty() && R.back().dot(r) < Scalar(0)) r = -r;
    R.push_back(r);
  }
  return R;
}

/// Relative residual (pose_residual) of the motion at every pose P_i at t_i. Exact Scalar:
/// 0 where Q(t_i) is exactly proportional to P_i, else the residual in double.
template <typename Scalar>
std::vector<double> pose_residuals(const QMotion<Scalar>& m, const std::vector<Pose<Scalar>>& poses,
                                   const std::vector<Scalar>& t) {
  std::vector<double> out;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const auto qi = evaluate(m, t[i]);
    const auto pi = poses[i].dual_quaternion();
    if constexpr (is_exact_v<Scalar>) {
      bool proportional = true;
      for (int c = 0; c < 8 && proportional; ++c)
        for (int d = c + 1; d < 8 && proportional; ++d)
          proportional = qi[c] * pi[d] == qi[d] * pi[c];
      if (proportional) {
        out.push_back(0.0);
        continue;
      }
      DualQuaternion<double> qd, pd;
      for (int c = 0; c < 8; ++c) {
        qd[c] = to_double(qi[c]);
        pd[c] = to_double(pi[c]);
      }
      out.push_back(pose_residual(qd, pd));
    } else {
      out.push_back(pose_residual(qi, pi));
    }
  }
  return out;
}

namespace detail {

template <typename Scalar>
Bernstein<Quaternion<Scalar>> quaternion_poly(const MatX<Scalar>& C, const Scalar& a,
                                              const Scalar& b) {
  std::vector<Quaternion<Scalar>> c;
  for (Eigen::Index j = 0; j < C.rows(); ++j) c.emplace_back(C(j, 0), C(j, 1), C(j, 2), C(j, 3));
  return Bernstein<Quaternion<Scalar>>(std::move(c), a, b);
}

/// Pure-quaternion polynomial from the rows of P (3 columns).
template <typename Scalar>
Bernstein<Quaternion<Scalar>> vector_poly(const MatX<Scalar>& P, const Scalar& a, const Scalar& b) {
  std::vector<Quaternion<Scalar>> c;
  for (Eigen::Index j = 0; j < P.rows(); ++j) c.emplace_back(Scalar(0), P(j, 0), P(j, 1), P(j, 2));
  return Bernstein<Quaternion<Scalar>>(std::move(c), a, b);
}

/// Dual-quaternion polynomial real + eps dual (both elevated to the higher degree).
template <typename Scalar>
Bernstein<DualQuaternion<Scalar>> dual_poly(const Bernstein<Quaternion<Scalar>>& real,
                                            const Bernstein<Quaternion<Scalar>>& dual) {
  const int n = std::max(real.degree(), dual.degree());
  const auto r = elevate(real, n - real.degree()), d = elevate(dual, n - dual.degree());
  std::vector<DualQuaternion<Scalar>> c;
  for (int i = 0; i <= n; ++i) c.emplace_back(r[i], d[i]);
  return Bernstein<DualQuaternion<Scalar>>(std::move(c), real.a(), real.b());
}

template <typename Scalar>
bool is_negligible_quaternion(const Quaternion<Scalar>& q, double scale) {
  if constexpr (is_exact_v<Scalar>) {
    (void)scale;
    return q.norm2() == Scalar(0);
  } else {
    return std::sqrt(q.norm2()) <= 1e-8 * scale;
  }
}

/// Interpolation results must be exact in exact arithmetic: a pose missed there is a bug.
template <typename Scalar>
std::vector<double> checked_residuals(const QMotion<Scalar>& m,
                                      const std::vector<Pose<Scalar>>& poses,
                                      const std::vector<Scalar>& t) {
  std::vector<double> r = pose_residuals(m, poses, t);
  if constexpr (is_exact_v<Scalar>)
    for (std::size_t i = 0; i < r.size(); ++i)
      if (r[i] != 0.0)
        throw Error(Errc::internal, "exact interpolation missed pose " + std::to_string(i));
  return r;
}

/// The factors of a Bezier interpolation (one Bezier piece each on [a, b]): Q_rot and the
/// translational coefficient rows (TRT: both).
template <typename Scalar>
MotionFactors<Scalar> bezier_factors(TranslationMethod method,
                                     const Bernstein<Quaternion<Scalar>>& rot,
                                     const MatX<Scalar>& P1, const MatX<Scalar>& P2) {
  using V3 = Eigen::Matrix<Scalar, 3, 1>;
  auto rows = [&](const MatX<Scalar>& P) {
    std::vector<V3> c;
    for (Eigen::Index j = 0; j < P.rows(); ++j) c.emplace_back(P(j, 0), P(j, 1), P(j, 2));
    return BSpline<V3>::from_bezier(Bernstein<V3>(std::move(c), rot.a(), rot.b()));
  };
  MotionFactors<Scalar> f{method, BSpline<Quaternion<Scalar>>::from_bezier(rot), rows(P1),
                          std::nullopt};
  if (method == TranslationMethod::trt) f.translation2 = rows(P2);
  return f;
}

}  // namespace detail

/// Rotational Q-motion (17) through the rotations of the poses at parameters t.
/// - elliptic (22)-(25): degree m through the normalised, sign-consistent R_i;
/// - affine (19)-(21): degree m, Scal Q_rot = 1; refuses half-turns (r_i0 = 0);
/// - projective (27)-(28): degree k = ceil(3m/4); among the solutions of the homogeneous
///   system (28), the one nearest (least squares at the poses) to the normalised,
///   sign-consistent R_i. This is unique also when the null space of (28) has dimension
///   above one (3m not divisible by 4), fixes scale and sign, and is linear (exact).
///   Poses with Q_rot(t_i) = 0 (inaccessible) are refused.
/// Throws Errc::numerical_failure (singular or refused systems).
template <typename Scalar>
Bernstein<Quaternion<Scalar>> interpolate_rotation(const std::vector<Pose<Scalar>>& poses,
                                                   const std::vector<Scalar>& t,
                                                   RotationMethod method) {
  const int m = static_cast<int>(poses.size()) - 1;
  const Scalar a = t.front(), b = t.back();
  const int k = rotation_degree(method, m);
  const MatX<Scalar> B = bernstein_collocation(t, k, a, b);
  if (method == RotationMethod::affine) {
    MatX<Scalar> V(m + 1, 3);
    for (int i = 0; i <= m; ++i) {
      const auto& r = poses[static_cast<std::size_t>(i)].rotation;
      const bool half_turn =
          is_exact_v<Scalar> ? r.w() == Scalar(0)
                             : std::abs(to_double(r.w())) <= 1e-9 * std::sqrt(to_double(r.norm2()));
      if (half_turn)
        throw Error(Errc::numerical_failure,
                    "pose " + std::to_string(i) +
                        " is a half-turn (rotation angle 180 degrees, r0 = 0): the affine method "
                        "maps it to infinity and cannot interpolate it; use --rotation elliptic");
      for (int c = 0; c < 3; ++c) V(i, c) = Scalar(r[c + 1] / r.w());
    }
    const MatX<Scalar> P = solve_square(B, V, "the affine rotation system (21)");
    MatX<Scalar> C(m + 1, 4);
    C.col(0).setConstant(Scalar(1));
    C.rightCols(3) = P;
    return detail::quaternion_poly(C, a, b);
  }
  const auto R = normalized_rotations(poses);
  if (method == RotationMethod::elliptic) {
    MatX<Scalar> Rm(m + 1, 4);
    for (int i = 0; i <= m; ++i)
      for (int c = 0; c < 4; ++c) Rm(i, c) = R[static_cast<std::size_t>(i)][c];
    return detail::quaternion_poly(solve_square(B, Rm, "the elliptic rotation system (25)"), a, b);
  }
  // Projective: unknowns c = (C_0, ..., C_k) stacked by 4.
  const Eigen::Index nu = 4 * (k + 1);
  MatX<Scalar> E = MatX<Scalar>::Zero(3 * (m + 1), nu), A = MatX<Scalar>::Zero(4 * (m + 1), nu);
  MatX<Scalar> rhs(4 * (m + 1), 1);
  for (int i = 0; i <= m; ++i) {
    const auto& r = poses[static_cast<std::size_t>(i)].rotation;
    for (int j = 0; j <= k; ++j) {
      const Scalar bij = B(i, j);
      for (int c = 1; c <= 3; ++c) {
        E(3 * i + c - 1, 4 * j + c) += Scalar(bij * r.w());
        E(3 * i + c - 1, 4 * j) -= Scalar(bij * r[c]);
      }
      for (int c = 0; c < 4; ++c) A(4 * i + c, 4 * j + c) = bij;
    }
    for (int c = 0; c < 4; ++c) rhs(4 * i + c, 0) = R[static_cast<std::size_t>(i)][c];
  }
  const MatX<Scalar> N = null_space(E);
  if (N.cols() == 0)
    throw Error(Errc::numerical_failure,
                "the projective rotation system (28) has only the zero solution");
  const MatX<Scalar> AN = A * N;
  const MatX<Scalar> y =
      solve_square(MatX<Scalar>(AN.transpose() * AN), MatX<Scalar>(AN.transpose() * rhs),
                   "the projective least-squares selection");
  const MatX<Scalar> c = N * y;
  MatX<Scalar> C(k + 1, 4);
  for (int j = 0; j <= k; ++j)
    for (int q = 0; q < 4; ++q) C(j, q) = c(4 * j + q, 0);
  auto rot = detail::quaternion_poly(C, a, b);
  double scale = 0;
  for (const auto& q : rot.coeffs()) scale = std::max(scale, std::sqrt(to_double(q.norm2())));
  for (int i = 0; i <= m; ++i)
    if (detail::is_negligible_quaternion(evaluate(rot, t[static_cast<std::size_t>(i)]), scale))
      throw Error(Errc::numerical_failure, "pose " + std::to_string(i) +
                                               " is inaccessible for the projective method "
                                               "(Q_rot(t_i) = 0); use --rotation elliptic");
  return rot;
}

/// Parameters (by index) where |Q_rot(t_i)| is below 1% of Q_rot's largest coefficient:
/// near-inaccessible poses (a somersault passes close by), where rounding is amplified, up
/// to the cube of the ratio under the minimal-order method.
template <typename Scalar>
std::vector<int> near_inaccessible(const BSpline<Quaternion<Scalar>>& rot,
                                   const std::vector<Scalar>& t) {
  double scale = 0;
  for (const auto& c : rot.ctrl()) scale = std::max(scale, std::sqrt(to_double(c.norm2())));
  std::vector<int> out;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (std::sqrt(to_double(evaluate(rot, t[i]).norm2())) < 0.01 * scale)
      out.push_back(static_cast<int>(i));
  return out;
}

/// Interpolating Bezier Q-motion through the poses at parameters t (strictly increasing),
/// by Juettler's rotation methods combined with TR (30)-(31) (Algorithm 1), TRT (32)-(34)
/// or the minimal-order translation (36)-(39). Checks every pose afterwards and refuses
/// (Errc::numerical_failure) a result whose relative residual exceeds
/// options.max_residual: one Bezier through many poses is ill-conditioned.
template <typename Scalar>
Motion<Scalar> interpolate_bezier(const std::vector<Pose<Scalar>>& poses,
                                  const std::vector<Scalar>& t,
                                  const InterpolationOptions& options) {
  if (poses.size() < 2) throw Error(Errc::invalid_input, "needs at least two poses");
  if (t.size() != poses.size()) throw Error(Errc::internal, "one parameter per pose expected");
  for (std::size_t i = 1; i < t.size(); ++i)
    if (!(t[i - 1] < t[i]))
      throw Error(Errc::invalid_input,
                  "parameters must increase strictly (pose " + std::to_string(i) + ")");
  const int m = static_cast<int>(poses.size()) - 1;
  const Scalar a = t.front(), b = t.back();
  if constexpr (!is_exact_v<Scalar>) {
    // The Bernstein collocation matrix of degree m is the heart of every system below; its
    // conditioning grows quickly with m, so one Bezier through many poses is refused here.
    const double rc = Eigen::FullPivLU<MatX<Scalar>>(bernstein_collocation(t, m, a, b)).rcond();
    if (!(rc > 1e-13))
      throw Error(Errc::numerical_failure,
                  "one Bezier motion through " + std::to_string(m + 1) +
                      " poses is ill-conditioned (Bernstein collocation of degree " +
                      std::to_string(m) + ", reciprocal condition " + detail::format_double(rc) +
                      "); use --form bspline");
  }
  Provenance<Scalar> prov;
  prov.rotation = options.rotation;
  prov.translation = options.translation;
  prov.parameters = t;
  prov.poses = poses;
  const Bernstein<Quaternion<Scalar>> rot = interpolate_rotation(poses, t, options.rotation);
  prov.rotation_degree = rot.degree();
  MatX<Scalar> translation, translation2;  // rows: coefficients of the translational factor(s)
  MatX<Scalar> S(m + 1, 3);
  for (int i = 0; i <= m; ++i) S.row(i) = poses[static_cast<std::size_t>(i)].position.transpose();

  Bernstein<DualQuaternion<Scalar>> q;
  switch (options.translation) {
    case TranslationMethod::tr: {
      prov.translation_degree = m;
      const MatX<Scalar> P =
          solve_square(bernstein_collocation(t, m, a, b), S, "the translation system (31)");
      translation = P;
      std::vector<DualQuaternion<Scalar>> trans;
      for (int j = 0; j <= m; ++j)
        trans.push_back(DualQuaternion<Scalar>::translation(P.row(j).transpose()));
      q = product(Bernstein<DualQuaternion<Scalar>>(std::move(trans), a, b), rot);
      break;
    }
    case TranslationMethod::trt: {
      const auto [l1, l2] = options.trt_degrees.value_or(std::make_pair(m - 1, 0));
      if (l1 < 0 || l2 < 0 || l1 + l2 != m - 1)
        throw Error(Errc::invalid_input,
                    "--trt-degrees " + std::to_string(l1) + "," + std::to_string(l2) +
                        ": needs L1, L2 >= 0 with L1 + L2 = m - 1 = " + std::to_string(m - 1));
      if (l1 == l2 && l1 % 2 == 0)
        throw Error(Errc::invalid_input,
                    "--trt-degrees " + std::to_string(l1) + "," + std::to_string(l2) +
                        ": a split with L1 = L2 even makes the TRT system (34) singular for every "
                        "data set" +
                        (m == 1 ? " (so TRT cannot interpolate two poses; use --translation tr)"
                                : "; choose another split"));
      prov.translation_degree = l1;
      prov.translation_degree2 = l2;
      // p1(t_i) + R(Q_rot(t_i)) p2(t_i) = s_i: (34) divided by |Q_rot(t_i)|^2.
      const MatX<Scalar> B1 = bernstein_collocation(t, l1, a, b),
                         B2 = bernstein_collocation(t, l2, a, b);
      const Eigen::Index n1 = 3 * (l1 + 1), n = n1 + 3 * (l2 + 1);
      MatX<Scalar> M = MatX<Scalar>::Zero(3 * (m + 1), n);
      MatX<Scalar> rhs(3 * (m + 1), 1);
      for (int i = 0; i <= m; ++i) {
        const Eigen::Matrix<Scalar, 3, 3> Ri =
            rotation_matrix(evaluate(rot, t[static_cast<std::size_t>(i)]));
        for (int j = 0; j <= l1; ++j)
          for (int c = 0; c < 3; ++c) M(3 * i + c, 3 * j + c) = B1(i, j);
        for (int j = 0; j <= l2; ++j)
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) M(3 * i + r, n1 + 3 * j + c) = Scalar(B2(i, j) * Ri(r, c));
        for (int c = 0; c < 3; ++c) rhs(3 * i + c, 0) = S(i, c);
      }
      Eigen::FullPivLU<MatX<Scalar>> lu(M);
      bool deficient = false;
      std::string cond;
      if constexpr (is_exact_v<Scalar>) {
        deficient = lu.rank() < M.rows();
      } else {
        // Full pivoting reveals the rank: a pivot below 1e-12 of the largest is a zero.
        lu.setThreshold(1e-12);
        deficient = lu.rank() < M.rows() || !(lu.rcond() > 1e-12);
        cond = " (rank " + std::to_string(lu.rank()) + " of " + std::to_string(M.rows()) +
               ", reciprocal condition " + detail::format_double(lu.rcond()) + ")";
      }
      if (deficient)
        throw Error(Errc::numerical_failure,
                    "the TRT system (34) is rank-deficient" + cond +
                        ", e.g. through repeated orientations or smooth data with many poses; use "
                        "--translation tr or another --trt-degrees split");
      const MatX<Scalar> p = lu.solve(rhs);
      MatX<Scalar> P1(l1 + 1, 3), P2(l2 + 1, 3);
      for (int j = 0; j <= l1; ++j)
        for (int c = 0; c < 3; ++c) P1(j, c) = p(3 * j + c, 0);
      for (int j = 0; j <= l2; ++j)
        for (int c = 0; c < 3; ++c) P2(j, c) = p(n1 + 3 * j + c, 0);
      // (2 + eps p1) Q_rot (2 + eps p2) = 4 Q_rot + eps 2 (p1 Q_rot + Q_rot p2).
      translation = P1;
      translation2 = P2;
      const auto p1 = detail::vector_poly(P1, a, b), p2 = detail::vector_poly(P2, a, b);
      const auto real = map_coeffs(
          rot, [](const Quaternion<Scalar>& x) { return Quaternion<Scalar>(x * Scalar(4)); });
      const auto dual =
          map_coeffs(product(p1, rot) + product(rot, p2),
                     [](const Quaternion<Scalar>& x) { return Quaternion<Scalar>(x * Scalar(2)); });
      q = detail::dual_poly(real, dual);
      break;
    }
    case TranslationMethod::minimal: {
      prov.translation_degree = m;
      // w(t_i) = |Q_rot(t_i)|^2 s_i (39); Q = (2 |Q_rot|^2 + eps w) * Q_rot (36)-(38).
      MatX<Scalar> W = S;
      for (int i = 0; i <= m; ++i)
        W.row(i) *= evaluate(rot, t[static_cast<std::size_t>(i)]).norm2();
      const MatX<Scalar> P =
          solve_square(bernstein_collocation(t, m, a, b), W, "the translation system (39)");
      translation = P;
      const auto w = detail::vector_poly(P, a, b);
      const auto n2 =
          product(rot, map_coeffs(rot, [](const Quaternion<Scalar>& x) { return x.conj(); }));
      const auto real = map_coeffs(product(n2, rot), [](const Quaternion<Scalar>& x) {
        return Quaternion<Scalar>(x * Scalar(2));
      });
      q = detail::dual_poly(real, product(w, rot));
      break;
    }
  }
  Motion<Scalar> out(
      QMotion<Scalar>{Basis::bezier, BSpline<DualQuaternion<Scalar>>::from_bezier(q)},
      detail::bezier_factors(options.translation, rot, translation, translation2));
  prov.near_inaccessible = near_inaccessible(out.factors->rotation, t);
  // Check every pose: exactly proportional for exact Scalar, within max_residual otherwise.
  prov.residuals = detail::checked_residuals(out.curve, poses, t);
  for (int i = 0; i <= m; ++i) {
    const double res = prov.residuals[static_cast<std::size_t>(i)];
    if (!(res <= options.max_residual))
      throw Error(Errc::numerical_failure,
                  "interpolation residual " + detail::format_double(res) + " at pose " +
                      std::to_string(i) + " exceeds " +
                      detail::format_double(options.max_residual) +
                      ": one Bezier motion of degree " + std::to_string(q.degree()) + " through " +
                      std::to_string(m + 1) + " poses is ill-conditioned; use --form bspline");
  }
  out.provenance = std::move(prov);
  return out;
}

}  // namespace qmotion::kernel
