// tests/kernel/order_test.cpp mirrors kernel/order.hpp
#include <qmotion/kernel/order.hpp>

#include "test_util.hpp"

namespace qmotion::test {
namespace {
using kernel::Bernstein;

template <typename S>
class OrderTest : public ::testing::Test {};
TYPED_TEST_SUITE(OrderTest, Scalars);

/// (s - r) as a degree-1 Bernstein polynomial on [0, 1].
template <typename S>
Bernstein<S> linear(const S& r) {
  return Bernstein<S>({S(-r), S(S(1) - r)});
}

TYPED_TEST(OrderTest, CommonFactorDegreeOfBernsteinPolynomials) {
  using S = TypeParam;
  const S a = S(1) / S(3), b = S(2), c = S(-1), d = S(3) / S(4);
  // f = (s-a)(s-b)(s-d), g = (s-a)(s-d)(s-c): common factor of degree 2.
  const auto f = kernel::product(kernel::product(linear(a), linear(b)), linear(d));
  const auto g = kernel::product(kernel::product(linear(a), linear(d)), linear(c));
  EXPECT_EQ(kernel::common_factor_degree(f, g), 2);
  // Coprime.
  EXPECT_EQ(kernel::common_factor_degree(
                f, kernel::product(kernel::product(linear(c), linear(S(5))), linear(S(-3)))),
            0);
  // Elevation is a common factor "at infinity": both elevated by 2 from degree 2.
  const auto f2 = kernel::elevate(kernel::product(linear(a), linear(b)), 2);
  const auto g2 = kernel::elevate(kernel::product(linear(c), linear(d)), 2);
  EXPECT_EQ(kernel::common_factor_degree(f2, g2), 2);
}

}  // namespace
}  // namespace qmotion::test
