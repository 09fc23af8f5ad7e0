// tests/cam/machine_test.cpp: <qmotion/cam/machine.hpp>: kinematics of 5-axis machines and
// the certified bound on their linear interpolation of the axes.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <qmotion/cam/machine.hpp>
#include <random>
#include <vector>

#include "io_test_util.hpp"

namespace qmotion::test {
namespace {

using V3 = Eigen::Vector3d;
using cam::Machine;
using cam::MachineAxes;
using cam::RotaryAxis;
constexpr double kPi = 3.14159265358979323846;

/// Every layout: the two built-in tables, a head-head machine (C about Z carrying A about X,
/// pivot 150 above the tip), a head-table machine (table C, head B at a pivot) and a table
/// with its pivots off the origin and a tilted (45 degree, nutating) B axis.
std::vector<Machine> machines() {
  std::vector<Machine> out{cam::builtin_machine("ac"), cam::builtin_machine("bc")};
  Machine hh;
  hh.name = "head C/A";
  hh.axes = {RotaryAxis{'C', true, V3::UnitZ(), V3(0, 0, 150)},
             RotaryAxis{'A', true, V3::UnitX(), V3(0, 0, 150)}};
  out.push_back(hh);
  Machine ht;
  ht.name = "head B, table C";
  ht.axes = {RotaryAxis{'B', true, V3::UnitY(), V3(0, 0, 120)},
             RotaryAxis{'C', false, V3::UnitZ(), V3(20, -10, 0)}};
  out.push_back(ht);
  Machine tt;
  tt.name = "table B (45 degrees) / C, pivots off the origin";
  tt.axes = {RotaryAxis{'B', false, V3(0, 1, 1).normalized(), V3(0, 0, -80)},
             RotaryAxis{'C', false, V3::UnitZ(), V3(5, 5, 0)}};
  out.push_back(tt);
  return out;
}

TEST(Machine, EveryLayoutIsAcceptedAndBrokenOnesAreNot) {
  for (const auto& m : machines()) EXPECT_EQ(cam::machine_problem(m), "") << m.name;
  Machine m = cam::builtin_machine("ac");
  m.axes[1].direction = V3::UnitX();
  EXPECT_NE(cam::machine_problem(m).find("parallel"), std::string::npos);
  m = cam::builtin_machine("ac");
  m.axes[0].direction = V3::UnitZ();  // the outer table axis along the tool cannot tilt it
  m.axes[1].direction = V3::UnitX();
  EXPECT_NE(cam::machine_problem(m).find("cannot tilt"), std::string::npos);
  m = cam::builtin_machine("bc");
  m.axes[1].name = 'B';
  EXPECT_NE(cam::machine_problem(m).find("two axes"), std::string::npos);
  EXPECT_THROW(cam::builtin_machine("xy"), Error);
}

TEST(Machine, BuiltInTablesAreTheDocumentedRotations) {
  const MachineAxes q{10, 20, 30, 25, -70};
  const auto ac = cam::forward_kinematics(cam::builtin_machine("ac"), q);
  const auto bc = cam::forward_kinematics(cam::builtin_machine("bc"), q);
  const double a = 25 * kPi / 180, c = -70 * kPi / 180;
  const Eigen::Matrix3d tac =
      (Eigen::AngleAxisd(a, V3::UnitX()) * Eigen::AngleAxisd(c, V3::UnitZ())).toRotationMatrix();
  const Eigen::Matrix3d tbc =
      (Eigen::AngleAxisd(a, V3::UnitY()) * Eigen::AngleAxisd(c, V3::UnitZ())).toRotationMatrix();
  // machine XYZ = T p and T k = +Z.
  EXPECT_LE((tac * ac.first - V3(10, 20, 30)).norm(), 1e-12);
  EXPECT_LE((tac * ac.second - V3::UnitZ()).norm(), 1e-15);
  EXPECT_LE((tbc * bc.first - V3(10, 20, 30)).norm(), 1e-12);
  EXPECT_LE((tbc * bc.second - V3::UnitZ()).norm(), 1e-15);
}

TEST(Machine, ForwardAfterInverseIsTheIdentityOnRandomPoses) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const auto& m : machines()) {
    MachineAxes prev{};
    int reached = 0;
    for (int i = 0; i < 2000; ++i) {
      const V3 p(200 * u(rng), 200 * u(rng), 200 * u(rng));
      V3 k(u(rng), u(rng), u(rng));
      if (k.norm() < 0.1) continue;
      k.normalize();
      MachineAxes q;
      try {
        q = cam::inverse_kinematics(m, p, k, prev, false, "test");
      } catch (const Error& e) {  // the nutating table reaches half the sphere
        EXPECT_NE(std::string(e.what()).find("cannot turn"), std::string::npos) << e.what();
        continue;
      }
      ++reached;
      const auto [p2, k2] = cam::forward_kinematics(m, q);
      EXPECT_LE((p2 - p).norm(), 1e-12 * (1 + p.norm())) << m.name;
      EXPECT_LE((k2 - k).norm(), 1e-12) << m.name;
      // Unwrapped: every angle within 180 degrees of the one before.
      EXPECT_LE(std::abs(q[3] - prev[3]), 180 + 1e-9) << m.name;
      EXPECT_LE(std::abs(q[4] - prev[4]), 180 + 1e-9) << m.name;
      prev = q;
    }
    EXPECT_GT(reached, 900) << m.name;
  }
}

