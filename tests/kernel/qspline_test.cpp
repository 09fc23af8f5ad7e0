// tests/kernel/qspline_test.cpp: the non-rational unit-quaternion splines (kernel/qspline.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <qmotion/kernel/qspline.hpp>
#include <random>

namespace qmotion::test {
namespace {
using kernel::Quaternion;
using kernel::QuaternionSpline;
using V3 = Eigen::Vector3d;
using V4 = Eigen::Vector4d;

struct Keys {
  std::vector<Quaternion<double>> q;
  std::vector<V3> p;
};

/// n keys turning by up to about 90 degrees between neighbours, about random axes.
Keys random_keys(unsigned seed, int n) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-1, 1);
  Keys k;
  Quaternion<double> q(1, 0, 0, 0);
  for (int i = 0; i < n; ++i) {
    const V3 axis = V3(d(rng), d(rng), d(rng)).normalized();
    q = q * kernel::from_axis_angle(axis, 1.5 * (0.3 + 0.7 * std::abs(d(rng))));
    k.q.push_back(i % 2 ? -q : q);  // signs as a user might give them
    k.p.push_back(V3(10 * i, 5 * d(rng), 3 * d(rng)));
  }
  return k;
}

V4 vec(const Quaternion<double>& q) { return V4(q.w(), q.x(), q.y(), q.z()); }

/// First and second derivative of f at x from one side (dir -1: left, +1: right), by
/// one-sided differences of second order (steps h stay inside one segment).
template <typename F>
std::pair<V4, V4> one_sided(F f, double x, double dir, double h) {
  const V4 f0 = f(x), f1 = f(x + dir * h), f2 = f(x + 2 * dir * h), f3 = f(x + 3 * dir * h);
  const V4 d1 = dir * (-3 * f0 + 4 * f1 - f2) / (2 * h);
  const V4 d2 = (2 * f0 - 5 * f1 + 4 * f2 - f3) / (h * h);
  return {d1, d2};
}

QuaternionSpline quintic(const Keys& k, std::vector<double> u, double alpha = 0.5) {
  return kernel::quintic_spline(k.q, k.p, std::move(u), std::vector<double>(k.q.size(), alpha));
}

std::vector<double> uniform(int n) {
  std::vector<double> u;
  for (int i = 0; i < n; ++i) u.push_back(i);
  return u;
}

TEST(QSpline, EverySchemePassesThroughItsKeysOnTheUnitSphere) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Keys k = random_keys(seed, 7);
    const std::vector<double> knots = {0, 0.5, 2, 2.2, 3, 4.5, 5};
    for (const QuaternionSpline& s :
         {kernel::quartic_spline(k.q, k.p, 0, 5), quintic(k, knots), quintic(k, uniform(7), 1.3),
          kernel::kks_spline(k.q, k.p, 0, 5)}) {
      SCOPED_TRACE(std::string(kernel::to_string(s.scheme)) + " seed " + std::to_string(seed));
      for (std::size_t i = 0; i < k.q.size(); ++i) {
        const Quaternion<double> q = s.rotation(s.knots[i]);
        EXPECT_LE(std::min((vec(q) - vec(k.q[i])).norm(), (vec(q) + vec(k.q[i])).norm()), 1e-12)
            << "key " << i;
        EXPECT_LE((s.position(s.knots[i]) - k.p[i]).norm(), 1e-12 * 50) << "key " << i;
      }
      for (int j = 0; j <= 1000; ++j) {
        const double u = s.a() + (s.b() - s.a()) * j / 1000.0;
        EXPECT_NEAR(vec(s.rotation(u)).norm(), 1.0, 1e-14);
      }
    }
  }
}

