// tests/cli/exact_test.cpp: the program, run as a user runs it: the exact modes: `interpolate
// --exact`, `info --exact`, `check --exact`.
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

#ifdef QMOTION_WITH_CGAL

TEST(Cli, InterpolateExactIsExact) {
  for (const std::string tr : {"tr", "trt", "minimal"}) {
    const fs::path out = scratch_dir() / ("exact_" + tr + ".json");
    const Result r = run({"interpolate", test_data("poses/rational_exact.json"), "--exact",
                          "--translation", tr, "-o", out.string()});
    ASSERT_EQ(r.status, 0) << r.err;
    const json i = run_json({"info", "--exact", out.string()});
    EXPECT_EQ(i["plucker_residual"], 0.0);
    for (const auto& x : i["interpolation_residual"]) EXPECT_EQ(x.get<double>(), 0.0);
    if (tr == "minimal") {
      EXPECT_EQ(i["order"], 6);   // 2m, computed exactly (Theorem 6)
      EXPECT_EQ(i["degree"], 9);  // 3m
    }
    // Without --exact, info reports the order the recorded construction guarantees
    // (order_source "construction"); it must be the order the geometry has, computed
    // exactly above from the control points (Bernstein Sylvester rank).
    const json recorded = run_json({"info", out.string()});
    EXPECT_EQ(recorded["order_source"], "construction");
    EXPECT_EQ(i["order_source"], "exact");
    EXPECT_EQ(recorded["order"], i["order"]) << tr;
  }
}

TEST(Cli, ExactInfoWorkIsBounded) {
  // Degree 21 (one above the limit): the exact rank would take about 9 s and grows as the
  // fifth power of the degree; the double report is immediate.
  const std::string big = test_data("limits/degree_21.json");
  const Result r = run({"info", "--exact", big});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("limited to motions of degree 20"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(big), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(run_json({"info", big})["degree"], 21);
}

// check --exact: the motion recomputed in exact rationals from the poses its file records.
// For every sample pose set and several methods the exact motion satisfies the Plucker
// condition and interpolates every pose with exact zeros, the double file agrees with it,
// and the trajectory order by an exact gcd equals the degree `trajectory` writes.
TEST(Cli, CheckExactVerifiesEverySamplePoseSet) {
  struct Case {
    std::string poses;
    std::vector<std::string> options;
  };
  const std::vector<Case> cases = {
      {"poses/five_positions.json", {}},
      {"poses/five_positions.json", {"--rotation", "affine"}},
      {"poses/five_positions.json", {"--rotation", "projective", "--translation", "minimal"}},
      {"poses/five_positions.json", {"--translation", "trt", "--trt-degrees", "1,2"}},
      {"poses/five_positions.json", {"--form", "bspline"}},
      {"poses/rational_exact.json", {}},
      {"poses/rational_exact.json", {"--exact"}},
      {"poses/screw_three.json", {}},
      {"poses/three_positions_no_t.json", {"--param", "chordal"}},
      {"helix_10.json", {}},
      {"helix_10.json", {"--translation", "minimal", "--degree", "4"}},
      {"poses/helix_40.json", {}},
  };
  int k = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.poses + " " + ::testing::PrintToString(c.options));
    const std::string motion =
        (scratch_dir() / ("exact_" + std::to_string(k++) + ".json")).string();
    std::vector<std::string> args{"interpolate", test_data(c.poses), "-o", motion};
    args.insert(args.end(), c.options.begin(), c.options.end());
    const Result made = run(args);
    ASSERT_EQ(made.status, 0) << made.err;
    const Result r = run({"check", "--exact", "--motion", motion});
    ASSERT_EQ(r.status, 0) << r.err << r.out;
    const json j = json::parse(r.out);
    EXPECT_TRUE(j["verified"].get<bool>());
    EXPECT_TRUE(j["plucker"]["exact_zero"].get<bool>());
    EXPECT_EQ(j["plucker"]["exact_max_abs"], 0.0);
    EXPECT_TRUE(j["interpolation"]["exact_zero"].get<bool>());
    for (const auto& x : j["interpolation"]["exact_residuals"]) EXPECT_EQ(x, 0.0);
    EXPECT_LE(j["file_deviation"]["control_points"].get<double>(), 1e-8);
    EXPECT_EQ(j["order"]["gcd"], j["order"]["trajectory_degree"]);
    EXPECT_LE(j["order"]["gcd"].get<int>(), j["order"]["construction"].get<int>());
    if (c.options == std::vector<std::string>{"--exact"}) {
      // An exact file: the same numbers, and info --exact's Sylvester rank on its digits
      // finds the same order. (On a double file it finds the generic 2n: rounding breaks
      // the common factors, which is why check --exact recomputes.)
      EXPECT_EQ(j["file_deviation"]["control_points"], 0.0);
      EXPECT_EQ(j["order"]["gcd"], run_json({"info", "--exact", motion})["order"]);
    }
  }
}

