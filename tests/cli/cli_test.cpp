// tests/cli/cli_test.cpp: the qmotion executable against docs/formats.md (exit codes, messages,
// JSON output, no output file on failure).
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

#include "io_test_util.hpp"

namespace qmotion::test {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;

const std::string kExe = QMOTION_EXE;
const std::string kData = QMOTION_TEST_DATA;
const std::string kExamples = QMOTION_EXAMPLES;

struct Result {
  int status;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

fs::path scratch_dir() {
  static const fs::path d = [] {
    const fs::path p = fs::temp_directory_path() / ("qmotion_cli_" + std::to_string(::getpid()));
    fs::create_directories(p);
    return p;
  }();
  return d;
}

std::string quote(const std::string& a) {
  std::string q = "'";
  for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

Result run(const std::vector<std::string>& args) {
  const fs::path out = scratch_dir() / "stdout", err = scratch_dir() / "stderr";
  std::string cmd = quote(kExe);
  for (const auto& a : args) cmd += " " + quote(a);
  cmd += " >" + quote(out.string()) + " 2>" + quote(err.string()) + " </dev/null";
  const int raw = std::system(cmd.c_str());
  return Result{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), slurp(err)};
}

json run_json(const std::vector<std::string>& args) {
  const Result r = run(args);
  EXPECT_EQ(r.status, 0) << r.err;
  return json::parse(r.out);
}

TEST(Cli, HelpVersionAndUsage) {
  const Result h = run({"--help"});
  EXPECT_EQ(h.status, 0);
  for (const char* cmd : {"info", "eval", "poses", "interpolate", "trajectory", "sweep", "check",
                          "demo", "Exit status"})
    EXPECT_NE(h.out.find(cmd), std::string::npos) << cmd;
  const Result sub = run({"eval", "--help"});
  EXPECT_EQ(sub.status, 0);
  EXPECT_NE(sub.out.find("--point"), std::string::npos);
  const Result v = run({"--version"});
  EXPECT_EQ(v.status, 0);
  EXPECT_NE(v.out.find("OpenCASCADE 7."), std::string::npos);
  EXPECT_EQ(run({}).status, 2);
  const Result bad = run({"frobnicate"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("qmotion: error:"), std::string::npos);
  EXPECT_EQ(run({"eval", kExamples + "/motions/bezier_tr.json"}).status, 2);  // --t missing
}

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
  const json ex = run_json({"info", "--exact", kExamples + "/motions/bspline_tr.json"});
  EXPECT_EQ(ex["exact"], true);
  EXPECT_EQ(ex["plucker_residual"], 0.0);
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

TEST(Cli, CompareMeasuresEverySchemeOnOneInterval) {
  const json figures =
      run_json({"compare", test_data("helix_10.json"), "--json", "--point", "2,0,0"});
  ASSERT_EQ(figures.size(), 5u);
  const std::vector<std::string> names{"elliptic bspline", "c1", "kks", "quintic", "quartic"};
  double shortest = HUGE_VAL, longest = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const json& f = figures[i];
    EXPECT_EQ(f["scheme"], names[i]);
    ASSERT_FALSE(f.contains("error")) << f.dump();
    EXPECT_EQ(f["rational"].get<bool>(), i < 2);
    EXPECT_GT(f["max_angular_velocity"].get<double>(), 0);
    EXPECT_GT(f["sweep_poles"].get<int>(), 0);
    EXPECT_LE(f["max_key_residual"].get<double>(), 1e-10);
    if (i >= 2) {
      EXPECT_GT(f["sweep_deviation"].get<double>(), 0);
    }
    shortest = std::min(shortest, f["trajectory_length"].get<double>());
    longest = std::max(longest, f["trajectory_length"].get<double>());
  }
  // Every scheme passes through the same ten poses: the lengths differ by a few percent.
  EXPECT_LE(longest, 1.1 * shortest);
  const Result table = run({"compare", test_data("helix_10.json")});
  ASSERT_EQ(table.status, 0) << table.err;
  for (const auto& n : names) EXPECT_NE(table.out.find(n), std::string::npos) << table.out;
  // Bad options are exit 2.
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"compare", test_data("helix_10.json"), "--tol", "2"},
        std::vector<std::string>{"compare", test_data("helix_10.json"), "--param", "sideways"},
        std::vector<std::string>{"compare", test_data("helix_10.json"), "--point", "1,2"},
        std::vector<std::string>{"compare", test_data("helix_10.json"), "--profile",
                                 "circle:-1"}}) {
    const Result r = run(args);
    EXPECT_EQ(r.status, 2) << r.err;
  }
}

/// The STRAIGHT_TRAVERSE and STRAIGHT_FEED positions LinuxCNC's interpreter prints for a
/// G-code file (x, y, z, a, b, c), or nothing when it is absent (the test then skips).
std::optional<std::vector<std::array<double, 6>>> rs274_moves(const std::string& ngc,
                                                              std::string& log) {
  if (!fs::exists("/usr/bin/rs274")) return std::nullopt;
  const fs::path out = scratch_dir() / "rs274.out";
  const int raw = std::system(
      ("/usr/bin/rs274 -g " + quote(ngc) + " >" + quote(out.string()) + " 2>&1 </dev/null")
          .c_str());
  log = slurp(out);
  EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << log;
  std::vector<std::array<double, 6>> moves;
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);) {
    const auto p = line.find("STRAIGHT_");
    if (p == std::string::npos) continue;
    std::array<double, 6> v{};
    const std::string args = line.substr(line.find('(', p) + 1);
    EXPECT_EQ(std::sscanf(args.c_str(), "%lf, %lf, %lf, %lf, %lf, %lf", &v[0], &v[1], &v[2], &v[3],
                          &v[4], &v[5]),
              6)
        << line;
    moves.push_back(v);
  }
  EXPECT_EQ(log.find("error"), std::string::npos) << log;
  return moves;
}

/// The rows of a toolpath CSV (t, x, y, z, i, j, k).
std::vector<std::vector<double>> csv_rows(const std::string& path) {
  std::ifstream f(path);
  std::vector<std::vector<double>> rows;
  std::string line;
  std::getline(f, line);  // header
  while (std::getline(f, line)) {
    std::vector<double> r;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) r.push_back(std::stod(cell));
    rows.push_back(r);
  }
  return rows;
}

