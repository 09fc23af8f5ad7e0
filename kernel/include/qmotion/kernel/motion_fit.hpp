// <qmotion/kernel/motion_fit.hpp>: a lean B-spline Q-motion near many poses (docs/fitting.md).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <qmotion/kernel/banded.hpp>
#include <qmotion/kernel/fit_between.hpp>
#include <qmotion/kernel/fit_knots.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/kernel/motion_value.hpp>
#include <qmotion/kernel/qspline.hpp>
#include <qmotion/kernel/spline_interpolation.hpp>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace qmotion::kernel {

/// What a fit must meet at every pose, and the factors' degrees.
struct FitOptions {
  double tol = 0;              ///< distance of the moving origin from the pose's position (> 0)
  double angle_tol_deg = 0.1;  ///< rotation angle between the motion's and the pose's frame
  int k = 3;                   ///< degree of Q_rot (2 to 25)
  int l = 3;                   ///< degree of the translation p (2 to 25)
  /// Hold the tolerances along the whole motion (`fit --between`): the moving origin within
  /// tol of the polyline through the positions, the rotation within angle_tol_deg of the
  /// geodesic between neighbouring rotations, proven (fit_between.hpp).
  bool between = false;
};

/// How near the fitted motion comes to each pose, measured on the composed Q-motion (the
/// curve the file holds), and how the knots were found.
struct FitReport {
  std::vector<double> position_deviation;   ///< |origin(t_i) - s_i| per pose
  std::vector<double> angle_deviation_deg;  ///< rotation angle of R(t_i) R_i^T per pose
  std::size_t worst_position_pose = 0, worst_angle_pose = 0;
  double worst_position = 0, worst_angle_deg = 0;
  int insertion_rounds = 0;  ///< rounds that split the spans where a pose failed
  int knots_removed = 0;     ///< interior knots removed after the tolerance was met
  int solves = 0;            ///< least-squares fits made (each linear in the poses)
  /// With FitOptions::between: the proven bounds along the motion, the interval (between
  /// poses i and i + 1) where each is largest, and the largest a sample of 16 times per
  /// interval finds (beside the bounds, never in their place).
  bool between = false;
  double between_position_bound = 0, between_angle_bound_deg = 0;
  std::size_t between_position_interval = 0, between_angle_interval = 0;
  double between_position_sampled = 0, between_angle_sampled_deg = 0;
};

/// A fitted motion (provenance form `fit`, with its poses, parameters and tolerances) and its
/// deviations.
struct FittedMotion {
  Motion<double> motion;
  FitReport report;
};