// C² at the interior keys for uniform knots, measured from both sides (Theorem 1 of seed
// 003; section 3.2 of seed 002), for rotations and positions alike.
TEST(QSpline, UniformKnotsGiveC2AtEveryInteriorKey) {
  const Keys k = random_keys(7, 6);
  for (const QuaternionSpline& s : {kernel::quartic_spline(k.q, k.p, 0, 5), quintic(k, uniform(6)),
                                    kernel::kks_spline(k.q, k.p, 0, 5)}) {
    SCOPED_TRACE(kernel::to_string(s.scheme));
    const auto rot = [&](double u) { return vec(s.rotation(u)); };
    const auto pos = [&](double u) {
      const V3 p = s.position(u);
      return V4(0, p(0), p(1), p(2));
    };
    for (std::size_t i = 1; i + 1 < k.q.size(); ++i) {
      for (const auto& f : {std::function<V4(double)>(rot), std::function<V4(double)>(pos)}) {
        const auto [l1, l2] = one_sided(f, s.knots[i], -1, 1e-4);
        const auto [r1, r2] = one_sided(f, s.knots[i], +1, 1e-4);
        EXPECT_LE((l1 - r1).norm(), 1e-6 * (1 + l1.norm())) << "key " << i;
        EXPECT_LE((l2 - r2).norm(), 1e-3 * (1 + l2.norm())) << "key " << i;
      }
    }
  }
}

// Non-uniform knots: the quintic is G², with q'_- = (Δ_{i}/Δ_{i-1}) q'_+ and
// q''_- = (Δ_{i}/Δ_{i-1})² q''_+ at key i ((3.14) of seed 002): not C², so the test above
// would fail on these knots.
TEST(QSpline, QuinticWithNonUniformKnotsIsG2InTheRatioOfTheSpans) {
  const Keys k = random_keys(3, 5);
  const std::vector<double> u = {0, 1, 3, 3.5, 5};
  const QuaternionSpline s = quintic(k, u, 0.8);
  const auto rot = [&](double x) { return vec(s.rotation(x)); };
  for (std::size_t i = 1; i + 1 < u.size(); ++i) {
    const double ratio = (u[i + 1] - u[i]) / (u[i] - u[i - 1]);
    const auto [l1, l2] = one_sided(rot, u[i], -1, 1e-4);
    const auto [r1, r2] = one_sided(rot, u[i], +1, 1e-4);
    EXPECT_LE((l1 - ratio * r1).norm(), 1e-5 * (1 + l1.norm())) << "key " << i;
    EXPECT_LE((l2 - ratio * ratio * r2).norm(), 1e-3 * (1 + l2.norm())) << "key " << i;
    EXPECT_GT((l1 - r1).norm(), 1e-2 * l1.norm()) << "key " << i << " is C1, not only G1";
  }
}

// One tension changes only the two segments beside its key.
TEST(QSpline, QuinticTensionIsLocal) {
  const Keys k = random_keys(11, 7);
  const std::vector<double> u = uniform(7);
  std::vector<double> alpha(7, 0.5);
  const QuaternionSpline before = kernel::quintic_spline(k.q, k.p, u, alpha);
  alpha[3] = 1.7;
  const QuaternionSpline after = kernel::quintic_spline(k.q, k.p, u, alpha);
  for (int j = 0; j < 600; ++j) {
    const double x = 6.0 * (j + 0.5) / 600;
    const bool near = x > 2 && x < 4;  // segments 2 and 3, beside key 3
    const double d = (vec(before.rotation(x)) - vec(after.rotation(x))).norm() +
                     (before.position(x) - after.position(x)).norm();
    if (near) {
      EXPECT_GT(d, 1e-6) << "u = " << x;
    } else {
      EXPECT_EQ(d, 0.0) << "u = " << x;
    }
  }
}

