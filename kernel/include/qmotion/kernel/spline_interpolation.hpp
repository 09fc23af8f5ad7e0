// <qmotion/kernel/spline_interpolation.hpp>
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <qmotion/kernel/banded.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/kernel/motion_factors.hpp>
#include <string>
#include <type_traits>
#include <vector>

namespace qmotion::kernel {

/// Clamped knot vector for interpolation of n = t.size() values by degree p, by averaging
/// (interior knot j + p is the mean of t_j .. t_{j+p-1}): the Schoenberg-Whitney
/// conditions hold, so the collocation matrix is nonsingular and totally positive.
/// @see Piegl & Tiller, The NURBS Book, (9.8)
template <typename Scalar>
std::vector<Scalar> averaged_knots(const std::vector<Scalar>& t, int p) {
  const std::size_t n = t.size(), up = static_cast<std::size_t>(p);
  std::vector<Scalar> k(up + 1, t.front());
  for (std::size_t j = 1; j + up < n; ++j) {
    Scalar s(0);
    for (std::size_t i = j; i < j + up; ++i) s += t[i];
    k.push_back(Scalar(s / Scalar(p)));
  }
  k.insert(k.end(), up + 1, t.back());
  return k;
}

/// The interior knots of `knots` that lie within rounding (64 ulp of the interval) of a
/// knot of `ref`, replaced by it. Averages of different lengths coincide for uniform
/// parameters but round differently; snapped, the product of the two splines has one
/// breakpoint there instead of two a few ulp apart (whose tiny span would make its
/// reassembly ill-conditioned). Interpolation stays exact: any knots satisfying
/// Schoenberg-Whitney serve. Exact scalars are left alone (their averages are exact).
template <typename Scalar>
std::vector<Scalar> snap_knots(std::vector<Scalar> knots, const std::vector<Scalar>& ref) {
  if constexpr (std::is_floating_point_v<Scalar>) {
    const Scalar tol = 64 * std::numeric_limits<Scalar>::epsilon() * (knots.back() - knots.front());
    for (auto& k : knots) {
      const auto it = std::lower_bound(ref.begin(), ref.end(), k);
      if (it != ref.end() && *it - k <= tol) {
        k = *it;
      } else if (it != ref.begin() && k - *(it - 1) <= tol) {
        k = *(it - 1);
      }
    }
  }
  return knots;
}

/// Poles of the degree-p B-spline on averaged knots through the rows of V at t (one banded
/// solve: O(n p^2), linear in the number of values).
template <typename Scalar>
MatX<Scalar> interpolating_poles(const std::vector<Scalar>& t, const std::vector<Scalar>& knots,
                                 int p, const MatX<Scalar>& V, const std::string& what) {
  const Eigen::Index n = static_cast<Eigen::Index>(t.size());
  BandMatrix<Scalar> A(n, p);
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::size_t ui = static_cast<std::size_t>(i);
    int j =
        static_cast<int>(std::upper_bound(knots.begin(), knots.end(), t[ui]) - knots.begin()) - 1;
    j = std::min(std::max(j, p), static_cast<int>(n) - 1);
    const auto N = basis_functions(knots, j, p, t[ui]);
    for (int k = 0; k <= p; ++k) {
      const Eigen::Index col = j - p + k;
      if (N[static_cast<std::size_t>(k)] != Scalar(0)) A(i, col) = N[static_cast<std::size_t>(k)];
    }
  }
  return solve_banded(A, V, what);
}

struct SplineOptions {
  TranslationMethod translation = TranslationMethod::tr;  ///< tr or minimal
  int k = 3;                                              ///< rotational degree
  int l = 3;                                              ///< translational degree
  double max_residual = 1e-9;
};