namespace detail {

/// Clamped knot vector of degree p on [a, b] with the simple interior knots x.
inline std::vector<double> clamped_knots(double a, double b, const std::vector<double>& x, int p) {
  std::vector<double> T(static_cast<std::size_t>(p + 1), a);
  T.insert(T.end(), x.begin(), x.end());
  T.insert(T.end(), static_cast<std::size_t>(p + 1), b);
  return T;
}

/// Values of the p + 1 basis functions non-zero on span j at x (The NURBS Book, A2.2),
/// without allocating (p <= 25).
inline void basis_values(const std::vector<double>& T, int j, int p, double x,
                         std::array<double, 26>& N) {
  std::array<double, 26> left{}, right{};
  N[0] = 1.0;
  for (int k = 1; k <= p; ++k) {
    const std::size_t uk = static_cast<std::size_t>(k);
    left[uk] = x - T[static_cast<std::size_t>(j + 1 - k)];
    right[uk] = T[static_cast<std::size_t>(j + k)] - x;
    double saved = 0.0;
    for (std::size_t r = 0; r < uk; ++r) {
      const double tmp = N[r] / (right[r + 1] + left[uk - r]);
      N[r] = saved + right[r + 1] * tmp;
      saved = left[uk - r] * tmp;
    }
    N[uk] = saved;
  }
}

/// Spans and basis values of a degree-p knot vector at every (sorted) parameter.
struct Collocation {
  std::vector<int> first;  ///< index of the first non-zero basis function per parameter
  Eigen::MatrixXd rows;    ///< its p + 1 values
};

inline Collocation collocation(const std::vector<double>& T, int p, const std::vector<double>& t) {
  const int n = static_cast<int>(T.size()) - p - 1;
  Collocation c{std::vector<int>(t.size()),
                Eigen::MatrixXd(static_cast<Eigen::Index>(t.size()), p + 1)};
  std::array<double, 26> N{};
  for (std::size_t i = 0; i < t.size(); ++i) {
    const int j = knot_span(T, p, n, t[i]);
    basis_values(T, j, p, t[i], N);
    c.first[i] = j - p;
    for (int k = 0; k <= p; ++k)
      c.rows(static_cast<Eigen::Index>(i), k) = N[static_cast<std::size_t>(k)];
  }
  return c;
}

/// The values at the parameters of the spline with control points P (rows) on `c`.
inline Eigen::MatrixXd collocate(const Collocation& c, const Eigen::MatrixXd& P) {
  Eigen::MatrixXd V = Eigen::MatrixXd::Zero(c.rows.rows(), P.cols());
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    for (Eigen::Index k = 0; k < c.rows.cols(); ++k)
      V.row(i) += c.rows(i, k) * P.row(c.first[static_cast<std::size_t>(i)] + k);
  return V;
}

/// The pose data of a fit: parameters, sign-consistent unit rotations (rows w, x, y, z)
/// and positions.
struct FitData {
  std::vector<double> t;
  Eigen::MatrixXd R;  ///< n x 4
  Eigen::MatrixXd S;  ///< n x 3
  FitOptions opt;
};

/// One least-squares candidate on the interior knots x: both factors' control points and
/// the deviations at the poses.
struct FitCandidate {
  std::vector<double> x;
  Eigen::MatrixXd rot, trans;
  std::vector<double> pos, ang;  ///< per pose; ang in degrees
  bool meets = false;
};

inline double rotation_angle_deg(const Quaternion<double>& r, const Quaternion<double>& q) {
  const Quaternion<double> d = r.conj() * q;
  return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w())) * 180.0 / M_PI;
}

/// Q_rot refined so that the norm it has at each pose is free: the least squares of
/// |P_i (Q(t_i) - l_i R_i)|^2 with P_i = (I - R_i R_i^T) + mu R_i R_i^T, l_i = R_i . Q_prev(t_i):
/// the part of Q(t_i) across R_i (which turns the frame) weighs fully, the part along it (its
/// norm, which turns nothing) weighs mu (a motion's rotation is Q_rot / |Q_rot|, so a
/// B-spline Q-motion's unit rotations are not a spline: plain least squares to them cannot
/// recover one). Normal equations, banded (4(p+1) - 1) in the
/// interleaved coefficients, assembled in O(n p^2).
inline Eigen::MatrixXd free_norm_rotation(const FitData& d, const Collocation& c, int p,
                                          const Eigen::MatrixXd& prev) {
  // mu = (angle tolerance in radians)^2, at least 1e-8: the rotation this weight costs is
  // about mu times the norm's change, far inside the tolerance; and noise below the
  // tolerance (whose cross residual grows with |Q|^2) cannot pay to shrink Q towards a pole.
  const double tol_rad = d.opt.angle_tol_deg * M_PI / 180;
  const double mu = std::clamp(tol_rad * tol_rad, 1e-8, 1e-3);
  const Eigen::Index m = prev.rows(), n = d.R.rows();
  const int w = 4 * (p + 1) - 1;
  BandMatrix<double> M(4 * m, w);
  MatX<double> rhs = MatX<double>::Zero(4 * m, 1);
  const Eigen::MatrixXd V = collocate(c, prev);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector4d r = d.R.row(i).transpose();
    const Eigen::Matrix4d W = Eigen::Matrix4d::Identity() - (1 - mu) * r * r.transpose();
    const double l = r.dot(V.row(i).transpose());
    const Eigen::Index f = c.first[static_cast<std::size_t>(i)];
    for (int a = 0; a <= p; ++a) {
      const double na = c.rows(i, a);
      for (int q = 0; q < 4; ++q) rhs(4 * (f + a) + q, 0) += na * mu * l * r(q);
      for (int b = 0; b <= p; ++b) {
        const double nab = na * c.rows(i, b);
        for (int q = 0; q < 4; ++q)
          for (int s = 0; s < 4; ++s) M(4 * (f + a) + q, 4 * (f + b) + s) += nab * W(q, s);
      }
    }
  }
  const MatX<double> x = solve_banded(std::move(M), std::move(rhs), "the rotational fit");
  Eigen::MatrixXd out(m, 4);
  for (Eigen::Index j = 0; j < m; ++j)
    for (int q = 0; q < 4; ++q) out(j, q) = x(4 * j + q, 0);
  return out;
}

