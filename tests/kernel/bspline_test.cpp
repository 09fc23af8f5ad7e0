// tests/kernel/bspline_test.cpp mirrors kernel/bspline.hpp
#include <qmotion/kernel/bspline.hpp>

#include "test_util.hpp"

namespace qmotion::test {
namespace {
using kernel::BSpline;

/// Random spline of degree p on [0, 3] with interior knots 1/2, 1 (x mult), 2.
template <typename C>
BSpline<C> rand_spline(std::mt19937& g, int p, int mult) {
  using S = kernel::coef_scalar_t<C>;
  std::vector<S> k(static_cast<std::size_t>(p + 1), S(0));
  k.push_back(S(1) / S(2));
  k.insert(k.end(), static_cast<std::size_t>(mult), S(1));
  k.push_back(S(2));
  k.insert(k.end(), static_cast<std::size_t>(p + 1), S(3));
  std::vector<C> c;
  for (std::size_t i = 0; i + static_cast<std::size_t>(p) + 1 < k.size(); ++i)
    c.push_back(rand_coef<C>(g));
  return BSpline<C>::make(p, std::move(k), std::move(c));
}

/// Cox-de Boor recursion for the basis function N_{i,p}: an independent evaluator.
template <typename S>
S basis(const std::vector<S>& T, int i, int p, const S& t) {
  const std::size_t ui = static_cast<std::size_t>(i);
  if (p == 0) {
    if (T[ui] <= t && t < T[ui + 1]) return S(1);
    // Right end: the last non-empty span is closed.
    if (t == T.back() && T[ui] < T[ui + 1] && T[ui + 1] == T.back()) return S(1);
    return S(0);
  }
  S r(0);
  const std::size_t up = static_cast<std::size_t>(p);
  if (T[ui + up] != T[ui]) r += S((t - T[ui]) / (T[ui + up] - T[ui]) * basis(T, i, p - 1, t));
  if (T[ui + up + 1] != T[ui + 1])
    r += S((T[ui + up + 1] - t) / (T[ui + up + 1] - T[ui + 1]) * basis(T, i + 1, p - 1, t));
  return r;
}

template <typename C>
C cox_de_boor(const BSpline<C>& s, const kernel::coef_scalar_t<C>& t) {
  C sum = kernel::coef_zero<C>();
  for (std::size_t i = 0; i < s.ctrl().size(); ++i)
    sum += kernel::scale(basis(s.knots(), static_cast<int>(i), s.degree(), t), s.ctrl()[i]);
  return sum;
}

template <typename S>
class BSplineTest : public ::testing::Test {};
TYPED_TEST_SUITE(BSplineTest, Scalars);

template <typename S>
std::vector<S> sample_params(std::mt19937& g, int n) {
  std::vector<S> t = {S(0), S(1) / S(2), S(1), S(2), S(3)};  // knots and both ends
  for (int i = 0; i < n; ++i) t.push_back(S(S(3) * rand_unit<S>(g)));
  return t;
}

template <typename C>
void check_spline_ops(std::mt19937& g) {
  using S = kernel::coef_scalar_t<C>;
  for (int p = 1; p <= 5; ++p)
    for (int mult = 1; mult <= p; ++mult) {
      const auto s = rand_spline<C>(g, p, mult);
      const auto ins =
          kernel::insert_knot(kernel::insert_knot(s, S(5) / S(4), std::min(2, p)), S(1) / S(2));
      const auto pieces = kernel::bezier_pieces(s);
      ASSERT_EQ(pieces.size(), 4u);
      const auto back = kernel::from_bezier_pieces(pieces, p, s.knots());
      // The same poles: those whose knot window is a span's end points are read off the
      // pieces' Bernstein coefficients, the others blossomed (both exact in rationals).
      ASSERT_EQ(back.ctrl().size(), s.ctrl().size());
      for (std::size_t i = 0; i < s.ctrl().size(); ++i)
        ASSERT_TRUE(coef_near(back.ctrl()[i], s.ctrl()[i], 1e-12)) << "p=" << p << " pole " << i;
      for (const S& t : sample_params<S>(g, 20)) {
        const C v = kernel::evaluate(s, t);
        ASSERT_TRUE(coef_near(cox_de_boor(s, t), v, 1e-12)) << "p=" << p;
        ASSERT_TRUE(coef_near(kernel::evaluate(ins, t), v, 1e-12));
        ASSERT_TRUE(coef_near(kernel::evaluate(back, t), v, 1e-12));
        std::size_t k = 0;
        while (k + 1 < pieces.size() && !(t < pieces[k].b())) ++k;
        ASSERT_TRUE(coef_near(kernel::evaluate(pieces[k], t), v, 1e-12));
      }
      // Knot insertion (A5.6) gives the blossoms bezier_piece computes, and a refinement of
      // the breakpoints gives the pieces of the finer spans.
      const auto same = [](const auto& u, const auto& v) {
        if (u.a() != v.a() || u.b() != v.b() || u.coeffs().size() != v.coeffs().size())
          return false;
        for (std::size_t i = 0; i < u.coeffs().size(); ++i)
          if (!coef_near(u.coeffs()[i], v.coeffs()[i], 1e-12)) return false;
        return true;
      };
      for (const auto& piece : pieces)
        ASSERT_TRUE(same(piece, kernel::bezier_piece(s, piece.a(), piece.b()))) << "p=" << p;
      const std::vector<S> x = {S(0), S(1) / S(4), S(1) / S(2), S(1), S(5) / S(4), S(2), S(3)};
      const auto fine = kernel::bezier_pieces(s, x);
      ASSERT_EQ(fine.size(), 6u);
      for (std::size_t k = 0; k < fine.size(); ++k)
        ASSERT_TRUE(same(fine[k], kernel::bezier_piece(s, x[k], x[k + 1]))) << "p=" << p;
      // Reassembly gives back the same poles (exactly for rationals).
      for (std::size_t i = 0; i < s.ctrl().size(); ++i)
        ASSERT_TRUE(coef_near(back.ctrl()[i], s.ctrl()[i], 1e-10));
    }
}

TYPED_TEST(BSplineTest, InsertionDecompositionAndEvaluationAgree) {
  using S = TypeParam;
  std::mt19937 g(21);
  {  // degree 0: the poles are the pieces
    const auto s0 = BSpline<S>::make(0, {S(0), S(1), S(2), S(3)}, {S(5), S(-1), S(2)});
    const auto p0 = kernel::bezier_pieces(s0);
    ASSERT_EQ(p0.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(p0[k].coeffs()[0], s0.ctrl()[k]);
      EXPECT_EQ(p0[k].a(), S(int(k)));
    }
  }
  check_spline_ops<S>(g);
  check_spline_ops<Eigen::Matrix<S, 3, 1>>(g);
  check_spline_ops<kernel::DualQuaternion<S>>(g);
}

template <typename A, typename B>
void check_spline_product(std::mt19937& g) {
  using S = kernel::coef_scalar_t<A>;
  for (int p = 0; p <= 3; ++p)
    for (int q = 1; q <= 3; ++q) {
      const auto s = rand_spline<A>(g, std::max(p, 1), 1);
      const auto r = rand_spline<B>(g, q, q);
      const auto sr = kernel::product(s, r);
      ASSERT_EQ(sr.degree(), s.degree() + q);
      // Continuity of the product at x = 1: min(p - m_s, q - m_r) = min(p-1, 0) = 0, so
      // multiplicity = degree; at 1/2 and 2 both are C^(p-1) resp. C^(q-1).
      EXPECT_EQ(sr.multiplicity(S(1)), sr.degree());
      for (const S& t : sample_params<S>(g, 20)) {
        const auto lhs = kernel::evaluate(sr, t);
        const auto rhs = kernel::ring_mul(kernel::evaluate(s, t), kernel::evaluate(r, t));
        ASSERT_TRUE(coef_near(lhs, rhs, 1e-11));
      }
    }
}

TYPED_TEST(BSplineTest, ProductEqualsPointwiseProduct) {
  using S = TypeParam;
  std::mt19937 g(22);
  check_spline_product<S, S>(g);
  check_spline_product<kernel::Quaternion<S>, kernel::Quaternion<S>>(g);
  check_spline_product<kernel::DualQuaternion<S>, kernel::DualQuaternion<S>>(g);
  check_spline_product<S, Eigen::Matrix<S, 3, 1>>(g);
}

TYPED_TEST(BSplineTest, ProductKnotMultiplicityFollowsContinuity) {
  using S = TypeParam;
  std::mt19937 g(23);
  // Two cubic C^2 splines with the same simple knots: product degree 6, C^2, so each
  // interior knot has multiplicity 6 - 2 = 4.
  const auto s = rand_spline<S>(g, 3, 1), r = rand_spline<S>(g, 3, 1);
  const auto sr = kernel::product(s, r);
  EXPECT_EQ(sr.degree(), 6);
  EXPECT_EQ(sr.multiplicity(S(1) / S(2)), 4);
  EXPECT_EQ(sr.multiplicity(S(2)), 4);
  // The derivative of the product is continuous across the knots (C^2 => C^1 of derivative).
  const auto d = kernel::derivative(sr);
  const S eps = kernel::is_exact_v<S> ? S(0) : S(1e-12);
  for (const S& x : std::vector<S>{S(S(1) / S(2)), S(1), S(2)}) {
    const int j = d.find_span(x);
    const std::vector<S> args(static_cast<std::size_t>(d.degree()), x);
    EXPECT_TRUE(coef_near(kernel::blossom(d, j, args), kernel::evaluate(d, S(x - eps)), 1e-9));
  }
}

TYPED_TEST(BSplineTest, ABreakpointOneFactorLacksKeepsTheOthersContinuity) {
  using S = TypeParam;
  std::mt19937 g(24);
  // A product with a constant (degree 0, no interior knot) keeps every multiplicity.
  const auto s = rand_spline<S>(g, 3, 2);  // knots 1/2 (C2), 1 (C1), 2 (C2)
  const auto c = BSpline<S>::make(0, {S(0), S(3)}, {S(S(5) / S(2))});
  for (const auto& p : {kernel::product(s, c), kernel::product(c, s)}) {
    EXPECT_EQ(p.degree(), 3);
    EXPECT_EQ(p.knots(), s.knots());
    for (const S& t : sample_params<S>(g, 10))
      EXPECT_TRUE(
          coef_near(kernel::evaluate(p, t), S(S(5) / S(2) * kernel::evaluate(s, t)), 1e-12));
  }
  // Factors with different breakpoints: each breakpoint keeps the continuity of the factor
  // that has it, the other being C-infinity there. s: cubic, simple knots 1/2, 1, 2 (C2);
  // r: quadratic with a single knot at 5/4 (C1). Product degree 5: multiplicity 5 - 2 = 3
  // at s's knots, 5 - 1 = 4 at r's.
  const auto s3 = rand_spline<S>(g, 3, 1);
  const auto r =
      BSpline<S>::make(2, {S(0), S(0), S(0), S(S(5) / S(4)), S(3), S(3), S(3)},
                       {rand_coef<S>(g), rand_coef<S>(g), rand_coef<S>(g), rand_coef<S>(g)});
  const auto sr = kernel::product(s3, r);
  EXPECT_EQ(sr.degree(), 5);
  EXPECT_EQ(sr.multiplicity(S(S(1) / S(2))), 3);
  EXPECT_EQ(sr.multiplicity(S(1)), 3);
  EXPECT_EQ(sr.multiplicity(S(2)), 3);
  EXPECT_EQ(sr.multiplicity(S(S(5) / S(4))), 4);
  for (const S& t : sample_params<S>(g, 20))
    EXPECT_TRUE(coef_near(kernel::evaluate(sr, t),
                          S(kernel::evaluate(s3, t) * kernel::evaluate(r, t)), 1e-11));
  // The declared continuity is true: at 1/2 the two pieces' second derivatives agree, their
  // third derivatives do not (random data).
  const S x = S(S(1) / S(2));
  auto left = kernel::bezier_piece(sr, S(0), x), right = kernel::bezier_piece(sr, x, S(1));
  for (int k = 0; k < 2; ++k) {
    left = kernel::derivative(left);
    right = kernel::derivative(right);
  }
  EXPECT_TRUE(coef_near(kernel::evaluate(left, x), kernel::evaluate(right, x), 1e-9));
  const S jump = S(kernel::evaluate(kernel::derivative(left), x) -
                   kernel::evaluate(kernel::derivative(right), x));
  EXPECT_GT(kernel::to_double(kernel::abs_value(jump)), 1e-6);
}

/// The joiner, fed piece by piece, makes from_bezier_pieces' poles bit for bit while holding
/// at most degree + 1 pieces, on knot vectors of many spans with every multiplicity and spans
/// a thousand times narrower than their neighbours (where the widest piece is chosen).
TYPED_TEST(BSplineTest, JoinerMatchesWholeReassemblyHoldingFewPieces) {
  using S = TypeParam;
  std::mt19937 g(7);
  for (int p = 0; p <= 6; ++p) {
    std::vector<S> k(static_cast<std::size_t>(p + 1), S(0));
    S x(0);
    for (int j = 0; j < 40; ++j) {
      x += j % 7 == 3 ? S(1) / S(1000) : S(1 + j % 3);
      const int mult = p == 0 ? 1 : 1 + static_cast<int>(g() % static_cast<unsigned>(p));
      k.insert(k.end(), static_cast<std::size_t>(mult), x);
    }
    x += S(1);
    k.insert(k.end(), static_cast<std::size_t>(p + 1), x);
    std::vector<Eigen::Matrix<S, 4, 1>> c;
    for (std::size_t i = 0; i + static_cast<std::size_t>(p) + 1 < k.size(); ++i)
      c.push_back(rand_coef<Eigen::Matrix<S, 4, 1>>(g));
    const auto s = BSpline<Eigen::Matrix<S, 4, 1>>::make(p, k, std::move(c));
    const auto pieces = kernel::bezier_pieces(s);
    const auto whole = kernel::from_bezier_pieces(pieces, p, k);
    kernel::BezierJoiner<Eigen::Matrix<S, 4, 1>> joiner(p, k);
    for (const auto& piece : pieces) {
      joiner.add(piece);
      ASSERT_LE(joiner.held(), static_cast<std::size_t>(p + 1)) << "p=" << p;
    }
    EXPECT_THROW(joiner.add(pieces.front()), Error) << "a piece beyond the last span";
    const auto joined = std::move(joiner).finish();
    ASSERT_EQ(joined.knots(), whole.knots());
    ASSERT_EQ(joined.ctrl().size(), s.ctrl().size());
    for (std::size_t i = 0; i < s.ctrl().size(); ++i) {
      ASSERT_TRUE(joined.ctrl()[i] == whole.ctrl()[i]) << "p=" << p << " pole " << i;
      ASSERT_TRUE(coef_near(joined.ctrl()[i], s.ctrl()[i], 1e-9)) << "p=" << p << " pole " << i;
    }
    kernel::BezierJoiner<Eigen::Matrix<S, 4, 1>> early(p, k);
    early.add(pieces.front());
    EXPECT_THROW((void)std::move(early).finish(), Error) << "finished before the last span";
  }
}

TEST(BSplineValidation, ReportsEachProblem) {
  using B = BSpline<double>;
  EXPECT_FALSE(B::validate(2, {0, 0, 0, 1, 1, 1}, 3).size());
  EXPECT_TRUE(B::validate(2, {0, 0, 0, 1, 1}, 3).size());            // too short
  EXPECT_TRUE(B::validate(2, {0, 0, 0, 1, 0.5, 1, 1}, 4).size());    // decreasing
  EXPECT_TRUE(B::validate(2, {0, 0, 0.1, 0.5, 1, 1, 1}, 4).size());  // not clamped
  EXPECT_TRUE(B::validate(2, {1, 1, 1, 1, 1, 1}, 3).size());         // empty interval
  EXPECT_TRUE(B::validate(-1, {}, 0).size());
  EXPECT_TRUE(B::validate(1, {0, 0, 0.5, 0.5, 0.5, 1, 1}, 5).size());  // multiplicity > p+1
  EXPECT_THROW(B::make(2, {0, 0, 0, 1, 1}, {1.0, 2.0, 3.0}), Error);
}

}  // namespace
}  // namespace qmotion::test
