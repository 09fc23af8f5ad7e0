// <qmotion/kernel/bernstein.hpp>
#pragma once
#include <cstddef>
#include <qmotion/kernel/coefficient.hpp>
#include <qmotion/kernel/error.hpp>
#include <string>
#include <utility>
#include <vector>

namespace qmotion::kernel {

/// Binomial coefficient C(n, k) as Scalar (exact for exact Scalar, and for double while
/// it stays below 2^53).
template <typename Scalar>
Scalar binomial(int n, int k) {
  if (k < 0 || k > n) return Scalar(0);
  if (k > n - k) k = n - k;
  Scalar c(1);
  for (int i = 0; i < k; ++i) c = Scalar(c * Scalar(n - i) / Scalar(i + 1));
  return c;
}

/// Polynomial in Bernstein form over [a, b]: p(t) = sum_i b_i^n(s) c_i with s = (t-a)/(b-a)
/// (Juettler 1994, eq. (13) on a general interval). Coefficients in any ring of
/// kernel/coefficient.hpp.
/// @tparam Coef  scalar, Eigen fixed-size vector/matrix, Quaternion or DualQuaternion
template <typename Coef>
class Bernstein {
 public:
  using Scalar = coef_scalar_t<Coef>;

  Bernstein() : c_{coef_zero<Coef>()}, a_(0), b_(1) {}
  /// @pre !coeffs.empty() and a < b (throws Errc::invalid_input otherwise)
  explicit Bernstein(std::vector<Coef> coeffs, Scalar a = Scalar(0), Scalar b = Scalar(1))
      : c_(std::move(coeffs)), a_(std::move(a)), b_(std::move(b)) {
    if (c_.empty()) throw Error(Errc::invalid_input, "Bernstein polynomial with no coefficients");
    if (!(a_ < b_)) throw Error(Errc::invalid_input, "Bernstein polynomial on an empty interval");
  }

  int degree() const { return static_cast<int>(c_.size()) - 1; }
  const std::vector<Coef>& coeffs() const { return c_; }
  /// The coefficients moved out (the polynomial is left empty and must not be used): a
  /// caller that makes one piece after another reuses their storage.
  std::vector<Coef> take_coeffs() && { return std::move(c_); }
  const Coef& operator[](int i) const { return c_[static_cast<std::size_t>(i)]; }
  const Scalar& a() const { return a_; }
  const Scalar& b() const { return b_; }
  /// Local parameter s = (t - a)/(b - a).
  Scalar local(const Scalar& t) const { return Scalar((t - a_) / (b_ - a_)); }