inline FitCandidate fit_on_knots(const FitData& d, std::vector<double> x, int* solves) {
  const double a = d.t.front(), b = d.t.back();
  FitCandidate c;
  const auto Tr = clamped_knots(a, b, x, d.opt.k), Tt = clamped_knots(a, b, x, d.opt.l);
  const auto cr = collocation(Tr, d.opt.k, d.t), ct = collocation(Tt, d.opt.l, d.t);
  c.rot = least_squares_banded(static_cast<Eigen::Index>(Tr.size()) - d.opt.k - 1, d.opt.k,
                               cr.first, cr.rows, d.R, "the rotational fit");
  c.trans = least_squares_banded(static_cast<Eigen::Index>(Tt.size()) - d.opt.l - 1, d.opt.l,
                                 ct.first, ct.rows, d.S, "the translational fit");
  *solves += 1;
  const std::size_t n = d.t.size();
  auto angles = [&] {
    const Eigen::MatrixXd Rv = collocate(cr, c.rot);
    double worst = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Index e = static_cast<Eigen::Index>(i);
      c.ang[i] = rotation_angle_deg(Quaternion<double>(d.R(e, 0), d.R(e, 1), d.R(e, 2), d.R(e, 3)),
                                    Quaternion<double>(Rv(e, 0), Rv(e, 1), Rv(e, 2), Rv(e, 3)));
      worst = std::max(worst, c.ang[i]);
    }
    return worst;
  };
  c.pos.resize(n);
  c.ang.resize(n);
  // Unit targets fix Q_rot's norm at every pose, which the rotation does not need: where
  // they miss the angle, two rounds with the norm free.
  for (int round = 0; round < 2 && angles() > d.opt.angle_tol_deg; ++round) {
    c.rot = free_norm_rotation(d, cr, d.opt.k, c.rot);
    if (round == 1) angles();  // the last round's angles (the test measured the others)
  }
  const Eigen::MatrixXd Sv = collocate(ct, c.trans);
  for (std::size_t i = 0; i < n; ++i)
    c.pos[i] =
        (Sv.row(static_cast<Eigen::Index>(i)) - d.S.row(static_cast<Eigen::Index>(i))).norm();
  auto meets = [&] {
    c.meets = true;
    for (std::size_t i = 0; i < n; ++i)
      c.meets = c.meets && c.pos[i] <= d.opt.tol && c.ang[i] <= d.opt.angle_tol_deg;
    return c.meets;
  };
  // Between the poses only when the poses are met: a candidate that misses one is refined or
  // dropped anyway. Each interval's bounds count for the poses at both its ends.
  if (meets() && d.opt.between) {
    const auto b = between::bounds({d.t, d.S, d.R, d.opt.tol, d.opt.angle_tol_deg},
                                   {Tr, d.opt.k, c.rot, Tt, d.opt.l, c.trans});
    for (std::size_t i = 0; i + 1 < n; ++i)
      for (const std::size_t e : {i, i + 1}) {
        c.pos[e] = std::max(c.pos[e], b.position[i]);
        c.ang[e] = std::max(c.ang[e], b.angle_deg[i]);
      }
    meets();
  }
  c.x = std::move(x);
  return c;
}

/// The factors of a candidate, TR: (2 + eps p) Q_rot.
inline MotionFactors<double> candidate_factors(const FitData& d, const FitCandidate& c) {
  const double a = d.t.front(), b = d.t.back();
  return MotionFactors<double>{
      TranslationMethod::tr, quaternion_spline(d.opt.k, clamped_knots(a, b, c.x, d.opt.k), c.rot),
      vector_spline(d.opt.l, clamped_knots(a, b, c.x, d.opt.l), c.trans), std::nullopt};
}