namespace detail {

template <typename Scalar>
BSpline<Quaternion<Scalar>> quaternion_spline(int p, std::vector<Scalar> knots,
                                              const MatX<Scalar>& C) {
  std::vector<Quaternion<Scalar>> c;
  for (Eigen::Index j = 0; j < C.rows(); ++j) c.emplace_back(C(j, 0), C(j, 1), C(j, 2), C(j, 3));
  return BSpline<Quaternion<Scalar>>::make(p, std::move(knots), std::move(c));
}

template <typename Scalar>
BSpline<Eigen::Matrix<Scalar, 3, 1>> vector_spline(int p, std::vector<Scalar> knots,
                                                   const MatX<Scalar>& P) {
  std::vector<Eigen::Matrix<Scalar, 3, 1>> c;
  for (Eigen::Index j = 0; j < P.rows(); ++j) c.emplace_back(P(j, 0), P(j, 1), P(j, 2));
  return BSpline<Eigen::Matrix<Scalar, 3, 1>>::make(p, std::move(knots), std::move(c));
}

/// The Q-motion of the factors: TR (2 + eps p) Q_rot (30), or minimal order
/// (2 |Q_rot|^2 + eps w) Q_rot (36), as exact spline products (Bezier decomposition, (29),
/// reassembly with the multiplicities the factors' continuity allows).
template <typename Scalar>
BSpline<DualQuaternion<Scalar>> compose(const MotionFactors<Scalar>& f) {
  using DQ = DualQuaternion<Scalar>;
  using Q = Quaternion<Scalar>;
  using V3 = Eigen::Matrix<Scalar, 3, 1>;
  if (f.method == TranslationMethod::tr) {
    const auto T = map_coeffs(f.translation, [](const V3& p) { return DQ::translation(p); });
    return product(T, f.rotation);
  }
  const auto rc = map_coeffs(f.rotation, [](const Q& q) { return q.conj(); });
  const auto n2 = map_coeffs(product(f.rotation, rc), [](const Q& q) { return Scalar(q.w()); });
  const auto real =
      map_coeffs(product(n2, f.rotation), [](const Q& q) { return Q(q * Scalar(2)); });
  const auto dual =
      product(map_coeffs(f.translation, [](const V3& p) { return Q::pure(p); }), f.rotation);
  return combine(real, dual, [](const Bernstein<Q>& a, const Bernstein<Q>& b) {
    std::vector<DQ> c;
    for (int i = 0; i <= a.degree(); ++i) c.emplace_back(a[i], b[i]);
    return Bernstein<DQ>(std::move(c), a.a(), a.b());
  });
}

template <typename Scalar>
Motion<Scalar> finish(MotionFactors<Scalar> f, int k, int l, const std::vector<Pose<Scalar>>& poses,
                      const std::vector<Scalar>& t, double max_residual, Form form) {
  Provenance<Scalar> prov;
  prov.form = form;
  prov.translation = f.method;
  prov.rotation_degree = k;
  prov.translation_degree = l;
  prov.parameters = t;
  prov.poses = poses;
  QMotion<Scalar> curve{Basis::bspline, compose(f)};
  Motion<Scalar> out(std::move(curve), std::move(f));
  prov.residuals = checked_residuals(out.curve, poses, t);
  for (std::size_t i = 0; i < prov.residuals.size(); ++i)
    if (!(prov.residuals[i] <= max_residual))
      throw Error(Errc::numerical_failure,
                  std::string(form == Form::c1 ? "C1 spline" : "B-spline") +
                      " motion: interpolation residual " +
                      detail::format_double(prov.residuals[i]) + " at pose " + std::to_string(i) +
                      " exceeds " + detail::format_double(max_residual));
  out.provenance = std::move(prov);
  return out;
}

inline void check_parameters(std::size_t poses, std::size_t params) {
  if (poses < 2) throw Error(Errc::invalid_input, "needs at least two poses");
  if (params != poses) throw Error(Errc::internal, "one parameter per pose expected");
}

}  // namespace detail