 private:
  std::vector<Coef> c_;
  Scalar a_, b_;
};

namespace detail {
template <typename Coef>
Coef lerp(const Coef& x, const Coef& y, const coef_scalar_t<Coef>& s) {
  using S = coef_scalar_t<Coef>;
  Coef r = scale(S(S(1) - s), x);
  r += scale(s, y);
  return r;
}
}  // namespace detail

/// p(t) by de Casteljau's algorithm (only +, -, *: exact for exact Scalar).
/// @see Farin, Curves and Surfaces for CAGD, ch. 4
template <typename Coef>
Coef evaluate(const Bernstein<Coef>& p, const coef_scalar_t<Coef>& t) {
  using S = coef_scalar_t<Coef>;
  std::vector<Coef> c = p.coeffs();
  const S s = p.local(t);
  for (std::size_t r = 1; r < c.size(); ++r)
    for (std::size_t i = 0; i + r < c.size(); ++i) c[i] = detail::lerp(c[i], c[i + 1], s);
  return c[0];
}

/// Blossom (polar form) of p at the degree parameters u[0], u[1], ... (global parameters, any
/// iterator), with `work` as scratch space: its capacity is reused from call to call. An
/// argument at an end of [a, b] costs nothing: the step would take every coefficient's
/// right (at b) or left (at a) neighbour whole, so the live coefficients' window moves
/// instead (same value: lerp at 1 or 0 is exact). A B-spline pole's knot window mostly
/// holds span ends (from_bezier_pieces).
template <typename Coef, typename It>
Coef blossom(const Bernstein<Coef>& p, It u, std::vector<Coef>& work) {
  work.assign(p.coeffs().begin(), p.coeffs().end());
  std::size_t lo = 0, hi = work.size();  // the live coefficients: work[lo, hi)
  for (std::size_t r = 1; r < work.size(); ++r, ++u) {
    if (*u == p.b()) {  // work[i] <- work[i + 1]
      ++lo;
      continue;
    }
    if (*u != p.a()) {  // at a: work[i] <- work[i]
      const auto s = p.local(*u);
      for (std::size_t i = lo; i + 1 < hi; ++i) work[i] = detail::lerp(work[i], work[i + 1], s);
    }
    --hi;
  }
  return work[lo];
}

/// Blossom (polar form) of p at the n parameters u (global parameters).
/// @pre u.size() == p.degree()
template <typename Coef>
Coef blossom(const Bernstein<Coef>& p, const std::vector<coef_scalar_t<Coef>>& u) {
  QMOTION_EXPECTS(static_cast<int>(u.size()) == p.degree(), "blossom needs degree arguments");
  std::vector<Coef> c;
  return blossom(p, u.begin(), c);
}

/// The same polynomial in Bernstein form over [s, e] (any s < e; extrapolates outside [a, b]).
template <typename Coef>
Bernstein<Coef> restrict_to(const Bernstein<Coef>& p, const coef_scalar_t<Coef>& s,
                            const coef_scalar_t<Coef>& e) {
  const int n = p.degree();
  std::vector<Coef> c;
  c.reserve(static_cast<std::size_t>(n + 1));
  for (int i = 0; i <= n; ++i) {
    std::vector<coef_scalar_t<Coef>> u(static_cast<std::size_t>(n - i), s);
    u.insert(u.end(), static_cast<std::size_t>(i), e);
    c.push_back(blossom(p, u));
  }
  return Bernstein<Coef>(std::move(c), s, e);
}

/// Splits p at t (a < t < b) into its pieces over [a, t] and [t, b].
template <typename Coef>
std::pair<Bernstein<Coef>, Bernstein<Coef>> subdivide(const Bernstein<Coef>& p,
                                                      const coef_scalar_t<Coef>& t) {
  if (!(p.a() < t && t < p.b()))
    throw Error(Errc::invalid_input, "subdivision parameter outside the open interval");
  using S = coef_scalar_t<Coef>;
  const S s = p.local(t);
  std::vector<Coef> c = p.coeffs();
  const std::size_t n = c.size() - 1;
  std::vector<Coef> left(n + 1, c[0]), right(n + 1, c[n]);
  for (std::size_t r = 1; r <= n; ++r) {
    for (std::size_t i = 0; i + r <= n; ++i) c[i] = detail::lerp(c[i], c[i + 1], s);
    left[r] = c[0];
    right[n - r] = c[n - r];
  }
  return {Bernstein<Coef>(std::move(left), p.a(), t), Bernstein<Coef>(std::move(right), t, p.b())};
}

/// Derivative dp/dt (degree n-1; the zero polynomial of degree 0 for constants).
template <typename Coef>
Bernstein<Coef> derivative(const Bernstein<Coef>& p) {
  using S = coef_scalar_t<Coef>;
  const int n = p.degree();
  if (n == 0) return Bernstein<Coef>({coef_zero<Coef>()}, p.a(), p.b());
  const S f = S(S(n) / (p.b() - p.a()));
  std::vector<Coef> c;
  for (int i = 0; i < n; ++i) c.push_back(scale(f, Coef(p[i + 1] - p[i])));
  return Bernstein<Coef>(std::move(c), p.a(), p.b());
}

/// Degree elevation by r of the coefficients c, in place: step by step, the new coefficient
/// i mixes the old i and i - 1, so going down reads every old one before overwriting it.
template <typename Coef>
void elevate_coeffs(std::vector<Coef>& c, int r) {
  using S = coef_scalar_t<Coef>;
  if (r <= 0) return;
  c.reserve(c.size() + static_cast<std::size_t>(r));
  for (int step = 0; step < r; ++step) {
    const int n1 = static_cast<int>(c.size());  // new degree
    c.push_back(c.back());
    for (int i = n1 - 1; i >= 1; --i) {
      const S w = S(S(i) / S(n1));
      c[static_cast<std::size_t>(i)] =
          detail::lerp(c[static_cast<std::size_t>(i)], c[static_cast<std::size_t>(i - 1)], w);
    }
  }
}

/// Degree elevation by r: the same polynomial with degree n + r.
template <typename Coef>
Bernstein<Coef> elevate(const Bernstein<Coef>& p, int r = 1) {
  std::vector<Coef> c = p.coeffs();
  elevate_coeffs(c, r);
  return Bernstein<Coef>(std::move(c), p.a(), p.b());
}

/// Applies f to every coefficient (e.g. the scalar part of a quaternion polynomial).
template <typename Coef, typename F>
auto map_coeffs(const Bernstein<Coef>& p, F&& f) {
  using R = std::decay_t<decltype(f(p[0]))>;
  std::vector<R> c;
  c.reserve(p.coeffs().size());
  for (const auto& x : p.coeffs()) c.push_back(f(x));
  return Bernstein<R>(std::move(c), p.a(), p.b());
}

/// Sum of two polynomials on the same interval (the lower degree is elevated).
template <typename Coef>
Bernstein<Coef> operator+(const Bernstein<Coef>& p, const Bernstein<Coef>& q) {
  if (p.a() != q.a() || p.b() != q.b())
    throw Error(Errc::invalid_input, "sum of polynomials on different intervals");
  if (p.degree() < q.degree()) return elevate(p, q.degree() - p.degree()) + q;
  if (q.degree() < p.degree()) return p + elevate(q, p.degree() - q.degree());
  std::vector<Coef> c = p.coeffs();
  for (std::size_t i = 0; i < c.size(); ++i) c[i] += q.coeffs()[i];
  return Bernstein<Coef>(std::move(c), p.a(), p.b());
}

template <typename Coef>
Bernstein<Coef> operator-(const Bernstein<Coef>& p, const Bernstein<Coef>& q) {
  using S = coef_scalar_t<Coef>;
  return p + map_coeffs(q, [](const Coef& x) { return scale(S(-1), x); });
}

/// The ring product as a function object (default of the product functions).
struct RingMul {
  template <typename A, typename B>
  auto operator()(const A& a, const B& b) const {
    return ring_mul(a, b);
  }
};

/// The weights C(k,i) C(l,j) / C(k+l,i+j) of formula (29) for degrees k and l, (i, j) row
/// by row: a caller that multiplies many pairs of one pair of degrees makes them once.
template <typename S>
std::vector<S> product_weights(int k, int l) {
  std::vector<S> bk, bl, bkl, w;
  for (int i = 0; i <= k; ++i) bk.push_back(binomial<S>(k, i));
  for (int j = 0; j <= l; ++j) bl.push_back(binomial<S>(l, j));
  for (int i = 0; i <= k + l; ++i) bkl.push_back(binomial<S>(k + l, i));
  for (int i = 0; i <= k; ++i)
    for (int j = 0; j <= l; ++j)
      w.push_back(S(bk[static_cast<std::size_t>(i)] * bl[static_cast<std::size_t>(j)] /
                    bkl[static_cast<std::size_t>(i + j)]));
  return w;
}

/// Product p * q by formula (29): b_i^k b_j^l = C(k,i) C(l,j) / C(k+l,i+j) b_{i+j}^{k+l}.
/// The coefficient order is kept (p's coefficient on the left) for non-commutative rings.
/// `op` may be any bilinear map of the coefficients (e.g. the polar form of a quadratic
/// map, which turns Q(t) into its 4x4 matrix polynomial).
template <typename A, typename B, typename Op = RingMul>
auto product(const Bernstein<A>& p, const Bernstein<B>& q, Op op = {}) {
  using R = std::decay_t<decltype(op(p[0], q[0]))>;
  using S = coef_scalar_t<R>;
  if (p.a() != q.a() || p.b() != q.b())
    throw Error(Errc::invalid_input, "product of polynomials on different intervals");
  const int k = p.degree(), l = q.degree();
  const std::vector<S> w = product_weights<S>(k, l);
  std::vector<R> c(static_cast<std::size_t>(k + l + 1), coef_zero<R>());
  std::size_t n = 0;
  for (int i = 0; i <= k; ++i)
    for (int j = 0; j <= l; ++j, ++n)
      c[static_cast<std::size_t>(i + j)] += scale(w[n], R(op(p[i], q[j])));
  return Bernstein<R>(std::move(c), p.a(), p.b());
}

/// Default relative tolerance of the exactness tests below: 0 for exact Scalar.
template <typename Scalar>
double default_rel_tol() {
  return is_exact_v<Scalar> ? 0.0 : 1e-12;
}

/// Largest coefficient magnitude of p (as double).
template <typename Coef>
double max_coeff_abs(const Bernstein<Coef>& p) {
  double m = 0.0;
  for (const auto& c : p.coeffs()) m = std::max(m, max_abs(c));
  return m;
}

namespace detail {
/// One degree-reduction step: the degree n-1 polynomial whose elevation is p, when p is
/// exactly (exact Scalar) or within rel_tol (double) degree-elevated; false otherwise.
template <typename Coef>
bool reduce_once(const Bernstein<Coef>& p, double rel_tol, Bernstein<Coef>& out) {
  using S = coef_scalar_t<Coef>;
  const int n = p.degree();
  if (n == 0) return false;
  // The n-th forward difference is n! times the leading power coefficient.
  Coef lead = coef_zero<Coef>();
  double scale_sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    S w = binomial<S>(n, i);
    if ((n - i) % 2 == 1) w = S(-w);
    lead += scale(w, p[i]);
    scale_sum += std::abs(to_double(w)) * max_abs(p[i]);
  }
  if (!coef_negligible(lead, scale_sum, rel_tol)) return false;
  // Invert the elevation formula from the front for the first half, from the back for the
  // second (each recursion is stable in its own half).
  std::vector<Coef> c(static_cast<std::size_t>(n), coef_zero<Coef>());
  const int half = n / 2;
  c[0] = p[0];
  for (int i = 1; i < half; ++i)
    c[static_cast<std::size_t>(i)] =
        scale(S(S(1) / S(n - i)),
              Coef(scale(S(n), p[i]) - scale(S(i), c[static_cast<std::size_t>(i - 1)])));
  c[static_cast<std::size_t>(n - 1)] = p[n];
  for (int i = n - 1; i > half; --i)
    c[static_cast<std::size_t>(i - 1)] = scale(
        S(S(1) / S(i)), Coef(scale(S(n), p[i]) - scale(S(n - i), c[static_cast<std::size_t>(i)])));
  Bernstein<Coef> reduced(std::move(c), p.a(), p.b());
  // Confirm: elevating back must give p.
  const Bernstein<Coef> back = elevate(reduced);
  const double ref = std::max(max_coeff_abs(p), 1e-300);
  for (int i = 0; i <= n; ++i)
    if (!coef_negligible(Coef(back[i] - p[i]), ref, rel_tol)) return false;
  out = std::move(reduced);
  return true;
}
}  // namespace detail