// Kim-Kim-Shin: the fixed-point iteration (13) reaches the paper's 1e-4, Gauss-Newton then
// solves (11) to rounding; the natural ends make the curve's second derivative vanish there.
TEST(QSpline, KksIteratesThenRefinesToRounding) {
  const Keys k = random_keys(5, 10);
  kernel::KksOptions plain;
  plain.refine = false;
  const QuaternionSpline fp = kernel::kks_spline(k.q, k.p, 0, 9, plain);
  const QuaternionSpline gn = kernel::kks_spline(k.q, k.p, 0, 9);
  EXPECT_GT(fp.iterations, 2);
  EXPECT_LT(fp.contraction, 1.0);
  EXPECT_GT(fp.residual, 1e-9);  // the fixed point alone stops near its 1e-4 step
  EXPECT_LE(fp.residual, 1e-3);
  EXPECT_EQ(gn.iterations, fp.iterations);
  EXPECT_GE(gn.newton_steps, 1);
  EXPECT_LE(gn.residual, 1e-12);
  for (int i = 0; i < 10; ++i) {
    const auto q = gn.rotation(i);
    EXPECT_LE(std::min((vec(q) - vec(k.q[i])).norm(), (vec(q) + vec(k.q[i])).norm()), 1e-12);
  }
  // Natural ends: the angular acceleration vanishes at both ends (the body angular velocity
  // 2 log(q(u)^-1 q(u + e)) / e has zero derivative there); the quartic, whose ends repeat
  // the keys instead, has none of that.
  const auto omega = [](const QuaternionSpline& s, double dir) {
    return [&s, dir](double x) {
      const double e = 1e-7;
      const V3 w = 2 * kernel::log_unit(s.rotation(x).conj() * s.rotation(x + dir * e)).vec() / e;
      return V4(0, w(0), w(1), w(2));
    };
  };
  const QuaternionSpline quartic = kernel::quartic_spline(k.q, k.p, 0, 9);
  for (const double end : {0.0, 9.0}) {
    const double dir = end == 0 ? 1 : -1;
    const V4 acc = one_sided(omega(gn, dir), end, dir, 1e-3).first;
    const V4 quartic_acc = one_sided(omega(quartic, dir), end, dir, 1e-3).first;
    EXPECT_LE(acc.norm(), 1e-4 * (1 + omega(gn, dir)(end).norm())) << "u = " << end;
    EXPECT_GT(quartic_acc.norm(), 1e-2) << "u = " << end;
  }
}

// Beyond the paper's bound the iteration fails and says why (exit 3 in the CLI).
TEST(QSpline, KksRefusesKeysTooFarApart) {
  // Key distance 1.5 rad (half-angle; a 172 degree turn) with the axis turning by pi/2.
  std::vector<Quaternion<double>> q{Quaternion<double>(1, 0, 0, 0)};
  const V3 axes[] = {V3(1, 0, 0), V3(0, 1, 0), V3(0, 0, 1)};
  for (int i = 1; i < 10; ++i) q.push_back(q.back() * kernel::from_axis_angle(axes[i % 3], 3.0));
  std::vector<V3> p(10, V3::Zero());
  try {
    (void)kernel::kks_spline(q, p, 0, 1);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), Errc::numerical_failure);
    EXPECT_NE(std::string(e.what()).find("largest key distance"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1.5"), std::string::npos) << e.what();
  }
  // Key distance 1 rad with the axis nearly reversing at every key (3 rad between axes):
  // the map cycles instead of contracting, and is stopped after 100 steps without progress.
  std::vector<Quaternion<double>> r{Quaternion<double>(1, 0, 0, 0)};
  V3 axis(1, 0, 0);
  for (int i = 1; i < 10; ++i) {
    r.push_back(r.back() * kernel::from_axis_angle(axis, 2.0));
    axis = V3(std::cos(3.0 * i), std::sin(3.0 * i), 0);
  }
  try {
    (void)kernel::kks_spline(r, p, 0, 1);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), Errc::numerical_failure);
    EXPECT_NE(std::string(e.what()).find("did not converge"), std::string::npos) << e.what();
  }
}

