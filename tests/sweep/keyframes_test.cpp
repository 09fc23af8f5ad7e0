// Tests of <qmotion/sweep/keyframes.hpp>: keyframes that players blend between stay within
// the tolerance of the exact motion, for both kinds of motion and both blends, by dense
// sampling against the certified bound; the blend bound against its closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <qmotion/qmotion.hpp>
#include <qmotion/sweep/keyframes.hpp>
#include <random>

#include "io_test_util.hpp"

namespace qmotion {
namespace {

using test::test_data;
using V3 = Eigen::Vector3d;

Motion helix(bool rational) {
  const auto poses = io::read_poses(test_data("helix_10.json"));
  if (rational) return interpolate(poses, {}).motion;
  QSplineOptions o;
  o.scheme = "kks";
  return qspline(poses, o).motion;
}

/// Points at distance rho from the origin in 26 directions, and the origin.
std::vector<V3> lever_points(double rho) {
  std::vector<V3> p{V3::Zero()};
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) p.push_back(rho * V3(x, y, z).normalized());
  return p;
}

/// The largest distance between the exact images of the points and what plays, sampled at
/// 64 times inside every interval; the largest per interval over its certified bound.
struct Sampled {
  double worst = 0, worst_ratio = 0;
};
Sampled sample(const Motion& m, const sweep::Keyframes& k, const std::vector<V3>& pts,
               double radius, bool spherical) {
  const sweep::KeyframeBound bound(m, radius, 4);
  Sampled s;
  for (std::size_t i = 0; i + 1 < k.keys.size(); ++i) {
    double here = 0;
    for (int j = 0; j <= 64; ++j) {
      const double t = k.keys[i].t + (k.keys[i + 1].t - k.keys[i].t) * j / 64;
      const Eigen::Matrix4d f = m.frame(t);
      const sweep::Keyframe p = sweep::play(k.keys[i], k.keys[i + 1], t, spherical);
      const Eigen::Matrix3d R = p.rotation.normalized().toRotationMatrix();
      for (const V3& x : pts)
        here = std::max(
            here, (f.block<3, 1>(1, 0) + f.block<3, 3>(1, 1) * x - (p.translation + R * x)).norm());
    }
    s.worst = std::max(s.worst, here);
    s.worst_ratio = std::max(s.worst_ratio, here / bound(k.keys[i], k.keys[i + 1]));
  }
  return s;
}

class Keyframes : public ::testing::TestWithParam<bool> {};

TEST_P(Keyframes, EveryPointStaysWithinTheToleranceUnderBothBlends) {
  const Motion m = helix(GetParam());
  for (double rho : {0.0, 5.0, 40.0})
    for (double tol : {0.1, 1e-3}) {
      sweep::KeyframeOptions o;
      o.tol = tol;
      o.radius = rho;
      const auto k = sweep::place_keyframes(m, o);
      SCOPED_TRACE(testing::Message()
                   << "rho " << rho << " tol " << tol << ", " << k.keys.size() << " keys");
      ASSERT_GE(k.keys.size(), 2u);
      EXPECT_EQ(k.keys.front().t, m.a());
      EXPECT_EQ(k.keys.back().t, m.b());
      EXPECT_LE(k.max_bound, tol);
      for (bool spherical : {true, false}) {
        const Sampled s = sample(m, k, lever_points(rho), rho, spherical);
        EXPECT_LE(s.worst, tol);
        EXPECT_LE(s.worst_ratio, 1.0);  // no interval exceeds its own certificate
      }
      // Every key is the exact pose at its parameter.
      for (const auto& key : k.keys) {
        const Eigen::Matrix4d f = m.frame(key.t);
        EXPECT_LT((key.translation - f.block<3, 1>(1, 0)).norm(), 1e-9);
        EXPECT_LT((key.rotation.toRotationMatrix() - f.block<3, 3>(1, 1)).norm(), 1e-12);
      }
    }
}

TEST_P(Keyframes, TheBoundIsTightAndFallsAsTheStepSquared) {
  const Motion m = helix(GetParam());
  sweep::KeyframeOptions o;
  o.radius = 10;
  o.tol = 1e-2;
  const auto coarse = sweep::place_keyframes(m, o);
  o.tol = 1e-4;
  const auto fine = sweep::place_keyframes(m, o);
  // Second order: 100 times tighter takes about 10 times the keys, not 100.
  const double growth = static_cast<double>(fine.keys.size()) / coarse.keys.size();
  EXPECT_GT(growth, 5.0);
  EXPECT_LT(growth, 20.0);
  // The certificate is within a factor 2 of what is sampled (rational: convex hulls of
  // four parts; spline: the Peano bound with a proven second derivative).
  const Sampled s = sample(m, fine, lever_points(10), 10, true);
  EXPECT_GT(s.worst, 0.5 * fine.max_bound * (GetParam() ? 1.0 : 0.25));
}

TEST_P(Keyframes, RoundedKeysAreCertifiedAsWritten) {
  const Motion m = helix(GetParam());
  sweep::KeyframeOptions o;
  o.tol = 0.01;
  o.radius = 20;
  // Keys written to 2 decimals in position and 3 in the quaternion: the bound covers it.
  o.write = [](const sweep::Keyframe& e) {
    sweep::Keyframe w = e;
    for (int i = 0; i < 3; ++i) w.translation(i) = std::round(e.translation(i) * 1e3) / 1e3;
    for (int i = 0; i < 4; ++i)
      w.rotation.coeffs()(i) = std::round(e.rotation.coeffs()(i) * 1e5) / 1e5;
    return w;
  };
  o.time = [](double t) { return std::round(t * 1e6) / 1e6; };
  const auto k = sweep::place_keyframes(m, o);
  for (const auto& key : k.keys) EXPECT_EQ(key.t, std::round(key.t * 1e6) / 1e6);
  for (bool spherical : {true, false}) {
    const Sampled s = sample(m, k, lever_points(20), 20, spherical);
    EXPECT_LE(s.worst, o.tol);
    EXPECT_LE(s.worst_ratio, 1.0);
  }
  // Coarser rounding than the tolerance allows: refused, naming the motion.
  o.write = [](const sweep::Keyframe& e) {
    sweep::Keyframe w = e;
    w.translation = e.translation.array().round();
    return w;
  };
  EXPECT_THROW(sweep::place_keyframes(m, o), Error);
}

INSTANTIATE_TEST_SUITE_P(BothKinds, Keyframes, ::testing::Values(true, false),
                         [](const auto& info) { return info.param ? "rational" : "kks"; });

TEST(KeyframeBlend, TheBlendBoundHoldsForSlerpAndComponentWiseBlending) {
  std::mt19937 g(7);
  std::normal_distribution<double> n;
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Quaterniond q0(n(g), n(g), n(g), n(g));
    q0.normalize();
    const double angle = 1.5 * std::pow(10.0, -3.0 * trial / 200);  // 1.5 rad to 1.5e-3
    const Eigen::Quaterniond q1 =
        q0 * Eigen::Quaterniond(Eigen::AngleAxisd(angle, V3(n(g), n(g), n(g)).normalized()));
    const double bound = sweep::detail::blend_bound(q0, q1);
    const Eigen::Matrix3d R0 = q0.toRotationMatrix(), R1 = q1.toRotationMatrix();
    double worst = 0;
    for (int j = 0; j <= 200; ++j) {
      const double s = j / 200.0;
      const Eigen::Matrix3d blend = (1 - s) * R0 + s * R1;
      const Eigen::Matrix3d slerp = q0.slerp(s, q1).toRotationMatrix();
      Eigen::Quaterniond nl;
      nl.coeffs() = ((1 - s) * q0.coeffs() + s * q1.coeffs()).normalized();
      for (const Eigen::Matrix3d& R : {slerp, Eigen::Matrix3d(nl.toRotationMatrix())}) {
        Eigen::JacobiSVD<Eigen::Matrix3d> svd(blend - R);
        worst = std::max(worst, svd.singularValues()(0));  // operator norm
      }
    }
    EXPECT_LE(worst, bound) << "angle " << angle;
    EXPECT_GE(worst, 0.5 * angle * angle / 8) << "angle " << angle;  // and close to it
  }
  // From a quarter turn between keys, no bound.
  EXPECT_TRUE(std::isinf(sweep::detail::blend_bound(
      Eigen::Quaterniond::Identity(), Eigen::Quaterniond(Eigen::AngleAxisd(1.6, V3::UnitZ())))));
}