/// Exact degree reduction: strips every degree elevation the representation carries.
/// Exact for exact Scalar; for double, a step is taken when the representation is
/// elevated within rel_tol relative to its coefficients.
template <typename Coef>
Bernstein<Coef> reduce_degree(const Bernstein<Coef>& p,
                              double rel_tol = default_rel_tol<coef_scalar_t<Coef>>()) {
  Bernstein<Coef> cur = p, next;
  while (detail::reduce_once(cur, rel_tol, next)) cur = std::move(next);
  return cur;
}

/// The true degree of p (its degree after reduce_degree).
template <typename Coef>
int exact_degree(const Bernstein<Coef>& p,
                 double rel_tol = default_rel_tol<coef_scalar_t<Coef>>()) {
  return reduce_degree(p, rel_tol).degree();
}

/// Side of a known factor F in exact division.
enum class Side { right, left };  ///< P = G * F (right) or P = F * G (left)

/// Exact division by a known factor: the G with P = G * F (Side::right) or P = F * G
/// (Side::left). In scaled Bernstein coefficients (C(n,i) c_i) the product is a
/// convolution, so G follows by forward substitution from the front (needs F(a) != 0) and
/// backward from the back (needs F(b) != 0); each half is taken from its stable side.
/// Throws Errc::numerical_failure when F does not divide P (exactly, or within rel_tol).
template <typename CP, typename CF>
Bernstein<CP> divide_exact(const Bernstein<CP>& p, const Bernstein<CF>& f, Side side = Side::right,
                           double rel_tol = default_rel_tol<coef_scalar_t<CP>>()) {
  using S = coef_scalar_t<CP>;
  const int n = p.degree(), df = f.degree(), g = n - df;
  if (g < 0) throw Error(Errc::numerical_failure, "divisor has a higher degree than the dividend");
  if (p.a() != f.a() || p.b() != f.b())
    throw Error(Errc::invalid_input, "division of polynomials on different intervals");
  std::vector<CP> ph;
  std::vector<CF> fh;
  for (int i = 0; i <= n; ++i) ph.push_back(scale(binomial<S>(n, i), p[i]));
  for (int j = 0; j <= df; ++j) fh.push_back(scale(binomial<S>(df, j), f[j]));
  const double fscale = max_coeff_abs(f);
  const bool front_ok = !coef_negligible(fh.front(), fscale, 1e-8);
  const bool back_ok = !coef_negligible(fh.back(), fscale, 1e-8);
  if (!front_ok && !back_ok)
    throw Error(Errc::numerical_failure, "divisor vanishes at both ends of the interval");
  auto mul = [side](const CP& gg, const CF& ff) -> CP {
    if (side == Side::right) return ring_mul(gg, ff);
    return ring_mul(ff, gg);
  };
  auto solve = [side](const CP& rhs, const CF& inv) -> CP {
    if (side == Side::right) return ring_mul(rhs, inv);
    return ring_mul(inv, rhs);
  };
  std::vector<CP> gh(static_cast<std::size_t>(g + 1), coef_zero<CP>());
  const int split = !back_ok ? g + 1 : (!front_ok ? 0 : g / 2 + 1);
  if (split > 0) {
    const CF inv0 = coef_inverse(fh.front());
    for (int k = 0; k < split; ++k) {
      CP rhs = ph[static_cast<std::size_t>(k)];
      for (int j = 1; j <= std::min(k, df); ++j)
        rhs -= mul(gh[static_cast<std::size_t>(k - j)], fh[static_cast<std::size_t>(j)]);
      gh[static_cast<std::size_t>(k)] = solve(rhs, inv0);
    }
  }
  if (split <= g) {
    const CF invn = coef_inverse(fh.back());
    for (int k = 0; g - k >= split; ++k) {
      CP rhs = ph[static_cast<std::size_t>(n - k)];
      for (int j = 1; j <= std::min(k, df); ++j)
        rhs -= mul(gh[static_cast<std::size_t>(g - k + j)], fh[static_cast<std::size_t>(df - j)]);
      gh[static_cast<std::size_t>(g - k)] = solve(rhs, invn);
    }
  }
  std::vector<CP> gc;
  for (int i = 0; i <= g; ++i)
    gc.push_back(scale(S(S(1) / binomial<S>(g, i)), gh[static_cast<std::size_t>(i)]));
  Bernstein<CP> quotient(std::move(gc), p.a(), p.b());
  // Verify the division: G * F (or F * G) must reproduce P.
  const Bernstein<CP> back = side == Side::right ? Bernstein<CP>(product(quotient, f))
                                                 : Bernstein<CP>(product(f, quotient));
  const double ref = std::max(max_coeff_abs(p), 1e-300);
  for (int i = 0; i <= n; ++i)
    if (!coef_negligible(CP(back[i] - p[i]), ref, rel_tol == 0.0 ? 0.0 : rel_tol * 1e3))
      throw Error(Errc::numerical_failure, "the given factor does not divide the polynomial");
  return quotient;
}

}  // namespace qmotion::kernel
