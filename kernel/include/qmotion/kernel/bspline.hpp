// <qmotion/kernel/bspline.hpp>
#pragma once
#include <algorithm>
#include <limits>
#include <qmotion/kernel/bernstein.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace qmotion::kernel {

/// Index j with T[j] <= t < T[j+1] of a degree-p knot vector T with n poles (the last
/// non-empty span for t >= its end, the first for t before its start).
template <typename Scalar>
int knot_span(const std::vector<Scalar>& T, int p, int n, const Scalar& t) {
  if (!(t < T[static_cast<std::size_t>(n)])) {
    int j = n - 1;
    while (j > p && !(T[static_cast<std::size_t>(j)] < T[static_cast<std::size_t>(j + 1)])) --j;
    return j;
  }
  const auto it = std::upper_bound(T.begin() + p, T.begin() + n, t);
  return std::max(p, static_cast<int>(it - T.begin()) - 1);
}

/// B-spline function with coefficients in any ring of kernel/coefficient.hpp, on a clamped
/// knot vector (poles + degree + 1 entries, first and last value degree+1 times, interior
/// multiplicities at most degree+1: degree+1 is a break, which derivatives can need). A value
/// class: the factory validates the invariant.
/// @see Piegl & Tiller, The NURBS Book, ch. 2-5; Ramshaw 1989 for blossoms
template <typename Coef>
class BSpline {
 public:
  using Scalar = coef_scalar_t<Coef>;

  /// Readable problems with a (degree, knots, pole count) triple; empty when valid.
  static std::vector<std::string> validate(int degree, const std::vector<Scalar>& knots,
                                           std::size_t poles) {
    std::vector<std::string> issues;
    if (degree < 0) {
      issues.push_back("degree must be >= 0");
      return issues;
    }
    const std::size_t p = static_cast<std::size_t>(degree);
    if (poles < p + 1)
      issues.push_back("needs at least degree+1 = " + std::to_string(p + 1) +
                       " control points, has " + std::to_string(poles));
    if (knots.size() != poles + p + 1) {
      issues.push_back(
          "knot vector has " + std::to_string(knots.size()) +
          " entries, expected control points + degree + 1 = " + std::to_string(poles + p + 1));
      return issues;
    }
    for (std::size_t i = 1; i < knots.size(); ++i)
      if (knots[i] < knots[i - 1]) {
        issues.push_back("knots decrease at index " + std::to_string(i));
        return issues;
      }
    if (!issues.empty()) return issues;
    for (std::size_t i = 1; i <= p; ++i)
      if (knots[i] != knots[0] || knots[knots.size() - 1 - i] != knots.back()) {
        issues.push_back(
            "knot vector is not clamped (first and last knot must repeat degree+1 times)");
        break;
      }
    if (!(knots.front() < knots.back()))
      issues.push_back("knot vector spans an empty interval");
    else if (knots[p + 1] == knots[0] || knots[knots.size() - p - 2] == knots.back())
      issues.push_back("end knots repeat more than degree+1 times");
    std::size_t run = 1;
    for (std::size_t i = p + 2; i + p + 1 < knots.size(); ++i) {
      run = knots[i] == knots[i - 1] ? run + 1 : 1;
      if (run > p + 1 && knots[i] != knots.back()) {
        issues.push_back("interior knot at index " + std::to_string(i) +
                         " has multiplicity above degree+1");
        break;
      }
    }
    return issues;
  }

  /// Validating factory; throws Errc::invalid_input naming the first problem.
  static BSpline make(int degree, std::vector<Scalar> knots, std::vector<Coef> ctrl) {
    const auto issues = validate(degree, knots, ctrl.size());
    if (!issues.empty()) throw Error(Errc::invalid_input, "invalid B-spline: " + issues.front());
    return BSpline(degree, std::move(knots), std::move(ctrl));
  }

  /// The Bezier polynomial p as a B-spline on the knot vector a^(n+1) b^(n+1).
  static BSpline from_bezier(const Bernstein<Coef>& p) {
    std::vector<Scalar> k(static_cast<std::size_t>(p.degree() + 1), p.a());
    k.insert(k.end(), static_cast<std::size_t>(p.degree() + 1), p.b());
    return BSpline(p.degree(), std::move(k), p.coeffs());
  }