TEST(Cli, ToolpathGcodeRunsInLinuxCncsInterpreter) {
  const std::string m = (scratch_dir() / "tp_motion.json").string();
  ASSERT_EQ(run({"interpolate", test_data("poses/helix_40.json"), "-o", m}).status, 0);
  const std::string csv = (scratch_dir() / "tp.csv").string(),
                    ngc = (scratch_dir() / "tp.ngc").string(),
                    ngc5 = (scratch_dir() / "tp5.ngc").string();
  const std::vector<std::string> common{"--point", "1,0,2",       "--axis",
                                        "1,0,1",   "--chord-tol", "0.01"};
  for (const auto& out : {csv, ngc, ngc5}) {
    std::vector<std::string> args{"toolpath", m, "-o", out};
    args.insert(args.end(), common.begin(), common.end());
    if (out == ngc5) args.insert(args.end(), {"--rotary", "ac"});
    const Result r = run(args);
    ASSERT_EQ(r.status, 0) << r.err;
    const json report = json::parse(r.out);
    EXPECT_LE(report["max_chord_deviation_bound"].get<double>(), 0.01);
    EXPECT_LE(report["max_chord_deviation_measured"].get<double>(),
              report["max_chord_deviation_bound"].get<double>());
    EXPECT_GT(report["machining_time_min"].get<double>(), 0);
  }
  const auto rows = csv_rows(csv);
  // Every CSV point on the exact trajectory (eval at its t).
  for (std::size_t i = 0; i < rows.size(); i += 7) {
    std::ostringstream t;
    t.precision(17);
    t << rows[i][0];
    const json e = run_json({"eval", m, "--t", t.str(), "--point", "1,0,2"});
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(e["point"][c].get<double>(), rows[i][1 + c], 1e-8) << "row " << i;
    }
  }
  std::string log;
  const auto moves = rs274_moves(ngc, log);
  if (!moves) GTEST_SKIP() << "rs274 not installed (linuxcnc-uspace)";
  ASSERT_EQ(moves->size(), rows.size()) << log;
  // The file's 6 decimals, then the interpreter's 4: within 5e-5 + 5e-7.
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR((*moves)[i][c], rows[i][1 + c], 5.1e-5) << "move " << i;
    }
  // 5-axis: machine XYZ = Rx(A) Rz(C) p, and A, C take the axis onto +Z.
  const auto moves5 = rs274_moves(ngc5, log);
  ASSERT_TRUE(moves5);
  ASSERT_EQ(moves5->size(), rows.size()) << log;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& mv = (*moves5)[i];
    const double A = mv[3] * 3.14159265358979323846 / 180, C = mv[5] * 3.14159265358979323846 / 180;
    const Eigen::Matrix3d T = (Eigen::AngleAxisd(A, Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(C, Eigen::Vector3d::UnitZ()))
                                  .toRotationMatrix();
    const Eigen::Vector3d p = T * Eigen::Vector3d(rows[i][1], rows[i][2], rows[i][3]);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(mv[c], p(c), 5.1e-5 + 1e-6 * p.norm()) << "move " << i;
    }
    const Eigen::Vector3d z = T * Eigen::Vector3d(rows[i][4], rows[i][5], rows[i][6]);
    EXPECT_LE(z.cross(Eigen::Vector3d::UnitZ()).norm(), 2e-6) << "move " << i;  // 4 decimals
  }
  // The file's own 9 decimals of A and C reproduce the axis within 1e-9 rad.
  std::ifstream f(ngc5);
  std::size_t k = 0;
  for (std::string line; std::getline(f, line);) {
    const auto a = line.find(" A"), c = line.find(" C");
    if (a == std::string::npos || c == std::string::npos) continue;
    const double A = std::stod(line.substr(a + 2)) * 3.14159265358979323846 / 180;
    const double C = std::stod(line.substr(c + 2)) * 3.14159265358979323846 / 180;
    const Eigen::Matrix3d T = (Eigen::AngleAxisd(A, Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(C, Eigen::Vector3d::UnitZ()))
                                  .toRotationMatrix();
    const Eigen::Vector3d z = T * Eigen::Vector3d(rows[k][4], rows[k][5], rows[k][6]).normalized();
    EXPECT_LE(std::atan2(z.cross(Eigen::Vector3d::UnitZ()).norm(), z(2)), 1e-9) << line;
    ++k;
  }
  EXPECT_EQ(k, rows.size());
}