/// B-spline Q-motion through the poses (section 6): the normalised, sign-consistent
/// rotations (23)-(24) interpolated by a B-spline of degree k, the positions (TR) or
/// |Q_rot(t_i)|^2 s_i (minimal order, (39)) by one of degree l, each on knots averaged from
/// the parameters, each by one banded solve (cost linear in the number of poses); then
/// the product. Degree k + l (TR) or k + max(2k, l) (minimal order); the motion and every
/// trajectory are C^(min(k, l) - 1) (C^2 for the default cubic factors). With fewer poses
/// than degree + 1 a factor's degree drops to (poses - 1).
template <typename Scalar>
Motion<Scalar> interpolate_bspline(const std::vector<Pose<Scalar>>& poses,
                                   const std::vector<Scalar>& t, const SplineOptions& opt) {
  detail::check_parameters(poses.size(), t.size());
  if (opt.translation == TranslationMethod::trt)
    throw Error(Errc::invalid_input,
                "--translation trt is not available for spline motions (use tr or minimal)");
  if (opt.k < 1 || opt.l < 1) throw Error(Errc::invalid_input, "spline degrees must be at least 1");
  for (std::size_t i = 1; i < t.size(); ++i)
    if (!(t[i - 1] < t[i]))
      throw Error(Errc::invalid_input,
                  "parameters must increase strictly (pose " + std::to_string(i) + ")");
  const int n = static_cast<int>(poses.size());
  const int k = std::min(opt.k, n - 1), l = std::min(opt.l, n - 1);
  const auto R = normalized_rotations(poses);
  MatX<Scalar> Rm(n, 4);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 4; ++c) Rm(i, c) = R[static_cast<std::size_t>(i)][c];
  const auto kr = averaged_knots(t, k);
  auto rot = detail::quaternion_spline(
      k, kr, interpolating_poles(t, kr, k, Rm, "the rotational B-spline system"));
  MatX<Scalar> S(n, 3);
  for (int i = 0; i < n; ++i) {
    S.row(i) = poses[static_cast<std::size_t>(i)].position.transpose();
    if (opt.translation == TranslationMethod::minimal)
      S.row(i) *= evaluate(rot, t[static_cast<std::size_t>(i)]).norm2();
  }
  const auto kt = snap_knots(averaged_knots(t, l), kr);
  auto trans = detail::vector_spline(
      l, kt, interpolating_poles(t, kt, l, S, "the translational B-spline system"));
  return detail::finish(
      MotionFactors<Scalar>{opt.translation, std::move(rot), std::move(trans), std::nullopt}, k, l,
      poses, t, opt.max_residual, Form::bspline);
}

/// Velocity estimates at the parameters (documented for Algorithm 2): with
/// D_i = (x_{i+1} - x_i) / h_i and h_i = t_{i+1} - t_i, at interior points the derivative
/// of the parabola through the three neighbours (Bessel),
///   v_i = (h_i D_{i-1} + h_{i-1} D_i) / (h_{i-1} + h_i),
/// at the ends the same parabola's end derivative,
///   v_0 = ((2 h_0 + h_1) D_0 - h_0 D_1) / (h_0 + h_1), symmetric at v_m;
/// with two points both are D_0. `D` holds the m differences D_i.
inline std::vector<Eigen::Vector3d> bessel_estimates(const std::vector<Eigen::Vector3d>& D,
                                                     const std::vector<double>& t) {
  const std::size_t m = D.size();
  std::vector<Eigen::Vector3d> v(m + 1);
  if (m == 1) {
    v[0] = v[1] = D[0];
    return v;
  }
  auto h = [&](std::size_t i) { return t[i + 1] - t[i]; };
  for (std::size_t i = 1; i < m; ++i)
    v[i] = (h(i) * D[i - 1] + h(i - 1) * D[i]) / (h(i - 1) + h(i));
  v[0] = ((2 * h(0) + h(1)) * D[0] - h(0) * D[1]) / (h(0) + h(1));
  v[m] = ((2 * h(m - 1) + h(m - 2)) * D[m - 1] - h(m - 1) * D[m - 2]) / (h(m - 2) + h(m - 1));
  return v;
}

