// tests/api/exact_check_test.cpp: check --exact as a library call (io/exact_check.hpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <qmotion/api/exact_check.hpp>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/order.hpp>

#include "io_test_util.hpp"

namespace qmotion::test {
namespace {
namespace fs = std::filesystem;

struct Case {
  std::string poses;
  qmotion::InterpolateOptions options;
};

std::vector<Case> cases() {
  qmotion::InterpolateOptions affine, projective_minimal, trt, spline;
  affine.rotation = "affine";
  projective_minimal.rotation = "projective";
  projective_minimal.translation = "minimal";
  trt.translation = "trt";
  trt.trt_degrees = "2,1";
  spline.form = "bspline";
  return {{"poses/five_positions.json", {}},
          {"poses/five_positions.json", affine},
          {"poses/five_positions.json", projective_minimal},
          {"poses/five_positions.json", trt},
          {"poses/rational_exact.json", {}},
          {"helix_10.json", spline}};
}

// Two exact algorithms on the same exact motion: the gcd of the trajectory's coordinates
// (CGAL's Polynomial package, in check_exact) and the rank of the Bernstein Sylvester
// matrix (kernel::motion_order) give the same order, and it is what trajectory writes.
TEST(ExactCheck, GcdOrderEqualsTheSylvesterRankAndTheWrittenDegree) {
  int k = 0;
  for (const auto& c : cases()) {
    SCOPED_TRACE(c.poses + " " + c.options.rotation + " " + c.options.translation);
    const io::PoseSet set = io::read_poses(test_data(c.poses));
    const std::string path = scratch_path("api", "m" + std::to_string(k++) + ".json").string();
    io::save_motion(qmotion::interpolate(set, c.options).motion.rational(), path);
    const auto report = qmotion::check_exact(path);
    EXPECT_TRUE(report["verified"].get<bool>()) << report.dump(1);
    const auto exact = qmotion::interpolate_exact(io::with_quaternion_rotations(set), c.options);
    EXPECT_EQ(report["order"]["gcd"].get<int>(), kernel::motion_order(exact.curve));
    EXPECT_EQ(report["order"]["gcd"], report["order"]["trajectory_degree"]);
  }
}

// Proposition 4: under TR the moving origin's trajectory has degree m (the translation's),
// below a general point's 2k + m; the exact gcd finds the drop for that point.
TEST(ExactCheck, TheOriginsTrajectoryUnderTrHasDegreeM) {
  const io::PoseSet set = io::read_poses(test_data("poses/five_positions.json"));  // m = 4
  const std::string path = scratch_path("api", "origin.json").string();
  io::save_motion(qmotion::interpolate(set, {}).motion.rational(), path);
  const auto origin = qmotion::check_exact(path, Eigen::Vector3d::Zero());
  EXPECT_EQ(origin["order"]["gcd"], 4);
  EXPECT_EQ(origin["order"]["trajectory_degree"], 4);
  EXPECT_EQ(qmotion::check_exact(path)["order"]["gcd"], 12);  // 2k + m, k = m = 4
}

// Matrix and axis-angle rotations enter as the double pipeline's unit quaternions, exactly.
TEST(ExactCheck, InexactRotationsEnterAsTheDoubleQuaternionsExactly) {
  const io::PoseSet set = io::read_poses(test_data("poses/five_positions.json"));
  EXPECT_THROW((void)io::to_poses_exact(set), Error);
  std::vector<std::size_t> replaced;
  const io::PoseSet q = io::with_quaternion_rotations(set, &replaced);
  EXPECT_EQ(replaced, (std::vector<std::size_t>{1, 2, 4}));
  const auto exact = io::to_poses_exact(q);
  const auto dbl = io::to_poses_double(set);
  for (std::size_t i = 0; i < set.poses.size(); ++i) {
    const bool was_replaced = std::find(replaced.begin(), replaced.end(), i) != replaced.end();
    if (!was_replaced) continue;
    EXPECT_EQ(CGAL::to_double(exact[i].rotation.w()), dbl[i].rotation.w());
    EXPECT_EQ(exact[i].rotation.w(), kernel::Rational(dbl[i].rotation.w()));
    EXPECT_EQ(exact[i].rotation.z(), kernel::Rational(dbl[i].rotation.z()));
  }
}

}  // namespace
}  // namespace qmotion::test
