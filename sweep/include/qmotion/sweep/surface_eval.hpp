// <qmotion/sweep/surface_eval.hpp>: fast evaluation of a NURBS surface with its first derivatives
// (homogeneous poles prepared once, basis functions per call), and the nearest surface
// point to a point near a known parameter (Gauss-Newton): what measuring a mesh against
// the exact surface needs.
#pragma once
#include <Eigen/Core>
#include <Eigen/Dense>
#include <algorithm>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/sweep/nurbs.hpp>
#include <vector>

namespace qmotion::sweep {

class SurfaceEvaluator {
 public:
  explicit SurfaceEvaluator(const NurbsSurface<double>& s)
      : p_(s.degree_u),
        q_(s.degree_v),
        U_(s.knots_u),
        V_(s.knots_v),
        nu_(static_cast<int>(s.points.size())),
        nv_(static_cast<int>(s.points.front().size())) {
    h_.reserve(static_cast<std::size_t>(nu_ * nv_));
    for (int i = 0; i < nu_; ++i)
      for (int j = 0; j < nv_; ++j) {
        const double w = s.weights[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
        Eigen::Vector4d v;
        v << w, w * s.points[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
        h_.push_back(v);
      }
  }

  double u0() const { return U_.front(); }
  double u1() const { return U_.back(); }
  double v0() const { return V_.front(); }
  double v1() const { return V_.back(); }

  /// S(u, v), and dS/du, dS/dv when su, sv are given.
  Eigen::Vector3d operator()(double u, double v, Eigen::Vector3d* su = nullptr,
                             Eigen::Vector3d* sv = nullptr) const {
    const int i = span(U_, p_, nu_, u), j = span(V_, q_, nv_, v);
    std::vector<double> Nu, Nv, dNu, dNv;
    basis(U_, i, p_, u, Nu, dNu);
    basis(V_, j, q_, v, Nv, dNv);
    Eigen::Vector4d A = Eigen::Vector4d::Zero(), Au = A, Av = A;
    for (int a = 0; a <= p_; ++a)
      for (int b = 0; b <= q_; ++b) {
        const Eigen::Vector4d& P = h_[static_cast<std::size_t>((i - p_ + a) * nv_ + (j - q_ + b))];
        const double nu = Nu[static_cast<std::size_t>(a)], nv = Nv[static_cast<std::size_t>(b)];
        A += nu * nv * P;
        Au += dNu[static_cast<std::size_t>(a)] * nv * P;
        Av += nu * dNv[static_cast<std::size_t>(b)] * P;
      }
    const Eigen::Vector3d S = A.tail<3>() / A(0);
    if (su) *su = (Au.tail<3>() - Au(0) * S) / A(0);
    if (sv) *sv = (Av.tail<3>() - Av(0) * S) / A(0);
    return S;
  }

  /// The grid S(us[i], vs[j]) for rows i in [row_begin, row_end), written row-major to
  /// out[i * vs.size() + j]: per row the poles are contracted once with the u basis into the
  /// homogeneous poles of the v-curve, then each point costs degree_v + 1 terms.
  /// @pre every parameter inside the surface's rectangle
  void grid(const std::vector<double>& us, const std::vector<double>& vs, Eigen::Vector3d* out,
            std::size_t row_begin, std::size_t row_end) const {
    const std::size_t nv = vs.size(), q1 = static_cast<std::size_t>(q_ + 1);
    std::vector<int> vspan(nv);
    std::vector<double> vbasis(nv * q1);
    for (std::size_t j = 0; j < nv; ++j) {
      vspan[j] = span(V_, q_, nv_, vs[j]);
      const auto N = kernel::basis_functions(V_, vspan[j], q_, vs[j]);
      std::copy(N.begin(), N.end(), vbasis.begin() + static_cast<std::ptrdiff_t>(j * q1));
    }
    std::vector<Eigen::Vector4d> col(static_cast<std::size_t>(nv_));
    for (std::size_t i = row_begin; i < row_end; ++i) {
      const int su = span(U_, p_, nu_, us[i]);
      const auto N = kernel::basis_functions(U_, su, p_, us[i]);
      for (int k = 0; k < nv_; ++k) {
        Eigen::Vector4d c = Eigen::Vector4d::Zero();
        for (int a = 0; a <= p_; ++a)
          c += N[static_cast<std::size_t>(a)] *
               h_[static_cast<std::size_t>((su - p_ + a) * nv_ + k)];
        col[static_cast<std::size_t>(k)] = c;
      }
      for (std::size_t j = 0; j < nv; ++j) {
        Eigen::Vector4d c = Eigen::Vector4d::Zero();
        const double* M = &vbasis[j * q1];
        const Eigen::Vector4d* C = &col[static_cast<std::size_t>(vspan[j] - q_)];
        for (std::size_t b = 0; b < q1; ++b) c += M[b] * C[b];
        out[i * nv + j] = c.tail<3>() / c(0);
      }
    }
  }

  /// The distance from x to the surface point nearest it near (u, v): Gauss-Newton on
  /// |S(u, v) - x|^2 inside the parameter rectangle. Always the distance to a point of the
  /// surface, so never below the true distance; the true distance when it converges.
  double distance(const Eigen::Vector3d& x, double u, double v, int iterations = 6) const {
    Eigen::Vector3d su, sv;
    double best = HUGE_VAL;
    for (int it = 0;; ++it) {
      const Eigen::Vector3d S = (*this)(u, v, &su, &sv);
      const Eigen::Vector3d r = x - S;
      best = std::min(best, r.norm());
      if (it == iterations) break;
      Eigen::Matrix2d JtJ;
      JtJ << su.dot(su), su.dot(sv), su.dot(sv), sv.dot(sv);
      const Eigen::Vector2d g(su.dot(r), sv.dot(r));
      if (!(JtJ.determinant() > 1e-30 * JtJ.squaredNorm())) break;  // degenerate there
      const Eigen::Vector2d d = JtJ.ldlt().solve(g);
      u = std::clamp(u + d(0), u0(), u1());
      v = std::clamp(v + d(1), v0(), v1());
      if (std::abs(d(0)) <= 1e-15 * (u1() - u0()) && std::abs(d(1)) <= 1e-15 * (v1() - v0())) break;
    }
    return best;
  }

 private:
  static int span(const std::vector<double>& T, int p, int n, double t) {
    const auto it = std::upper_bound(T.begin() + p, T.begin() + n, t);
    return std::clamp(static_cast<int>(it - T.begin()) - 1, p, n - 1);
  }
  /// The p + 1 basis functions of span i at t and their derivatives.
  static void basis(const std::vector<double>& T, int i, int p, double t, std::vector<double>& N,
                    std::vector<double>& dN) {
    N = kernel::basis_functions(T, i, p, t);
    dN.assign(static_cast<std::size_t>(p + 1), 0.0);
    if (p == 0) return;
    const std::vector<double> M = kernel::basis_functions(T, i, p - 1, t);  // N_{i-p+1..i}
    for (int a = 0; a <= p; ++a) {
      const int k = i - p + a;  // N'_{k,p} = p (N_{k,p-1} / (T_{k+p} - T_k)
      double d = 0;             //            - N_{k+1,p-1} / (T_{k+p+1} - T_{k+1}))
      if (a >= 1) {
        const double den = T[static_cast<std::size_t>(k + p)] - T[static_cast<std::size_t>(k)];
        if (den > 0) d += M[static_cast<std::size_t>(a - 1)] / den;
      }
      if (a <= p - 1) {
        const double den =
            T[static_cast<std::size_t>(k + p + 1)] - T[static_cast<std::size_t>(k + 1)];
        if (den > 0) d -= M[static_cast<std::size_t>(a)] / den;
      }
      dN[static_cast<std::size_t>(a)] = p * d;
    }
  }

  int p_, q_;
  std::vector<double> U_, V_;
  int nu_, nv_;
  std::vector<Eigen::Vector4d> h_;
};

}  // namespace qmotion::sweep