/// Algorithm 2 (section 6): the local C^1 spline motion. Velocities v_i of the origin and
/// angular velocities w_i (fixed frame) are estimated by bessel_estimates from the chord
/// velocities D_i = (s_{i+1} - s_i)/h_i and the relative angular velocities
/// 2 log(R_{i+1} R_i~)/h_i of the normalised, sign-consistent rotations. Segment i is
///   Q_rot: C0 = R_i, C1 = R_i + h_i/6 w_i R_i, C2 = R_{i+1} - h_i/6 w_{i+1} R_{i+1}, C3 = R_{i+1}
/// (the rotational segment of Algorithm 2, which the text misprints as 2 + eps ...; it
/// satisfies (43) with lambda = 0), and the cubic Hermite translation (41); composed by
/// (40): segments of degree 6, C^1. With TranslationMethod::minimal, w = that cubic gives
/// (2 |Q_rot|^2 + eps w) Q_rot: segments of degree 9 and order 6, C^1 (|Q_rot(t_i)|^2 = 1
/// and its derivative vanishes there, so w keeps the translation's end data). Local: a
/// pose influences the segments whose end estimates use it (at most four). Double only.
inline Motion<double> interpolate_c1(const std::vector<Pose<double>>& poses,
                                     const std::vector<double>& t, TranslationMethod method,
                                     double max_residual = 1e-9) {
  detail::check_parameters(poses.size(), t.size());
  if (method == TranslationMethod::trt)
    throw Error(Errc::invalid_input,
                "--translation trt is not available for spline motions (use tr or minimal)");
  for (std::size_t i = 1; i < t.size(); ++i)
    if (!(t[i - 1] < t[i]))
      throw Error(Errc::invalid_input,
                  "parameters must increase strictly (pose " + std::to_string(i) + ")");
  const std::size_t m = poses.size() - 1;
  const auto R = normalized_rotations(poses);
  std::vector<Eigen::Vector3d> D(m), W(m);
  for (std::size_t i = 0; i < m; ++i) {
    const double h = t[i + 1] - t[i];
    D[i] = (poses[i + 1].position - poses[i].position) / h;
    W[i] = 2.0 * log_unit(Quaternion<double>(R[i + 1] * R[i].conj())).vec() / h;
  }
  const auto v = bessel_estimates(D, t), w = bessel_estimates(W, t);
  std::vector<Bernstein<Quaternion<double>>> rp;
  std::vector<Bernstein<Eigen::Vector3d>> tp;
  for (std::size_t i = 0; i < m; ++i) {
    const double h = t[i + 1] - t[i];
    const auto wi = Quaternion<double>::pure(w[i]), wj = Quaternion<double>::pure(w[i + 1]);
    rp.emplace_back(std::vector<Quaternion<double>>{R[i], R[i] + wi * R[i] * (h / 6),
                                                    R[i + 1] - wj * R[i + 1] * (h / 6), R[i + 1]},
                    t[i], t[i + 1]);
    const Eigen::Vector3d &s0 = poses[i].position, &s1 = poses[i + 1].position;
    tp.emplace_back(std::vector<Eigen::Vector3d>{s0, s0 + h / 3 * v[i], s1 - h / 3 * v[i + 1], s1},
                    t[i], t[i + 1]);
  }
  std::vector<double> knots(4, t.front());
  for (std::size_t i = 1; i < m; ++i) knots.insert(knots.end(), 2, t[i]);  // C^1 cubic
  knots.insert(knots.end(), 4, t.back());
  auto rot = from_bezier_pieces(rp, 3, knots);
  auto trans = from_bezier_pieces(tp, 3, knots);
  return detail::finish(
      MotionFactors<double>{method, std::move(rot), std::move(trans), std::nullopt}, 3, 3, poses, t,
      max_residual, Form::c1);
}

/// The interpolator of `form` (docs/interpolation.md): `interpolate_bezier` with `bezier`'s
/// options, `interpolate_bspline` or, in double only, `interpolate_c1` with `spline`'s. The
/// one dispatch the library call and the viewer's kernel share.
template <typename Scalar>
Motion<Scalar> interpolate(const std::vector<Pose<Scalar>>& poses, const std::vector<Scalar>& t,
                           Form form, const InterpolationOptions& bezier,
                           const SplineOptions& spline) {
  if (form == Form::bezier) return interpolate_bezier(poses, t, bezier);
  if constexpr (std::is_same_v<Scalar, double>)
    if (form == Form::c1) return interpolate_c1(poses, t, spline.translation, spline.max_residual);
  if (form != Form::bspline)
    throw Error(Errc::invalid_input,
                std::string("--form ") + to_string(form) + " does not interpolate poses here");
  return interpolate_bspline(poses, t, spline);
}

}  // namespace qmotion::kernel
