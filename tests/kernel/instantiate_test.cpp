// tests/kernel/instantiate_test.cpp: every class template of the kernel instantiated
// explicitly for double and CGAL::Exact_rational, so members no test calls still compile.
#include <qmotion/kernel/bernstein.hpp>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/kernel/motion.hpp>

#include "test_util.hpp"

namespace qmotion::kernel {
template class Quaternion<double>;
#ifdef QMOTION_WITH_CGAL
template class Quaternion<Rational>;
#endif
template class DualQuaternion<double>;
#ifdef QMOTION_WITH_CGAL
template class DualQuaternion<Rational>;
#endif
template class Bernstein<double>;
#ifdef QMOTION_WITH_CGAL
template class Bernstein<Rational>;
#endif
#ifdef QMOTION_WITH_CGAL
template class Bernstein<Quaternion<Rational>>;
#endif
#ifdef QMOTION_WITH_CGAL
template class Bernstein<DualQuaternion<Rational>>;
#endif
#ifdef QMOTION_WITH_CGAL
template class Bernstein<Eigen::Matrix<Rational, 4, 4>>;
#endif
template class BSpline<double>;
#ifdef QMOTION_WITH_CGAL
template class BSpline<Rational>;
#endif
template class BSpline<DualQuaternion<double>>;
#ifdef QMOTION_WITH_CGAL
template class BSpline<DualQuaternion<Rational>>;
#endif
#ifdef QMOTION_WITH_CGAL
template class BSpline<Eigen::Matrix<Rational, 3, 1>>;
#endif
template struct QMotion<double>;
#ifdef QMOTION_WITH_CGAL
template struct QMotion<Rational>;
#endif
}  // namespace qmotion::kernel

namespace qmotion::test {
namespace {
#ifdef QMOTION_WITH_CGAL
TEST(Instantiate, ExactRationalIsTheExactScalar) {
  static_assert(kernel::is_exact_v<Rational>);
  static_assert(!kernel::is_exact_v<double>);
  EXPECT_EQ(tol_for<Rational>(1.0), 0.0);
  EXPECT_EQ(kernel::ScalarTraits<Rational>::tolerance(), Rational(0));
}
#endif
}  // namespace
}  // namespace qmotion::test
