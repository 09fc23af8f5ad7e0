// Tests of <qmotion/motion.hpp>: one motion value, the same properties for both kinds
// (Bezier, B-spline and C1 Q-motions; kks, quintic and quartic quaternion splines).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <qmotion/qmotion.hpp>
#include <string>

#include "io_test_util.hpp"

namespace qmotion {
namespace {

namespace fs = std::filesystem;
using V3 = Eigen::Vector3d;
using test::test_data;

/// The rotation matrix of a quaternion, written out here (not the kernel's).
Eigen::Matrix3d rotation(const kernel::Quaternion<double>& q) {
  const double n = std::sqrt(q.w() * q.w() + q.x() * q.x() + q.y() * q.y() + q.z() * q.z());
  const double w = q.w() / n, x = q.x() / n, y = q.y() / n, z = q.z() / n;
  Eigen::Matrix3d R;
  R << 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),  //
      2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),   //
      2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y);
  return R;
}

struct Kind {
  std::string name;
  bool rational;
};

void PrintTo(const Kind& k, std::ostream* os) { *os << k.name; }

/// The motion of the kind through five_positions.json (interpolate or qspline, as the CLI).
Motion make(const Kind& k, const io::PoseSet& poses) {
  if (k.rational) {
    InterpolateOptions o;
    o.form = k.name;
    return interpolate(poses, o).motion;
  }
  QSplineOptions o;
  o.scheme = k.name;
  return qspline(poses, o).motion;
}

class EitherKind : public ::testing::TestWithParam<Kind> {
 protected:
  io::PoseSet poses = io::read_poses(test_data("poses/five_positions.json"));
  Motion m = make(GetParam(), poses);
};

TEST_P(EitherKind, InterpolatesEveryPoseThroughFrameAndPlace) {
  EXPECT_EQ(m.is_rational(), GetParam().rational);
  const std::vector<double> keys = m.key_parameters();
  ASSERT_EQ(keys.size(), poses.poses.size());
  EXPECT_EQ(keys.front(), m.a());
  EXPECT_EQ(keys.back(), m.b());
  const V3 x(3, -2, 5);
  const auto input = io::to_poses_double(poses);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const Eigen::Matrix4d F = m.frame(keys[i]);
    EXPECT_EQ(F(0, 0), 1.0);
    EXPECT_EQ((F.block<1, 3>(0, 1).norm()), 0.0);
    const Eigen::Matrix3d R = rotation(input[i].rotation);
    EXPECT_LE((F.block<3, 3>(1, 1) - R).norm(), 1e-9) << i;
    EXPECT_LE((F.block<3, 1>(1, 0) - input[i].position).norm(), 1e-9) << i;
    EXPECT_LE((m.place(keys[i], x) - (R * x + input[i].position)).norm(), 1e-9) << i;
  }
}

TEST_P(EitherKind, VelocitiesAreTheDerivativesOfThePlacement) {
  const V3 x(3, -2, 5);
  const double h = 1e-6 * (m.b() - m.a());
  for (int k = 1; k < 12; ++k) {
    const double t = m.a() + (m.b() - m.a()) * (k + 0.37) / 13;
    const V3 fd = (m.place(t + h, x) - m.place(t - h, x)) / (2 * h);
    EXPECT_LE((m.point_velocity(t, x) - fd).norm(), 1e-6 * std::max(1.0, fd.norm())) << t;
    const Eigen::Matrix3d W = (m.frame(t + h) - m.frame(t - h)).block<3, 3>(1, 1) / (2 * h) *
                              m.frame(t).block<3, 3>(1, 1).transpose();
    const V3 w(W(2, 1), W(0, 2), W(1, 0));
    EXPECT_LE((m.angular_velocity(t) - w).norm(), 1e-6 * std::max(1.0, w.norm())) << t;
  }
}

TEST_P(EitherKind, ContinuityAtBreakpointsHoldsForTheVelocity) {
  const std::vector<double> x = m.breakpoints();
  const std::vector<int> c = m.continuity();
  ASSERT_EQ(c.size() + 2, x.size());
  EXPECT_EQ(x.front(), m.a());
  EXPECT_EQ(x.back(), m.b());
  const V3 p(1, 2, 3);
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double t = x[i + 1], e = 1e-9 * (m.b() - m.a());
    EXPECT_LE((m.place(t - e, p) - m.place(t + e, p)).norm(), 1e-6);  // C0 always
    if (c[i] >= 1) {
      EXPECT_LE((m.point_velocity(t - e, p) - m.point_velocity(t + e, p)).norm(),
                1e-5 * std::max(1.0, m.point_velocity(t, p).norm()))
          << "declared C" << c[i] << " at " << t;
    }
  }
}

