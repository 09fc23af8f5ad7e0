// tests/cli/verify_cad_test.cpp: `qmotion verify` with STEP solids for the part and a
// fixture (docs/guide/verify.md, "Parts"): tests/data/verify/plate_boss.step is plate.obj's
// plate with a cylindrical boss r = 10 about (30, 30) up to z = 5, and clamp.step the box
// box:22,-5,-10,30,5,5, both written by FreeCAD.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <string>

#include "cli_util.hpp"

namespace qmotion::test {
namespace {

json verify_args(std::vector<std::string> args) {
  args.insert(args.begin(), "verify");
  return run_json(args);
}

/// The plate's faces are planes, so its mesh is exact: offsets.ngc names the blocks the mesh
/// plate's run names, each with an interval at most T wide that holds its offset. The boss's
/// side is a cylinder meshed within T / 4: a cut entering it by 0.2 mm is found within
/// T + T / 4.
TEST(VerifyCad, AStepPartHasTheMeshPartsGougesAndItsCurvedFacesWithinTheDeflection) {
  const double tol = 0.004;
  const std::map<std::size_t, double> depth = {{4, 0.005}, {5, 0.005}, {6, 0.05},
                                               {7, 0.05},  {8, 0.5},   {9, 0.5}};
  const json step =
      verify_args({test_data("verify/offsets.ngc"), "--tool", "cutter:ball,6,30", "--part",
                   test_data("verify/plate_boss.step"), "--tol", std::to_string(tol)});
  const json mesh =
      verify_args({test_data("verify/offsets.ngc"), "--tool", "cutter:ball,6,30", "--part",
                   test_data("verify/plate.obj"), "--tol", std::to_string(tol)});
  EXPECT_DOUBLE_EQ(step["cad_deflection"].get<double>(), tol / 4);
  EXPECT_FALSE(mesh.contains("cad_deflection"));
  const json& a = step["gouge"]["moves"];
  const json& b = mesh["gouge"]["moves"];
  ASSERT_EQ(a.size(), b.size()) << step.dump();
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i]["block"], b[i]["block"]);
    const double d = depth.at(a[i]["block"].get<std::size_t>());
    EXPECT_LE(a[i]["depth"][0].get<double>(), d);
    EXPECT_GE(a[i]["depth"][1].get<double>(), d);
    EXPECT_LE(a[i]["depth"][1].get<double>() - a[i]["depth"][0].get<double>(), tol);
  }
  const json side =
      verify_args({test_data("verify/boss_side.ngc"), "--tool", "cutter:flat,6,30", "--part",
                   test_data("verify/plate_boss.step"), "--tol", std::to_string(tol)})["gouge"];
  ASSERT_EQ(side["moves"].size(), 1u) << side.dump();
  EXPECT_EQ(side["moves"][0]["line"], 8);
  const double lo = side["depth"][0], hi = side["depth"][1];
  EXPECT_LE(hi - lo, tol);
  EXPECT_LE(lo, 0.2 + 1e-9);  // the mesh's boss lies inside the cylinder
  EXPECT_GE(hi, 0.2 - tol / 4);
  EXPECT_NEAR(side["deepest"]["point"][1].get<double>(), 39.8, 0.01);
}

/// clamp.step is the box of VerifyCollide.AFixtureTouchedAndAFixtureCleared: the cut meets
/// it at the same instant, t = 49/60.
TEST(VerifyCad, AStepFixtureIsMetWhereItsBoxIs) {
  const fs::path ngc = scratch_dir() / "cad_fixture.ngc";
  std::ofstream(ngc) << "G21 G90 G17\nG0 Z20\nG0 X-30 Y0\nG1 Z-5 F500\nG1 X30\nM2\n";
  const json f = verify_args({ngc.string(), "--tool", "cutter:flat,6,10", "--part",
                              test_data("verify/plate.obj"), "--fixture",
                              test_data("verify/clamp.step"), "--tol", "0.01"});
  const json& first = f["collisions"]["fixtures"]["first"];
  ASSERT_FALSE(first.is_null()) << f.dump(1);
  EXPECT_EQ(first["block"], 3);
  EXPECT_LE(first["t"][0].get<double>(), 49.0 / 60 + 1e-12);
  EXPECT_GE(first["t"][1].get<double>(), 49.0 / 60 - 1e-12);
  EXPECT_DOUBLE_EQ(f["cad_deflection"].get<double>(), 0.0025);
}

}  // namespace
}  // namespace qmotion::test
