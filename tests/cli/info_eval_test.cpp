// tests/cli/info_eval_test.cpp: the program, run as a user runs it: `qmotion info` and `qmotion
// eval`.
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

TEST(Cli, EvalFollowsTheHandDerivedMotion) {
  // bezier_tr.json is (2 + eps p(t)) * r(t), p(t) = t (10, 20, 0), r from 1 to 1 + k.
  const std::string f = kExamples + "/motions/bezier_tr.json";
  const json a = run_json({"eval", f, "--t", "0.5"});
  EXPECT_EQ(a["t"], 0.5);
  EXPECT_NEAR(a["position"][0].get<double>(), 5.0, 1e-13);
  EXPECT_NEAR(a["position"][1].get<double>(), 10.0, 1e-13);
  // r(1/2) = 1 + k/2: angle 2 atan(1/2) about z, returned as a unit quaternion, w >= 0.
  const double half = std::atan(0.5);
  EXPECT_NEAR(a["quaternion"][0].get<double>(), std::cos(half), 1e-15);
  EXPECT_NEAR(a["quaternion"][3].get<double>(), std::sin(half), 1e-15);
  EXPECT_EQ(a["point"], a["position"]);  // default point: the origin
  // At t = 1 the rotation is 90 degrees about z: (1, 0, 0) goes to p(1) + (0, 1, 0).
  const json b = run_json({"eval", f, "--t", "1", "--point", "1,0,0"});
  EXPECT_NEAR(b["point"][0].get<double>(), 10.0, 1e-13);
  EXPECT_NEAR(b["point"][1].get<double>(), 21.0, 1e-13);
  EXPECT_NEAR(b["point"][2].get<double>(), 0.0, 1e-13);
}

TEST(Cli, NegativeParametersAreValues) {
  // The example shifted to [-2, -1]: --t -1.5 is its midpoint.
  json m = json::parse(slurp(kExamples + "/motions/bezier_tr.json"));
  m["param_range"] = {-2, -1};
  const fs::path f = scratch_dir() / "shifted.json";
  std::ofstream(f) << m.dump();
  const json a = run_json({"eval", f.string(), "--t", "-1.5"});
  EXPECT_NEAR(a["position"][0].get<double>(), 5.0, 1e-13);
  const Result out = run({"eval", kExamples + "/motions/bezier_tr.json", "--t", "-1.5"});
  EXPECT_EQ(out.status, 2);
  EXPECT_NE(out.err.find("outside"), std::string::npos) << out.err;
}

TEST(Cli, InfoReportsTheSpecKeys) {
  for (const std::string name : {"bezier_tr.json", "bspline_tr.json"}) {
    const json i = run_json({"info", kExamples + "/motions/" + name});
    for (const char* key : {"type", "basis", "degree", "order", "segments", "param_range",
                            "plucker_residual", "interpolation_residual", "poles"})
      EXPECT_TRUE(i.contains(key)) << key;
    EXPECT_EQ(i["degree"], 2);
    // TR with rotation degree k = 1 and translation degree l = 1: a general point's
    // trajectory has degree 2k + l = 3, below the 2n = 4 of its representation.
    EXPECT_EQ(i["order"], 3);
    EXPECT_EQ(i["plucker_residual"], 0.0);
    EXPECT_TRUE(i["poles"].empty());
  }
  EXPECT_EQ(run_json({"info", kExamples + "/motions/bspline_tr.json"})["segments"], 2);
#ifdef QMOTION_WITH_CGAL
  const json ex = run_json({"info", "--exact", kExamples + "/motions/bspline_tr.json"});
  EXPECT_EQ(ex["exact"], true);
  EXPECT_EQ(ex["plucker_residual"], 0.0);
#endif
}

TEST(Cli, PolesAreReportedAndEvalAtAPoleIsANumericalFailure) {
  // Rotational part 2(1 - 2t): zero at t = 1/2.
  const json m{{"type", "q-motion"},
               {"basis", "bezier"},
               {"degree", 1},
               {"param_range", {0, 1}},
               {"control_points", {{2, 0, 0, 0, 0, 0, 0, 0}, {-2, 0, 0, 0, 0, 0, 0, 0}}}};
  const fs::path f = scratch_dir() / "pole.json";
  std::ofstream(f) << m.dump();
  const json i = run_json({"info", f.string()});
  ASSERT_EQ(i["poles"].size(), 1u);
  EXPECT_NEAR(i["poles"][0].get<double>(), 0.5, 1e-8);
  const Result e = run({"eval", f.string(), "--t", "0.5"});
  EXPECT_EQ(e.status, 3);
  EXPECT_NE(e.err.find("pole"), std::string::npos) << e.err;
}

TEST(Cli, BadMotionFilesExitTwoNamingTheFile) {
  for (const auto& entry : fs::directory_iterator(kData + "/bad_motions")) {
    const Result r = run({"info", entry.path().string()});
    EXPECT_EQ(r.status, 2) << entry.path() << ": " << r.err;
    EXPECT_NE(r.err.find(entry.path().string()), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
  }
  const Result missing = run({"info", (scratch_dir() / "nope.json").string()});
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.err.find("cannot open"), std::string::npos);
  const Result badpoint =
      run({"eval", kExamples + "/motions/bezier_tr.json", "--t", "0", "--point", "1,2"});
  EXPECT_EQ(badpoint.status, 2);
  EXPECT_NE(badpoint.err.find("--point"), std::string::npos);
}

}  // namespace
}  // namespace qmotion::test
