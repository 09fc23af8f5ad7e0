// tests/cli/verify_test.cpp: `qmotion verify`: its G-code reader against LinuxCNC's rs274,
// and the gouges it certifies against depths worked out by hand (tests/data/verify).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <qmotion/io/bodies.hpp>
#include <qmotion/io/gcode.hpp>
#include <string>
#include <vector>

#include "cli_util.hpp"
#include "rs274_util.hpp"

namespace qmotion::test {
namespace {

/// The canonical moves of the reader equal rs274's, to its four printed decimals.
TEST(Verify, ReaderMovesEqualLinuxCncs) {
  for (const std::string name : {"reader", "offsets", "clear", "dip", "arc_dip", "rotary"}) {
    const std::string ngc = test_data("verify/" + name + ".ngc");
    const auto log = rs274_log(ngc);
    RS274_OR_SKIP(log);
    const std::vector<CanonMove> canon = canonical_moves(*log);
    const cam::Program p = io::read_gcode(ngc);
    ASSERT_EQ(p.moves.size(), canon.size()) << name << "\n" << *log;
    for (std::size_t i = 0; i < canon.size(); ++i) {
      const cam::Move& m = p.moves[i];
      const CanonMove& c = canon[i];
      const std::string at = name + " move " + std::to_string(i) + " " + c.kind;
      const double eps = 6e-5;  // rs274 prints four decimals in its unit
      if (c.kind == "ARC_FEED") {
        ASSERT_EQ(m.kind, cam::Move::Kind::arc) << at;
        ASSERT_EQ(m.plane, c.plane) << at;
        const auto [u, v, w] = cam::plane_axes(m.plane);
        EXPECT_NEAR(m.to(u) / c.unit, c.v[0], eps) << at;
        EXPECT_NEAR(m.to(v) / c.unit, c.v[1], eps) << at;
        EXPECT_NEAR(m.centre(u) / c.unit, c.v[2], eps) << at;
        EXPECT_NEAR(m.centre(v) / c.unit, c.v[3], eps) << at;
        EXPECT_EQ(m.turns, static_cast<int>(c.v[4])) << at;
        EXPECT_NEAR(m.to(w) / c.unit, c.v[5], eps) << at;
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(m.abc_to[static_cast<std::size_t>(k)], c.v[6 + static_cast<std::size_t>(k)],
                      eps)
              << at;
      } else {
        EXPECT_EQ(m.kind,
                  c.kind == "STRAIGHT_TRAVERSE" ? cam::Move::Kind::traverse : cam::Move::Kind::feed)
            << at;
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(m.to(k) / c.unit, c.v[static_cast<std::size_t>(k)], eps) << at;
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(m.abc_to[static_cast<std::size_t>(k)], c.v[3 + static_cast<std::size_t>(k)],
                      eps)
              << at;
      }
    }
  }
}

json verify(const std::string& program, const std::string& tool, const std::string& part,
            double tol) {
  const fs::path report = scratch_dir() / "verify.json";
  fs::remove(report);
  const json out =
      run_json({"verify", test_data("verify/" + program), "--tool", tool, "--part",
                test_data("verify/" + part), "--tol", std::to_string(tol), "-o", report.string()});
  EXPECT_EQ(json::parse(slurp(report)), out);  // the report written is the one printed
  return out;
}

/// offsets.ngc's moves go into the plate by 0.005, 0.05 and 0.5 mm: each is found, named,
/// and its depth bounded to within the tolerance, for every kind of cutter.
TEST(Verify, GougesFoundAndNamedAtEachDepth) {
  const std::map<std::size_t, double> depth = {{4, 0.005}, {5, 0.005}, {6, 0.05},
                                               {7, 0.05},  {8, 0.5},   {9, 0.5}};
  for (const std::string tool : {"cutter:ball,6,30", "cutter:flat,8,30", "cutter:bull,10,2,30"}) {
    const double tol = 0.001;
    const json r = verify("offsets.ngc", tool, "plate.obj", tol);
    const json& g = r["gouge"];
    EXPECT_TRUE(g["certified"].get<bool>()) << tool;
    EXPECT_FALSE(g["within_tolerance"].get<bool>()) << tool;
    EXPECT_LE(g["depth"][0].get<double>(), 0.5) << tool;
    EXPECT_GE(g["depth"][1].get<double>(), 0.5) << tool;
    const std::size_t deepest = g["deepest"]["block"];
    EXPECT_TRUE(deepest == 8 || deepest == 9) << tool;
    EXPECT_EQ(g["deepest"]["line"].get<int>(), deepest == 8 ? 13 : 14) << tool;
    std::map<std::size_t, json> listed;
    for (const json& m : g["moves"]) listed[m["block"].get<std::size_t>()] = m;
    for (const auto& [block, d] : depth) {
      ASSERT_TRUE(listed.count(block)) << tool << " block " << block;
      const json& m = listed[block];
      EXPECT_EQ(m["line"].get<int>(), static_cast<int>(block) + 5) << tool;
      EXPECT_LE(m["depth"][0].get<double>(), d) << tool << " block " << block;
      EXPECT_GE(m["depth"][1].get<double>(), d) << tool << " block " << block;
      EXPECT_LE(m["depth"][1].get<double>() - m["depth"][0].get<double>(), tol) << tool;
    }
    EXPECT_EQ(listed.size(), depth.size()) << tool << g.dump();
  }
}

/// The same passes 0.02 mm above the plate: no gouge, certified.
TEST(Verify, NoGougeCertifiedWhenThePassesClearThePart) {
  for (const std::string tool : {"cutter:ball,6,30", "cutter:flat,8,30", "cutter:bull,10,2,30"}) {
    const json g = verify("clear.ngc", tool, "plate.obj", 0.01)["gouge"];
    EXPECT_TRUE(g["certified"].get<bool>()) << tool;
    EXPECT_TRUE(g["within_tolerance"].get<bool>()) << tool;
    EXPECT_EQ(g["depth"][0].get<double>(), 0) << tool;
    EXPECT_LE(g["depth"][1].get<double>(), 0.01) << tool;
    EXPECT_TRUE(g["moves"].empty()) << tool;
  }
}

/// The largest depth of the cutter's triangulated surface, stamped at every block's end.
double stamped_at_block_ends(const std::string& program, const std::string& tool,
                             const std::string& part) {
  const cam::Program p = io::read_gcode(test_data("verify/" + program));
  const sweep::Body c = io::read_body(tool);
  const sweep::Body b = io::read_body(test_data("verify/" + part));
  const sweep::TriangleMesh skin = sweep::triangulate(c, 1e-3);
  double worst = -HUGE_VAL;
  for (const cam::Move& m : p.moves)
    for (const Eigen::Vector3d& v : skin.vertices)
      worst = std::max(worst, -sweep::signed_distance(b, m.to + v));
  return worst;
}

/// One G1 dips into the ridge of bump.obj between its ends: stamping at the ends of the
/// blocks misses it; verify finds 0.5 mm at that block.
TEST(Verify, AGougeBetweenTheEndsOfABlock) {
  EXPECT_LT(stamped_at_block_ends("dip.ngc", "cutter:ball,6,30", "bump.obj"), 0);
  const json g = verify("dip.ngc", "cutter:ball,6,30", "bump.obj", 0.01)["gouge"];
  EXPECT_LE(g["depth"][0].get<double>(), 0.5);
  EXPECT_GE(g["depth"][1].get<double>(), 0.5);
  ASSERT_EQ(g["moves"].size(), 1u) << g.dump();
  EXPECT_EQ(g["moves"][0]["block"].get<int>(), 3);
  EXPECT_EQ(g["moves"][0]["line"].get<int>(), 7);
  EXPECT_EQ(g["moves"][0]["move"].get<std::string>(), "G1");
  // An arc in the ZX plane that dips 10 sqrt 2 - 11 mm below the plate's top between ends
  // 1 mm above it.
  EXPECT_LT(stamped_at_block_ends("arc_dip.ngc", "cutter:ball,6,30", "plate.obj"), 0);
  const json a = verify("arc_dip.ngc", "cutter:ball,6,30", "plate.obj", 0.01)["gouge"];
  const double expected = 10 * std::sqrt(2.0) - 11;
  EXPECT_LE(a["depth"][0].get<double>(), expected);
  EXPECT_GE(a["depth"][1].get<double>(), expected);
  EXPECT_LE(a["depth"][1].get<double>() - a["depth"][0].get<double>(), 0.01);
  ASSERT_EQ(a["moves"].size(), 1u) << a.dump();
  EXPECT_EQ(a["moves"][0]["move"].get<std::string>(), "arc");
}

/// A G0 that ends inside the part, and the G0 that leaves it, are reported as collisions
/// with their depth; the feed between them, inside the part too, is a gouge only.
TEST(Verify, ARapidMoveIntoThePartIsACollision) {
  const json r = verify("rapid.ngc", "cutter:ball,6,30", "plate.obj", 0.01);
  const json& c = r["collisions"]["rapids_through_part"];
  ASSERT_EQ(c.size(), 2u) << r.dump();
  EXPECT_EQ(c[1]["block"].get<int>(), 4);
  EXPECT_EQ(c[1]["line"].get<int>(), 7);
  EXPECT_EQ(c[0]["block"].get<int>(), 2);
  EXPECT_EQ(c[0]["line"].get<int>(), 5);
  EXPECT_EQ(c[0]["move"].get<std::string>(), "G0");
  EXPECT_LE(c[0]["depth"][0].get<double>(), 0.3);
  EXPECT_GE(c[0]["depth"][1].get<double>(), 0.3);
  ASSERT_EQ(r["gouge"]["moves"].size(), 3u);
  EXPECT_EQ(r["gouge"]["moves"][1]["move"].get<std::string>(), "G1");
  // Nothing of the kind in a program whose rapids stay clear.
  EXPECT_TRUE(verify("offsets.ngc", "cutter:ball,6,30", "plate.obj",
                     0.01)["collisions"]["rapids_through_part"]
                  .empty());
}

}  // namespace
}  // namespace qmotion::test