TEST_P(EitherKind, TheSameExportAndCheckCallsTakeIt) {
  const fs::path dir = fs::temp_directory_path() / ("qmotion_motion_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  ExportOptions o;
  o.output = (dir / (GetParam().name + ".json")).string();
  o.tol = 1e-6;
  const V3 x(1, 0, 2);
  const ExportResult r = export_geometry(m, Geometry::trajectory(x), o);
  EXPECT_EQ(r.approx_deviation.has_value(), !m.is_rational());
  const auto c = check(o.output, m, Geometry::trajectory(x));
  // Exact for a Q-motion (rounding only); within the fit's tolerance for a spline.
  EXPECT_LE(c["max_deviation"].get<double>(), m.is_rational() ? 1e-10 : 1e-6);
  fs::remove_all(dir);
}

TEST_P(EitherKind, TheToolFollowsThePointAndTheAxisWithinATenthOfTheTolerance) {
  const V3 x(1, 0, 2), axis = V3(0.2, 0.1, 1).normalized();
  const double tol = 1e-3;
  const cam::ToolTrajectories tt = cam::tool_trajectories(m, x, axis, tol);
  EXPECT_EQ(tt.fit_error == 0, m.is_rational());
  EXPECT_LE(tt.fit_error, 0.1 * tol);
  for (int k = 0; k <= 50; ++k) {
    const double t = m.a() + (m.b() - m.a()) * k / 50;
    const Eigen::Vector4d h = kernel::evaluate(tt.h, t), d = kernel::evaluate(tt.d, t);
    const V3 want = m.place(t, x);
    EXPECT_LE((V3(h.tail<3>() / h(0)) - want).norm(), m.is_rational() ? 1e-9 : 0.1 * tol) << t;
    const V3 dir = m.place(t, axis) - m.place(t, V3::Zero());  // R axis
    EXPECT_LE(std::acos(std::min(1.0, V3(d.tail<3>()).normalized().dot(dir))), 2e-3 * tol) << t;
    EXPECT_LE((tt.exact_point(t) - want).norm(), 1e-9) << t;
  }
}

TEST_P(EitherKind, ItsFileReadsBackAsTheSameMotion) {
  const fs::path dir = fs::temp_directory_path() / ("qmotion_mfile_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "m.json").string();
  if (GetParam().rational) {
    InterpolateOptions o;
    o.form = GetParam().name;
    interpolate(poses, o).save(path);
  } else {
    QSplineOptions o;
    o.scheme = GetParam().name;
    qspline(poses, o).save(path);
  }
  const Motion back = io::load_motion(path);
  EXPECT_EQ(back.is_rational(), m.is_rational());
  EXPECT_EQ(back.name(), path);
  EXPECT_EQ(back.units(), m.units());
  EXPECT_EQ(back.breakpoints(), m.breakpoints());
  for (double t : {m.a(), 0.3 * m.a() + 0.7 * m.b(), m.b()})
    EXPECT_LE((back.frame(t) - m.frame(t)).norm(), 1e-12) << t;
  fs::remove_all(dir);
}

TEST_P(EitherKind, IoWritesEitherKindAndReadsItBack) {
  const fs::path dir = fs::temp_directory_path() / ("qmotion_msave_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "saved.json").string();
  io::save_motion(m, path);
  const Motion back = io::load_motion(path);
  EXPECT_EQ(back.is_rational(), m.is_rational());
  EXPECT_EQ(back.units(), m.units());
  EXPECT_EQ(back.key_parameters(), m.key_parameters());
  EXPECT_EQ(back.continuity(), m.continuity());
  for (int k = 0; k <= 20; ++k) {
    const double t = m.a() + (m.b() - m.a()) * k / 20;
    EXPECT_LE((back.frame(t) - m.frame(t)).norm(), 1e-12) << t;
  }
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Motion, EitherKind,
                         ::testing::Values(Kind{"bezier", true}, Kind{"bspline", true},
                                           Kind{"c1", true}, Kind{"kks", false},
                                           Kind{"quintic", false}, Kind{"quartic", false}),
                         [](const auto& info) { return info.param.name; });

TEST(Motion, AskingForTheOtherKindIsRefusedNamingTheMotion) {
  QSplineOptions o;
  o.scheme = "quartic";
  const Motion q = qspline(io::read_poses(test_data("poses/five_positions.json")), o).motion;
  try {
    (void)q.rational();
    ADD_FAILURE() << "a spline gave a rational motion";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), Errc::invalid_input);
    EXPECT_NE(std::string(e.what()).find("not rational"), std::string::npos) << e.what();
  }
  const Motion r = interpolate(io::read_poses(test_data("poses/five_positions.json")), {}).motion;
  EXPECT_THROW((void)r.spline(), Error);
}

TEST(Motion, APoleIsANumericalFailureNamingTheMotion) {
  // Q(t) = (1 - 2t) + 0 eps: its rotational part vanishes at t = 1/2.
  kernel::DualQuaternion<double> a, b;
  a[0] = 1;
  b[0] = -1;
  kernel::Motion<double> pole(
      kernel::QMotion<double>{
          kernel::Basis::bezier,
          kernel::BSpline<kernel::DualQuaternion<double>>::make(1, {0, 0, 1, 1}, {a, b})},
      std::nullopt, std::nullopt, "mm", "pole.json");
  const Motion m(std::move(pole));
  try {
    (void)m.frame(0.5);
    ADD_FAILURE() << "no pole found";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), Errc::numerical_failure);
    EXPECT_NE(std::string(e.what()).find("pole.json"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)m.place(0.5, V3(1, 0, 0)), Error);
}

}  // namespace
}  // namespace qmotion