  int degree() const { return p_; }
  const std::vector<Scalar>& knots() const { return t_; }
  const std::vector<Coef>& ctrl() const { return c_; }
  const Scalar& a() const { return t_.front(); }
  const Scalar& b() const { return t_.back(); }

  /// Index j with knots[j] <= t < knots[j+1] (the last non-empty span for t >= b, the
  /// first for t < a).
  int find_span(const Scalar& t) const { return knot_span(t_, p_, static_cast<int>(c_.size()), t); }

  /// Distinct knot values a = x_0 < x_1 < ... < x_r = b.
  std::vector<Scalar> breakpoints() const {
    std::vector<Scalar> x;
    for (const auto& v : t_)
      if (x.empty() || x.back() != v) x.push_back(v);
    return x;
  }

  /// Multiplicity of the value x in the knot vector (0 when absent).
  int multiplicity(const Scalar& x) const {  // knots are sorted: O(log n)
    const auto range = std::equal_range(t_.begin(), t_.end(), x);
    return static_cast<int>(range.second - range.first);
  }

 private:
  BSpline(int degree, std::vector<Scalar> knots, std::vector<Coef> ctrl)
      : p_(degree), t_(std::move(knots)), c_(std::move(ctrl)) {}
  int p_;
  std::vector<Scalar> t_;
  std::vector<Coef> c_;
};

/// Blossom of the polynomial piece on knot span j at the degree arguments u (de Boor's
/// triangle with one argument per level).
template <typename Coef>
Coef blossom(const BSpline<Coef>& s, int j, const std::vector<coef_scalar_t<Coef>>& u) {
  using S = coef_scalar_t<Coef>;
  const int p = s.degree();
  QMOTION_EXPECTS(static_cast<int>(u.size()) == p, "blossom needs degree arguments");
  const auto& T = s.knots();
  std::vector<Coef> d(s.ctrl().begin() + (j - p), s.ctrl().begin() + (j + 1));
  for (int r = 1; r <= p; ++r)
    for (int i = p; i >= r; --i) {
      const std::size_t idx = static_cast<std::size_t>(j - p + i);
      const S alpha = S((u[static_cast<std::size_t>(r - 1)] - T[idx]) /
                        (T[idx + static_cast<std::size_t>(p + 1 - r)] - T[idx]));
      d[static_cast<std::size_t>(i)] =
          detail::lerp(d[static_cast<std::size_t>(i - 1)], d[static_cast<std::size_t>(i)], alpha);
    }
  return d[static_cast<std::size_t>(p)];
}

/// s(t) by de Boor's algorithm (exact for exact Scalar).
template <typename Coef>
Coef evaluate(const BSpline<Coef>& s, const coef_scalar_t<Coef>& t) {
  return blossom(s, s.find_span(t),
                 std::vector<coef_scalar_t<Coef>>(static_cast<std::size_t>(s.degree()), t));
}

/// Inserts the knot t (a < t < b) `times` times by Boehm's algorithm; the function is
/// unchanged. Throws when the multiplicity would exceed the degree.
template <typename Coef>
BSpline<Coef> insert_knot(const BSpline<Coef>& s, const coef_scalar_t<Coef>& t, int times = 1) {
  using S = coef_scalar_t<Coef>;
  if (!(s.a() < t && t < s.b()))
    throw Error(Errc::invalid_input, "knot insertion outside the open parameter interval");
  if (s.multiplicity(t) + times > s.degree() + 1)
    throw Error(Errc::invalid_input, "knot insertion would exceed multiplicity degree+1");
  std::vector<S> T = s.knots();
  std::vector<Coef> P = s.ctrl();
  const int p = s.degree();
  for (int step = 0; step < times; ++step) {
    const int k = static_cast<int>(std::upper_bound(T.begin(), T.end(), t) - T.begin()) - 1;
    std::vector<Coef> Q;
    Q.reserve(P.size() + 1);
    for (int i = 0; i <= static_cast<int>(P.size()); ++i) {
      if (i <= k - p) {
        Q.push_back(P[static_cast<std::size_t>(i)]);
      } else if (i <= k) {
        const std::size_t ui = static_cast<std::size_t>(i);
        const S alpha = S((t - T[ui]) / (T[ui + static_cast<std::size_t>(p)] - T[ui]));
        Q.push_back(detail::lerp(P[ui - 1], P[ui], alpha));
      } else {
        Q.push_back(P[static_cast<std::size_t>(i - 1)]);
      }
    }
    T.insert(T.begin() + (k + 1), t);
    P = std::move(Q);
  }
  return BSpline<Coef>::make(p, std::move(T), std::move(P));
}

