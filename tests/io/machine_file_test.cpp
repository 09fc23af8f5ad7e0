// tests/io/machine_file_test.cpp mirrors io/machine_file.hpp: machine files and limits.
#include <gtest/gtest.h>

#include <qmotion/io/machine_file.hpp>

#include "io_test_util.hpp"

namespace qmotion::test {
namespace {

TEST(MachineFile, TheSampleMachinesReadAsTheyAreWritten) {
  const io::MachineFile f = io::read_machine_file(test_data("machines/head_table.json"));
  EXPECT_EQ(f.machine.name, "head B, table C");
  EXPECT_EQ(f.machine.units, "mm");
  EXPECT_EQ(f.machine.axes[0].name, 'B');
  EXPECT_TRUE(f.machine.axes[0].head);
  EXPECT_EQ(f.machine.axes[0].pivot, Eigen::Vector3d(0, 0, 120));
  EXPECT_EQ(f.machine.axes[1].name, 'C');
  EXPECT_FALSE(f.machine.axes[1].head);
  EXPECT_EQ(f.machine.axes[1].direction, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(f.velocity.at('C'), 3000);
  EXPECT_EQ(f.velocity.size(), 5u);
  const io::MachineFile h = io::read_machine_file(test_data("machines/head_head.json"));
  EXPECT_TRUE(h.machine.axes[0].head && h.machine.axes[1].head);
  EXPECT_TRUE(h.velocity.empty());
  // Directions need not be unit: they are normalised.
  const io::MachineFile n = io::parse_machine_file(
      R"({"axes": [{"name": "A", "on": "table", "direction": [2, 0, 0]},
                   {"name": "C", "on": "table", "direction": [0, 0, 0.5]}], "units": "in"})",
      "n.json");
  EXPECT_EQ(n.machine.axes[0].direction, Eigen::Vector3d::UnitX());
  EXPECT_EQ(n.machine.units, "in");
  EXPECT_EQ(n.machine.name, "n.json");
}

TEST(MachineFile, BadFilesNameTheFileAndTheField) {
  auto bad = [](const std::string& text, const std::vector<std::string>& needles) {
    return throws_error([&] { io::parse_machine_file(text, "m.json"); }, Errc::invalid_input,
                        needles);
  };
  const std::string ok_axis = R"({"name": "C", "on": "table", "direction": [0, 0, 1]})";
  EXPECT_TRUE(bad("[1, 2]", {"m.json", "object"}));
  EXPECT_TRUE(bad("{", {"m.json"}));
  EXPECT_TRUE(bad(R"({"axes": []})", {"m.json: axes", "two"}));
  EXPECT_TRUE(
      bad(R"({"axes": [{"name": "A", "on": "table", "direction": [0, 0, 0]}, )" + ok_axis + "]}",
          {"m.json: axes[0]: direction", "zero-length"}));
  EXPECT_TRUE(
      bad(R"({"axes": [{"name": "D", "on": "table", "direction": [1, 0, 0]}, )" + ok_axis + "]}",
          {"axis D", "A, B or C"}));
  EXPECT_TRUE(
      bad(R"({"axes": [{"name": "A", "on": "bed", "direction": [1, 0, 0]}, )" + ok_axis + "]}",
          {"axes[0]: on", "table"}));
  EXPECT_TRUE(
      bad(R"({"axes": [{"name": "A", "on": "table", "direction": [0, 0, 2]}, )" + ok_axis + "]}",
          {"parallel"}));
  EXPECT_TRUE(
      bad(R"({"axes": [{"name": "A", "on": "table", "direction": [1, 0]}, )" + ok_axis + "]}",
          {"axes[0]: direction", "three numbers"}));
  EXPECT_TRUE(bad(
      R"({"axes": [{"name": "A", "on": "table", "direction": [1, 0, 0], "pivit": [0, 0, 0]}, )" +
          ok_axis + "]}",
      {"axes[0]", "pivit"}));
  EXPECT_TRUE(bad(R"({"axes": [{"name": "A", "on": "table", "direction": [1, 0, 0]}, )" + ok_axis +
                      R"(], "velocity": {"X": -5}})",
                  {"velocity: X", "positive"}));
  EXPECT_TRUE(bad(R"({"axes": [{"name": "A", "on": "table", "direction": [1, 0, 0]}, )" + ok_axis +
                      R"(], "velocity": {"B": 5}})",
                  {"velocity: B", "not an axis"}));
  EXPECT_TRUE(bad(R"({"axes": [{"name": "A", "on": "table", "direction": [1, 0, 0]}, )" + ok_axis +
                      R"(], "units": "furlong"})",
                  {"units"}));
  EXPECT_TRUE(bad(R"({"axes": [{"name": "A", "on": "table", "direction": [1, 0, 0]}, )" + ok_axis +
                      R"(], "spindle": 1})",
                  {"spindle"}));
  EXPECT_TRUE(throws_error([] { io::read_machine_file("/nonexistent/m.json"); },
                           Errc::invalid_input, {"/nonexistent/m.json"}));
}

TEST(MachineFile, AxisLimitsParseWordByWord) {
  const auto l = io::parse_axis_limits("X=20000,C=7200.5", "--axis-limits");
  EXPECT_EQ(l.at('X'), 20000);
  EXPECT_EQ(l.at('C'), 7200.5);
  for (const std::string bad : {"", "X", "X=", "X=-1", "X=0", "Q=5", "X=1,X=2", "XY=3", "X=nan"})
    EXPECT_TRUE(throws_error([&] { io::parse_axis_limits(bad, "--axis-limits"); },
                             Errc::invalid_input, {"--axis-limits"}))
        << bad;
}

}  // namespace
}  // namespace qmotion::test