/// Index of the span of the interior knots x (0 .. x.size()) holding parameter v.
inline std::size_t span_of(const std::vector<double>& x, double v) {
  return static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), v) - x.begin());
}

/// A candidate meets the tolerances and its rotational part has no zero (no pole).
inline bool acceptable(const FitData& d, const FitCandidate& c) {
  if (!c.meets) return false;
  const MotionFactors<double> f = candidate_factors(d, c);
  return find_poles(QMotion<double>{Basis::bspline, compose(f)}).empty();
}

/// The density a passing candidate suggests: on a span of width h whose worst pose uses the
/// fraction e of its tolerance, a degree-p fit errs like h^(p+1), so the span wants
/// e^(1/(p+1)) knots. Its total estimates the spans needed.
inline KnotDensity suggested_density(const FitData& d, const FitCandidate& c, int p) {
  const std::size_t spans = c.x.size() + 1;
  KnotDensity k{std::vector<double>(spans + 1), std::vector<double>(spans, 1e-6)};
  k.edge.front() = d.t.front();
  k.edge.back() = d.t.back();
  for (std::size_t s = 1; s < spans; ++s) k.edge[s] = c.x[s - 1];
  for (std::size_t i = 0; i < d.t.size(); ++i) {
    const std::size_t s = span_of(c.x, d.t[i]);
    k.weight[s] = std::max({k.weight[s], c.pos[i] / d.opt.tol, c.ang[i] / d.opt.angle_tol_deg});
  }
  for (double& w : k.weight) w = std::pow(w, 1.0 / (p + 1));
  return k;
}

/// The search for the knots of a fit: the best candidate so far and what it cost.
struct KnotSearch {
  const FitData& d;
  FitCandidate best;
  FitReport rep;

  /// Fewer knots than refinement found, from three families, each by count: the knots that
  /// B-spline interpolation places for evenly spaced parameters (which recovers a motion
  /// made that way), uniform knots, and knots equidistributing the density the refined fit
  /// suggests. For the first, the fewest below 48 that pass, by scanning (its passing counts
  /// need not be contiguous); for the others, a multiplicative search up from the density's
  /// estimate, then bisection down. A candidate that meets replaces `best` when it has fewer
  /// knots, or whatever it has when `best` does not meet (`passing` false); true when one did.
  bool fewer_knots(bool passing) {
    bool found = false;
    const std::size_t least = static_cast<std::size_t>(std::max(d.opt.k, d.opt.l) + 1);
    const int order = std::max(d.opt.k, d.opt.l);
    const KnotDensity suggested = suggested_density(d, best, order);
    double total = 0;
    for (double w : suggested.weight) total += w;
    const std::vector<double>& t = d.t;
    const double a = t.front(), b = t.back();
    auto interpolation_knots = [&](std::size_t count, bool* ok) {
      std::vector<double> u;  // count + order + 1 evenly spaced parameters
      for (std::size_t i = 0, m = count + static_cast<std::size_t>(order); i <= m; ++i)
        u.push_back(a + (b - a) * static_cast<double>(i) / static_cast<double>(m));
      const auto k = averaged_knots(u, order);
      std::vector<double> x(k.begin() + order + 1, k.end() - order - 1);
      *ok = spans_hold(x, t, least);
      return x;
    };
    const KnotDensity uniform{{a, b}, {1.0}};
    for (int family = 0; family < 3; ++family) {
      auto attempt = [&](std::size_t count) -> bool {
        bool ok = false;
        auto x = family == 0
                     ? interpolation_knots(count, &ok)
                     : equidistributed(family == 1 ? uniform : suggested, t, count, least, &ok);
        if (!ok) return false;
        FitCandidate c = fit_on_knots(d, std::move(x), &rep.solves);
        if (!acceptable(d, c)) return false;
        if (!passing || c.x.size() < best.x.size()) best = std::move(c);
        passing = found = true;
        return true;
      };
      std::size_t lo = 0, hi = best.x.size();  // hi passes
      if (family == 0) {  // exact recovery needs the very count: scan the small ones
        for (std::size_t count = 0; count < std::min<std::size_t>(hi, 48); ++count)
          if (attempt(count)) break;
        continue;
      }
      std::size_t guess = static_cast<std::size_t>(std::max(0.0, std::ceil(total) - 1));
      while (guess < hi) {
        if (attempt(guess)) {
          hi = guess;
          break;
        }
        lo = guess + 1;
        guess = std::max(guess + 1, static_cast<std::size_t>(static_cast<double>(guess) * 1.2));
      }
      while (lo < hi) {
        const std::size_t mid = lo + (hi - lo) / 2;
        if (attempt(mid))
          hi = mid;
        else
          lo = mid + 1;
      }
    }
    return found;
  }