TEST(Cli, ToolpathBadInputsExitTwoAndLeaveNoFile) {
  const std::string m = (scratch_dir() / "tp_bad_motion.json").string();
  ASSERT_EQ(run({"interpolate", test_data("poses/five_positions.json"), "-o", m}).status, 0);
  const std::string out = (scratch_dir() / "tp_bad.ngc").string();
  struct Case {
    std::vector<std::string> args;
    std::string needle;
  };
  const std::vector<Case> cases{
      {{"--axis", "0,0,0"}, "--axis"},
      {{"--chord-tol", "0"}, "--chord-tol"},
      {{"--chord-tol", "-1"}, "--chord-tol"},
      {{"--chord-tol", "1e99"}, "--chord-tol"},
      {{"--chord-tol", "0.01", "--rotary", "bc"}, "--rotary bc"},
      {{"--chord-tol", "0.01", "--angle-tol", "120"}, "--angle-tol"},
      {{"--chord-tol", "0.01", "--feed", "0"}, "--feed"},
      {{"--chord-tol", "0.01", "--nurbs", "--rotary", "ac"}, "--nurbs"},
      {{"--chord-tol", "0.01", "--nurbs", "--max-step", "2"}, "--max-step"},
      {{"--chord-tol", "0.01", "--arc-length"}, "--arc-length"},
  };
  for (const auto& c : cases) {
    std::vector<std::string> args{"toolpath", m, "--point", "1,2,3", "-o", out};
    if (c.args.front() != "--chord-tol") args.insert(args.end(), {"--chord-tol", "0.01"});
    args.insert(args.end(), c.args.begin(), c.args.end());
    const Result r = run(args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
  const Result fmt = run({"toolpath", m, "--point", "1,2,3", "--chord-tol", "0.01", "-o",
                          (scratch_dir() / "tp.gcode").string()});
  EXPECT_EQ(fmt.status, 2);
  EXPECT_NE(fmt.err.find(".ngc"), std::string::npos) << fmt.err;
  const std::string csv = (scratch_dir() / "tp_bad.csv").string();
  const Result nurbs_csv =
      run({"toolpath", m, "--point", "1,2,3", "--chord-tol", "0.01", "--nurbs", "-o", csv});
  EXPECT_EQ(nurbs_csv.status, 2);
  EXPECT_NE(nurbs_csv.err.find("--nurbs"), std::string::npos) << nurbs_csv.err;
  EXPECT_FALSE(fs::exists(csv));
}

/// Runs qmotion with stderr on a pseudo-terminal (stdout to /dev/null) and the progress
/// threshold at 0 s; returns what the terminal received.
std::string run_on_terminal(const std::vector<std::string>& args) {
  int master = -1, slave = -1;
  if (openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) return "(no pty)";
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(slave, 2);
    ::close(master);
    std::vector<char*> argv{const_cast<char*>(kExe.c_str())};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::setenv("QMOTION_PROGRESS_AFTER", "0", 1);
    ::execv(kExe.c_str(), argv.data());
    ::_exit(127);
  }
  ::close(slave);
  std::string out;
  char buf[4096];
  for (ssize_t n; (n = ::read(master, buf, sizeof buf)) > 0;)
    out.append(buf, static_cast<std::size_t>(n));
  ::close(master);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << out;
  return out;
}

TEST(Cli, ProgressBarsOnlyOnATerminalAndNotWithQuiet) {
  const std::string m = (scratch_dir() / "progress_motion.json").string();
  ASSERT_EQ(run({"interpolate", test_data("poses/helix_40.json"), "-o", m}).status, 0);
  const std::string out = (scratch_dir() / "progress.ngc").string();
  const std::vector<std::string> toolpath{"toolpath",    m,       "--point", "1,0,2",
                                          "--chord-tol", "0.001", "-o",      out};
  const std::string tty = run_on_terminal(toolpath);
  EXPECT_NE(tty.find("qmotion: toolpath ["), std::string::npos) << tty;
  EXPECT_NE(tty.find("%"), std::string::npos) << tty;
  // --quiet, before or after the command: no bar.
  std::vector<std::string> quiet{"--quiet"};
  quiet.insert(quiet.end(), toolpath.begin(), toolpath.end());
  EXPECT_EQ(run_on_terminal(quiet).find("qmotion: toolpath ["), std::string::npos);
  std::vector<std::string> quiet_after = toolpath;
  quiet_after.push_back("--quiet");
  EXPECT_EQ(run_on_terminal(quiet_after).find("qmotion: toolpath ["), std::string::npos);
  // STEP translation and meshing report too.
  const std::string step = run_on_terminal(
      {"sweep", m, "--profile", "circle:3", "-o", (scratch_dir() / "progress.step").string()});
  EXPECT_NE(step.find("qmotion: STEP translation ["), std::string::npos) << step;
  // Not a terminal: silent.
  const Result piped = run(toolpath);
  EXPECT_EQ(piped.err.find('\r'), std::string::npos) << piped.err;
}

TEST(Cli, ToolpathNurbsReportsItsCertifiedDeviation) {
  const std::string m = (scratch_dir() / "tpn_motion.json").string();
  ASSERT_EQ(run({"interpolate", test_data("poses/helix_40.json"), "-o", m}).status, 0);
  const std::string ngc = (scratch_dir() / "tpn.ngc").string();
  const Result r = run({"toolpath", m, "--point", "1,0,2", "--chord-tol", "0.001", "--nurbs",
                        "--feed", "600", "-o", ngc});
  ASSERT_EQ(r.status, 0) << r.err;
  const json report = json::parse(r.out);
  EXPECT_TRUE(report["nurbs"].get<bool>());
  EXPECT_LE(report["degree"].get<int>(), 3);
  EXPECT_LE(report["max_deviation_bound"].get<double>(), 0.001);
  EXPECT_LE(report["max_deviation_measured"].get<double>(),
            report["max_deviation_bound"].get<double>());
  EXPECT_NEAR(report["machining_time_min"].get<double>(), report["path_length"].get<double>() / 600,
              1e-12);
  std::ifstream f(ngc);
  std::size_t blocks = 0;
  for (std::string line; std::getline(f, line);) blocks += line.rfind("K", 0) == 0;
  EXPECT_EQ(blocks + 1, report["control_points"].get<std::size_t>() + 4);  // + the G06.2 block
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
  const Result check_exact = run({"check", "--exact", "--motion", ok});
  EXPECT_EQ(check_exact.status, 2);
  EXPECT_NE(check_exact.err.find("non-rational"), std::string::npos) << check_exact.err;
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
      {{d + "projective_inaccessible.json", "--rotation", "projective", "--exact"},
       3,
       "inaccessible"},
      {{test_data("poses/helix_40.json"), "--form", "bezier"}, 3, "--form bspline"},
      {{test_data("poses/five_positions.json"), "--exact"}, 2, "pose 1"},
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

/// Interpolates five_positions with the given methods into the scratch folder.
fs::path five_motion(const std::string& rot, const std::string& tr) {
  const fs::path m = scratch_dir() / ("five_" + rot + "_" + tr + ".json");
  const Result r = run({"interpolate", test_data("poses/five_positions.json"), "-o", m.string(),
                        "--rotation", rot, "--translation", tr});
  EXPECT_EQ(r.status, 0) << r.err;
  return m;
}

json check(const fs::path& file, const fs::path& motion, const std::vector<std::string>& what) {
  std::vector<std::string> args = {"check", file.string(), "--motion", motion.string()};
  args.insert(args.end(), what.begin(), what.end());
  return run_json(args);
}

TEST(Cli, TrajectoriesAndSurfacesAreExactInEveryFormat) {
  // A STEP profile made by qmotion itself: the trajectory of a point under another motion.
  const fs::path prof_step = scratch_dir() / "profile.step";
  ASSERT_EQ(run({"trajectory", kExamples + "/motions/bezier_tr.json", "--point", "3,1,0", "-o",
                 prof_step.string()})
                .status,
            0);
  const fs::path prof_igs = scratch_dir() / "profile.igs";
  ASSERT_EQ(run({"trajectory", kExamples + "/motions/bezier_tr.json", "--point", "3,1,0", "-o",
                 prof_igs.string()})
                .status,
            0);
  const std::vector<std::string> profiles = {test_data("profiles/parabola.json"),
                                             "circle:12",
                                             "arc:9,-30,120",
                                             "segment:-5,0,0:5,2,3",
                                             prof_step.string(),
                                             prof_igs.string()};
  for (const std::string rot : {"elliptic", "affine", "projective"})
    for (const std::string tr : {"tr", "trt", "minimal"}) {
      const fs::path m = five_motion(rot, tr);
      for (const std::string ext : {".json", ".step", ".igs"}) {
        SCOPED_TRACE(rot + "+" + tr + " " + ext);
        const fs::path c = scratch_dir() / ("traj" + ext);
        Result r = run({"trajectory", m.string(), "--point", "0,0,1", "-o", c.string()});
        ASSERT_EQ(r.status, 0) << r.err;
        json k = check(c, m, {"--point", "0,0,1"});
        EXPECT_LE(k["relative_deviation"].get<double>(), 1e-11);
        EXPECT_TRUE(k["weights_positive"].get<bool>());
        EXPECT_TRUE(k["param_range_matches_motion"].get<bool>());
        for (const auto& p : profiles) {
          const fs::path s = scratch_dir() / ("surf" + ext);
          r = run({"sweep", m.string(), "--profile", p, "-o", s.string()});
          ASSERT_EQ(r.status, 0) << p << ": " << r.err;
          k = check(s, m, {"--profile", p});
          EXPECT_LE(k["relative_deviation"].get<double>(), 1e-11) << p;
          EXPECT_TRUE(k["weights_positive"].get<bool>()) << p;
          EXPECT_TRUE(k["param_range_matches_motion"].get<bool>()) << p;
          EXPECT_GE(k["samples"].get<int>(), 400);
          if (ext != ".json") {
            EXPECT_TRUE(k["valid"].get<bool>()) << p;
            const std::string u = k["file_units"].get<std::string>();
            EXPECT_TRUE(u == "mm" || u == "millimetre") << u;
          }
        }
      }
    }
}

TEST(Cli, TrajectoryDegreesAreMinimal) {
  // Elliptic + TR through five poses: k = l = 4. Origin: l = 4; general point: 2k + l = 12.
  const fs::path m = five_motion("elliptic", "tr");
  const fs::path o = scratch_dir() / "origin.json", z = scratch_dir() / "z.json";
  ASSERT_EQ(run({"trajectory", m.string(), "--point", "0,0,0", "-o", o.string()}).status, 0);
  ASSERT_EQ(run({"trajectory", m.string(), "--point", "0,0,1", "-o", z.string()}).status, 0);
  EXPECT_EQ(json::parse(slurp(o))["degree"], 4);
  EXPECT_EQ(json::parse(slurp(z))["degree"], 12);
  // Minimal order: 2m = 8 for a general point, though the Q-motion has degree 3m = 12.
  const fs::path mm = five_motion("elliptic", "minimal");
  ASSERT_EQ(run({"trajectory", mm.string(), "--point", "0,0,1", "-o", z.string()}).status, 0);
  EXPECT_EQ(json::parse(slurp(z))["degree"], 8);
}

TEST(Cli, DegreesAboveTheCadLimitAreRefusedOrApproximatedOnRequest) {
  // Ten poses in one Bezier motion: a general point's trajectory has degree 2k + l = 27.
  const fs::path m = scratch_dir() / "helix10.json";
  ASSERT_EQ(
      run({"interpolate", kData + "/helix_10.json", "--form", "bezier", "-o", m.string()}).status,
      0);
  const fs::path step = scratch_dir() / "high.step";
  fs::remove(step);
  Result r = run({"trajectory", m.string(), "--point", "0,0,1", "-o", step.string()});
  EXPECT_EQ(r.status, 3);
  EXPECT_NE(r.err.find("degree 27"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--max-degree"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(step));
  // JSON has no such limit.
  const fs::path js = scratch_dir() / "high.json";
  ASSERT_EQ(run({"trajectory", m.string(), "--point", "0,0,1", "-o", js.string()}).status, 0);
  EXPECT_EQ(json::parse(slurp(js))["degree"], 27);
  // Rhino's 11 on request: an approximation within the stated tolerance, measured.
  r = run({"trajectory", m.string(), "--point", "0,0,1", "-o", step.string(), "--max-degree", "11",
           "--tol", "1e-6"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("approximated"), std::string::npos);
  json k = check(step, m, {"--point", "0,0,1"});
  EXPECT_EQ(k["degree_u"], 11);
  EXPECT_LE(k["max_deviation"].get<double>(), 1e-6);
  const fs::path sj = scratch_dir() / "high_surface.json";
  r = run({"sweep", m.string(), "--profile", "circle:5", "-o", sj.string(), "--max-degree", "11",
           "--tol", "1e-5"});
  ASSERT_EQ(r.status, 0) << r.err;
  const json sd = json::parse(slurp(sj));
  EXPECT_EQ(sd["degree_u"], 11);
  EXPECT_LE(sd["approximation"]["max_deviation"].get<double>(), 1e-5);
  // The stated tolerance holds for check's own, denser and random, samples too.
  k = check(sj, m, {"--profile", "circle:5"});
  EXPECT_LE(k["max_deviation"].get<double>(), 1e-5);
}

TEST(Cli, BadProfilesAndPolesLeaveNoFile) {
  const fs::path m = five_motion("elliptic", "tr");
  const std::string d = kData + "/profiles/";
  struct Case {
    std::vector<std::string> args;
    int status;
    std::string needle;
  };
  const json pole{{"type", "q-motion"},
                  {"basis", "bezier"},
                  {"degree", 1},
                  {"param_range", {0, 1}},
                  {"control_points", {{2, 0, 0, 0, 0, 0, 0, 0}, {-2, 0, 0, 0, 0, 0, 0, 0}}}};
  const fs::path pm = scratch_dir() / "pole_motion.json";
  std::ofstream(pm) << pole.dump();
  const std::vector<Case> cases = {
      {{"sweep", m.string(), "--profile", d + "negative_weight.json"}, 2, "positive"},
      {{"sweep", m.string(), "--profile", d + "no_curve.step"}, 2, "no_curve.step"},
      {{"sweep", m.string(), "--profile", d + "garbage.step"}, 2, "garbage.step"},
      {{"sweep", m.string(), "--profile", d + "absent.igs"}, 2, "absent.igs"},
      {{"sweep", m.string(), "--profile", "circle:0"}, 2, "radius"},
      {{"sweep", m.string(), "--profile", "square:3"}, 2, "--profile"},
      {{"sweep", pm.string(), "--profile", "circle:3"}, 3, "pole"},
      {{"trajectory", pm.string(), "--point", "1,2,3"}, 3, "pole"},
      {{"trajectory", m.string(), "--point", "1,2"}, 2, "--point"},
      // New kinds (shells, solids, units): each exit 2 naming what is wrong, or 3 for the
      // numerical refusal of a back-sweeping solid.
      {{"sweep", m.string(), "--profile", "arc:3,0,90", "--solid"}, 2, "open"},
      {{"sweep", m.string(), "--profile", "polyline:0,0,0:1,0,0:1,1,0", "--solid"}, 2, "open"},
      {{"sweep", m.string(), "--profile", "polyline:0,0,0:1,0,0:1,1,1:0,1,0:0,0,0", "--solid"},
       2,
       "planar"},
      {{"sweep", m.string(), "--profile", d + "wire_gap.json"}, 2, "gap"},
      {{"sweep", m.string(), "--profile", "rect:2"}, 2, "rect:2"},
      {{"sweep", m.string(), "--profile", "polyline:1,2,3"}, 2, "at least two points"},
      {{"sweep", m.string(), "--profile", "circle:3", "--units", "furlong"}, 2, "furlong"},
      {{"trajectory", m.string(), "--point", "1,2,3", "--units", "yd"}, 2, "unknown length unit"},
      {{"sweep", m.string(), "--profile", "circle:3", "--solid"}, 3, "sweeps back"},
      {{"sweep", m.string(), "--profile", "circle:3", "--max-degree", "0"}, 2, "--max-degree 0"},
      {{"trajectory", m.string(), "--point", "1,2,3", "--max-degree", "-5"}, 2, "at least 1"},
  };
  for (const std::string ext : {".json", ".step", ".igs"})
    for (const auto& c : cases) {
      const fs::path out = scratch_dir() / ("bad_out" + ext);
      fs::remove(out);
      std::vector<std::string> args = c.args;
      args.insert(args.end(), {"-o", out.string()});
      const Result r = run(args);
      EXPECT_EQ(r.status, c.status) << c.args[3] << ": " << r.err;
      EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.needle << " in: " << r.err;
      EXPECT_FALSE(fs::exists(out)) << c.args[3];
    }
  const Result wrong_ext =
      run({"sweep", m.string(), "--profile", "circle:3", "-o", (scratch_dir() / "x.dxf").string()});
  EXPECT_EQ(wrong_ext.status, 2);
  // Meshes: bad mesher options, and mesh options for a NURBS file.
  for (const auto& [args, needle] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--deflection", "0"}, "--deflection"},
           {{"--deflection", "-0.5"}, "--deflection"},
           {{"--angle", "0"}, "--angle"},
           {{"--angle", "120"}, "--angle"}}) {
    for (const std::string ext : {".stl", ".obj", ".ply"}) {
      const fs::path out = scratch_dir() / ("bad_mesh" + ext);
      std::vector<std::string> a{"sweep", m.string(), "--profile", "circle:3", "-o", out.string()};
      a.insert(a.end(), args.begin(), args.end());
      const Result r = run(a);
      EXPECT_EQ(r.status, 2) << r.err;
      EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
      EXPECT_FALSE(fs::exists(out));
    }
  }
  const Result mesh_option = run({"sweep", m.string(), "--profile", "circle:3", "--deflection",
                                  "0.1", "-o", (scratch_dir() / "x.step").string()});
  EXPECT_EQ(mesh_option.status, 2);
  EXPECT_NE(mesh_option.err.find("mesh output"), std::string::npos) << mesh_option.err;
  const Result both = run({"check", (scratch_dir() / "x.json").string(), "--motion", m.string()});
  EXPECT_EQ(both.status, 2);
}

TEST(Cli, SelfIntersectingSweepsAreFlagged) {
  // Sweeps that cross themselves, and clean ones: the mesh check (CGAL) must tell them apart.
  struct Case {
    std::string poses, profile;
    bool crosses;
  };
  const std::string d = "self_intersection/";
  const std::vector<Case> cases = {
      // A long segment turning by three quarters about an axis inside it (5 from one end):
      // near the axis the two sides sweep the same sector twice.
      {d + "turn270.json", "segment:-5,0,0:15,0,0", true},
      // The same segment turning by a half-turn about its midpoint covers the disk once.
      {d + "half_turn.json", "segment:-10,0,0:10,0,0", false},
      // A tube of radius 3 along a coil of pitch 2 (the coils overlap), and of pitch 20.
      {d + "coil_tight.json", "circle:3", true},
      {d + "coil_open.json", "circle:3", false},
      // A tube along a figure-eight crosses itself at the middle.
      {d + "figure8.json", "circle:3", true},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.poses);
    const fs::path m = scratch_dir() / "si_motion.json";
    ASSERT_EQ(run({"interpolate", test_data(c.poses), "-o", m.string()}).status, 0);
    const fs::path out = scratch_dir() / "si.step";
    fs::remove(out);
    const Result r = run({"sweep", m.string(), "--profile", c.profile, "-o", out.string()});
    EXPECT_EQ(r.status, 0) << r.err;  // a warning, the file is written
    EXPECT_EQ(r.err.find("intersects itself") != std::string::npos, c.crosses) << r.err;
    if (c.crosses) {
      EXPECT_NE(r.err.find("t in ["), std::string::npos) << r.err;
    }
    fs::remove(out);
    const Result f = run({"sweep", m.string(), "--profile", c.profile, "-o", out.string(),
                          "--fail-on-self-intersection"});
    EXPECT_EQ(f.status, c.crosses ? 3 : 0) << f.err;
    EXPECT_EQ(fs::exists(out), !c.crosses);
  }
  // --solid refuses a self-intersecting tube and accepts the clean one (no back-sweep in
  // either: the disk always moves along its normal).
  const fs::path m = scratch_dir() / "si_coil.json";
  for (const auto& [poses, ok] :
       {std::make_pair(d + "coil_tight.json", false), std::make_pair(d + "coil_open.json", true)}) {
    ASSERT_EQ(run({"interpolate", test_data(poses), "-o", m.string()}).status, 0);
    const fs::path out = scratch_dir() / "si_solid.step";
    fs::remove(out);
    const Result r =
        run({"sweep", m.string(), "--profile", "circle:3", "--solid", "-o", out.string()});
    EXPECT_EQ(r.status, ok ? 0 : 3) << poses << ": " << r.err;
    if (!ok) {
      EXPECT_NE(r.err.find("bounds no solid"), std::string::npos) << r.err;
    }
    EXPECT_EQ(fs::exists(out), ok);
  }
}

TEST(Cli, DamagedCadFilesAreRefusedNotCrashedOn) {
  // Each of these once crashed qmotion inside OpenCASCADE's readers (SIGSEGV): mutated
  // STEP/IGES files written by `qmotion trajectory`, and one whose entity name lost a letter
  // and whose B-spline line was cut. Now each is bad input, whichever command reads it.
  const fs::path m = five_motion("elliptic", "tr");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(kData + "/damaged_cad")) files.push_back(e.path());
  ASSERT_GE(files.size(), 12u);
  for (const auto& f : files) {
    const fs::path out = scratch_dir() / "damaged_out.step";
    fs::remove(out);
    for (const auto& args : {std::vector<std::string>{"sweep", m.string(), "--profile", f.string(),
                                                      "-o", out.string()},
                             std::vector<std::string>{"check", f.string(), "--motion", m.string(),
                                                      "--point", "1,2,3"}}) {
      const Result r = run(args);
      EXPECT_EQ(r.status, 2) << args[0] << " " << f << ": " << r.err;
      EXPECT_NE(r.err.find(f.string()), std::string::npos) << r.err;
      EXPECT_NE(r.err.find("damaged"), std::string::npos) << r.err;
      EXPECT_FALSE(fs::exists(out)) << f;
    }
  }
}

/// Multiplicity of each distinct interior knot of a clamped vector.
std::map<double, int> interior_multiplicities(const json& knots, int degree) {
  std::map<double, int> m;
  const std::size_t n = knots.size();
  for (std::size_t i = static_cast<std::size_t>(degree) + 1; i + degree + 1 < n; ++i)
    ++m[knots[i].get<double>()];
  return m;
}

TEST(Cli, CheckReadsTheWeightsOfJsonCurvesAndSurfaces) {
  const fs::path m = five_motion("elliptic", "tr");
  for (const bool surface : {false, true}) {
    const fs::path js = scratch_dir() / (surface ? "w_surface.json" : "w_curve.json");
    const std::vector<std::string> what = surface
                                              ? std::vector<std::string>{"--profile", "circle:3"}
                                              : std::vector<std::string>{"--point", "1,2,3"};
    std::vector<std::string> args = {
        surface ? "sweep" : "trajectory", m.string(), what[0], what[1], "-o", js.string()};
    ASSERT_EQ(run(args).status, 0);
    EXPECT_TRUE(check(js, m, what)["weights_positive"].get<bool>());
    // The same file with one weight made negative is refused, naming the weight.
    json doc = json::parse(slurp(js));
    if (surface) {
      doc["weights"][1][1] = -0.5;
    } else {
      doc["weights"][1] = -0.5;
    }
    std::ofstream(js) << doc.dump();
    const Result r = run({"check", js.string(), "--motion", m.string(), what[0], what[1]});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("weights[1]"), std::string::npos) << r.err;
  }
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

TEST(Cli, SplineExportsCarryTheMotionsContinuityInTheirKnots) {
  // Each exported knot has multiplicity degree - c, c the continuity there of the factors
  // that have that knot (rotation C^(K-1), translation C^(L-1); c1: both C1): never less
  // than the motion's C^(min(K,L)-1), and the export stays exact.
  const fs::path m = scratch_dir() / "cont_motion.json";
  struct Form {
    std::vector<std::string> args;
    int k, l, factor_continuity_r, factor_continuity_t;
  };
  const std::vector<Form> forms = {{{"--degree", "3", "--translation-degree", "3"}, 3, 3, 2, 2},
                                   {{"--degree", "2", "--translation-degree", "4"}, 2, 4, 1, 3},
                                   {{"--degree", "4", "--translation-degree", "3"}, 4, 3, 3, 2},
                                   {{"--degree", "5", "--translation-degree", "2"}, 5, 2, 4, 1},
                                   {{"--form", "c1"}, 3, 3, 1, 1}};
  for (const auto& form : forms) {
    SCOPED_TRACE(form.args[1]);
    std::vector<std::string> args = {"interpolate", test_data("poses/helix_40.json"), "-o",
                                     m.string()};
    args.insert(args.end(), form.args.begin(), form.args.end());
    ASSERT_EQ(run(args).status, 0);
    const json motion = json::parse(slurp(m));
    const auto rot = interior_multiplicities(motion["method"]["rotation_knots"], form.k);
    const auto tra = interior_multiplicities(motion["method"]["translation_knots"], form.l);
    const int motion_continuity = std::min(form.factor_continuity_r, form.factor_continuity_t);
    const fs::path c = scratch_dir() / "cont_curve.json", s = scratch_dir() / "cont_surf.json";
    ASSERT_EQ(run({"trajectory", m.string(), "--point", "1,2,3", "-o", c.string()}).status, 0);
    ASSERT_EQ(run({"sweep", m.string(), "--profile", test_data("profiles/parabola.json"), "-o",
                   s.string()})
                  .status,
              0);
    const json curve = json::parse(slurp(c)), surf = json::parse(slurp(s));
    EXPECT_EQ(curve["continuity"], motion_continuity);
    EXPECT_EQ(surf["continuity"][0], motion_continuity);
    for (const auto& [knots, degree] :
         {std::make_pair(curve["knots"], curve["degree"].get<int>()),
          std::make_pair(surf["knots_u"], surf["degree_u"].get<int>())}) {
      const auto mult = interior_multiplicities(knots, degree);
      ASSERT_FALSE(mult.empty());
      for (const auto& [x, mu] : mult) {
        int cont = std::numeric_limits<int>::max();
        if (rot.count(x)) cont = std::min(cont, form.k - rot.at(x));
        if (tra.count(x)) cont = std::min(cont, form.l - tra.at(x));
        ASSERT_NE(cont, std::numeric_limits<int>::max()) << "a knot of neither factor: " << x;
        EXPECT_EQ(mu, degree - cont) << "knot " << x;
        EXPECT_LE(mu, degree - motion_continuity);
      }
    }
    EXPECT_LE(check(c, m, {"--point", "1,2,3"})["relative_deviation"].get<double>(), 1e-11);
    EXPECT_LE(check(s, m, {"--profile", test_data("profiles/parabola.json")})["relative_deviation"]
                  .get<double>(),
              1e-11);
  }
  // helix_40, default B-spline motion: the trajectory of (1,2,3) has degree 9 and C2 knots:
  // 40 poses, 36 interior knots of multiplicity 7, so 10 + 36 * 7 = 262 poles.
  ASSERT_EQ(run({"interpolate", test_data("poses/helix_40.json"), "-o", m.string()}).status, 0);
  const fs::path c = scratch_dir() / "helix_curve.json";
  ASSERT_EQ(run({"trajectory", m.string(), "--point", "1,2,3", "-o", c.string()}).status, 0);
  EXPECT_EQ(json::parse(slurp(c))["control_points"].size(), 262u);
}

TEST(Cli, ShellsSolidsAndUnitsReadBackExactly) {
  const fs::path screw = scratch_dir() / "screw_motion.json";
  ASSERT_EQ(run({"interpolate", test_data("poses/screw_three.json"), "-o", screw.string()}).status,
            0);
  const fs::path five = five_motion("elliptic", "tr");
  // circle:3 has C0 joints: four faces in STEP/IGES, one with --single-face; a rect gives
  // four faces (one per edge); all read back exact, covering the profile.
  struct Case {
    fs::path motion;
    std::string profile;
    std::vector<std::string> extra;
    int faces, planar;
    bool solid;
  };
  const std::vector<Case> cases = {{five, "circle:3", {}, 4, 0, false},
                                   {five, "circle:3", {"--single-face"}, 1, 0, false},
                                   {screw, "rect:4,2", {}, 4, 0, false},
                                   {screw, "polyline:0,0,0:3,0,0:3,2,0", {}, 2, 0, false},
                                   {screw, "circle:3", {"--solid"}, 4, 2, true},
                                   {screw, "rect:4,2", {"--solid"}, 4, 2, true}};
  for (const auto& c : cases) {
    for (const std::string ext : {".step", ".igs", ".json"}) {
      SCOPED_TRACE(c.profile + (c.extra.empty() ? "" : " " + c.extra[0]) + ext);
      const fs::path out = scratch_dir() / ("shell" + ext);
      std::vector<std::string> args = {"sweep", c.motion.string(), "--profile", c.profile,
                                       "-o",    out.string()};
      args.insert(args.end(), c.extra.begin(), c.extra.end());
      const Result r = run(args);
      ASSERT_EQ(r.status, 0) << r.err;
      const json k = check(out, c.motion, {"--profile", c.profile});
      EXPECT_LE(k["relative_deviation"].get<double>(), 1e-11);
      EXPECT_TRUE(k["faces_cover_profile"].get<bool>());
      EXPECT_TRUE(k["weights_positive"].get<bool>());
      if (ext == ".json") continue;
      EXPECT_TRUE(k["valid"].get<bool>());
      EXPECT_EQ(k["checked_faces"], c.faces);
      EXPECT_EQ(k["planar_faces"], c.planar);
      EXPECT_EQ(k["closed"].get<bool>(), c.solid);
      if (c.solid && ext == ".step") {
        EXPECT_EQ(k["solids"], 1);
        // The independent volume (motion alone) against OpenCASCADE's of the written solid.
        const fs::path js = scratch_dir() / "solid.json";
        args[5] = js.string();
        ASSERT_EQ(run(args).status, 0);
        const double v = json::parse(slurp(js))["volume"].get<double>();
        EXPECT_NEAR(k["volume"].get<double>(), v, 1e-6 * v);
        EXPECT_NE(slurp(out).find("MANIFOLD_SOLID_BREP"), std::string::npos);
      }
    }
  }
  // --units converts: the same geometry in inches and metres (numbers scaled, unit
  // declared), and check compares in the file's unit.
  const fs::path mm = scratch_dir() / "u_mm.json";
  ASSERT_EQ(run({"sweep", five.string(), "--profile", "circle:3", "-o", mm.string()}).status, 0);
  const json base = json::parse(slurp(mm));
  std::map<std::string, double> mm_diagonal;  // per format, of the same samples
  for (const std::string ext : {".step", ".igs"}) {
    const fs::path cad = scratch_dir() / ("u_mm" + ext);
    ASSERT_EQ(run({"sweep", five.string(), "--profile", "circle:3", "-o", cad.string()}).status, 0);
    mm_diagonal[ext] = check(cad, five, {"--profile", "circle:3"})["bbox_diagonal"].get<double>();
  }
  for (const auto& [unit, per_mm] :
       {std::make_pair(std::string("in"), 1 / 25.4), std::make_pair(std::string("m"), 1e-3),
        std::make_pair(std::string("um"), 1e3)}) {
    SCOPED_TRACE(unit);
    const fs::path js = scratch_dir() / ("u." + unit + ".json");
    ASSERT_EQ(
        run({"sweep", five.string(), "--profile", "circle:3", "--units", unit, "-o", js.string()})
            .status,
        0);
    const json doc = json::parse(slurp(js));
    EXPECT_EQ(doc["units"], unit);
    const double x0 = base["control_points"][3][2][0].get<double>();
    EXPECT_NEAR(doc["control_points"][3][2][0].get<double>(), x0 * per_mm,
                1e-15 * std::abs(x0 * per_mm));
    const json k = check(js, five, {"--profile", "circle:3"});
    EXPECT_EQ(k["units"], unit);
    EXPECT_LE(k["relative_deviation"].get<double>(), 1e-11);
    for (const std::string ext : {".step", ".igs"}) {
      const fs::path cad = scratch_dir() / ("u" + ext);
      ASSERT_EQ(run({"sweep", five.string(), "--profile", "circle:3", "--units", unit, "-o",
                     cad.string()})
                    .status,
                0);
      const json kc = check(cad, five, {"--profile", "circle:3"});
      EXPECT_EQ(kc["units"], unit) << ext;
      EXPECT_LE(kc["relative_deviation"].get<double>(), 1e-11) << ext;
      // Reported in the file's unit: the millimetre file's size, converted.
      EXPECT_NEAR(kc["bbox_diagonal"].get<double>(), mm_diagonal[ext] * per_mm,
                  1e-9 * mm_diagonal[ext] * per_mm);
    }
  }
  // The micro sign is read as um.
  const fs::path micro = scratch_dir() / "u_micro.json";
  ASSERT_EQ(run({"sweep", five.string(), "--profile", "circle:3", "--units", "\xC2\xB5m", "-o",
                 micro.string()})
                .status,
            0);
  EXPECT_EQ(json::parse(slurp(micro))["units"], "um");
  // A trajectory in inches: the numbers are the millimetre numbers / 25.4.
  const fs::path tmm = scratch_dir() / "t_mm.json", tin = scratch_dir() / "t_in.json";
  ASSERT_EQ(run({"trajectory", five.string(), "--point", "1,2,3", "-o", tmm.string()}).status, 0);
  ASSERT_EQ(
      run({"trajectory", five.string(), "--point", "1,2,3", "--units", "in", "-o", tin.string()})
          .status,
      0);
  const json a = json::parse(slurp(tmm)), b = json::parse(slurp(tin));
  ASSERT_EQ(a["control_points"].size(), b["control_points"].size());
  for (std::size_t i = 0; i < a["control_points"].size(); ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(b["control_points"][i][j].get<double>() * 25.4,
                  a["control_points"][i][j].get<double>(), 1e-12 * 200);
  EXPECT_LE(check(tin, five, {"--point", "1,2,3"})["relative_deviation"].get<double>(), 1e-11);
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
  // Exact B-spline motion from rational input.
  r = run({"interpolate", test_data("poses/rational_exact.json"), "--form", "bspline", "--exact",
           "-o", m.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  i = run_json({"info", "--exact", m.string()});
  EXPECT_EQ(i["plucker_residual"], 0.0);
  for (const auto& x : i["interpolation_residual"]) EXPECT_EQ(x.get<double>(), 0.0);
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

TEST(Cli, DemoWritesEveryFormatAndAnExactnessReport) {
  const fs::path dir = scratch_dir() / "demo";
  fs::remove_all(dir);
  const Result r = run({"demo", "-o", dir.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json report = json::parse(r.out);
  ASSERT_EQ(report["exactness"].size(), 9u);  // 2 trajectories + 1 surface, x JSON, STEP, IGES
  for (const auto& c : report["exactness"]) {
    EXPECT_LE(c["relative_deviation"].get<double>(), 1e-11) << c["file"];
    EXPECT_TRUE(c["weights_positive"].get<bool>());
    EXPECT_TRUE(fs::exists(dir / c["file"].get<std::string>()));
  }
  for (const char* f :
       {"motion.json", "demo.svg", "report.json", "surface_parabola.step", "surface_parabola.igs"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  // The figure by the renderer: five numbered key poses, two trajectories, the swept
  // parabola.
  const std::string svg = slurp(dir / "demo.svg");
  auto count = [&](const std::string& needle) {
    std::size_t n = 0;
    for (auto p = svg.find(needle); p != std::string::npos; p = svg.find(needle, p + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("class=\"key-marker\""), 5u);
  EXPECT_EQ(count("class=\"trajectory\""), 2u);
  EXPECT_GT(count("class=\"surface\""), 100u);
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_NE(e.path().filename().string().rfind(".qmotion", 0), 0u);
}

TEST(Cli, DemoWritesAllItsFilesOrNone) {
  // A folder where the demo must write a file: exit 2, and the folder holds what it held.
  const fs::path dir = scratch_dir() / "demo_blocked";
  fs::remove_all(dir);
  fs::create_directories(dir / "surface_parabola.step");
  std::ofstream(dir / "mine.txt") << "the user's";
  const Result r = run({"demo", "-o", dir.string()});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("surface_parabola.step"), std::string::npos) << r.err;
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"mine.txt", "surface_parabola.step"}));
  for (const auto& e : fs::directory_iterator(scratch_dir()))
    EXPECT_EQ(e.path().filename().string().find(".qmotion-demo"), std::string::npos);
  // Into a folder that exists, with a trailing slash: every file, the user's kept.
  fs::remove_all(dir / "surface_parabola.step");
  ASSERT_EQ(run({"demo", "-o", dir.string() + "/"}).status, 0);
  EXPECT_TRUE(fs::exists(dir / "mine.txt"));
  EXPECT_TRUE(fs::exists(dir / "surface_parabola.step"));
}

TEST(Cli, RenderAndPlotWriteFiguresAndRefuseBadOptions) {
  const fs::path motion = scratch_dir() / "render_motion.json";
  ASSERT_EQ(
      run({"interpolate", kData + "/poses/five_positions.json", "-o", motion.string()}).status, 0);
  const fs::path svg = scratch_dir() / "render.svg", png = scratch_dir() / "plot.png";
  fs::remove(svg);
  fs::remove(png);
  Result r = run({"render", motion.string(), "-o", svg.string(), "--point", "0,0,0", "--point",
                  "0,0,20", "--profile", "segment:0,0,0:0,0,10", "--view", "front", "--size",
                  "640,480", "--frames", "4"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("640x480, 2 trajectories, 4 instants, 5 key poses, swept surface"),
            std::string::npos)
      << r.err;
  EXPECT_NE(slurp(svg).find("width=\"640\" height=\"480\""), std::string::npos);
  r = run({"plot", motion.string(), "-o", png.string(), "--quantity", "angular-speed", "--compare",
           motion.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(png));
  EXPECT_NE(r.err.find("max"), std::string::npos);
  // Bad input: exit 2 naming the option, nothing written.
  const fs::path out = scratch_dir() / "refused.svg";
  const std::vector<std::pair<std::vector<std::string>, std::string>> bad = {
      {{"render", motion.string(), "-o", out.string(), "--view", "diagonal"}, "--view diagonal"},
      {{"render", motion.string(), "-o", out.string(), "--size", "0,480"}, "--size 0,480"},
      {{"render", motion.string(), "-o", out.string(), "--size", "640"}, "--size 640"},
      {{"render", motion.string(), "-o", out.string(), "--frames", "-3"}, "--frames -3"},
      {{"render", motion.string(), "-o", out.string(), "--point", "1,2"}, "--point"},
      {{"render", motion.string(), "-o", out.string(), "--object", "nothing.stl"}, "nothing.stl"},
      {{"render", motion.string(), "-o", (scratch_dir() / "refused.pdf").string()}, ".svg or .png"},
      {{"render", (scratch_dir() / "no_motion.json").string(), "-o", out.string()},
       "no_motion.json"},
      {{"plot", motion.string(), "-o", out.string(), "--quantity", "jerk"}, "--quantity jerk"},
      {{"plot", motion.string(), "-o", out.string(), "--quantity", "speed", "--size", "10,10"},
       "--size 10,10"},
  };
  for (const auto& [args, needle] : bad) {
    fs::remove(out);
    r = run(args);
    EXPECT_EQ(r.status, 2) << needle << ": " << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << needle;
  }
  // Motions of different units on one plot.
  const fs::path inches = scratch_dir() / "render_motion_in.json";
  std::string doc = slurp(motion);
  for (auto u = doc.find("\"units\": \"mm\""); u != std::string::npos;
       u = doc.find("\"units\": \"mm\"", u))
    doc.replace(u, 13, "\"units\": \"in\"");
  std::ofstream(inches) << doc;
  fs::remove(out);
  r = run({"plot", motion.string(), "--compare", inches.string(), "-o", out.string(), "--quantity",
           "speed"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("its unit in differs from the first motion's (mm)"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace qmotion::test
