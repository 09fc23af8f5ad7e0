// tests/kernel/quaternion_test.cpp mirrors kernel/quaternion.hpp
#include <cmath>
#include <qmotion/kernel/quaternion.hpp>

#include "test_util.hpp"

namespace qmotion::test {
namespace {
using kernel::Quaternion;

template <typename S>
class QuaternionTest : public ::testing::Test {};
TYPED_TEST_SUITE(QuaternionTest, Scalars);

TYPED_TEST(QuaternionTest, ProductIsAssociativeAndConjugationReversesIt) {
  using S = TypeParam;
  using Q = Quaternion<S>;
  std::mt19937 g(7);
  for (int k = 0; k < 50; ++k) {
    const Q a = rand_coef<Q>(g), b = rand_coef<Q>(g), c = rand_coef<Q>(g);
    EXPECT_TRUE(coef_near(Q((a * b) * c), Q(a * (b * c))));
    EXPECT_TRUE(coef_near(Q((a * b).conj()), Q(b.conj() * a.conj())));
    EXPECT_TRUE(coef_near(S((a * b).norm2()), S(a.norm2() * b.norm2())));
  }
}

TYPED_TEST(QuaternionTest, HamiltonUnitsFollowTheSpecOrder) {
  using S = TypeParam;
  using Q = Quaternion<S>;
  const Q i(S(0), S(1), S(0), S(0)), j(S(0), S(0), S(1), S(0)), k(S(0), S(0), S(0), S(1));
  EXPECT_EQ(i * j, k);
  EXPECT_EQ(j * k, i);
  EXPECT_EQ(k * i, j);
  EXPECT_EQ(i * i, Q::real(S(-1)));
}

TYPED_TEST(QuaternionTest, InverseAndMatrixAreExactForNonUnitQuaternions) {
  using S = TypeParam;
  using Q = Quaternion<S>;
  std::mt19937 g(11);
  for (int k = 0; k < 30; ++k) {
    const Q a = rand_coef<Q>(g);
    if (a.norm2() == S(0)) continue;
    EXPECT_TRUE(coef_near(Q(a * kernel::inverse(a)), Q::real(S(1))));
    // Rotation matrix: orthogonal, det 1, and rotate() agrees with it.
    const Eigen::Matrix<S, 3, 3> r = kernel::rotation_matrix(a);
    const Eigen::Matrix<S, 3, 3> rtr = r.transpose() * r;
    EXPECT_TRUE(coef_near(rtr, Eigen::Matrix<S, 3, 3>(Eigen::Matrix<S, 3, 3>::Identity())));
    EXPECT_TRUE(coef_near(S(r.determinant()), S(1)));
    const Eigen::Matrix<S, 3, 1> v = rand_coef<Eigen::Matrix<S, 3, 1>>(g);
    EXPECT_TRUE(coef_near(Eigen::Matrix<S, 3, 1>(r * v), kernel::rotate(a, v)));
    // Scale freedom: 3a gives the same rotation.
    EXPECT_TRUE(coef_near(kernel::rotation_matrix(Q(a * S(3))), r));
  }
}

TEST(QuaternionDouble, AxisAngleAndMatrixRoundTrip) {
  using Q = Quaternion<double>;
  std::mt19937 g(3);
  for (int k = 0; k < 200; ++k) {
    Eigen::Vector3d axis = rand_coef<Eigen::Vector3d>(g);
    const double angle = std::uniform_real_distribution<double>(-M_PI, M_PI)(g);
    const Q q = kernel::from_axis_angle(axis, angle);
    EXPECT_NEAR(q.norm2(), 1.0, 1e-15);
    const Q back = kernel::from_rotation_matrix(Eigen::Matrix3d(kernel::rotation_matrix(q)));
    const double sign = q.dot(back) < 0 ? -1.0 : 1.0;
    EXPECT_TRUE(coef_near(back * sign, q, 1e-14));
    // The rotation moves a vector on the axis nowhere and turns a perpendicular one by angle.
    const Eigen::Vector3d n = axis.normalized();
    EXPECT_TRUE(coef_near(Eigen::Vector3d(kernel::rotate(q, n)), n, 1e-14));
    const Eigen::Vector3d p = n.unitOrthogonal();
    EXPECT_NEAR(std::acos(std::clamp(kernel::rotate(q, p).dot(p), -1.0, 1.0)), std::abs(angle),
                1e-7);
  }
  // Half turn: Shepperd's method must not divide by the small trace.
  const Q half = kernel::from_axis_angle(Eigen::Vector3d(1, 2, 2), M_PI);
  const Q back = kernel::from_rotation_matrix(Eigen::Matrix3d(kernel::rotation_matrix(half)));
  EXPECT_NEAR(std::abs(back.dot(half)), 1.0, 1e-15);
}

TEST(QuaternionDouble, LogExpPowSlerp) {
  using Q = Quaternion<double>;
  std::mt19937 g(5);
  for (int k = 0; k < 100; ++k) {
    const Q a = kernel::normalized(rand_coef<Q>(g)), b = kernel::normalized(rand_coef<Q>(g));
    EXPECT_TRUE(coef_near(kernel::exp_pure(kernel::log_unit(a)), a, 1e-14));
    EXPECT_TRUE(coef_near(kernel::pow_unit(a, 2.0), Q(a * a), 1e-13));
    EXPECT_TRUE(coef_near(kernel::pow_unit(a, 0.5) * kernel::pow_unit(a, 0.5), a, 1e-13));
    const Q s0 = kernel::slerp(a, b, 0.0), s1 = kernel::slerp(a, b, 1.0);
    EXPECT_TRUE(coef_near(s0, a, 1e-14));
    EXPECT_NEAR(std::abs(s1.dot(b)), 1.0, 1e-13);
    // Constant angular speed: the angle to a grows linearly in s.
    const double full = std::acos(std::min(1.0, std::abs(a.dot(b))));
    const Q sm = kernel::slerp(a, b, 0.3);
    EXPECT_NEAR(std::acos(std::min(1.0, std::abs(a.dot(sm)))), 0.3 * full, 1e-9);
    EXPECT_NEAR(sm.norm2(), 1.0, 1e-14);
  }
  EXPECT_TRUE(coef_near(kernel::log_unit(Q::real(1.0)), Q(), 0.0));
}

TEST(QuaternionDouble, ZeroQuaternionIsRefused) {
  EXPECT_THROW(kernel::normalized(Quaternion<double>()), Error);
  EXPECT_THROW(kernel::inverse(Quaternion<double>()), Error);
  EXPECT_THROW(kernel::from_axis_angle(Eigen::Vector3d(0, 0, 0), 1.0), Error);
}

}  // namespace
}  // namespace qmotion::test
