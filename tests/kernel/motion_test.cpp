// tests/kernel/motion_test.cpp mirrors kernel/motion.hpp
#include <qmotion/kernel/motion.hpp>

#include "test_util.hpp"

namespace qmotion::test {
namespace {
using kernel::Bernstein;
using kernel::BSpline;
using kernel::DualQuaternion;
using kernel::QMotion;
using kernel::Quaternion;

template <typename S>
class MotionTest : public ::testing::Test {};
TYPED_TEST_SUITE(MotionTest, Scalars);

/// A Q-motion built as a product of translation and rotation polynomials: it satisfies
/// Plucker identically, whatever the coefficients (Trans * Rot, eq. (30)).
template <typename S>
QMotion<S> tr_motion(std::mt19937& g, int k, int l) {
  using DQ = DualQuaternion<S>;
  using Q = Quaternion<S>;
  std::vector<Q> rot;
  for (int i = 0; i <= k; ++i) rot.push_back(rand_coef<Q>(g));
  rot[0] = Q::real(S(1));
  std::vector<DQ> trans;
  for (int i = 0; i <= l; ++i)
    trans.push_back(DQ::translation(rand_coef<Eigen::Matrix<S, 3, 1>>(g)));
  const auto q = kernel::product(Bernstein<DQ>(trans), Bernstein<Q>(rot));
  return QMotion<S>{kernel::Basis::bezier, BSpline<DQ>::from_bezier(q)};
}

TYPED_TEST(MotionTest, ProductMotionsSatisfyPluckerExactly) {
  using S = TypeParam;
  std::mt19937 g(31);
  for (int k = 1; k <= 4; ++k) {
    const auto m = tr_motion<S>(g, k, k);
    EXPECT_EQ(m.degree(), 2 * k);
    const S res = kernel::plucker_residual(m);
    if constexpr (kernel::is_exact_v<S>) {
      EXPECT_EQ(res, S(0));
    } else {
      EXPECT_LE(res, 1e-14);
    }
  }
  // A generic dual-quaternion curve violates Plucker.
  std::vector<DualQuaternion<S>> c;
  for (int i = 0; i < 3; ++i) c.push_back(rand_coef<DualQuaternion<S>>(g));
  const QMotion<S> bad{kernel::Basis::bezier,
                       BSpline<DualQuaternion<S>>::from_bezier(Bernstein<DualQuaternion<S>>(c))};
  EXPECT_GT(kernel::to_double(kernel::plucker_residual(bad)), 1e-6);
}

TYPED_TEST(MotionTest, MatrixAndTrajectorySplinesMatchPointwise) {
  using S = TypeParam;
  using V4 = Eigen::Matrix<S, 4, 1>;
  std::mt19937 g(32);
  const auto m = tr_motion<S>(g, 2, 2);
  const auto M = kernel::matrix_spline(m);
  V4 x;
  x << S(1), rand_scalar<S>(g), rand_scalar<S>(g), rand_scalar<S>(g);
  const auto y = kernel::homogeneous_trajectory(m, x);
  EXPECT_EQ(M.degree(), 2 * m.degree());
  for (int i = 0; i <= 10; ++i) {
    const S t = S(S(i) / S(10));
    const auto q = kernel::evaluate(m, t);
    EXPECT_TRUE(coef_near(kernel::evaluate(M, t), kernel::to_matrix4(q), 1e-12));
    EXPECT_TRUE(coef_near(kernel::evaluate(y, t), kernel::apply(q, x), 1e-12));
    EXPECT_TRUE(coef_near(kernel::evaluate(kernel::weight_spline(m), t), q.real().norm2(), 1e-12));
  }
  // Under a TR motion the origin's homogeneous trajectory carries the factor |Q_rot|^2;
  // a general point's does not reduce below 2k + l.
  EXPECT_EQ(kernel::exact_degree(kernel::bezier_pieces(y)[0], kernel::is_exact_v<S> ? 0.0 : 1e-10),
            6);
}

TEST(MotionPoles, FindsTheZeroOfTheRotationalPart) {
  using DQ = DualQuaternion<double>;
  using Q = Quaternion<double>;
  // Q_rot(t) = (1 - 2t) + t k ... vanishes nowhere; (1-2t) alone vanishes at t = 1/2.
  const Bernstein<Q> rot({Q(1, 0, 0, 0), Q(-1, 0, 0, 0)});  // 1 - 2t: zero at 1/2
  const Bernstein<DQ> trans({DQ::translation(Eigen::Vector3d(1, 2, 3))});
  const QMotion<double> m{kernel::Basis::bezier,
                          BSpline<DQ>::from_bezier(kernel::product(trans, rot))};
  const auto poles = kernel::find_poles(m);
  ASSERT_EQ(poles.size(), 1u);
  EXPECT_NEAR(poles[0], 0.5, 1e-9);
  // A rotation that only gets small (|Q0| >= 0.1) is no pole.
  const Bernstein<Q> rot2({Q(1, 0, 0, 0), Q(-1, 0.1, 0, 0)});
  const QMotion<double> m2{kernel::Basis::bezier,
                           BSpline<DQ>::from_bezier(kernel::product(trans, rot2))};
  EXPECT_TRUE(kernel::find_poles(m2).empty());
}

}  // namespace
}  // namespace qmotion::test
