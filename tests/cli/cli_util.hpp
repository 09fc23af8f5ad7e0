// tests/cli/cli_util.hpp: running the qmotion program from the CLI tests: its exit status,
// standard output and error, in a scratch folder of the test process.
#pragma once
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
namespace fs = std::filesystem;
using json = nlohmann::json;

inline const std::string kExe = QMOTION_EXE;
inline const std::string kData = QMOTION_TEST_DATA;
inline const std::string kExamples = QMOTION_EXAMPLES;

/// What a run of the program gave.
struct Result {
  int status;
  std::string out, err;
};

/// The whole file as text.
inline std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

/// A folder of this test process for outputs.
inline fs::path scratch_dir() {
  static const fs::path d = [] {
    const fs::path p = fs::temp_directory_path() / ("qmotion_cli_" + std::to_string(::getpid()));
    fs::create_directories(p);
    return p;
  }();
  return d;
}

/// A shell word.
inline std::string quote(const std::string& a) {
  std::string q = "'";
  for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// Runs the program with the arguments (stdin closed).
inline Result run(const std::vector<std::string>& args) {
  const fs::path out = scratch_dir() / "stdout", err = scratch_dir() / "stderr";
  std::string cmd = quote(kExe);
  for (const auto& a : args) cmd += " " + quote(a);
  cmd += " >" + quote(out.string()) + " 2>" + quote(err.string()) + " </dev/null";
  const int raw = std::system(cmd.c_str());
  return Result{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), slurp(err)};
}

/// Runs the program, expects exit 0, and parses its standard output as JSON.
inline json run_json(const std::vector<std::string>& args) {
  const Result r = run(args);
  EXPECT_EQ(r.status, 0) << r.err;
  return json::parse(r.out);
}

/// The five-pose motion of the given rotation and translation methods, written once here.
inline fs::path five_motion(const std::string& rot, const std::string& tr) {
  const fs::path m = scratch_dir() / ("five_" + rot + "_" + tr + ".json");
  const Result r = run({"interpolate", test_data("poses/five_positions.json"), "-o", m.string(),
                        "--rotation", rot, "--translation", tr});
  EXPECT_EQ(r.status, 0) << r.err;
  return m;
}

/// `qmotion check FILE --motion MOTION` with `what` (--point or --profile), as JSON.
inline json check(const fs::path& file, const fs::path& motion,
                  const std::vector<std::string>& what) {
  std::vector<std::string> args = {"check", file.string(), "--motion", motion.string()};
  args.insert(args.end(), what.begin(), what.end());
  return run_json(args);
}

}  // namespace qmotion::test
