// tests/kernel/parametrization_test.cpp mirrors kernel/parametrization.hpp
#include <cmath>
#include <qmotion/kernel/parametrization.hpp>

#include "io_test_util.hpp"
#include "test_util.hpp"

namespace qmotion::test {
namespace {
using kernel::ParamRule;
using kernel::Pose;

Pose<double> pose(Eigen::Vector3d s, double angle, Eigen::Vector3d axis) {
  Pose<double> p;
  p.position = s;
  p.rotation = kernel::from_axis_angle(axis, angle);
  return p;
}

TEST(Parametrization, StepsFollowEachRule) {
  const std::vector<Pose<double>> P = {pose({0, 0, 0}, 0.0, {0, 0, 1}),
                                       pose({3, 4, 0}, 0.5, {0, 0, 1}),
                                       pose({3, 4, 9}, 1.5, {0, 0, 1})};
  auto check = [&](ParamRule r, double s0, double s1) {
    const auto t = kernel::parametrize(P, r);
    EXPECT_EQ(t.front(), 0.0);
    EXPECT_EQ(t.back(), 1.0);
    EXPECT_NEAR(t[1], s0 / (s0 + s1), 1e-15) << kernel::to_string(r);
  };
  check(ParamRule::uniform, 1, 1);
  check(ParamRule::chordal, 5, 9);
  check(ParamRule::centripetal, std::sqrt(5.0), 3);
  check(ParamRule::angular, 0.5, 1.0);
  check(ParamRule::angular_chordal, 5.5, 10.0);
  // Screw about z: dist* is the z part of the displacement (0, then 9).
  EXPECT_THROW(kernel::parametrize(P, ParamRule::star_chordal), Error);  // first step is 0
}

TEST(Parametrization, StarChordalIsIndependentOfTheMovingOrigin) {
  std::mt19937 g(4);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 50; ++k) {
    const Pose<double> a = pose({u(g), u(g), u(g)}, 2 * u(g), {u(g), u(g), u(g)});
    const Pose<double> b = pose({u(g), u(g), u(g)}, 2 * u(g), {u(g), u(g), u(g)});
    const Eigen::Vector3d c(u(g) * 10, u(g) * 10, u(g) * 10);
    Pose<double> a2 = a, b2 = b;
    a2.position += kernel::rotate(a.rotation, c);
    b2.position += kernel::rotate(b.rotation, c);
    EXPECT_NEAR(kernel::screw_distance(a, b), kernel::screw_distance(a2, b2), 1e-12);
    // The plain chord does depend on it.
    if (k == 0) {
      EXPECT_GT(std::abs((b.position - a.position).norm() - (b2.position - a2.position).norm()),
                1e-6);
    }
  }
  // Pure translation: dist* is the distance.
  EXPECT_NEAR(
      kernel::screw_distance(pose({0, 0, 0}, 0.3, {1, 0, 0}), pose({1, 2, 2}, 0.3, {1, 0, 0})), 3.0,
      1e-12);
}

TEST(Parametrization, GivenAndErrors) {
  std::vector<Pose<double>> P = {pose({0, 0, 0}, 0, {0, 0, 1}), pose({0, 0, 0}, 0.4, {0, 0, 1})};
  P[0].t = -2.0;
  P[1].t = 5.0;
  EXPECT_EQ(kernel::parametrize(P, ParamRule::given), (std::vector<double>{-2.0, 5.0}));
  EXPECT_TRUE(throws_error([&] { kernel::parametrize(P, ParamRule::chordal); }, Errc::invalid_input,
                           {"chordal", "poses 0 and 1"}));
  P[1].t.reset();
  EXPECT_TRUE(throws_error([&] { kernel::parametrize(P, ParamRule::given); }, Errc::invalid_input,
                           {"pose 1"}));
  EXPECT_EQ(kernel::param_rule_from_string("*-chordal"), ParamRule::star_chordal);
  EXPECT_EQ(kernel::param_rule_from_string("equidistant"), ParamRule::uniform);
  EXPECT_FALSE(kernel::param_rule_from_string("random").has_value());
}

}  // namespace
}  // namespace qmotion::test