  /// Halves the spans holding a failing pose (or a pole) until every pose is met.
  void refine() {
    const std::vector<double>& t = d.t;
    const std::size_t n = t.size();
    const FitOptions& opt = d.opt;
    while (!acceptable(d, best)) {
      std::vector<char> fails(best.x.size() + 1, 0);
      std::size_t worst = 0;
      double worst_excess = -1;
      for (std::size_t i = 0; i < n; ++i) {
        const double excess = std::max(best.pos[i] / opt.tol, best.ang[i] / opt.angle_tol_deg);
        if (excess > 1) fails[span_of(best.x, t[i])] = 1;
        if (excess > worst_excess) worst_excess = excess, worst = i;
      }
      if (best.meets)  // a pole: split every span
        std::fill(fails.begin(), fails.end(), 1);
      // Each span keeps at least max(k, l) + 1 poses, so every least-squares problem is well
      // posed and well conditioned: a failing span is halved, or split at its median pose
      // when halving would leave a side short, or left whole (saturated).
      const std::size_t least = static_cast<std::size_t>(std::max(d.opt.k, d.opt.l) + 1);
      std::vector<double> x;
      int inserted = 0;
      for (std::size_t s = 0, i0 = 0; s < fails.size(); ++s) {
        const double hi = s == best.x.size() ? t.back() : best.x[s];
        std::size_t i1 = i0;  // poses i0 .. i1-1 lie in span s
        while (i1 < n && (s == best.x.size() || t[i1] < hi)) ++i1;
        if (s > 0) x.push_back(best.x[s - 1]);
        if (fails[s] && i1 - i0 >= 2 * least) {
          const double lo = s == 0 ? t.front() : best.x[s - 1], mid = 0.5 * (lo + hi);
          const auto at = std::lower_bound(t.begin() + static_cast<std::ptrdiff_t>(i0),
                                           t.begin() + static_cast<std::ptrdiff_t>(i1), mid);
          const std::size_t left = static_cast<std::size_t>(at - t.begin()) - i0;
          const std::size_t m = i0 + (i1 - i0) / 2;
          const double knot =
              left >= least && i1 - i0 - left >= least ? mid : 0.5 * (t[m - 1] + t[m]);
          if (knot > lo && knot < hi) {
            x.push_back(knot);
            ++inserted;
          }
        }
        i0 = i1;
      }
      if (inserted == 0) {
        if (fewer_knots(false)) break;  // a family meets what halving cannot
        throw Error(
            Errc::numerical_failure,
            "--tol " + format_double(opt.tol) + " and --angle-tol " +
                format_double(opt.angle_tol_deg) + " cannot be met by degrees " +
                std::to_string(d.opt.k) + " and " + std::to_string(d.opt.l) +
                " on these poses (noise above the tolerance?): every span that misses holds "
                "fewer than 2(max(K, L) + 1) poses, too few to split; pose " +
                std::to_string(worst) + " (t = " + format_double(t[worst]) + ") is off by " +
                format_double(best.pos[worst]) + " and " + format_double(best.ang[worst]) +
                " degrees");
      }
      best = fit_on_knots(d, std::move(x), &rep.solves);
      ++rep.insertion_rounds;
    }
  }

