// tests/kernel/dual_quaternion_test.cpp mirrors kernel/dual_quaternion.hpp
#include <qmotion/kernel/dual_quaternion.hpp>

#include "test_util.hpp"

namespace qmotion::test {
namespace {
using kernel::DualQuaternion;
using kernel::Quaternion;

template <typename S>
class DualQuaternionTest : public ::testing::Test {};
TYPED_TEST_SUITE(DualQuaternionTest, Scalars);

template <typename S>
DualQuaternion<S> rand_pose(std::mt19937& g) {
  Quaternion<S> r;
  do r = rand_coef<Quaternion<S>>(g);
  while (r.norm2() == S(0));
  return DualQuaternion<S>::pose(rand_coef<Eigen::Matrix<S, 3, 1>>(g), r);
}

TYPED_TEST(DualQuaternionTest, ProductIsAssociativeAndConjugationReversesIt) {
  using S = TypeParam;
  using DQ = DualQuaternion<S>;
  std::mt19937 g(1);
  for (int k = 0; k < 50; ++k) {
    const DQ a = rand_coef<DQ>(g), b = rand_coef<DQ>(g), c = rand_coef<DQ>(g);
    EXPECT_TRUE(coef_near(DQ((a * b) * c), DQ(a * (b * c))));
    EXPECT_TRUE(coef_near(DQ((a * b).conj()), DQ(b.conj() * a.conj())));
  }
}

TYPED_TEST(DualQuaternionTest, PosesAndTheirProductsSatisfyPlucker) {
  using S = TypeParam;
  using DQ = DualQuaternion<S>;
  std::mt19937 g(2);
  for (int k = 0; k < 50; ++k) {
    const DQ a = rand_pose<S>(g), b = rand_pose<S>(g);
    EXPECT_TRUE(coef_near(kernel::plucker(a), S(0)));
    EXPECT_TRUE(coef_near(kernel::plucker(DQ(a * b)), S(0)));
    EXPECT_TRUE(coef_near(kernel::plucker(DQ(a * b * a)), S(0)));
    // A scale factor keeps Plucker and the displacement.
    EXPECT_TRUE(coef_near(kernel::plucker(DQ(a * S(5))), S(0)));
  }
  // A random dual quaternion is generally not a displacement: its Plucker form is not zero
  // (equal to the 4-vector dot product of its parts, checked on a hand-made one).
  const DQ r = rand_coef<DQ>(g);
  EXPECT_FALSE(coef_near(kernel::plucker(r), S(0)));
  const DQ h(kernel::Quaternion<S>(S(1), S(2), S(0), S(-1)),
             kernel::Quaternion<S>(S(3), S(0), S(5), S(2)));
  EXPECT_EQ(kernel::plucker(h), S(1));  // 1*3 + 2*0 + 0*5 + (-1)*2
}

TYPED_TEST(DualQuaternionTest, PoseMapsOriginToPositionAndComposes) {
  using S = TypeParam;
  using DQ = DualQuaternion<S>;
  using V3 = Eigen::Matrix<S, 3, 1>;
  using V4 = Eigen::Matrix<S, 4, 1>;
  std::mt19937 g(3);
  for (int k = 0; k < 30; ++k) {
    const V3 s = rand_coef<V3>(g);
    Quaternion<S> r = rand_coef<Quaternion<S>>(g);
    if (r.norm2() == S(0)) continue;
    const DQ p = DQ::pose(s, r);
    EXPECT_TRUE(coef_near(kernel::translation_vector(p), s));
    EXPECT_TRUE(coef_near(kernel::apply_point(p, V3(V3::Zero())), s));
    // (12) and the 4x4 matrix (10) agree; both give R x + s.
    const V3 x = rand_coef<V3>(g);
    const V3 expected = kernel::rotation_matrix(r) * x + s;
    EXPECT_TRUE(coef_near(kernel::apply_point(p, x), expected));
    V4 xh;
    xh << S(1), x;
    const V4 ym = kernel::to_matrix4(p) * xh;
    EXPECT_TRUE(coef_near(V4(ym), kernel::apply(p, xh)));
    // Composition: (P2 * P1) applies P1 first.
    const DQ p2 = rand_pose<S>(g);
    EXPECT_TRUE(coef_near(kernel::apply_point(DQ(p2 * p), x),
                          kernel::apply_point(p2, kernel::apply_point(p, x))));
    // Trans/Rot (9): Q = Trans(Q) * Rot(Q).
    EXPECT_TRUE(coef_near(DQ(kernel::trans_part(p) * kernel::rot_part(p)), p));
    // Points at infinity (directions) are only rotated.
    V4 dir;
    dir << S(0), x;
    const V4 yd = kernel::apply(p, dir);
    EXPECT_TRUE(coef_near(S(yd(0)), S(0)));
    EXPECT_TRUE(coef_near(V3(yd.template tail<3>() / kernel::to_matrix4(p)(0, 0)),
                          V3(kernel::rotation_matrix(r) * x)));
  }
}

TEST(DualQuaternionDouble, ZeroRealPartIsRefused) {
  const DualQuaternion<double> q(Quaternion<double>(), Quaternion<double>(0, 1, 0, 0));
  EXPECT_THROW(kernel::translation_vector(q), Error);
  EXPECT_THROW(kernel::rot_part(q), Error);
}

}  // namespace
}  // namespace qmotion::test