/// The Bezier form of s on [x, y], a sub-interval of one knot span.
template <typename Coef>
Bernstein<Coef> bezier_piece(const BSpline<Coef>& s, const coef_scalar_t<Coef>& x,
                             const coef_scalar_t<Coef>& y) {
  const int p = s.degree();
  const int j = s.find_span(x);
  std::vector<Coef> c;
  for (int i = 0; i <= p; ++i) {
    std::vector<coef_scalar_t<Coef>> u(static_cast<std::size_t>(p - i), x);
    u.insert(u.end(), static_cast<std::size_t>(i), y);
    c.push_back(blossom(s, j, u));
  }
  return Bernstein<Coef>(std::move(c), x, y);
}

/// Decomposition into Bezier pieces, one per non-empty knot span: every interior knot
/// raised to multiplicity p by knot insertion, O(p^2) per span (Piegl and Tiller, The
/// NURBS Book, A5.6) where bezier_piece's blossoms take O(p^3).
template <typename Coef>
std::vector<Bernstein<Coef>> bezier_pieces(const BSpline<Coef>& s) {
  using S = coef_scalar_t<Coef>;
  const std::vector<S>& U = s.knots();
  const std::vector<Coef>& P = s.ctrl();
  const std::size_t p = static_cast<std::size_t>(s.degree());
  const std::size_t m = U.size() - 1;
  std::vector<Bernstein<Coef>> pieces;
  // At most one piece a knot span.
  pieces.reserve(m > 2 * p ? m - 2 * p : 1);
  if (p == 0) {  // piecewise constant: the poles themselves
    for (std::size_t k = 0; k < P.size(); ++k)
      if (U[k] < U[k + 1]) pieces.emplace_back(std::vector<Coef>{P[k]}, U[k], U[k + 1]);
    return pieces;
  }
  std::vector<Coef> Q(P.begin(), P.begin() + static_cast<std::ptrdiff_t>(p + 1)), next(p + 1, P[0]);
  std::vector<S> alphas(p + 1, S(0));
  std::size_t a = p, b = p + 1;
  while (b < m) {
    const std::size_t i = b;
    while (b < m && U[b + 1] == U[b]) ++b;
    const std::size_t mult = b - i + 1;
    if (mult < p) {
      const S numer = S(U[b] - U[a]);
      for (std::size_t j = p; j > mult; --j) alphas[j - mult - 1] = S(numer / S(U[a + j] - U[a]));
      const std::size_t r = p - mult;
      for (std::size_t j = 1; j <= r; ++j) {
        const std::size_t save = r - j, first = mult + j;
        for (std::size_t k = p; k >= first; --k)
          Q[k] = detail::lerp(Q[k - 1], Q[k], alphas[k - first]);
        next[save] = Q[p];
      }
    }
    const S x0 = U[a], x1 = U[b];
    if (b < m) {
      for (std::size_t k = p - std::min(mult, p); k <= p; ++k) next[k] = P[b - p + k];
      a = b;
      ++b;
    }
    pieces.emplace_back(Q, x0, x1);
    Q.swap(next);
  }
  return pieces;
}

/// The Bezier pieces of s on the spans between consecutive breakpoints x (sorted, ends at
/// s's ends, including all of s's own breakpoints): its own pieces, subdivided.
template <typename Coef>
std::vector<Bernstein<Coef>> bezier_pieces(const BSpline<Coef>& s,
                                           const std::vector<coef_scalar_t<Coef>>& x) {
  std::vector<Bernstein<Coef>> out;
  out.reserve(x.size());
  std::size_t k = 1;
  for (auto& own : bezier_pieces(s)) {
    Bernstein<Coef> rest = std::move(own);
    for (; k + 1 < x.size() && x[k] < rest.b(); ++k) {
      auto halves = subdivide(rest, x[k]);
      out.push_back(std::move(halves.first));
      rest = std::move(halves.second);
    }
    out.push_back(std::move(rest));
    ++k;
  }
  if (out.size() + 1 != x.size())
    throw Error(Errc::internal, "bezier_pieces: the breakpoints do not refine the spline's");
  return out;
}

