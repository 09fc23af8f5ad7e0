// tests/cli/export_test.cpp: the program, run as a user runs it: `qmotion trajectory`, `qmotion
// sweep` and `qmotion check`.
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

/// Interpolates five_positions with the given methods into the scratch folder.
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

#ifdef QMOTION_WITH_CGAL
TEST(Cli, SelfIntersectingSweepsAreFlagged) {
  // Sweeps that cross themselves, and clean ones. The mesh check (CGAL) warns of crossings it
  // sees; --fail-on-self-intersection and --solid also run the proof on the exact surfaces,
  // which sees what the mesh misses.
  struct Case {
    std::string poses, profile;
    bool mesh_sees, refused;
  };
  const std::string d = "self_intersection/";
  const std::vector<Case> cases = {
      // A long segment turning by three quarters about an axis inside it (5 from one end):
      // near the axis the two sides sweep the same sector twice.
      {d + "turn270.json", "segment:-5,0,0:15,0,0", true, true},
      // The same segment turning by a half-turn about its midpoint covers the disk once; its
      // still midpoint is singular, not proven: refused under the flag.
      {d + "half_turn.json", "segment:-10,0,0:10,0,0", false, true},
      // A tube of radius 3 along a coil of pitch 2 (the coils overlap), and of pitch 20.
      {d + "coil_tight.json", "circle:3", true, true},
      {d + "coil_open.json", "circle:3", false, false},
      // Pitch 6.02764: the turns overlap by about 1e-5, finer than the tessellation.
      {d + "coil_touching.json", "circle:3", false, true},
      // A tube along a figure-eight crosses itself at the middle.
      {d + "figure8.json", "circle:3", true, true},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.poses);
    const fs::path m = scratch_dir() / "si_motion.json";
    ASSERT_EQ(run({"interpolate", test_data(c.poses), "-o", m.string()}).status, 0);
    const fs::path out = scratch_dir() / "si.step";
    fs::remove(out);
    const Result r = run({"sweep", m.string(), "--profile", c.profile, "-o", out.string()});
    EXPECT_EQ(r.status, 0) << r.err;  // a warning, the file is written
    EXPECT_EQ(r.err.find("intersects itself") != std::string::npos, c.mesh_sees) << r.err;
    if (c.mesh_sees) {
      EXPECT_NE(r.err.find("t in ["), std::string::npos) << r.err;
    }
    fs::remove(out);
    const Result f = run({"sweep", m.string(), "--profile", c.profile, "-o", out.string(),
                          "--fail-on-self-intersection"});
    EXPECT_EQ(f.status, c.refused ? 3 : 0) << f.err;
    EXPECT_EQ(fs::exists(out), !c.refused);
    if (!c.mesh_sees && c.refused) {
      EXPECT_TRUE(f.err.find("touches itself") != std::string::npos ||
                  f.err.find("crosses itself") != std::string::npos ||
                  f.err.find("singular near t in [") != std::string::npos)
          << f.err;
    }
    if (!c.refused) {
      EXPECT_NE(f.err.find("the sweep is proven free"), std::string::npos) << f.err;
    }
  }
  // --solid refuses a tube that is not proven free of self-intersection, whether the mesh
  // sees it or not, and accepts the clean one (no back-sweep in any: the disk always moves
  // along its normal).
  const fs::path m = scratch_dir() / "si_coil.json";
  for (const auto& [poses, ok] : {std::make_pair(d + "coil_tight.json", false),
                                  std::make_pair(d + "coil_touching.json", false),
                                  std::make_pair(d + "coil_open.json", true)}) {
    ASSERT_EQ(run({"interpolate", test_data(poses), "-o", m.string()}).status, 0);
    const fs::path out = scratch_dir() / "si_solid.step";
    fs::remove(out);
    const Result r =
        run({"sweep", m.string(), "--profile", "circle:3", "--solid", "-o", out.string()});
    EXPECT_EQ(r.status, ok ? 0 : 3) << poses << ": " << r.err;
    if (!ok) {
      EXPECT_NE(r.err.find("bounds no solid"), std::string::npos) << r.err;
    } else {
      EXPECT_NE(r.err.find("the sweep is proven free of self-intersection"), std::string::npos)
          << r.err;
    }
    EXPECT_EQ(fs::exists(out), ok);
  }
}
#endif

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

/// Runs the program with files limited to `blocks` of 512 bytes and SIGXFSZ ignored, so that
/// a write past the limit fails with EFBIG part-way, as on a full disk.
Result run_with_file_limit(const std::vector<std::string>& args, int blocks) {
  const fs::path out = scratch_dir() / "limited_stdout", err = scratch_dir() / "limited_stderr";
  std::string cmd = "sh -c 'trap \"\" XFSZ; ulimit -f " + std::to_string(blocks) +
                    "; exec \"$0\" \"$@\"' " + quote(kExe);
  for (const auto& a : args) cmd += " " + quote(a);
  cmd += " >" + quote(out.string()) + " 2>" + quote(err.string()) + " </dev/null";
  const int raw = std::system(cmd.c_str());
  return Result{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), slurp(err)};
}

TEST(Cli, AWriteThatFailsPartWayLeavesNoFile) {
  const fs::path dir = scratch_dir() / "write_failure";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string m = (dir / "m.json").string();
  ASSERT_EQ(run({"interpolate", test_data("poses/helix_40.json"), "-o", m}).status, 0);
  // Each output is far larger than 4 KB: STEP and IGES through OpenCASCADE's printer, JSON
  // and G-code through qmotion's own writer.
  const std::vector<std::vector<std::string>> jobs{
      {"sweep", m, "--profile", "circle:3", "-o", (dir / "tube.step").string()},
      {"sweep", m, "--profile", "circle:3", "-o", (dir / "tube.igs").string()},
      {"sweep", m, "--profile", "circle:3", "-o", (dir / "tube.json").string()},
      {"toolpath", m, "--point", "1,0,2", "--chord-tol", "0.01", "-o", (dir / "tp.ngc").string()}};
  for (const auto& args : jobs) {
    const std::string target = args.back();
    SCOPED_TRACE(target);
    const Result r = run_with_file_limit(args, 8);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(target), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(target));
    // Nothing else either: no temporary file beside it.
    for (const auto& e : fs::directory_iterator(dir))
      EXPECT_EQ(e.path().filename(), "m.json") << "left behind: " << e.path();
    // Without the limit the same job writes its file (the limit is what failed it).
    ASSERT_EQ(run(args).status, 0);
    EXPECT_GT(fs::file_size(target), 8u * 512u);
    fs::remove(target);
  }
}

}  // namespace
}  // namespace qmotion::test