TEST(Cli, CheckExactRefusesWhatItCannotVerify) {
  const std::string motion = (scratch_dir() / "exact_refusals.json").string();
  ASSERT_EQ(run({"interpolate", test_data("poses/five_positions.json"), "-o", motion}).status, 0);
  json doc = json::parse(slurp(motion));

  // A control point moved after interpolation: the recomputation disagrees (exit 3).
  json moved = doc;
  moved["control_points"][2][5] = moved["control_points"][2][5].get<double>() * 1.001 + 0.01;
  const std::string moved_path = (scratch_dir() / "exact_moved.json").string();
  std::ofstream(moved_path) << moved.dump();
  const Result m = run({"check", "--exact", "--motion", moved_path});
  EXPECT_EQ(m.status, 3) << m.err;
  EXPECT_NE(m.err.find("does not verify"), std::string::npos) << m.err;
  EXPECT_FALSE(json::parse(m.out)["verified"].get<bool>());
  EXPECT_GT(json::parse(m.out)["file_deviation"]["control_points"].get<double>(), 1e-6);

  // A hand-written motion (no method block) has nothing to recompute from (exit 2).
  json bare = doc;
  bare.erase("method");
  const std::string bare_path = (scratch_dir() / "exact_bare.json").string();
  std::ofstream(bare_path) << bare.dump();
  const Result b = run({"check", "--exact", "--motion", bare_path});
  EXPECT_EQ(b.status, 2) << b.err;
  EXPECT_NE(b.err.find("records none"), std::string::npos) << b.err;

  // A c1 motion has no exact recomputation; GEOMETRY does not go with --exact.
  const std::string c1 = (scratch_dir() / "exact_c1.json").string();
  ASSERT_EQ(run({"interpolate", test_data("helix_10.json"), "--form", "c1", "-o", c1}).status, 0);
  const Result c = run({"check", "--exact", "--motion", c1});
  EXPECT_EQ(c.status, 2) << c.err;
  EXPECT_NE(c.err.find("no exact recomputation"), std::string::npos) << c.err;
  const Result g = run({"check", "--exact", "--motion", motion, "curve.json"});
  EXPECT_EQ(g.status, 2) << g.err;
  EXPECT_NE(g.err.find("no GEOMETRY"), std::string::npos) << g.err;
  const Result none = run({"check", "--motion", motion, "--point", "1,2,3"});
  EXPECT_EQ(none.status, 2) << none.err;
  EXPECT_NE(none.err.find("GEOMETRY is required"), std::string::npos) << none.err;
}
#else
// Without CGAL (QMOTION_WITH_CGAL=OFF) every exact mode is refused as bad input, naming
// the build option, and writes nothing.
TEST(Cli, ExactModesAreRefusedInABuildWithoutCgal) {
  const fs::path out = scratch_dir() / "exact_off.json";
  fs::remove(out);
  const std::string motion = kExamples + "/motions/bspline_tr.json";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"interpolate", test_data("poses/rational_exact.json"), "--exact",
                                 "-o", out.string()},
        {"info", "--exact", motion},
        {"check", "--exact", "--motion", motion}}) {
    const Result r = run(args);
    EXPECT_EQ(r.status, 2) << args.front() << ": " << r.err;
    EXPECT_NE(r.err.find("QMOTION_WITH_CGAL=OFF"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}
#endif

}  // namespace
}  // namespace qmotion::test