namespace detail {

/// The non-empty knot spans j (T_j < T_(j+1)) of a knot vector, in order.
template <typename Scalar>
std::vector<std::size_t> nonempty_spans(const std::vector<Scalar>& knots) {
  std::vector<std::size_t> span;
  for (std::size_t j = 0; j + 1 < knots.size(); ++j)
    if (knots[j] < knots[j + 1]) span.push_back(j);
  return span;
}

/// Pole i of the spline of degree d on `knots` (n poles) joined from Bezier pieces:
/// piece(k) is the piece on the non-empty span span[k]; `first` is the first index of span
/// not before the pole's window, advanced here (poles are asked for in order). The pole is
/// the blossom of the widest piece within its support [T_i, T_(i+d+1)]: every such piece
/// has the same blossom there (the continuity the knots state), and the widest evaluates it
/// best (a piece on a tiny span extrapolates badly).
template <typename Coef, typename Piece>
Coef joined_pole(const std::vector<coef_scalar_t<Coef>>& knots, std::size_t d, std::size_t n,
                 std::size_t i, const std::vector<std::size_t>& span, std::size_t& first,
                 const Piece& piece, std::vector<Coef>& work) {
  const std::size_t lo = std::max(i, d), hi = std::min(i + d, n - 1);
  while (first < span.size() && span[first] < lo) ++first;
  std::size_t k = first;
  if (k == span.size() || span[k] > hi)
    throw Error(Errc::internal, "pole without a non-empty span");
  for (std::size_t c = k + 1; c < span.size() && span[c] <= hi; ++c)
    if (knots[span[k] + 1] - knots[span[k]] < knots[span[c] + 1] - knots[span[c]]) k = c;
  const std::size_t best = span[k];
  const Bernstein<Coef>& b = piece(k);
  if (d == 0) return b[0];
  // A window made of the piece's own end points only, (x_k^(d-m), x_(k+1)^m), blossoms to
  // its Bernstein coefficient m: no evaluation (every pole of a Bezier-like knot vector).
  // The window T_(i+1..i+d) is sorted and no knot lies between x_k = T_best and
  // x_(k+1) = T_(best+1), so it is made of them when it lies in [x_k, x_(k+1)]; its
  // x_(k+1) are those from T_(best+1) on.
  if (!(knots[i + 1] < knots[best]) && !(knots[best + 1] < knots[i + d]))
    return b[static_cast<int>(i + d - best)];
  return blossom(b, knots.begin() + static_cast<std::ptrdiff_t>(i + 1), work);
}

}  // namespace detail

/// Reassembles a spline of the given degree and clamped knot vector from Bezier pieces on
/// its spans (pieces[k] on [x_k, x_{k+1}] of the knot vector's breakpoints). Each pole is
/// the blossom of a piece under its support at the pole's knot window (dual functionals);
/// exact when the pieces join with the continuity the knot vector states.
template <typename Coef>
BSpline<Coef> from_bezier_pieces(const std::vector<Bernstein<Coef>>& pieces, int degree,
                                 std::vector<coef_scalar_t<Coef>> knots) {
  const std::size_t d = static_cast<std::size_t>(degree);
  const std::size_t n = knots.size() - d - 1;
  const auto span = detail::nonempty_spans(knots);
  if (span.size() != pieces.size())
    throw Error(Errc::internal, "Bezier pieces do not match the knot vector");
  std::vector<Coef> ctrl, work;
  ctrl.reserve(n);
  std::size_t first = 0;
  const auto piece = [&pieces](std::size_t k) -> const Bernstein<Coef>& { return pieces[k]; };
  for (std::size_t i = 0; i < n; ++i)
    ctrl.push_back(detail::joined_pole(knots, d, n, i, span, first, piece, work));
  return BSpline<Coef>::make(degree, std::move(knots), std::move(ctrl));
}

/// from_bezier_pieces, fed one piece at a time in span order: each pole is made as soon as
/// the pieces its window may use are in, and a piece is dropped once no later pole can use
/// it, so at most degree + 1 pieces are held (a spline of 10^4 spans is not held twice).
/// The poles are those from_bezier_pieces makes, bit for bit.
template <typename Coef>
class BezierJoiner {
  using S = coef_scalar_t<Coef>;

