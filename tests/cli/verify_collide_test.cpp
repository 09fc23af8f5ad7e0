// tests/cli/verify_collide_test.cpp: `qmotion verify --holder` and rapid moves through the
// stock: the first instant at which the holder or a rapid's cutter enters the stock as cut
// so far, against the instant worked out by hand, a clearance of 0.02 mm proven, a pocket
// cut before the holder enters it, and a retract through the cut.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "cli_util.hpp"

namespace qmotion::test {
namespace {

/// A box [x0, x1] x [y0, y1] x [z0, z1] as a closed OBJ of 12 triangles.
fs::path box_part(const std::string& name, double x0, double y0, double z0, double x1, double y1,
                  double z1) {
  const fs::path p = scratch_dir() / name;
  std::ofstream f(p);
  for (int k = 0; k < 8; ++k)
    f << "v " << (k & 1 ? x1 : x0) << " " << (k & 2 ? y1 : y0) << " " << (k & 4 ? z1 : z0) << "\n";
  // Counter-clockwise seen from outside (vertices 1-based: bit 0 x, bit 1 y, bit 2 z).
  f << "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\n"
    << "f 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n";
  return p;
}

fs::path program(const std::string& name, const std::string& blocks) {
  const fs::path p = scratch_dir() / name;
  std::ofstream(p) << "G21 G90 G17\nG0 Z20\n" << blocks << "M2\n";
  return p;
}

/// The part lies deep in the stock (its top 25 mm down); a flat cutter D 6, L 10 with a
/// holder of radius 10 above it.
json verify_holder(const fs::path& ngc) {
  const fs::path part = box_part("deep_part.obj", -20, -20, -30, 20, 20, -25);
  return run_json({"verify", ngc.string(), "--tool", "cutter:flat,6,10", "--part", part.string(),
                   "--stock", "box:-20,-20,-30,20,20,0", "--holder", "cylinder:10,30", "--tol",
                   "0.01"});
}

/// One slanted cut from x = -30, z = -5 to x = 30, z = -12: the holder's bottom (10 mm above
/// the tip) reaches the stock's top z = 0 at t = 5/7, over uncut stock beside the slot.
TEST(VerifyCollide, TheHoldersFirstContactHoldsTheInstantWorkedOutByHand) {
  const json r = verify_holder(program("touch.ngc", "G0 X-30 Y0\nG1 Z-5 F500\nG1 X30 Z-12\n"));
  const json& h = r["collisions"]["holder"];
  ASSERT_FALSE(h["first"].is_null()) << h.dump(1);
  const json& f = h["first"];
  EXPECT_EQ(f["block"], 3);
  EXPECT_EQ(f["line"], 5);
  EXPECT_EQ(f["with"], "stock");
  EXPECT_EQ(f["found"], "contact");
  const double lo = f["t"][0], hi = f["t"][1], t = 5.0 / 7;
  EXPECT_LE(lo, t + 1e-12);
  EXPECT_GE(hi, t - 1e-12);
  // No longer than the time the tool takes to move T / 4 (its speed: |(60, 0, -7)| mm).
  EXPECT_LE((hi - lo) * std::hypot(60.0, 7.0), 0.01 / 4 + 1e-12);
  // The witness: a point of the holder's bottom, in the stock, beside the slot.
  EXPECT_NEAR(f["point"][2].get<double>(), 0, 0.01);
  EXPECT_GT(f["depth_at_least"].get<double>(), 0);
  EXPECT_GT(std::abs(f["point"][1].get<double>()), 3);
  // Nothing before it.
  for (const json& c : h["contacts"]) EXPECT_GE(c["block"].get<int>(), 3);
}

/// The same cut ending 0.02 mm before the holder reaches the stock: proven clear.
TEST(VerifyCollide, AClearanceOfTwoHundredthsIsProven) {
  const json r =
      verify_holder(program("clear.ngc", "G0 X-30 Y0\nG1 Z-5 F500\nG1 X30 Z-9.98\nG0 Z20\n"));
  const json& h = r["collisions"]["holder"];
  EXPECT_TRUE(h["clear"].get<bool>()) << h.dump(1);
  EXPECT_TRUE(h["first"].is_null());
}

/// A plunge to z = -12 at the centre puts the holder's bottom 2 mm into the raw stock. After
/// a pocket 5 mm deep and 26 x 30 mm wide has been cut, the holder enters only air there.
TEST(VerifyCollide, ThePocketCutBeforeIsNoLongerStock) {
  const std::string plunge = "G0 X0 Y0\nG1 Z-12 F500\nG0 Z20\n";
  const json raw = verify_holder(program("plunge.ngc", plunge));
  const json& f = raw["collisions"]["holder"]["first"];
  ASSERT_FALSE(f.is_null());
  EXPECT_EQ(f["block"], 2);
  // The holder's bottom reaches z = 0 when the tip is at -10: t = (20 + 10) / 32.
  EXPECT_LE(f["t"][0].get<double>(), 30.0 / 32 + 1e-12);
  EXPECT_GE(f["t"][1].get<double>(), 30.0 / 32 - 1e-12);
  std::string pocket = "G0 X-10 Y-12\nG1 Z-5 F500\n";
  for (int k = 0; k <= 12; ++k)
    pocket += "G1 Y" + std::to_string(-12 + 2 * k) + "\nG1 X" + (k % 2 ? "-10" : "10") + "\n";
  pocket += "G0 Z20\n";
  const json cut = verify_holder(program("pocket.ngc", pocket + plunge));
  const json& h = cut["collisions"]["holder"];
  EXPECT_TRUE(h["clear"].get<bool>()) << h.dump(1);
}

json verify_rapids(const fs::path& ngc) {
  const fs::path part = box_part("deep_part.obj", -20, -20, -30, 20, 20, -25);
  return run_json({"verify", ngc.string(), "--tool", "cutter:flat,6,10", "--part", part.string(),
                   "--stock", "box:-20,-20,-30,20,20,0", "--tol", "0.01"});
}

/// A rapid move 5 mm deep across the stock: the cutter's side reaches the stock's face
/// x = -20 when its axis is at x = -23, t = 7/60 of the way from x = -30 to 30.
TEST(VerifyCollide, ARapidThroughTheStockAtTheInstantWorkedOutByHand) {
  const json r = verify_rapids(program("rapid_stock.ngc", "G0 X-30 Y0\nG0 Z-5\nG0 X30\n"));
  const json& list = r["collisions"]["rapids_through_stock"];
  ASSERT_EQ(list.size(), 1u) << list.dump(1);
  const json& c = list[0];
  EXPECT_EQ(c["block"], 3);
  EXPECT_EQ(c["found"], "contact");
  EXPECT_LE(c["t"][0].get<double>(), 7.0 / 60 + 1e-12);
  EXPECT_GE(c["t"][1].get<double>(), 7.0 / 60 - 1e-12);
  EXPECT_LE((c["t"][1].get<double>() - c["t"][0].get<double>()) * 60, 0.01 / 4 + 1e-12);
}

/// Cutting into the stock with G1 and leaving it with G0 up the tool's axis: the cutter
/// rises through what it has cut. Proven clear; a rapid onwards above the stock too.
TEST(VerifyCollide, ARetractFromTheCutIsNotThroughTheStock) {
  const json r =
      verify_rapids(program("retract.ngc", "G0 X-30 Y0\nG1 Z-5 F500\nG1 X0\nG0 Z20\nG0 X30\n"));
  EXPECT_TRUE(r["collisions"]["rapids_through_stock"].empty()) << r["collisions"].dump(1);
}

json verify_fixture(const fs::path& ngc, const std::string& fixture) {
  const fs::path part = box_part("deep_part.obj", -20, -20, -30, 20, 20, -25);
  return run_json({"verify", ngc.string(), "--tool", "cutter:flat,6,10", "--part", part.string(),
                   "--holder", "cylinder:10,30", "--fixture", fixture, "--tol", "0.01"});
}

/// A stepped holder (holder:5,10,20,30: a nut of radius 5 for 10 mm, then a body of radius
/// 20) beside the stock: a plunge at x = 32 keeps the cutter and the nut clear of the stock's
/// face x = 20, but the body's bottom, 20 mm above the tip, reaches the stock's top when the
/// tip is 20 mm down: t = 40/50 of the plunge from z = 20 to -30. The nut alone, however
/// long, is proven clear.
TEST(VerifyCollide, AStepOfTheHolderMeetsTheStockWhereWorkedOutByHand) {
  const fs::path ngc = program("stepped.ngc", "G0 X32 Y0\nG1 Z-30 F500\n");
  const fs::path part = box_part("deep_part.obj", -20, -20, -30, 20, 20, -25);
  auto run = [&](const std::string& holder) {
    return run_json({"verify", ngc.string(), "--tool", "cutter:flat,6,10", "--part", part.string(),
                     "--stock", "box:-20,-20,-30,20,20,0", "--holder", holder, "--tol",
                     "0.01"})["collisions"]["holder"];
  };
  const json h = run("holder:5,10,20,30");
  ASSERT_FALSE(h["first"].is_null()) << h.dump(1);
  const json& f = h["first"];
  EXPECT_EQ(f["block"], 2);
  EXPECT_EQ(f["line"], 4);
  EXPECT_EQ(f["with"], "stock");
  EXPECT_LE(f["t"][0].get<double>(), 0.8 + 1e-12);
  EXPECT_GE(f["t"][1].get<double>(), 0.8 - 1e-12);
  EXPECT_GE(f["point"][2].get<double>(), -10 - 1e-9);  // on the body, not the nut
  EXPECT_EQ(h["holder"]["sections"].size(), 2u);
  EXPECT_TRUE(run("holder:5,40")["clear"].get<bool>());
}

/// A clamp at x from 22 to 30: a cut along y = 0 meets it with the cutter's side when the
/// axis reaches x = 19, t = 49/60; the same clamp moved to y >= 3.02 is cleared by 0.02 mm.
TEST(VerifyCollide, AFixtureTouchedAndAFixtureCleared) {
  const fs::path ngc = program("fixture.ngc", "G0 X-30 Y0\nG1 Z-5 F500\nG1 X30\n");
  const json hit = verify_fixture(ngc, "box:22,-5,-10,30,5,5")["collisions"]["fixtures"];
  const json& f = hit["first"];
  ASSERT_FALSE(f.is_null()) << hit.dump(1);
  EXPECT_EQ(f["block"], 3);
  EXPECT_EQ(f["with"], "fixture 1");
  EXPECT_EQ(f["body"], "cutter");
  EXPECT_LE(f["t"][0].get<double>(), 49.0 / 60 + 1e-12);
  EXPECT_GE(f["t"][1].get<double>(), 49.0 / 60 - 1e-12);
  const json clear = verify_fixture(ngc, "box:22,3.02,-10,30,10,5")["collisions"]["fixtures"];
  EXPECT_TRUE(clear["clear"].get<bool>()) << clear.dump(1);
}

}  // namespace
}  // namespace qmotion::test
