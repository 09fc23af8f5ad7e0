// tests/kernel/instantiate_test.cpp: every class template of the kernel instantiated
// explicitly for double and CGAL::Exact_rational, so members no test calls still compile.
#include <qmotion/kernel/bernstein.hpp>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/kernel/motion.hpp>

#include "test_util.hpp"

namespace qmotion::kernel {
template class Quaternion<double>;
template class Quaternion<Rational>;
template class DualQuaternion<double>;
template class DualQuaternion<Rational>;
template class Bernstein<double>;
template class Bernstein<Rational>;
template class Bernstein<Quaternion<Rational>>;
template class Bernstein<DualQuaternion<Rational>>;
template class Bernstein<Eigen::Matrix<Rational, 4, 4>>;
template class BSpline<double>;
template class BSpline<Rational>;
template class BSpline<DualQuaternion<double>>;
template class BSpline<DualQuaternion<Rational>>;
template class BSpline<Eigen::Matrix<Rational, 3, 1>>;
template struct QMotion<double>;
template struct QMotion<Rational>;
}  // namespace qmotion::kernel

namespace qmotion::test {
namespace {
TEST(Instantiate, ExactRationalIsTheExactScalar) {
  static_assert(kernel::is_exact_v<Rational>);
  static_assert(!kernel::is_exact_v<double>);
  EXPECT_EQ(tol_for<Rational>(1.0), 0.0);
  EXPECT_EQ(kernel::ScalarTraits<Rational>::tolerance(), Rational(0));
}
}  // namespace
}  // namespace qmotion::test