TEST(KeyframeRefusals, PolesTolerancesAndRadii) {
  const Motion m = helix(true);
  sweep::KeyframeOptions o;
  o.radius = 1;
  for (double tol : {0.0, -1.0, std::nan("")}) {
    o.tol = tol;
    EXPECT_TRUE(test::throws_error([&] { sweep::place_keyframes(m, o); }, Errc::invalid_input,
                                   {"tolerance"}))
        << tol;
  }
  o.tol = 1;
  o.radius = -1;
  EXPECT_THROW(sweep::place_keyframes(m, o), Error);
  // A motion whose rotational part vanishes at t = 1/2: Q(t) = (1 - 2t) + eps ...
  using DQ = kernel::DualQuaternion<double>;
  using Q = kernel::Quaternion<double>;
  std::vector<DQ> c{DQ(Q(1, 0, 0, 0), Q(0, 1, 0, 0)), DQ(Q(-1, 0, 0, 0), Q(0, 0, 1, 0))};
  kernel::QMotion<double> q{kernel::Basis::bezier,
                            kernel::BSpline<DQ>::make(1, {0.0, 0.0, 1.0, 1.0}, c)};
  const Motion pole = kernel::Motion<double>(q);
  o.radius = 1;
  EXPECT_TRUE(test::throws_error([&] { sweep::place_keyframes(pole, o); }, Errc::numerical_failure,
                                 {"pole"}));
}

}  // namespace
}  // namespace qmotion
