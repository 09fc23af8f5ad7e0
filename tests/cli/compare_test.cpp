// tests/cli/compare_test.cpp: the program, run as a user runs it: `qmotion compare`.
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

}  // namespace
}  // namespace qmotion::test