TEST(Machine, TheNearerBranchIsKeptAlongASmoothPath) {
  // The axis sweeps a cone about a tilted direction: the angles move in small steps.
  for (const auto& m : machines()) {
    MachineAxes prev{};
    for (int i = 0; i <= 720; ++i) {
      const double s = i * kPi / 180;
      const V3 k = V3(0.5 * std::cos(s), 0.5 * std::sin(s), 0.8).normalized();
      MachineAxes q;
      try {
        q = cam::inverse_kinematics(m, V3(50, 0, 0), k, prev, false, "test");
      } catch (const Error&) {
        break;
      }
      if (i > 0) {
        EXPECT_LT(std::abs(q[3] - prev[3]), 10.0) << m.name << " at " << i;
        EXPECT_LT(std::abs(q[4] - prev[4]), 10.0) << m.name << " at " << i;
      }
      prev = q;
    }
  }
  // Two turns of C are unwrapped, not folded back into (-180, 180].
  const Machine ac = cam::builtin_machine("ac");
  MachineAxes prev{};
  for (int i = 0; i <= 720; ++i) {
    const double s = i * kPi / 180;
    prev = cam::inverse_kinematics(ac, V3(0, 0, 0),
                                   V3(0.5 * std::sin(s), 0.5 * std::cos(s), 0.8).normalized(), prev,
                                   false, "test");
  }
  EXPECT_NEAR(std::abs(prev[4]), 720, 1e-9);
}

TEST(Machine, TheSingularAxisIsRefusedOrHeld) {
  const Machine ac = cam::builtin_machine("ac");
  MachineAxes prev{0, 0, 0, 10, 37};
  try {
    cam::inverse_kinematics(ac, V3(1, 2, 3), V3::UnitZ(), prev, false, "--rotary ac at t = 0.5");
    ADD_FAILURE() << "a vertical axis was accepted";
  } catch (const Error& e) {
    const std::string w = e.what();
    EXPECT_EQ(e.code(), Errc::invalid_input);
    for (const char* s : {"--rotary ac at t = 0.5", "vertical", "C", "--c-hold"})
      EXPECT_NE(w.find(s), std::string::npos) << w;
  }
  const MachineAxes q = cam::inverse_kinematics(ac, V3(1, 2, 3), V3::UnitZ(), prev, true, "");
  EXPECT_EQ(q[4], 37);
  EXPECT_NEAR(q[3], 0, 1e-12);
  EXPECT_LE((cam::forward_kinematics(ac, q).first - V3(1, 2, 3)).norm(), 1e-12);
}

