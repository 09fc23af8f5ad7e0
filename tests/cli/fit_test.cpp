// tests/cli/fit_test.cpp: `qmotion fit` run as a user runs it, and robot programs as pose
// files: the file it writes is read by every command, and its deviations are measured here
// through the motion the file holds.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/io/qspline_file.hpp>
#include <regex>

#include "cli_util.hpp"

namespace qmotion::test {
namespace {

/// The largest distance of the moving origin from the poses' positions and the largest
/// rotation angle (degrees) from their orientations, measured through Motion::frame.
std::pair<double, double> deviations(const fs::path& motion, const io::PoseSet& set,
                                     const std::vector<double>& t) {
  const Motion m = io::load_motion(motion.string());
  const auto poses = io::to_poses_double(set);
  double pos = 0, ang = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Matrix4d F = m.frame(t[i]);
    pos = std::max(pos, (F.block<3, 1>(1, 0) - poses[i].position).norm());
    const auto& q = poses[i].rotation;
    const Eigen::Matrix3d R =
        Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized().toRotationMatrix();
    ang = std::max(
        ang, Eigen::AngleAxisd(Eigen::Matrix3d(R.transpose() * F.block<3, 3>(1, 1))).angle() * 180 /
                 M_PI);
  }
  return {pos, ang};
}

double figure(const std::string& out, const std::string& label) {
  std::smatch m;
  const std::regex re(label + ": ([0-9.e+-]+)");
  EXPECT_TRUE(std::regex_search(out, m, re)) << label << " in\n" << out;
  return m.empty() ? NAN : std::stod(m[1]);
}

TEST(Cli, FitMeetsItsTolerancesWithATenthOfThePosesAndEveryCommandReadsIt) {
  const std::string poses = test_data("fit/noisy_helix.json");
  const fs::path m = scratch_dir() / "fit_helix.json";
  const Result r = run({"fit", poses, "-o", m.string(), "--tol", "0.01", "--angle-tol", "0.05"});
  ASSERT_EQ(r.status, 0) << r.err;
  const io::PoseSet set = io::read_poses(poses);
  std::vector<double> t;
  for (const auto& p : set.poses) t.push_back(p.t->value);
  const auto [pos, ang] = deviations(m, set, t);
  EXPECT_LE(pos, 0.01);
  EXPECT_LE(ang, 0.05);
  // The report's figures are the ones measured here (printed to 6 digits).
  EXPECT_NEAR(figure(r.out, "worst position deviation"), pos, 1e-5 * pos);
  EXPECT_NEAR(figure(r.out, "worst angle deviation"), ang, 1e-5 * ang);
  const double points = figure(r.out, "control points");
  EXPECT_LE(points * 10, static_cast<double>(set.poses.size()));
  const json info = run_json({"info", m.string()});
  EXPECT_EQ(info["method"]["form"], "fit");
  EXPECT_EQ(json::parse(slurp(m))["control_points"].size(), static_cast<std::size_t>(points));
  EXPECT_NEAR(info["fit"]["worst_position"].get<double>(), pos, 1e-9);
  EXPECT_LE(info["plucker_residual"].get<double>(), 1e-12);
  const fs::path traj = scratch_dir() / "fit_traj.json";
  ASSERT_EQ(run({"trajectory", m.string(), "--point", "5,0,0", "-o", traj.string()}).status, 0);
  const json c = check(traj, m, {"--point", "5,0,0"});
  EXPECT_LE(c["max_deviation"].get<double>(), 1e-9) << c.dump();
}

TEST(Cli, RobotProgramsAreReadWherePosesAreRead) {
  // A KRL program of 80 LIN moves along a smooth path, with its .dat: interpolate, fit and
  // poses read the same poses.
  const fs::path dir = scratch_dir() / "krl";
  fs::create_directories(dir);
  {
    std::ofstream src(dir / "path.src"), dat(dir / "path.dat");
    src << "DEF path( )\r\n;FOLD INI\r\nBAS (#INITMOV,0 )\r\n;ENDFOLD\r\n$VEL.CP = 0.1\r\n";
    dat << "DEFDAT path\r\n";
    for (int i = 0; i < 80; ++i) {
      const double u = i / 79.0;
      dat << "DECL E6POS XP" << i << "={X " << 300 + 50 * std::cos(2 * u) << ",Y "
          << 50 * std::sin(2 * u) << ",Z " << 400 + 20 * u << ",A " << 90 * u << ",B " << 10 * u
          << ",C " << 180 - 5 * u << ",S 6,T 27}\r\n";
      src << "LIN XP" << i << " C_DIS ; move " << i << "\r\n";
    }
    src << "END\r\n";
    dat << "ENDDAT\r\n";
  }
  const fs::path p = scratch_dir() / "krl_poses.json", m = scratch_dir() / "krl_fit.json";
  ASSERT_EQ(run({"poses", (dir / "path.src").string(), "-o", p.string()}).status, 0);
  EXPECT_EQ(io::read_poses(p.string()).poses.size(), 80u);
  const Result r = run({"fit", (dir / "path.src").string(), "-o", m.string(), "--tol", "0.05",
                        "--param", "chordal"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_LE(figure(r.out, "worst position deviation"), 0.05);
  const Result i = run({"interpolate", (dir / "path.src").string(), "-o",
                        (scratch_dir() / "krl_interp.json").string()});
  EXPECT_EQ(i.status, 0) << i.err;
}

}  // namespace
}  // namespace qmotion::test