// The analytic angular velocity 2 q' q^-1 agrees with a central difference of the rotation.
TEST(QSpline, AngularVelocityIsTheDerivativeOfTheRotation) {
  const Keys k = random_keys(9, 6);
  const std::vector<double> u = {0, 0.7, 2, 2.5, 4, 5};
  for (const QuaternionSpline& s : {kernel::quartic_spline(k.q, k.p, 0, 5), quintic(k, u, 0.9),
                                    kernel::kks_spline(k.q, k.p, 0, 5)}) {
    SCOPED_TRACE(kernel::to_string(s.scheme));
    for (int j = 1; j < 50; ++j) {
      const double x = 5.0 * j / 50 + 0.013;
      const double h = 1e-6;
      const Quaternion<double> dq = (s.rotation(x + h) - s.rotation(x - h)) * (1 / (2 * h));
      const V3 fd = 2 * (dq * s.rotation(x).conj()).vec();
      EXPECT_LE((s.angular_velocity(x) - fd).norm(), 1e-7 * (1 + fd.norm())) << "u = " << x;
    }
  }
}

TEST(QSpline, VelocityIsTheDerivativeOfThePositionAndFrameIsTheRigidMap) {
  const Keys k = random_keys(4, 6);
  const std::vector<double> u = {0, 0.7, 2, 2.5, 4, 5};
  for (const QuaternionSpline& s : {kernel::quartic_spline(k.q, k.p, 0, 5), quintic(k, u, 0.9),
                                    kernel::kks_spline(k.q, k.p, 0, 5)}) {
    SCOPED_TRACE(kernel::to_string(s.scheme));
    for (int j = 1; j < 50; ++j) {
      const double x = 5.0 * j / 50 + 0.013;
      const double h = 1e-6;
      const V3 fd = (s.position(x + h) - s.position(x - h)) / (2 * h);
      EXPECT_LE((s.velocity(x) - fd).norm(), 1e-6 * (1 + fd.norm())) << "u = " << x;
      const V3 y(0.3, -2, 1.5);
      const Eigen::Vector4d img = s.frame(x) * Eigen::Vector4d(1, y(0), y(1), y(2));
      EXPECT_EQ(img(0), 1.0);
      EXPECT_LE((img.tail<3>() - (kernel::rotate(s.rotation(x), y) + s.position(x))).norm(), 1e-12);
      EXPECT_LE((s.place(x, y) - img.tail<3>()).norm(), 1e-12);
      const V3 fdy = (s.place(x + h, y) - s.place(x - h, y)) / (2 * h);
      EXPECT_LE((s.point_velocity(x, y) - fdy).norm(), 1e-6 * (1 + fdy.norm())) << "u = " << x;
    }
  }
  // Continuity in u: 2 for uniform knots; the quintic's unequal spans are C0 in u.
  EXPECT_EQ(kernel::kks_spline(k.q, k.p, 0, 5).continuity(2), 2);
  const QuaternionSpline q = quintic(k, u, 0.9);
  EXPECT_EQ(q.continuity(1), 0);  // spans 0.7 and 1.3
  EXPECT_EQ(quintic(k, uniform(6)).continuity(3), 2);
}

TEST(QSpline, BadKeysAreRefused) {
  Keys k = random_keys(2, 4);
  // Keys a half-turn apart: q and a quaternion orthogonal to it.
  k.q[2] = k.q[1] * Quaternion<double>(0, 1, 0, 0);
  try {
    (void)kernel::quartic_spline(k.q, k.p, 0, 1);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), Errc::invalid_input);
    EXPECT_NE(std::string(e.what()).find("keys 1 and 2 are a half-turn apart"), std::string::npos)
        << e.what();
  }
  const Keys g = random_keys(2, 4);
  EXPECT_THROW((void)kernel::quintic_spline(g.q, g.p, uniform(4), {0.5, 0.5}), Error);
  EXPECT_THROW((void)kernel::quintic_spline(g.q, g.p, {0, 1, 1, 2}, {0.5, 0.5, 0.5, 0.5}), Error);
  EXPECT_THROW((void)kernel::quintic_spline(g.q, g.p, uniform(4), {0.5, NAN, 0.5, 0.5}), Error);
}

}  // namespace
}  // namespace qmotion::test