TEST(Machine, TravelKeepsABranchWithinItOrRefusesNamingTheAxis) {
  Machine ac = cam::builtin_machine("ac");
  // The tool tilted 20 degrees about X: the nearer branch has A = -20, C = 0, the other
  // A = 20, C = 180.
  const V3 k = cam::forward_kinematics(ac, {0, 0, 0, -20, 0}).second;
  const MachineAxes zero{};
  EXPECT_NEAR(cam::inverse_kinematics(ac, V3(5, 0, 0), k, zero, false, "", 0)[3], -20, 1e-9);
  ac.travel[3] = {-10, 90};
  MachineAxes q = cam::inverse_kinematics(ac, V3(5, 0, 0), k, zero, false, "", 0);
  EXPECT_NEAR(q[3], 20, 1e-9);
  EXPECT_NEAR(std::abs(q[4]), 180, 1e-9);
  EXPECT_LE((cam::forward_kinematics(ac, q).first - V3(5, 0, 0)).norm(), 1e-12);
  // C limited to [100, 400]: the first block starts at the turn within it, 180.
  ac.travel[4] = {100, 400};
  q = cam::inverse_kinematics(ac, V3(5, 0, 0), k, zero, false, "", 0);
  EXPECT_NEAR(q[4], 180, 1e-9);
  // Only one branch lies within travel: there is no other one to start from.
  EXPECT_TRUE(
      throws_error([&] { cam::inverse_kinematics(ac, V3(5, 0, 0), k, zero, false, "w", 1); },
                   Errc::invalid_input, {"w: ", "other branch", "A = -20", "[-10, 90]"}));
  ac.travel[3] = {-15, 15};
  EXPECT_TRUE(
      throws_error([&] { cam::inverse_kinematics(ac, V3(5, 0, 0), k, zero, false, "w", 0); },
                   Errc::invalid_input, {"neither branch", "A = -20", "A = 20", "[-15, 15]"}));
  // A following block never jumps to the other branch or unwinds: C at 359 turning on to
  // 365 leaves [-360, 360], which the same orientation reaches at 5 after unwinding.
  Machine c = cam::builtin_machine("ac");
  c.travel[4] = {-360, 360};
  const V3 k5 = cam::forward_kinematics(c, {0, 0, 0, -20, 5}).second;
  const MachineAxes prev{0, 0, 0, -20, 359};
  EXPECT_TRUE(throws_error([&] { cam::inverse_kinematics(c, V3(5, 0, 0), k5, prev, false, "t"); },
                           Errc::invalid_input, {"t: C reaches the end of its travel", "unwind"}));
  EXPECT_NO_THROW(cam::inverse_kinematics(c, V3(5, 0, 0), k5, {0, 0, 0, -20, 1}, false, "t"));
  // A linear axis's travel: X within [-1, 1] refuses a tip at x = 5 on both branches.
  Machine x = cam::builtin_machine("ac");
  x.travel[0] = {-1, 1};
  EXPECT_TRUE(throws_error([&] { cam::inverse_kinematics(x, V3(5, 0, 0), k, zero, false, "", 0); },
                           Errc::invalid_input, {"neither branch", "X = 5", "[-1, 1]"}));
}

/// The tip and the axis the machine runs at s in [0, 1] between q0 and q1, and how far
/// they leave the chord and the blend, sampled densely.
std::pair<double, double> sampled_deviation(const Machine& m, const MachineAxes& q0,
                                            const MachineAxes& q1) {
  const auto [p0, k0] = cam::forward_kinematics(m, q0);
  const auto [p1, k1] = cam::forward_kinematics(m, q1);
  double e = 0, a = 0;
  for (int i = 0; i <= 400; ++i) {
    const double s = i / 400.0;
    MachineAxes q;
    for (std::size_t j = 0; j < 5; ++j) q[j] = q0[j] + s * (q1[j] - q0[j]);
    const auto [p, k] = cam::forward_kinematics(m, q);
    e = std::max(e, (p - (p0 + s * (p1 - p0))).norm());
    const V3 blend = (1 - s) * k0 + s * k1;
    a = std::max(a, std::atan2(k.cross(blend).norm(), k.dot(blend)));
  }
  return {e, a};
}

TEST(Machine, TheInterpolationBoundHoldsAndIsTight) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const auto& m : machines()) {
    double worst_ratio = 0;  // sampled / bound: at most 1, and not far below for small steps
    for (int i = 0; i < 300; ++i) {
      const double step = i < 150 ? 2.0 : 20.0;  // degrees per block
      const MachineAxes q0{150 * u(rng), 150 * u(rng), 150 * u(rng), 60 * u(rng), 180 * u(rng)};
      const MachineAxes q1{q0[0] + 5 * u(rng), q0[1] + 5 * u(rng), q0[2] + 5 * u(rng),
                           q0[3] + step * u(rng), q0[4] + step * u(rng)};
      const auto [e, a] = cam::interpolation_bound(m, q0, q1);
      const auto [se, sa] = sampled_deviation(m, q0, q1);
      EXPECT_LE(se, e * (1 + 1e-9) + 1e-12) << m.name << " block " << i;
      EXPECT_LE(sa, a * (1 + 1e-9) + 1e-15) << m.name << " block " << i;
      if (i < 150 && e > 1e-6) worst_ratio = std::max(worst_ratio, se / e);
    }
    EXPECT_GT(worst_ratio, 0.8) << m.name;  // the bound is not loose for small steps
  }
}

}  // namespace
}  // namespace qmotion::test
