// tests/cli/interpolate_test.cpp: the program, run as a user runs it: `qmotion poses` and `qmotion
// interpolate`.
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

TEST(Cli, MorePosesThanTheLimitAreRefused) {
  // 10^5 poses take about 1 GB to interpolate and 4 GB to sweep: one more is refused before
  // any work, in CSV and in JSON.
  const fs::path csv = scratch_dir() / "too_many.csv";
  {
    std::ofstream f(csv);
    f << "x,y,z,qw,qx,qy,qz\n";
    for (std::size_t i = 0; i <= io::kMaxPoses; ++i) f << i << ",0,0,1,0,0,0\n";
  }
  const fs::path json_file = scratch_dir() / "too_many.json";
  {
    std::ofstream f(json_file);
    f << "{\"poses\":[";
    for (std::size_t i = 0; i <= io::kMaxPoses; ++i)
      f << (i ? "," : "") << "{\"position\":[" << i
        << ",0,0],\"rotation\":{\"quaternion\":[1,0,0,0]}}";
    f << "]}";
  }
  for (const auto& in : {csv, json_file}) {
    const fs::path out = scratch_dir() / "too_many_out.json";
    fs::remove(out);
    const Result r = run({"interpolate", in.string(), "-o", out.string()});
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(in.string() + ": more than 100000 poses"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST(Cli, BadPoseFilesExitTwoAndLeaveNoOutput) {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(kData + "/bad_poses")) files.push_back(e.path());
  files.push_back(scratch_dir() / "unreadable.json");  // does not exist
  ASSERT_GE(files.size(), 24u);  // the four sample bad files and twenty of our own
  for (const auto& in : files) {
    const fs::path out = scratch_dir() / "out.json";
    fs::remove(out);
    const Result r = run({"poses", in.string(), "-o", out.string()});
    EXPECT_EQ(r.status, 2) << in << ": " << r.err;
    EXPECT_NE(r.err.find(in.string()), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << in;
    for (const auto& left : fs::directory_iterator(scratch_dir()))
      EXPECT_EQ(left.path().filename().string().find(".tmp-"), std::string::npos)
          << "temporary left behind";
  }
}

TEST(Cli, PosesConvertsCsvToJson) {
  const fs::path out = scratch_dir() / "converted.json";
  const Result r = run({"poses", kData + "/good_poses.csv", "-o", out.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json j = json::parse(slurp(out));
  ASSERT_EQ(j["poses"].size(), 3u);
  EXPECT_EQ(j["poses"][2]["position"], json({10, 10, 5}));
  EXPECT_EQ(j["poses"][1]["rotation"]["quaternion"], json({0.5, 0.5, 0.5, 0.5}));
  const json s = run_json({"poses", test_data("poses/five_positions.json")});
  EXPECT_EQ(s["poses"], 5);
}

TEST(Cli, InterpolateWritesAMotionThatInterpolatesEveryPose) {
  const fs::path out = scratch_dir() / "five.json";
  const Result r = run({"interpolate", test_data("poses/five_positions.json"), "-o", out.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json i = run_json({"info", out.string()});
  EXPECT_EQ(i["degree"], 8);  // elliptic + TR, m = 4: k + m
  EXPECT_EQ(i["order"], 12);  // 2k + l
  EXPECT_EQ(i["order_source"], "construction");
  EXPECT_LE(i["plucker_residual"].get<double>(), 1e-12);
  ASSERT_EQ(i["interpolation_residual"].size(), 5u);
  for (const auto& x : i["interpolation_residual"]) EXPECT_LE(x.get<double>(), 1e-10);
  EXPECT_TRUE(i["poles"].empty());
  EXPECT_EQ(i["method"]["rotation"], "elliptic");
  EXPECT_EQ(i["method"]["param"], "given");
  // eval at a pose parameter reproduces the pose: t = 0.25 is (40, 10, 5), 45 deg about z.
  const json e = run_json({"eval", out.string(), "--t", "0.25"});
  EXPECT_NEAR(e["position"][0].get<double>(), 40.0, 1e-9);
  EXPECT_NEAR(e["position"][1].get<double>(), 10.0, 1e-9);
  EXPECT_NEAR(e["position"][2].get<double>(), 5.0, 1e-9);
  EXPECT_NEAR(e["quaternion"][0].get<double>(), std::cos(M_PI / 8), 1e-12);
  EXPECT_NEAR(e["quaternion"][3].get<double>(), std::sin(M_PI / 8), 1e-12);
}

TEST(Cli, InterpolateEveryMethodAndRule) {
  for (const std::string rot : {"elliptic", "affine", "projective"})
    for (const std::string tr : {"tr", "trt", "minimal"})
      for (const std::string param :
           {"uniform", "chordal", "star-chordal", "centripetal", "angular", "angular-chordal"}) {
        const fs::path out = scratch_dir() / "m.json";
        const Result r =
            run({"interpolate", test_data("poses/three_positions_no_t.json"), "-o", out.string(),
                 "--rotation", rot, "--translation", tr, "--param", param});
        ASSERT_EQ(r.status, 0) << rot << " " << tr << " " << param << ": "
                               << r.err;  // TRT: default split (1, 0)
        const json i = run_json({"info", out.string()});
        for (const auto& x : i["interpolation_residual"])
          EXPECT_LE(x.get<double>(), 1e-10) << rot << tr << param;
        EXPECT_EQ(i["method"]["param"], param);
      }
}

TEST(Cli, InterpolateRefusalsExitWithTheirStatusAndLeaveNoFile) {
  const std::string d = kData + "/refusals/";
  struct Case {
    std::vector<std::string> args;
    int status;
    std::string needle;
  };
  const std::vector<Case> cases = {
      {{d + "half_turn.json", "--rotation", "affine"}, 3, "half-turn"},
      {{d + "repeated_orientation.json", "--translation", "trt"}, 3, "rank-deficient"},
      {{d + "six_poses.json", "--translation", "trt", "--trt-degrees", "2,2"},
       2,
       "singular for every data set"},
      {{test_data("poses/three_positions_no_t.json"), "--translation", "trt", "--trt-degrees",
        "1,1"},
       2,
       "L1 + L2 = m - 1"},
      {{test_data("poses/three_positions_no_t.json"), "--translation", "trt", "--trt-degrees", "x"},
       2,
       "--trt-degrees"},
      {{kData + "/good_poses.csv", "--translation", "trt", "--trt-degrees", "0,1"}, 0, ""},
      {{d + "projective_inaccessible.json", "--rotation", "projective"}, 3, "inaccessible"},
#ifdef QMOTION_WITH_CGAL
      {{d + "projective_inaccessible.json", "--rotation", "projective", "--exact"},
       3,
       "inaccessible"},
      {{test_data("poses/five_positions.json"), "--exact"}, 2, "pose 1"},
#endif
      {{test_data("poses/helix_40.json"), "--form", "bezier"}, 3, "--form bspline"},
      {{test_data("poses/five_positions.json"), "--rotation", "slerp"}, 2, "--rotation"},
      {{test_data("poses/five_positions.json"), "--translation", "tt"}, 2, "--translation"},
      {{test_data("poses/five_positions.json"), "--param", "random"}, 2, "--param"},
      {{test_data("poses/three_positions_no_t.json"), "--param", "given"}, 2, "needs a t"},
      {{test_data("poses/five_positions.json"), "--degree", "3"}, 2, "--degree"},
      {{test_data("poses/five_positions.json"), "--trt-degrees", "3,0"}, 2, "--translation trt"},
      {{test_data("bad_poses/bad_nan.json")}, 2, "NaN"},
  };
  for (const auto& c : cases) {
    const fs::path out = scratch_dir() / "refused.json";
    fs::remove(out);
    std::vector<std::string> args = {"interpolate"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    args.insert(args.end(), {"-o", out.string()});
    const Result r = run(args);
    EXPECT_EQ(r.status, c.status) << c.args[0] << " " << (c.args.size() > 1 ? c.args[1] : "")
                                  << ": " << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << r.err;
    EXPECT_EQ(fs::exists(out), c.status == 0) << c.args[0];
  }
  // Two poses: TRT is refused, TR works.
  const fs::path two = scratch_dir() / "two.json";
  std::ofstream(two) << R"({"poses":[{"position":[0,0,0],"rotation":{"quaternion":[1,0,0,0]}},)"
                     << R"({"position":[5,1,0],"rotation":{"quaternion":[0.8,0,0.6,0]}}]})";
  const Result trt = run({"interpolate", two.string(), "--translation", "trt", "-o",
                          (scratch_dir() / "two_out.json").string()});
  EXPECT_EQ(trt.status, 2);
  EXPECT_NE(trt.err.find("two poses"), std::string::npos) << trt.err;
  EXPECT_EQ(
      run({"interpolate", two.string(), "-o", (scratch_dir() / "two_out.json").string()}).status,
      0);
}

TEST(Cli, HostileOptionValuesAndMethodBlocksAreBadInput) {
  const fs::path m = five_motion("elliptic", "tr");
  // A method block that is not an object: exit 2 naming it, not an internal error.
  json doc = json::parse(slurp(m));
  doc["method"] = "elliptic";
  const fs::path bad = scratch_dir() / "string_method.json";
  std::ofstream(bad) << doc.dump();
  for (const auto& args : {std::vector<std::string>{"info", bad.string()},
                           std::vector<std::string>{"eval", bad.string(), "--t", "0.5"}}) {
    const Result r = run(args);
    EXPECT_EQ(r.status, 2) << args[0] << ": " << r.err;
    EXPECT_NE(r.err.find("method: expected an object"), std::string::npos) << r.err;
  }
  // An out-of-range integer and a degree OpenCASCADE cannot store.
  const fs::path out = scratch_dir() / "hostile.json";
  Result r = run({"interpolate", test_data("poses/five_positions.json"), "-o", out.string(),
                  "--translation", "trt", "--trt-degrees", "99999999999999,0"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("--trt-degrees"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  const fs::path step = scratch_dir() / "hostile.step";
  r = run(
      {"trajectory", m.string(), "--point", "1,2,3", "-o", step.string(), "--max-degree", "30"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("up to 25"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(step));
}

TEST(Cli, SplineMotionsByDefaultBeyondSixPoses) {
  const fs::path m = scratch_dir() / "helix_bspline.json";
  Result r = run({"interpolate", test_data("poses/helix_40.json"), "-o", m.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  json i = run_json({"info", m.string()});
  EXPECT_EQ(i["basis"], "bspline");
  EXPECT_EQ(i["degree"], 6);  // cubic rotation x cubic translation
  EXPECT_EQ(i["order"], 9);   // 2k + l
  EXPECT_EQ(i["method"]["form"], "bspline");
  for (const auto& x : i["interpolation_residual"]) EXPECT_LE(x.get<double>(), 1e-10);
  EXPECT_LE(i["plucker_residual"].get<double>(), 1e-12);
  // Other degrees; Algorithm 2; minimal order.
  for (const auto& extra :
       {std::vector<std::string>{"--degree", "5", "--translation-degree", "4"},
        std::vector<std::string>{"--form", "c1"},
        std::vector<std::string>{"--form", "c1", "--translation", "minimal"},
        std::vector<std::string>{"--translation", "minimal", "--degree", "2"}}) {
    std::vector<std::string> args = {"interpolate", test_data("poses/helix_40.json"), "-o",
                                     m.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    r = run(args);
    ASSERT_EQ(r.status, 0) << extra[1] << ": " << r.err;
    i = run_json({"info", m.string()});
    for (const auto& x : i["interpolation_residual"]) EXPECT_LE(x.get<double>(), 1e-10);
    for (const std::string ext : {".json", ".step", ".igs"}) {
      const fs::path s = scratch_dir() / ("spline_surface" + ext),
                     c = scratch_dir() / ("spline_curve" + ext);
      ASSERT_EQ(run({"sweep", m.string(), "--profile", "circle:6", "-o", s.string()}).status, 0);
      ASSERT_EQ(run({"trajectory", m.string(), "--point", "4,0,2", "-o", c.string()}).status, 0);
      EXPECT_LE(check(s, m, {"--profile", "circle:6"})["relative_deviation"].get<double>(), 1e-11)
          << extra[1] << ext;
      EXPECT_LE(check(c, m, {"--point", "4,0,2"})["relative_deviation"].get<double>(), 1e-11)
          << extra[1] << ext;
    }
  }
#ifdef QMOTION_WITH_CGAL
  // Exact B-spline motion from rational input.
  r = run({"interpolate", test_data("poses/rational_exact.json"), "--form", "bspline", "--exact",
           "-o", m.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  i = run_json({"info", "--exact", m.string()});
  EXPECT_EQ(i["plucker_residual"], 0.0);
  for (const auto& x : i["interpolation_residual"]) EXPECT_EQ(x.get<double>(), 0.0);
#endif
}

TEST(Cli, SplineOptionRefusals) {
  const std::string poses = test_data("poses/helix_40.json");
  const fs::path out = scratch_dir() / "refused_spline.json";
  for (const auto& [args, needle] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--rotation", "affine"}, "elliptic"},
           {{"--translation", "trt"}, "trt"},
           {{"--form", "c1", "--exact"}, "--exact"},
           {{"--form", "c1", "--degree", "4"}, "cubic"},
           {{"--degree", "0"}, "--degree"},
           {{"--form", "nurbs"}, "--form"}}) {
    fs::remove(out);
    std::vector<std::string> a = {"interpolate", poses, "-o", out.string()};
    a.insert(a.end(), args.begin(), args.end());
    const Result r = run(a);
    EXPECT_EQ(r.status, 2) << args[0] << ": " << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

}  // namespace
}  // namespace qmotion::test