  /// Removes knots while every pose stays met.
  void remove_knots() {
    const std::vector<double>& t = d.t;
    const std::size_t n = t.size();
    const FitOptions& opt = d.opt;
    // Removal: every other knot at once; those beside a failing pose go back until the rest
    // may go; alternate which half, until two rounds remove nothing.
    for (int round = 0, idle = 0; idle < 2 && !best.x.empty(); ++round) {
      std::vector<double> keep, gone;
      for (std::size_t i = 0; i < best.x.size(); ++i)
        (i % 2 == static_cast<std::size_t>(round % 2) ? gone : keep).push_back(best.x[i]);
      bool removed = false;
      for (int attempt = 0; attempt < 40 && !gone.empty(); ++attempt) {
        FitCandidate c = fit_on_knots(d, keep, &rep.solves);
        if (acceptable(d, c)) {
          rep.knots_removed += static_cast<int>(gone.size());
          best = std::move(c);
          removed = true;
          break;
        }
        std::vector<char> back(gone.size(), 0);
        for (std::size_t i = 0; i < n; ++i) {
          if (c.pos[i] <= opt.tol && c.ang[i] <= opt.angle_tol_deg) continue;
          const std::size_t g = span_of(gone, t[i]);  // the removed knots around t_i
          if (g < gone.size()) back[g] = 1;
          if (g > 0) back[g - 1] = 1;
        }
        if (c.meets) std::fill(back.begin(), back.end(), 1);  // a pole: give up this round
        std::vector<double> still;
        for (std::size_t g = 0; g < gone.size(); ++g) (back[g] ? keep : still).push_back(gone[g]);
        std::sort(keep.begin(), keep.end());
        gone = std::move(still);
      }
      idle = removed ? 0 : idle + 1;
    }
  }
};

}  // namespace detail

/// The deviations of a motion from poses at their parameters: the moving origin's distance
/// from each position and the angle of the rotation between the motion's frame and the
/// pose's (the deviation fields of FitReport).
inline FitReport fit_deviations(const QMotion<double>& m, const std::vector<Pose<double>>& poses,
                                const std::vector<double>& t) {
  FitReport r;
  const std::size_t n = poses.size();
  r.position_deviation.resize(n);
  r.angle_deviation_deg.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto q = evaluate(m, t[i]);
    r.position_deviation[i] = (translation_vector(q) - poses[i].position).norm();
    r.angle_deviation_deg[i] = detail::rotation_angle_deg(poses[i].rotation, q.real());
    if (r.position_deviation[i] > r.worst_position)
      r.worst_position = r.position_deviation[i], r.worst_position_pose = i;
    if (r.angle_deviation_deg[i] > r.worst_angle_deg)
      r.worst_angle_deg = r.angle_deviation_deg[i], r.worst_angle_pose = i;
  }
  return r;
}

