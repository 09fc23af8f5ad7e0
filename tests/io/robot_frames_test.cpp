// Tests for the frames of robot programs (<qmotion/io/robot_programs.hpp>): KUKA tools and
// bases from FDAT, $TOOL/$BASE and BAS, mapped with a $config.dat; ABB work objects and
// tooldata; URScript pose literals, variables and set_tcp; statements refused by their exact
// construct, or skipped with a warning. Every expected pose is composed here with Eigen.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <functional>
#include <qmotion/io/robot_programs.hpp>
#include <qmotion/kernel/error.hpp>

#include "refusal_expect.hpp"

namespace qmotion::io {
namespace frames_test {

using Iso = Eigen::Isometry3d;

/// KUKA's {X, Y, Z, A, B, C}: R = Rz(A) Ry(B) Rx(C), degrees.
Iso kuka(double x, double y, double z, double a, double b, double c) {
  const double d = M_PI / 180;
  Iso f = Iso::Identity();
  f.translate(Eigen::Vector3d(x, y, z));
  f.rotate(Eigen::AngleAxisd(a * d, Eigen::Vector3d::UnitZ()) *
           Eigen::AngleAxisd(b * d, Eigen::Vector3d::UnitY()) *
           Eigen::AngleAxisd(c * d, Eigen::Vector3d::UnitX()));
  return f;
}

/// ABB's [[x, y, z], [q1, q2, q3, q4]].
Iso abb(double x, double y, double z, double q1, double q2, double q3, double q4) {
  Iso f = Iso::Identity();
  f.translate(Eigen::Vector3d(x, y, z));
  f.rotate(Eigen::Quaterniond(q1, q2, q3, q4).normalized());
  return f;
}

void expect_pose(const PoseSet& set, std::size_t i, const Iso& want, double tol = 1e-9) {
  const auto poses = to_poses_double(set);
  ASSERT_LT(i, poses.size());
  EXPECT_LE((poses[i].position - want.translation()).norm(), tol * 1000) << "pose " << i;
  const Eigen::Quaterniond r(poses[i].rotation.w(), poses[i].rotation.x(), poses[i].rotation.y(),
                             poses[i].rotation.z());
  EXPECT_LE(r.angularDistance(Eigen::Quaterniond(want.rotation())), tol) << "pose " << i;
}

using test::expect_refused;

// --- KUKA ---------------------------------------------------------------------------------

const char* kKrl =
    "&ACCESS RVP\nDEF cell( )\n;FOLD INI;%{PE}\n"
    "GLOBAL INTERRUPT DECL 3 WHEN $STOPMESS==TRUE DO IR_STOPM ( )\nINTERRUPT ON 3\n"
    "BAS (#INITMOV,0 )\n;ENDFOLD (INI)\n"
    ";FOLD PTP P1 Vel=100 % PDAT1 Tool[1] Base[0];%{PE}\n$BWDSTART=FALSE\nPDAT_ACT=PPDAT1\n"
    "FDAT_ACT=FP1\nBAS(#PTP_PARAMS,100)\nPTP XP1\n;ENDFOLD\n"         // line 13: tool 1, base 0
    "FDAT_ACT=FP2\nLIN XP2 C_DIS\n"                                   // line 15: tool 2, base 1
    "$TOOL = TOOL_DATA[2]\n$BASE = BASE_DATA[3]\nLIN XP3\n"           // line 18: tool 2, base 3
    "BAS(#TOOL, 1)\nBAS (#BASE, 0)\n$OUT[3] = TRUE\nLIN XP4\nEND\n";  // line 22: tool 1, base 0

const char* kDat =
    "DEFDAT cell\n"
    "DECL FDAT FP1={TOOL_NO 1,BASE_NO 0,IPO_FRAME #BASE,POINT2[] \" \",TQ_STATE FALSE}\n"
    "DECL FDAT FP2={TOOL_NO 2,BASE_NO 1,IPO_FRAME #BASE,POINT2[] \" \",TQ_STATE FALSE}\n"
    "DECL PDAT PPDAT1={VEL 100,ACC 100,APO_DIST 100}\n"
    "DECL E6POS XP1={X 100,Y 0,Z 500,A 0,B 90,C 0,S 6,T 27}\n"
    "DECL E6POS XP2={X 200,Y 10,Z 400,A 10,B 20,C 30}\n"
    "DECL E6POS XP3={X -50,Y 20,Z 30,A -40,B 5,C 170}\n"
    "DECL E6POS XP4={X 300,Y 0,Z 400,A 0,B 0,C 45}\nENDDAT\n";

const char* kConfig =
    "&ACCESS RV\nDEFDAT $CONFIG PUBLIC\n;FOLD BASIS\nDECL FRAME TOOL_DATA[16]\n"
    "TOOL_DATA[1]={X 0.0,Y 0.0,Z 150.0,A 0.0,B 0.0,C 0.0}\n"
    "TOOL_DATA[2]={X 10.0,Y -20.0,Z 200.0,A 30.0,B 0.0,C 15.0}\n"
    "BASE_DATA[1]={X 1000.0,Y 200.0,Z 0.0,A 90.0,B 0.0,C 0.0}\n"
    "BASE_DATA[3]={X -500.0,Y 0.0,Z 300.0,A 0.0,B 10.0,C 0.0}\n"
    "DECL INT SOMETHING_ELSE=3\nENDDAT\n";

TEST(RobotFrames, KrlMovesWithTwoToolsAreRefusedWithoutAConfig) {
  expect_refused([] { parse_krl(kKrl, "cell.src", std::string(kDat), "cell.dat"); },
                 "cell.src: line 16: this move uses TOOL_DATA[2], line 13 uses TOOL_DATA[1]");
  RobotOptions tool_only;
  tool_only.tool = "1";
  expect_refused([&] { parse_krl(kKrl, "cell.src", std::string(kDat), "cell.dat", tool_only); },
                 "--tool and --base need --robot-config");
}

TEST(RobotFrames, KrlMovesAreMappedIntoOneToolAndBaseWithTheConfig) {
  const Iso tools[] = {Iso::Identity(), kuka(0, 0, 150, 0, 0, 0), kuka(10, -20, 200, 30, 0, 15)};
  const Iso bases[] = {Iso::Identity(), kuka(1000, 200, 0, 90, 0, 0), Iso::Identity(),
                       kuka(-500, 0, 300, 0, 10, 0)};
  const Iso targets[] = {kuka(100, 0, 500, 0, 90, 0), kuka(200, 10, 400, 10, 20, 30),
                         kuka(-50, 20, 30, -40, 5, 170), kuka(300, 0, 400, 0, 0, 45)};
  const int tool_of[] = {1, 2, 2, 1}, base_of[] = {0, 1, 3, 0};
  for (const auto& [tool, base] : {std::pair{1, 0}, std::pair{2, 1}, std::pair{0, 3}}) {
    RobotOptions o;
    o.config_text = kConfig;
    o.config_path = "$config.dat";
    o.tool = std::to_string(tool);
    o.base = std::to_string(base);
    const PoseSet s = parse_krl(kKrl, "cell.src", std::string(kDat), "cell.dat", o);
    ASSERT_EQ(s.poses.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i)
      expect_pose(s, i,
                  bases[base].inverse() * bases[base_of[i]] * targets[i] *
                      tools[tool_of[i]].inverse() * tools[tool]);
  }
  RobotOptions o;
  o.config_text = kConfig;
  expect_refused([&] { parse_krl(kKrl, "cell.src", std::string(kDat), "cell.dat", o); },
                 "line 16: this move uses TOOL_DATA[2], line 13 uses TOOL_DATA[1]: name the TCP");
  o.tool = "5";
  o.config_path = "my_config.dat";
  expect_refused([&] { parse_krl(kKrl, "cell.src", std::string(kDat), "cell.dat", o); },
                 "my_config.dat: has no TOOL_DATA[5]");
}

TEST(RobotFrames, KrlStatementsAreKnownByTheirExactConstruct) {
  const std::string head = "DEF p( )\nINI\nPTP {X 1, Y 2, Z 3, A 0, B 0, C 0}\n";
  const std::string tail = "LIN {X 5, Y 2, Z 3, A 0, B 0, C 0}\nEND\n";
  auto krl = [&](const std::string& line) {
    return [=] { parse_krl(head + line + "\n" + tail, "p.src"); };
  };
  expect_refused(krl("INIT_GRIPPER()"), "p.src: line 4: 'INIT_GRIPPER()' calls the routine");
  expect_refused(krl("INITIAL_APPROACH(1, 2)"), "calls the routine INITIAL_APPROACH");
  expect_refused(krl("BAS(#GRIP, 1)"), "p.src: line 4: BAS(#GRIP, ...) is not a setting");
  expect_refused(krl("HALTED"), "p.src: line 4: 'HALTED' is not understood");
  expect_refused(krl("$VELOCITY = 3"), "assigns the system variable $VELOCITY");
  expect_refused(krl("INTERRUPT DECL 4 WHEN $IN[2] DO MY_MOVE()"), "line 4");
  expect_refused(krl("SLIN {X 1, Y 2, Z 3, A 0, B 0, C 0}"), "spline motion");
  for (const char* ok : {"HALT", "WAIT SEC 0.5", "WAIT FOR $IN[1]", "$VEL.CP = 0.2", "$APO.CDIS=2",
                         "BAS(#VEL_CP, 2)", "INTERRUPT OFF 3", "&PARAM EDITMASK = *"})
    EXPECT_EQ(parse_krl(head + ok + "\n" + tail, "p.src").poses.size(), 2u) << ok;
  RobotOptions skip;
  skip.skip_unknown = true;
  const PoseSet s =
      parse_krl(head + "INIT_GRIPPER()\nIF $IN[1] THEN\n" + tail, "p.src", {}, {}, skip);
  EXPECT_EQ(s.poses.size(), 2u);
  ASSERT_EQ(s.warnings.size(), 2u);
  EXPECT_NE(s.warnings[0].find("p.src: line 4: 'INIT_GRIPPER()' calls the routine"),
            std::string::npos);
  EXPECT_NE(s.warnings[1].find("p.src: line 5:"), std::string::npos);
  // A move the reader cannot place is never skipped.
  expect_refused([&] { parse_krl(head + "LIN_REL {X 1}\n" + tail, "p.src", {}, {}, skip); },
                 "relative motion");
}

// --- ABB ----------------------------------------------------------------------------------

const std::string kTarget = ",[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]]";

std::string rapid_module(const std::string& moves) {
  return "MODULE Cell\n"
         "  PERS tooldata gun := [TRUE, [[0, 0, 120], [1, 0, 0, 0]], [1, [0, 0, 1], [1, 0, 0, 0], "
         "0, 0, 0]];\n"
         "  PERS tooldata torch := [TRUE, [[10, 0, 200], [0.9238795325112867, 0, "
         "0.3826834323650898, 0]], [1, [0, 0, 1], [1, 0, 0, 0], 0, 0, 0]];\n"
         "  PERS wobjdata table := [FALSE, TRUE, \"\", [[500, -200, 100], [0.7071067811865476, 0, "
         "0, 0.7071067811865476]], [[0, 0, 50], [0.9659258262890683, 0.2588190451025208, 0, "
         "0]]];\n"
         "  CONST robtarget a := [[10, 20, 30], [1, 0, 0, 0]" +
         kTarget + ";\n  CONST robtarget b := [[300, 0, 400], [0.5, 0.5, 0.5, 0.5]" + kTarget +
         ";\n  CONST robtarget c := [[-40, 60, 5], [0, 1, 0, 0]" + kTarget + ";\n  PROC main()\n" +
         moves + "  ENDPROC\nENDMODULE\n";
}

TEST(RobotFrames, RapidWorkObjectsAreApplied) {
  const PoseSet s =
      parse_rapid(rapid_module("    MoveL a, v100, fine, gun \\WObj:=table;\n"
                               "    MoveL b, v100, fine, gun;\n"
                               "    MoveC c, a, v100\\V:=120, z10, gun\\WObj:=table;\n"),
                  "cell.mod");
  const Iso table = abb(500, -200, 100, 0.7071067811865476, 0, 0, 0.7071067811865476) *
                    abb(0, 0, 50, 0.9659258262890683, 0.2588190451025208, 0, 0);
  ASSERT_EQ(s.poses.size(), 4u);
  expect_pose(s, 0, table * abb(10, 20, 30, 1, 0, 0, 0));
  expect_pose(s, 1, abb(300, 0, 400, 0.5, 0.5, 0.5, 0.5));
  expect_pose(s, 2, table * abb(-40, 60, 5, 0, 1, 0, 0));
  expect_pose(s, 3, table * abb(10, 20, 30, 1, 0, 0, 0));
  EXPECT_EQ(s.poses[1].position[0].text.str(), "300");  // as written where nothing is mapped
  expect_refused(
      [] {
        parse_rapid(rapid_module("    MoveL a, v1, fine, gun\\WObj:=wobj9;\n"
                                 "    MoveL b, v1, fine, gun;\n"),
                    "cell.mod");
      },
      "cell.mod: line 9: work object 'wobj9' is not declared in the module");
}

TEST(RobotFrames, RapidMovesWithTwoToolsAreRefusedOrMappedWithTool) {
  const std::string moves =
      "    MoveL a, v100, fine, gun \\WObj:=table;\n    MoveJ b, v100, z10, torch;\n"
      "    MoveL c, v100, fine, tool0;\n";
  expect_refused([&] { parse_rapid(rapid_module(moves), "cell.mod"); },
                 "cell.mod: line 10: this move uses the tool 'torch', line 9 uses 'gun'");
  const Iso table = abb(500, -200, 100, 0.7071067811865476, 0, 0, 0.7071067811865476) *
                    abb(0, 0, 50, 0.9659258262890683, 0.2588190451025208, 0, 0);
  const Iso gun = abb(0, 0, 120, 1, 0, 0, 0);
  const Iso torch = abb(10, 0, 200, 0.9238795325112867, 0, 0.3826834323650898, 0);
  for (const char* name : {"torch", "tool0"}) {
    RobotOptions o;
    o.tool = name;
    const Iso tcp = std::string(name) == "torch" ? torch : Iso::Identity();
    const PoseSet s = parse_rapid(rapid_module(moves), "cell.mod", o);
    ASSERT_EQ(s.poses.size(), 3u);
    expect_pose(s, 0, table * abb(10, 20, 30, 1, 0, 0, 0) * gun.inverse() * tcp);
    expect_pose(s, 1, abb(300, 0, 400, 0.5, 0.5, 0.5, 0.5) * torch.inverse() * tcp);
    expect_pose(s, 2, abb(-40, 60, 5, 0, 1, 0, 0) * tcp);
  }
  RobotOptions o;
  o.tool = "laser";
  expect_refused([&] { parse_rapid(rapid_module(moves), "cell.mod", o); },
                 "tool 'laser' is not declared in the module");
}

// --- Universal Robots ---------------------------------------------------------------------

Iso ur(double x, double y, double z, double rx, double ry, double rz) {
  const Eigen::Vector3d r(rx, ry, rz);
  Iso f = Iso::Identity();
  f.translate(1000 * Eigen::Vector3d(x, y, z));
  if (r.norm() > 0) f.rotate(Eigen::AngleAxisd(r.norm(), r.normalized()));
  return f;
}

TEST(RobotFrames, UrScriptPosesAreTheRotationVectorsExponentialsInMillimetres) {
  const std::string script =
      "def prog():\n  set_standard_digital_out(1, True)\n"
      "  global home = p[0.4, -0.1, 0.3, 0, 3.14159, 0]  # above the part\n"
      "  speed = 0.25\n  movej(home, a=1.4, v=1.05)\n  $ 3 \"MoveL\"\n"
      "  movel(p[0.45, -0.1, 0.25, 0.1, 2.9, -0.2], a=1.2, v=speed, r=0.005)\n"
      "  movep(pose_trans(home, p[0, 0, 0.05, 0, 0, 0.3]), a=1.2, v=0.25, r=0.01)\n"
      "  movec(p[0.5, 0, 0.2, 0, 3.1, 0], p[0.55, 0.05, 0.2, 1e-3, 3.1, 0], a=1.2, v=0.25, r=0)\n"
      "  sleep(0.5)\nend\n";
  const PoseSet s = parse_urscript(script, "prog.script");
  ASSERT_EQ(s.poses.size(), 5u);
  EXPECT_EQ(s.units, "mm");
  const Iso home = ur(0.4, -0.1, 0.3, 0, 3.14159, 0);
  expect_pose(s, 0, home, 1e-12);
  expect_pose(s, 1, ur(0.45, -0.1, 0.25, 0.1, 2.9, -0.2), 1e-12);
  expect_pose(s, 2, home * ur(0, 0, 0.05, 0, 0, 0.3), 1e-12);
  expect_pose(s, 3, ur(0.5, 0, 0.2, 0, 3.1, 0), 1e-12);
  expect_pose(s, 4, ur(0.55, 0.05, 0.2, 1e-3, 3.1, 0), 1e-12);
  EXPECT_EQ(s.poses[1].position[0].text.str(), "450");  // the metres' text, shifted
  EXPECT_EQ(s.poses[1].position[1].text.str(), "-100");
  EXPECT_EQ(s.poses[4].position[1].text.str(), "50");
}

TEST(RobotFrames, UrScriptSetTcpIsAppliedAndUnknownCallsAreRefused) {
  const std::string moves =
      "movel(p[0.4, 0, 0.3, 0, 3.1, 0])\nset_tcp(p[0, 0.01, 0.2, 0, 0, 0.5])\n"
      "movel(p[0.5, 0, 0.3, 0, 3.1, 0])\n";
  const PoseSet s = parse_urscript("set_tcp(p[0, 0, 0.1, 0, 0, 0])\n" + moves, "tcp.script");
  const Iso first = ur(0, 0, 0.1, 0, 0, 0), second = ur(0, 0.01, 0.2, 0, 0, 0.5);
  expect_pose(s, 0, ur(0.4, 0, 0.3, 0, 3.1, 0), 1e-12);
  expect_pose(s, 1, ur(0.5, 0, 0.3, 0, 3.1, 0) * second.inverse() * first, 1e-12);
  expect_refused([&] { parse_urscript(moves, "tcp.script"); },
                 "tcp.script: line 3: set_tcp changes the TCP");
  const std::string two = "movel(p[0.4, 0, 0.3, 0, 3.1, 0])\nmovel(p[0.5, 0, 0.3, 0, 3.1, 0])\n";
  expect_refused([&] { parse_urscript("open_gripper()\n" + two, "u.script"); },
                 "u.script: line 1: 'open_gripper()' calls open_gripper");
  expect_refused([&] { parse_urscript("movej([0, -1.57, 0, 0, 0, 0])\n" + two, "u.script"); },
                 "u.script: line 1: '[0, -1.57, 0, 0, 0, 0]' is a list of joint angles");
  expect_refused([&] { parse_urscript("while True:\n" + two, "u.script"); }, "control flow");
  expect_refused([&] { parse_urscript("movel(q)\n" + two, "u.script"); },
                 "'q' is not assigned in the program");
  expect_refused([&] { parse_urscript("q = get_actual_tcp_pose()\nmovel(q)\n" + two, "u.script"); },
                 "u.script: line 1: 'q = get_actual_tcp_pose()' assigns 'q'");
  RobotOptions skip;
  skip.skip_unknown = true;
  const PoseSet k = parse_urscript("open_gripper()\n" + two, "u.script", skip);
  EXPECT_EQ(k.poses.size(), 2u);
  ASSERT_EQ(k.warnings.size(), 1u);
  EXPECT_NE(k.warnings[0].find("u.script: line 1:"), std::string::npos);
}

}  // namespace frames_test
}  // namespace qmotion::io
