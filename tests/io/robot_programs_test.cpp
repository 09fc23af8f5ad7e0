// Tests for <qmotion/io/robot_programs.hpp>: programs written here, with every construct the
// readers know, CRLF line ends and comments, give the poses the program means.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <qmotion/io/robot_programs.hpp>
#include <qmotion/kernel/error.hpp>

#include "refusal_expect.hpp"

namespace qmotion::io {
namespace {

/// KUKA's R = Rz(A) Ry(B) Rx(C), written here with Eigen.
Eigen::Quaterniond kuka(double a, double b, double c) {
  const double d = M_PI / 180;
  return Eigen::Quaterniond(Eigen::AngleAxisd(a * d, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(b * d, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(c * d, Eigen::Vector3d::UnitX()));
}

void expect_pose(const PoseSet& set, std::size_t i, const Eigen::Vector3d& p,
                 const Eigen::Quaterniond& q) {
  const auto poses = to_poses_double(set);
  ASSERT_LT(i, poses.size());
  EXPECT_LE((poses[i].position - p).norm(), 1e-9) << "pose " << i;
  const Eigen::Quaterniond r(poses[i].rotation.w(), poses[i].rotation.x(), poses[i].rotation.y(),
                             poses[i].rotation.z());
  EXPECT_LE(r.angularDistance(q), 1e-9) << "pose " << i;
}

std::string crlf(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '\n' ? std::string("\r\n") : std::string(1, c);
  return out;
}

TEST(RobotPrograms, KrlTargetsInlineAndDeclaredInOrder) {
  const std::string src = crlf(
      "&ACCESS RVP\n&REL 1\nDEF weld( )\n;FOLD INI;%{PE}\n  BAS (#INITMOV,0 )\n;ENDFOLD (INI)\n"
      "$VEL.CP = 0.2 ; metres per second\n$APO.CDIS = 2\n"
      "PTP {X 100, Y 0, Z 500, A 0, B 90, C 0, S 6, T 27} C_PTP\n"
      ";FOLD LIN P1 Vel=2 m/s CPDAT1 Tool[1] Base[0];%{PE}\n$BWDSTART=FALSE\nLDAT_ACT=LCPDAT1\n"
      "lin xp1 C_DIS\n;ENDFOLD\nDECL FRAME F1 = {X -5.5, Y 2, Z 3, A 10, B -20, C 30}\n"
      "CIRC XAUX, XEND\nLIN F1\nWAIT SEC 0.5\nLIN {E6POS: X 10, Y 20, Z 30, A 90, B 0, C "
      "0}\nEND\n");
  const std::string dat = crlf(
      "DEFDAT weld\nDECL E6POS XP1={X 200.5,Y 10,Z 400,A 10,B 20,C 30,S 6,T 27,E1 0,E2 0,E3 0,"
      "E4 0,E5 0,E6 0}\nDECL POS XAUX={X 250,Y 50,Z 400,A 0,B 0,C 0}\n"
      "DECL GLOBAL FRAME XEND={X 300,Y 0,Z 400,A 0,B 0,C 45}\nDECL LDAT LCPDAT1={VEL 2.0,ACC "
      "100.0}\n"
      "ENDDAT\n");
  const PoseSet s = parse_krl(src, "weld.src", dat, "weld.dat");
  ASSERT_EQ(s.poses.size(), 6u);
  EXPECT_EQ(s.units, "mm");
  EXPECT_FALSE(s.has_t());
  expect_pose(s, 0, {100, 0, 500}, kuka(0, 90, 0));
  expect_pose(s, 1, {200.5, 10, 400}, kuka(10, 20, 30));
  expect_pose(s, 2, {250, 50, 400}, kuka(0, 0, 0));  // CIRC: auxiliary point first
  expect_pose(s, 3, {300, 0, 400}, kuka(0, 0, 45));
  expect_pose(s, 4, {-5.5, 2, 3}, kuka(10, -20, 30));
  expect_pose(s, 5, {10, 20, 30}, kuka(90, 0, 0));
}

TEST(RobotPrograms, RapidRobtargetsInTheOrderOfTheMoves) {
  const std::string mod = crlf(
      "MODULE Cell\n  ! targets\n"
      "  CONST robtarget p10 := [[100,0,500],[0.7071067811865476,0,0.7071067811865476,0],"
      "[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n"
      "  PERS robtarget p20:=[[200,10,400],[1,0,0,0],[0,0,0,0],\n"
      "      [9E9,9E9,9E9,9E9,9E9,9E9]];\n"
      "  LOCAL CONST robtarget pc := "
      "[[250,50,400],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n"
      "  CONST robtarget pe := [[300,0,400],[0.9238795325112867,0,0,0.3826834323650898],[0,0,0,0],"
      "[9E9,9E9,9E9,9E9,9E9,9E9]];\n"
      "  PROC main()\n    ConfL \\Off;\n    MoveJ p10, v1000, z50, tool0;\n"
      "    MoveL p20, v200, fine, tool0 \\WObj:=wobj0; ! weld start\n"
      "    MoveC pc, pe, v100, z10, tool0;\n"
      "    MoveL [[10,20,30],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]], v100, fine, tool0;\n"
      "    MoveL p10, v100, fine, tool0;\n  ENDPROC\nENDMODULE\n");
  const PoseSet s = parse_rapid(mod, "cell.mod");
  ASSERT_EQ(s.poses.size(), 6u);
  const Eigen::Quaterniond q10(0.7071067811865476, 0, 0.7071067811865476, 0);
  expect_pose(s, 0, {100, 0, 500}, q10.normalized());
  expect_pose(s, 1, {200, 10, 400}, Eigen::Quaterniond::Identity());
  expect_pose(s, 2, {250, 50, 400}, Eigen::Quaterniond::Identity());  // MoveC: circle point
  expect_pose(s, 3, {300, 0, 400},
              Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ())));
  expect_pose(s, 4, {10, 20, 30}, Eigen::Quaterniond::Identity());
  expect_pose(s, 5, {100, 0, 500}, q10.normalized());
}

using test::expect_refused;

TEST(RobotPrograms, WhatAReaderDoesNotUnderstandIsRefusedWithFileAndLine) {
  const std::string head = "DEF p( )\nPTP {X 1, Y 2, Z 3, A 0, B 0, C 0}\n";
  auto krl = [&](const std::string& line) {
    return [=] { parse_krl(head + line + "\nEND\n", "p.src"); };
  };
  expect_refused(krl("IF $IN[1] THEN"), "p.src: line 3: 'IF $IN[1] THEN' is control flow");
  expect_refused(krl("$FOO = 1"), "p.src: line 3: '$FOO = 1' assigns the system variable $FOO");
  expect_refused(krl("WAIT 3"), "p.src: line 3: 'WAIT 3' is not understood");
  expect_refused(krl("LIN XNOPE"), "p.src: line 3: target 'XNOPE' is not declared");
  expect_refused(krl("LIN_REL {X 1}"), "relative motion");
  expect_refused(krl("$BASE = BASE_DATA[1]\nLIN {X 1, Y 2, Z 3, A 0, B 0, C 0}"),
                 "p.src: line 4: this move uses BASE_DATA[1], line 2 uses the robot's frame");
  expect_refused(krl("LIN {X 1, Y 2, Z 3}"), "the aggregate has no A");
  expect_refused(krl("LIN {X 1, Y 2, Z 3, A 0, B 0, C zero}"), "expected a number");
  expect_refused(krl("DECL E6AXIS XH={A1 0,A2 -90,A3 90,A4 0,A5 0,A6 0}\nPTP XH"), "joint angles");
  expect_refused(
      [] { parse_krl("DEF p( )\nLIN X1\nEND\n", "p.src", "DEFDAT p\nFOO\nENDDAT\n", "p.dat"); },
      "p.dat: line 2");
  const std::string rt = "[[1,2,3],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]]";
  auto rapid = [&](const std::string& decl, const std::string& line) {
    return [=] {
      parse_rapid("MODULE M\n" + decl + "PROC main()\nMoveL " + rt + ", v1, fine, tool0;\n" + line +
                      "\nENDPROC\nENDMODULE\n",
                  "m.mod");
    };
  };
  expect_refused(rapid("", "MoveL nowhere, v1, fine, tool0;"),
                 "m.mod: line 4: target 'nowhere' is not declared");
  expect_refused(rapid("CONST robtarget q := [[1,2,3],[1,0,0,0.1],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,"
                       "9E9]];\n",
                       "MoveL q, v1, fine, tool0;"),
                 "not a unit quaternion");
  expect_refused(rapid("", "MoveAbsJ home, v1, fine, tool0;"), "joint angles");
  expect_refused(rapid("", "GoHome;"), "m.mod: line 4: 'GoHome' calls the routine GoHome");
  expect_refused(rapid("", "n := n + 1;"), "m.mod: line 4: 'n := n + 1' assigns 'n'");
  expect_refused(rapid("", "TriggL p, v1, t, fine, tool0;"), "in a way the RAPID reader");
  expect_refused(rapid("", "IF di1 = 1 THEN"), "the statement has no closing ';'");
  expect_refused(rapid("", "MoveL Offs(p, 0, 0, 10), v1, fine, tool0;"), "is not declared");
}

}  // namespace
}  // namespace qmotion::io
