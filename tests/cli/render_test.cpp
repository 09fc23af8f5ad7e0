// tests/cli/render_test.cpp: the program, run as a user runs it: `qmotion render` and `qmotion
// plot`.
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