/// A B-spline Q-motion within opt.tol of every pose's position (the moving origin at t_i)
/// and within opt.angle_tol_deg of its rotation, with few control points. TR factors
/// (2 + eps p) Q_rot, so the Plucker condition holds by construction; both factors share
/// simple interior knots, so the motion is C^(min(k, l) - 1), at least C^1.
///
/// The knots (docs/fitting.md): least squares of each factor (Q_rot to the sign-consistent
/// unit rotations, with its norm then left free where the angle misses; p to the positions;
/// banded, linear in the poses) on no interior knot; rounds that halve every span holding a
/// pose that misses a tolerance, until none does; three knot families searched by count for
/// fewer (KnotSearch::fewer_knots); then rounds that try removing every other knot at once,
/// keeping back those next to the poses that would miss, while any can go. Every span of every
/// candidate holds at least max(k, l) + 1 poses, so each least-squares problem is well posed
/// (Schoenberg-Whitney). Throws Errc::invalid_input for bad options and Errc::numerical_failure
/// (naming the pose) for neighbours a half-turn apart or a tolerance no knot vector of the degrees
/// can meet on these poses.
inline FittedMotion fit_bspline(const std::vector<Pose<double>>& poses,
                                const std::vector<double>& t, const FitOptions& opt) {
  detail::check_parameters(poses.size(), t.size());
  if (!(opt.tol > 0) || !std::isfinite(opt.tol))
    throw Error(Errc::invalid_input, "--tol: expected a positive length");
  if (!(opt.angle_tol_deg > 0) || !(opt.angle_tol_deg < 180))
    throw Error(Errc::invalid_input, "--angle-tol: expected an angle between 0 and 180 degrees");
  if (opt.k < 2 || opt.l < 2 || opt.k > 25 || opt.l > 25)
    throw Error(Errc::invalid_input,
                "--degree and --translation-degree: expected 2 to 25 (a fit is at least C1)");
  for (std::size_t i = 1; i < t.size(); ++i)
    if (!(t[i - 1] < t[i]))
      throw Error(Errc::invalid_input,
                  "parameters must increase strictly (pose " + std::to_string(i) + ")");
  const std::size_t n = poses.size();
  detail::FitData d{t, Eigen::MatrixXd(static_cast<Eigen::Index>(n), 4),
                    Eigen::MatrixXd(static_cast<Eigen::Index>(n), 3), opt};
  const auto R = normalized_rotations(poses);
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0 && R[i - 1].dot(R[i]) <= kHalfTurnDot)
      throw Error(Errc::numerical_failure,
                  "poses " + std::to_string(i - 1) + " and " + std::to_string(i) +
                      " turn by 180 degrees: which way the motion turns between them is not "
                      "defined (add a pose between them)");
    const Eigen::Index e = static_cast<Eigen::Index>(i);
    for (int c = 0; c < 4; ++c) d.R(e, c) = R[i][c];
    d.S.row(e) = poses[i].position.transpose();
  }
  // A degree above what the poses determine drops, as interpolation's does.
  const int most = static_cast<int>(n) - 1;
  d.opt.k = std::min(opt.k, most);
  d.opt.l = std::min(opt.l, most);
  if (d.opt.k < 2 || d.opt.l < 2)
    throw Error(Errc::invalid_input, "a fit needs at least three poses (it is at least C1)");
  // The rounding floor: positions carry about 1e-15 of their size, angles 1e-13 degrees.
  double size = 0;
  for (std::size_t i = 0; i < n; ++i)
    size = std::max(size, poses[i].position.cwiseAbs().maxCoeff());
  if (opt.tol < 1e-12 * std::max(size, 1.0) || opt.angle_tol_deg < 1e-10)
    throw Error(Errc::numerical_failure,
                "--tol " + detail::format_double(opt.tol) + " / --angle-tol " +
                    detail::format_double(opt.angle_tol_deg) +
                    " is below what double precision resolves on poses of size " +
                    detail::format_double(size));

  detail::KnotSearch search{d, {}, {}};
  search.best = detail::fit_on_knots(d, {}, &search.rep.solves);
  search.refine();
  if (detail::acceptable(d, search.best)) search.fewer_knots(true);
  search.remove_knots();
  const detail::FitCandidate& best = search.best;
  const FitReport& rep = search.rep;

  // The motion, and its deviations measured on the composed curve.
  MotionFactors<double> f = detail::candidate_factors(d, best);
  Provenance<double> prov;
  prov.form = Form::fit;
  prov.translation = TranslationMethod::tr;
  prov.rotation_degree = d.opt.k;
  prov.translation_degree = d.opt.l;
  prov.parameters = t;
  prov.poses = poses;
  prov.tolerance = opt.tol;
  prov.angle_tolerance_deg = opt.angle_tol_deg;
  QMotion<double> curve{Basis::bspline, detail::compose(f)};
  prov.residuals = pose_residuals(curve, poses, t);
  FitReport report = fit_deviations(curve, poses, t);
  if (opt.between) {
    const double a = t.front(), b = t.back();
    const auto Tr = detail::clamped_knots(a, b, best.x, d.opt.k);
    const auto Tt = detail::clamped_knots(a, b, best.x, d.opt.l);
    const auto bb = between::bounds({d.t, d.S, d.R, d.opt.tol, d.opt.angle_tol_deg},
                                    {Tr, d.opt.k, best.rot, Tt, d.opt.l, best.trans}, true);
    report.between = true;
    std::tie(report.between_position_bound, report.between_position_interval) =
        between::largest(bb.position);
    std::tie(report.between_angle_bound_deg, report.between_angle_interval) =
        between::largest(bb.angle_deg);
    report.between_position_sampled = bb.sampled_position;
    report.between_angle_sampled_deg = bb.sampled_angle_deg;
  }
  report.insertion_rounds = rep.insertion_rounds;
  report.knots_removed = rep.knots_removed;
  report.solves = rep.solves;
  return FittedMotion{Motion<double>(std::move(curve), std::move(f), std::move(prov)),
                      std::move(report)};
}

}  // namespace qmotion::kernel