 public:
  BezierJoiner(int degree, std::vector<S> knots)
      : d_(static_cast<std::size_t>(degree)),
        n_(knots.size() - d_ - 1),
        knots_(std::move(knots)),
        span_(detail::nonempty_spans(knots_)) {
    ctrl_.reserve(n_);
  }
  /// The next piece, on the next non-empty span.
  void add(Bernstein<Coef> piece) {
    if (added_ == span_.size()) throw Error(Errc::internal, "more Bezier pieces than spans");
    held_.push_back(std::move(piece));
    const std::size_t last = span_[added_++];
    // Pole i's window reaches span min(i + d, n - 1): every piece it may use is in.
    while (ctrl_.size() < n_ && std::min(ctrl_.size() + d_, n_ - 1) <= last) pole();
    // Spans before the next pole's window are no longer needed.
    const std::size_t lo = std::max(ctrl_.size(), d_);
    while (!held_.empty() && span_[held_first_] < lo) {
      held_.erase(held_.begin());
      ++held_first_;
    }
  }
  /// How many pieces are held now: at most degree + 1 once add returns.
  std::size_t held() const { return held_.size(); }
  /// The spline, once every span has its piece.
  BSpline<Coef> finish() && {
    if (added_ != span_.size())
      throw Error(Errc::internal, "Bezier pieces do not match the knot vector");
    while (ctrl_.size() < n_) pole();
    return BSpline<Coef>::make(static_cast<int>(d_), std::move(knots_), std::move(ctrl_));
  }

 private:
  void pole() {
    const auto piece = [this](std::size_t k) -> const Bernstein<Coef>& {
      if (k < held_first_ || k - held_first_ >= held_.size())
        throw Error(Errc::internal, "Bezier joiner: a pole's piece was dropped");
      return held_[k - held_first_];
    };
    ctrl_.push_back(detail::joined_pole(knots_, d_, n_, ctrl_.size(), span_, first_, piece, work_));
  }
  std::size_t d_, n_;
  std::vector<S> knots_;
  std::vector<std::size_t> span_;
  std::vector<Bernstein<Coef>> held_;  // pieces on span_[held_first_ ...]
  std::size_t held_first_ = 0, added_ = 0, first_ = 0;
  std::vector<Coef> ctrl_, work_;
};

/// The continuity of s at x: C^(degree - multiplicity) at a knot, C-infinity (INT_MAX)
/// where x is no knot of s: a polynomial piece is smooth inside its span.
template <typename Coef>
int continuity_at(const BSpline<Coef>& s, const coef_scalar_t<Coef>& x) {
  const int m = s.multiplicity(x);
  return m == 0 ? std::numeric_limits<int>::max() : s.degree() - m;
}

/// Clamped knot vector of degree d on the breakpoints x for a spline built from s and r
/// piece by piece (product, sum): each interior breakpoint gets multiplicity d - c, with c
/// the lesser continuity of s and r there (at least -1: a break).
template <typename A, typename B>
std::vector<coef_scalar_t<A>> joined_knots(const std::vector<coef_scalar_t<A>>& x, int d,
                                           const BSpline<A>& s, const BSpline<B>& r) {
  std::vector<coef_scalar_t<A>> knots(static_cast<std::size_t>(d + 1), x.front());
  for (std::size_t k = 1; k + 1 < x.size(); ++k) {
    const int cont = std::min(continuity_at(s, x[k]), continuity_at(r, x[k]));
    knots.insert(knots.end(), static_cast<std::size_t>(std::clamp(d - cont, 0, d + 1)), x[k]);
  }
  knots.insert(knots.end(), static_cast<std::size_t>(d + 1), x.back());
  return knots;
}

/// Product s * r of two splines on the same interval (coefficient order kept). Degree
/// p + q; at a breakpoint x the product is as smooth as the less smooth factor there
/// (continuity_at: a breakpoint one factor lacks does not lower it), so x gets multiplicity
/// p + q - that continuity. Built per span by (29), reassembled exactly.
template <typename A, typename B, typename Op = RingMul>
auto product(const BSpline<A>& s, const BSpline<B>& r, Op op = {}) {
  using R = std::decay_t<decltype(op(s.ctrl()[0], r.ctrl()[0]))>;
  using S = coef_scalar_t<R>;
  if (s.a() != r.a() || s.b() != r.b())
    throw Error(Errc::invalid_input, "product of splines on different intervals");
  const int p = s.degree(), q = r.degree(), d = p + q;
  std::vector<S> x = s.breakpoints();
  for (const auto& v : r.breakpoints()) x.push_back(v);
  std::sort(x.begin(), x.end());
  x.erase(std::unique(x.begin(), x.end()), x.end());
  const auto ps = bezier_pieces(s, x);
  const auto pr = bezier_pieces(r, x);
  std::vector<Bernstein<R>> pieces;
  pieces.reserve(ps.size());
  for (std::size_t k = 0; k < ps.size(); ++k) pieces.push_back(product(ps[k], pr[k], op));
  return from_bezier_pieces(pieces, d, joined_knots(x, d, s, r));
}

