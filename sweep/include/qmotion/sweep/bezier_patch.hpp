// <qmotion/sweep/bezier_patch.hpp>: rational Bezier patches as the self-intersection proof
// uses them: de Casteljau restriction, the control points of the derivatives' numerators,
// and the injectivity test built on them (docs/geometry.md, "Self-intersection").
#pragma once
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <qmotion/kernel/bernstein.hpp>
#include <vector>

namespace qmotion::sweep::bezier {

using V3 = Eigen::Vector3d;
using V4 = Eigen::Vector4d;

/// A rational Bezier patch: homogeneous control points (w, w x, w y, w z), row-major,
/// (p + 1) x (q + 1), i along u (t) and j along v.
struct Net {
  int p = 0, q = 0;
  std::vector<V4> c;
  V4& at(int i, int j) { return c[static_cast<std::size_t>(i * (q + 1) + j)]; }
  const V4& at(int i, int j) const { return c[static_cast<std::size_t>(i * (q + 1) + j)]; }
};

/// The patch on [s, 1] (keep_right) or [0, s] along u (along_u) or v, by de Casteljau.
inline Net restrict_side(const Net& n, double s, bool along_u, bool keep_right) {
  Net out = n;
  const int m = along_u ? n.p : n.q, other = along_u ? n.q : n.p;
  std::vector<V4> row(static_cast<std::size_t>(m + 1));
  for (int o = 0; o <= other; ++o) {
    for (int k = 0; k <= m; ++k)
      row[static_cast<std::size_t>(k)] = along_u ? n.at(k, o) : n.at(o, k);
    std::vector<V4> left(row.size()), right(row.size());
    for (int r = 0; r <= m; ++r) {
      left[static_cast<std::size_t>(r)] = row[0];
      right[static_cast<std::size_t>(m - r)] = row[static_cast<std::size_t>(m - r)];
      for (int k = 0; k < m - r; ++k)
        row[static_cast<std::size_t>(k)] =
            (1 - s) * row[static_cast<std::size_t>(k)] + s * row[static_cast<std::size_t>(k + 1)];
    }
    const auto& keep = keep_right ? right : left;
    for (int k = 0; k <= m; ++k)
      (along_u ? out.at(k, o) : out.at(o, k)) = keep[static_cast<std::size_t>(k)];
  }
  return out;
}

/// The patch over [s0, s1] x [r0, r1] of its own [0, 1]^2.
inline Net restrict_net(const Net& n, double s0, double s1, double r0, double r1) {
  Net x = n;
  if (s1 < 1) x = restrict_side(x, s1, true, false);
  if (s0 > 0) x = restrict_side(x, s0 / s1, true, true);
  if (r1 < 1) x = restrict_side(x, r1, false, false);
  if (r0 > 0) x = restrict_side(x, r0 / r1, false, true);
  return x;
}

/// The numerators of the partial derivatives of x = P / w, (P_u w - P w_u) and
/// (P_v w - P w_v), as Bezier control points of bidegree (2p, 2q) (both elevated to it), so
/// that (x_u, x_v) = (N_u, N_v) / w^2 = sum_k B_k (Cu_k, Cv_k) / w^2 with the same Bernstein
/// weights B_k for both.
inline void hodographs(const Net& n, std::vector<V3>& cu, std::vector<V3>& cv) {
  const int p = n.p, q = n.q, P = 2 * p, Q = 2 * q;
  cu.assign(static_cast<std::size_t>((P + 1) * (Q + 1)), V3::Zero());
  cv.assign(cu.size(), V3::Zero());
  auto id = [Q](int i, int j) { return static_cast<std::size_t>(i * (Q + 1) + j); };
  // N_u: (p - 1, q) x (p, q) -> (2p - 1, 2q), then elevated along u.
  std::vector<V3> nu(static_cast<std::size_t>(P * (Q + 1)), V3::Zero());
  for (int i = 0; i < p; ++i)
    for (int j = 0; j <= q; ++j) {
      const V4 d = p * (n.at(i + 1, j) - n.at(i, j));
      for (int a = 0; a <= p; ++a)
        for (int b = 0; b <= q; ++b) {
          const V4& x = n.at(a, b);
          const double c = kernel::binomial<double>(p - 1, i) * kernel::binomial<double>(p, a) /
                           kernel::binomial<double>(P - 1, i + a) * kernel::binomial<double>(q, j) *
                           kernel::binomial<double>(q, b) / kernel::binomial<double>(Q, j + b);
          nu[static_cast<std::size_t>((i + a) * (Q + 1) + j + b)] +=
              c * (d.tail<3>() * x(0) - x.tail<3>() * d(0));
        }
    }
  for (int k = 0; k <= P; ++k)
    for (int l = 0; l <= Q; ++l) {
      const double f = static_cast<double>(k) / P;
      V3 v = V3::Zero();
      if (k > 0) v += f * nu[static_cast<std::size_t>((k - 1) * (Q + 1) + l)];
      if (k < P) v += (1 - f) * nu[static_cast<std::size_t>(k * (Q + 1) + l)];
      cu[id(k, l)] = v;
    }
  // N_v: (p, q - 1) x (p, q) -> (2p, 2q - 1), then elevated along v.
  std::vector<V3> nv(static_cast<std::size_t>((P + 1) * Q), V3::Zero());
  for (int i = 0; i <= p; ++i)
    for (int j = 0; j < q; ++j) {
      const V4 d = q * (n.at(i, j + 1) - n.at(i, j));
      for (int a = 0; a <= p; ++a)
        for (int b = 0; b <= q; ++b) {
          const V4& x = n.at(a, b);
          const double c = kernel::binomial<double>(p, i) * kernel::binomial<double>(p, a) /
                           kernel::binomial<double>(P, i + a) * kernel::binomial<double>(q - 1, j) *
                           kernel::binomial<double>(q, b) / kernel::binomial<double>(Q - 1, j + b);
          nv[static_cast<std::size_t>((i + a) * Q + j + b)] +=
              c * (d.tail<3>() * x(0) - x.tail<3>() * d(0));
        }
    }
  for (int k = 0; k <= P; ++k)
    for (int l = 0; l <= Q; ++l) {
      const double f = static_cast<double>(l) / Q;
      V3 v = V3::Zero();
      if (l > 0) v += f * nv[static_cast<std::size_t>(k * Q + l - 1)];
      if (l < Q) v += (1 - f) * nv[static_cast<std::size_t>(k * Q + l)];
      cv[id(k, l)] = v;
    }
}

/// The injectivity test. Over a convex parameter domain, x(a) - x(b) is the integral of
/// J (a - b) along the segment, J = [x_u x_v] = sum_k B_k [Cu_k Cv_k] / w^2 (piecewise, for
/// a continuous surface of several patches): a positive combination of the 3 x 2 matrices
/// [Cu_k Cv_k]. With A = the pseudo-inverse of their mean, every A [Cu_k Cv_k] = s_k (I + E_k)
/// with s_k > 0 and |E_k|_2 < 1 makes every positive combination s (I + E), |E|_2 < 1: never
/// singular, so x(a) != x(b) for a != b. The pairs are added per piece by `add`, each
/// scaled to the common parameters (dividing by the piece's extent in them).
class Injectivity {
 public:
  void add(const Net& n, double du, double dv) {
    hodographs(n, cu_, cv_);
    for (std::size_t k = 0; k < cu_.size(); ++k) {
      Eigen::Matrix<double, 3, 2> m;
      m.col(0) = cu_[k] / du;
      m.col(1) = cv_[k] / dv;
      const double f = m.norm();
      if (!(f > 0) || !std::isfinite(f)) {
        degenerate_ = true;
        continue;
      }
      js_.push_back(m / f);
    }
  }
  bool injective() const {
    if (degenerate_ || js_.empty()) return false;
    Eigen::Matrix<double, 3, 2> mean = Eigen::Matrix<double, 3, 2>::Zero();
    for (const auto& m : js_) mean += m;
    mean /= static_cast<double>(js_.size());
    const Eigen::Matrix2d gram = mean.transpose() * mean;
    if (!(gram.determinant() > 1e-12 * gram.trace() * gram.trace())) return false;
    const Eigen::Matrix<double, 2, 3> a = gram.inverse() * mean.transpose();
    std::vector<Eigen::Matrix2d> gs;
    double g12 = 0, g21 = 0;
    for (const auto& m : js_) {
      gs.push_back(a * m);
      g12 = std::max(g12, std::abs(gs.back()(0, 1)));
      g21 = std::max(g21, std::abs(gs.back()(1, 0)));
    }
    // Rescaling the second parameter by l (G -> diag(1, 1/l) G diag(1, l)) keeps the
    // argument and balances the two off-diagonal terms.
    const double l = g12 > 0 && g21 > 0 ? std::sqrt(g21 / g12) : 1.0;
    for (auto g : gs) {
      g(0, 1) *= l;
      g(1, 0) /= l;
      const double s = g.trace() / 2;
      if (!(s > 0)) return false;
      const Eigen::Matrix2d e = g / s - Eigen::Matrix2d::Identity();
      // |E|_2^2 is the larger eigenvalue of E^T E (2 x 2, closed form).
      const Eigen::Matrix2d ete = e.transpose() * e;
      const double tr = ete.trace(), det = ete.determinant();
      const double lmax = tr / 2 + std::sqrt(std::max(0.0, tr * tr / 4 - det));
      if (!(lmax < 1 - 1e-6)) return false;  // the margin covers rounding
    }
    return true;
  }

 private:
  std::vector<V3> cu_, cv_;
  std::vector<Eigen::Matrix<double, 3, 2>> js_;
  bool degenerate_ = false;
};

/// Whether the boxes [alo, ahi] and [blo, bhi] are apart along an axis by more than gap.
inline bool boxes_apart(const V3& alo, const V3& ahi, const V3& blo, const V3& bhi, double gap) {
  for (int k = 0; k < 3; ++k)
    if (ahi(k) + gap < blo(k) || bhi(k) + gap < alo(k)) return true;
  return false;
}

}  // namespace qmotion::sweep::bezier
