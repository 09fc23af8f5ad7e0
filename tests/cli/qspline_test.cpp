// tests/cli/qspline_test.cpp: the program, run as a user runs it: `qmotion qspline` and the
// commands on its motions.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <qmotion/io/poses.hpp>
#include <sstream>
#include <vector>

#include "cli_util.hpp"

namespace qmotion::test {
namespace {

// qspline: each scheme's file is read back by info and eval; eval at every key's knot gives
// the pose (the motion interpolates), info reports the residuals (and KKS its solve).
TEST(Cli, QsplineMotionsInterpolateThePosesThroughInfoAndEval) {
  const io::PoseSet set = io::read_poses(test_data("helix_10.json"));
  const auto poses = io::to_poses_double(set);
  for (const char* scheme : {"kks", "quintic", "quartic"}) {
    SCOPED_TRACE(scheme);
    const std::string out = (scratch_dir() / (std::string("q_") + scheme + ".json")).string();
    const Result made = run({"qspline", test_data("helix_10.json"), "-o", out, "--scheme", scheme});
    ASSERT_EQ(made.status, 0) << made.err;
    EXPECT_NE(made.err.find(scheme), std::string::npos) << made.err;
    const json info = run_json({"info", out});
    EXPECT_EQ(info["type"], "quaternion-spline");
    EXPECT_EQ(info["scheme"], scheme);
    EXPECT_EQ(info["segments"], 9);
    EXPECT_EQ(info["poles"].size(), 0u);
    ASSERT_EQ(info["interpolation_residual"].size(), poses.size());
    for (const auto& r : info["interpolation_residual"]) EXPECT_LE(r.get<double>(), 1e-10);
    if (std::string(scheme) == "kks") {
      EXPECT_GT(info["iterations"].get<int>(), 0);
      EXPECT_LT(info["contraction"].get<double>(), 1.0);
      EXPECT_LE(info["residual"].get<double>(), 1e-10);
    }
    for (std::size_t i = 0; i < poses.size(); ++i) {
      std::ostringstream t;
      t.precision(17);
      t << info["knots"][i].get<double>();
      const json e = run_json({"eval", out, "--t", t.str()});
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(e["position"][k].get<double>(), poses[i].position(k), 1e-9) << "pose " << i;
      }
      const double sign = e["quaternion"][0].get<double>() * poses[i].rotation.w() < 0 ? -1 : 1;
      EXPECT_NEAR(sign * e["quaternion"][1].get<double>(), poses[i].rotation.x(), 1e-9);
      EXPECT_NEAR(sign * e["quaternion"][3].get<double>(), poses[i].rotation.z(), 1e-9);
      EXPECT_EQ(e["angular_velocity"].size(), 3u);
    }
  }
}

TEST(Cli, QsplineTrajectoriesAndSweepsAreApproximatedWithinTol) {
  // Every scheme, every format: the message and the JSON state the tolerance, the measured
  // deviation, the degree and the poles; check measures the written file against the motion
  // itself.
  for (const char* scheme : {"kks", "quintic", "quartic"}) {
    SCOPED_TRACE(scheme);
    const std::string m = (scratch_dir() / (std::string("qa_") + scheme + ".json")).string();
    ASSERT_EQ(run({"qspline", test_data("helix_10.json"), "-o", m, "--scheme", scheme}).status, 0);
    for (const char* ext : {".json", ".step", ".igs"}) {
      SCOPED_TRACE(ext);
      const std::string traj = (scratch_dir() / (std::string("qa_traj") + ext)).string();
      const Result t = run({"trajectory", m, "--point", "1,-2,0.5", "-o", traj, "--tol", "1e-5"});
      ASSERT_EQ(t.status, 0) << t.err;
      EXPECT_NE(t.err.find("degree 5"), std::string::npos) << t.err;
      EXPECT_NE(t.err.find("within tolerance 1e-05"), std::string::npos) << t.err;
      const json ct = run_json({"check", traj, "--motion", m, "--point", "1,-2,0.5"});
      EXPECT_LE(ct["max_deviation"].get<double>(), 1e-5) << ct.dump();
      EXPECT_NE(ct["motion"].get<std::string>().find("quaternion-spline"), std::string::npos);
      const std::string surf = (scratch_dir() / (std::string("qa_surf") + ext)).string();
      const Result s = run({"sweep", m, "--profile", "arc:2,0,1.5", "-o", surf, "--tol", "1e-4"});
      ASSERT_EQ(s.status, 0) << s.err;
      EXPECT_NE(s.err.find("poles"), std::string::npos) << s.err;
      const json cs = run_json({"check", surf, "--motion", m, "--profile", "arc:2,0,1.5"});
      EXPECT_LE(cs["max_deviation"].get<double>(), 1e-4) << cs.dump();
      if (std::string(ext) == ".json") {
        const json doc = json::parse(slurp(surf));
        EXPECT_EQ(doc["approximation"]["tolerance"].get<double>(), 1e-4);
        EXPECT_LE(doc["approximation"]["measured_deviation"].get<double>(), 1e-4);
        EXPECT_EQ(doc["approximation"]["degree"].get<int>(), 5);
        EXPECT_GT(doc["approximation"]["poles_per_curve"].get<int>(), 5);
      }
    }
  }
  // --max-degree sets the fitted degree.
  const std::string m = (scratch_dir() / "qa_kks.json").string();
  const std::string c3 = (scratch_dir() / "qa_cubic.json").string();
  ASSERT_EQ(run({"trajectory", m, "--point", "0,0,0", "-o", c3, "--max-degree", "3"}).status, 0);
  EXPECT_EQ(json::parse(slurp(c3))["degree"].get<int>(), 3);
}

TEST(Cli, QsplineBadInputsExitWithTheirStatusAndLeaveNoFile) {
  const std::string out = (scratch_dir() / "q_bad.json").string();
  const fs::path half = scratch_dir() / "half_turn_keys.json";
  std::ofstream(half) << R"({"poses": [
    {"position": [0, 0, 0], "rotation": {"quaternion": [1, 0, 0, 0]}},
    {"position": [1, 0, 0], "rotation": {"quaternion": [0, 1, 0, 0]}},
    {"position": [2, 0, 0], "rotation": {"quaternion": [0, 0, 1, 0]}}]})";
  // Keys 2 rad apart (a 115 degree turn) whose axes nearly reverse at every key: the KKS
  // iteration cycles.
  const fs::path cycle = scratch_dir() / "kks_cycle.json";
  {
    std::ofstream f(cycle);
    f << R"({"poses": [)";
    double w = 1, x = 0, y = 0, z = 0;
    for (int i = 0; i < 10; ++i) {
      if (i) {
        const double ax = std::cos(3.0 * (i - 1)), ay = std::sin(3.0 * (i - 1));
        const double c = std::cos(1.0), sn = std::sin(1.0);  // exp(1 rad about (ax, ay, 0))
        const double bw = c, bx = sn * ax, by = sn * ay, bz = 0;
        const double nw = w * bw - x * bx - y * by - z * bz, nx = w * bx + x * bw + y * bz - z * by,
                     ny = w * by - x * bz + y * bw + z * bx, nz = w * bz + x * by - y * bx + z * bw;
        w = nw, x = nx, y = ny, z = nz;
      }
      f << (i ? "," : "") << R"({"position": [)" << i << R"(, 0, 0], "rotation": {"quaternion": [)"
        << w << "," << x << "," << y << "," << z << "]}}";
    }
    f << "]}";
  }
  const std::string poses = test_data("helix_10.json");
  struct Case {
    std::vector<std::string> args;
    int status;
    std::string needle;
  };
  const std::vector<Case> cases = {
      {{poses, "--scheme", "cubic"}, 2, "--scheme: expected kks, quintic or quartic"},
      {{poses, "--scheme", "quintic", "--tension", "0.5,0.5"}, 2, "one per pose (10), found 2"},
      {{poses, "--scheme", "quintic", "--tension", "-0.3"}, 2, "negative tension"},
      {{poses, "--scheme", "quintic", "--tension", "soft"}, 2, "--tension"},
      {{poses, "--scheme", "kks", "--tension", "1"}, 2, "--tension is for --scheme quintic"},
      {{half.string(), "--scheme", "quartic"}, 2, "a half-turn apart"},
      {{cycle.string(), "--scheme", "kks"}, 3, "largest key distance"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(::testing::PrintToString(c.args));
    std::vector<std::string> args{"qspline", "-o", out};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const Result r = run(args);
    EXPECT_EQ(r.status, c.status) << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
  // info --exact and check --exact are for rational motions.
  const std::string ok = (scratch_dir() / "q_ok.json").string();
  ASSERT_EQ(run({"qspline", poses, "-o", ok, "--scheme", "quartic"}).status, 0);
  const Result exact = run({"info", "--exact", ok});
  EXPECT_EQ(exact.status, 2);
  EXPECT_NE(exact.err.find("not rational"), std::string::npos) << exact.err;
#ifdef QMOTION_WITH_CGAL
  const Result check_exact = run({"check", "--exact", "--motion", ok});
  EXPECT_EQ(check_exact.status, 2);
  EXPECT_NE(check_exact.err.find("non-rational"), std::string::npos) << check_exact.err;
#endif
  // A fit that cannot reach its tolerance (degree 1, 1e-12 of the size) is exit 3 and
  // writes nothing; a degree below 1 is exit 2.
  const std::string curve = (scratch_dir() / "q_curve.step").string();
  const Result coarse = run(
      {"trajectory", ok, "--point", "1,2,3", "-o", curve, "--max-degree", "1", "--tol", "1e-11"});
  EXPECT_EQ(coarse.status, 3) << coarse.err;
  EXPECT_NE(coarse.err.find("above the tolerance"), std::string::npos) << coarse.err;
  EXPECT_FALSE(fs::exists(curve));
  const Result zero = run({"sweep", ok, "--profile", "rect:1,2", "-o", curve, "--max-degree", "0"});
  EXPECT_EQ(zero.status, 2) << zero.err;
  EXPECT_NE(zero.err.find("--max-degree"), std::string::npos) << zero.err;
  EXPECT_FALSE(fs::exists(curve));
}

}  // namespace
}  // namespace qmotion::test