/// Derivative ds/dt (degree p-1 on the inner knot vector).
template <typename Coef>
BSpline<Coef> derivative(const BSpline<Coef>& s) {
  using S = coef_scalar_t<Coef>;
  const int p = s.degree();
  const auto& T = s.knots();
  const auto& P = s.ctrl();
  if (p == 0) return BSpline<Coef>::make(0, {s.a(), s.b()}, {coef_zero<Coef>()});
  std::vector<Coef> Q;
  for (std::size_t i = 0; i + 1 < P.size(); ++i) {
    const S den = T[i + static_cast<std::size_t>(p) + 1] - T[i + 1];
    Q.push_back(den == S(0) ? coef_zero<Coef>() : scale(S(S(p) / den), Coef(P[i + 1] - P[i])));
  }
  return BSpline<Coef>::make(p - 1, std::vector<S>(T.begin() + 1, T.end() - 1), std::move(Q));
}

/// Values of the p+1 non-zero basis functions N_{j-p..j, p} at t on span j
/// (The NURBS Book, A2.2). Exact for exact Scalar.
template <typename Scalar>
std::vector<Scalar> basis_functions(const std::vector<Scalar>& T, int j, int p, const Scalar& t) {
  std::vector<Scalar> N(static_cast<std::size_t>(p + 1), Scalar(0)), left(N.size(), Scalar(0)),
      right(N.size(), Scalar(0));
  N[0] = Scalar(1);
  for (int k = 1; k <= p; ++k) {
    const std::size_t uk = static_cast<std::size_t>(k);
    left[uk] = Scalar(t - T[static_cast<std::size_t>(j + 1 - k)]);
    right[uk] = Scalar(T[static_cast<std::size_t>(j + k)] - t);
    Scalar saved(0);
    for (std::size_t r = 0; r < uk; ++r) {
      const Scalar tmp = Scalar(N[r] / (right[r + 1] + left[uk - r]));
      N[r] = Scalar(saved + right[r + 1] * tmp);
      saved = Scalar(left[uk - r] * tmp);
    }
    N[uk] = saved;
  }
  return N;
}

/// Combines two splines on the same interval piece by piece over the union of their
/// breakpoints: f(piece_a, piece_b) must return a Bernstein polynomial of degree
/// max(deg a, deg b) on the piece. At each breakpoint the result keeps the continuity of
/// the less smooth input.
template <typename A, typename B, typename F>
auto combine(const BSpline<A>& a, const BSpline<B>& b, F f) {
  using S = coef_scalar_t<A>;
  std::vector<S> x = a.breakpoints();
  for (const auto& v : b.breakpoints()) x.push_back(v);
  std::sort(x.begin(), x.end());
  x.erase(std::unique(x.begin(), x.end()), x.end());
  const int d = std::max(a.degree(), b.degree());
  const auto pas = bezier_pieces(a, x);
  const auto pbs = bezier_pieces(b, x);
  using R = typename std::decay_t<decltype(f(pas[0], pbs[0]))>;
  std::vector<R> pieces;
  pieces.reserve(pas.size());
  for (std::size_t k = 0; k < pas.size(); ++k)
    pieces.push_back(f(elevate(pas[k], d - pas[k].degree()), elevate(pbs[k], d - pbs[k].degree())));
  return from_bezier_pieces(pieces, d, joined_knots(x, d, a, b));
}

/// Applies f to every pole.
template <typename Coef, typename F>
auto map_coeffs(const BSpline<Coef>& s, F&& f) {
  using R = std::decay_t<decltype(f(s.ctrl()[0]))>;
  std::vector<R> c;
  for (const auto& x : s.ctrl()) c.push_back(f(x));
  return BSpline<R>::make(s.degree(), s.knots(), std::move(c));
}

}  // namespace qmotion::kernel
