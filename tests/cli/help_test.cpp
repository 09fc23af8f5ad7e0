// tests/cli/help_test.cpp: the program, run as a user runs it: `qmotion --help`, `--version`, usage
// errors, progress bars and `qmotion demo`.
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

TEST(Cli, HelpVersionAndUsage) {
  const Result h = run({"--help"});
  EXPECT_EQ(h.status, 0);
  for (const char* cmd : {"info", "eval", "poses", "interpolate", "fit", "trajectory", "sweep",
                          "check", "demo", "Exit status"})
    EXPECT_NE(h.out.find(cmd), std::string::npos) << cmd;
  const Result sub = run({"eval", "--help"});
  EXPECT_EQ(sub.status, 0);
  EXPECT_NE(sub.out.find("--point"), std::string::npos);
  const Result v = run({"--version"});
  EXPECT_EQ(v.status, 0);
  EXPECT_NE(v.out.find("OpenCASCADE 7."), std::string::npos);
  EXPECT_EQ(run({}).status, 2);
  const Result bad = run({"frobnicate"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("qmotion: error:"), std::string::npos);
  EXPECT_EQ(run({"eval", kExamples + "/motions/bezier_tr.json"}).status, 2);  // --t missing
}

/// Runs qmotion with stderr on a pseudo-terminal (stdout to /dev/null) and the progress
/// threshold at 0 s; returns what the terminal received.
std::string run_on_terminal(const std::vector<std::string>& args) {
  int master = -1, slave = -1;
  if (openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) return "(no pty)";
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(slave, 2);
    ::close(master);
    std::vector<char*> argv{const_cast<char*>(kExe.c_str())};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::setenv("QMOTION_PROGRESS_AFTER", "0", 1);
    ::execv(kExe.c_str(), argv.data());
    ::_exit(127);
  }
  ::close(slave);
  std::string out;
  char buf[4096];
  for (ssize_t n; (n = ::read(master, buf, sizeof buf)) > 0;)
    out.append(buf, static_cast<std::size_t>(n));
  ::close(master);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << out;
  return out;
}

TEST(Cli, ProgressBarsOnlyOnATerminalAndNotWithQuiet) {
  const std::string m = (scratch_dir() / "progress_motion.json").string();
  ASSERT_EQ(run({"interpolate", test_data("poses/helix_40.json"), "-o", m}).status, 0);
  const std::string out = (scratch_dir() / "progress.ngc").string();
  const std::vector<std::string> toolpath{"toolpath",    m,       "--point", "1,0,2",
                                          "--chord-tol", "0.001", "-o",      out};
  const std::string tty = run_on_terminal(toolpath);
  EXPECT_NE(tty.find("qmotion: toolpath ["), std::string::npos) << tty;
  EXPECT_NE(tty.find("%"), std::string::npos) << tty;
  // --quiet, before or after the command: no bar.
  std::vector<std::string> quiet{"--quiet"};
  quiet.insert(quiet.end(), toolpath.begin(), toolpath.end());
  EXPECT_EQ(run_on_terminal(quiet).find("qmotion: toolpath ["), std::string::npos);
  std::vector<std::string> quiet_after = toolpath;
  quiet_after.push_back("--quiet");
  EXPECT_EQ(run_on_terminal(quiet_after).find("qmotion: toolpath ["), std::string::npos);
  // STEP translation and meshing report too.
  const std::string step = run_on_terminal(
      {"sweep", m, "--profile", "circle:3", "-o", (scratch_dir() / "progress.step").string()});
  EXPECT_NE(step.find("qmotion: STEP translation ["), std::string::npos) << step;
  // Not a terminal: silent.
  const Result piped = run(toolpath);
  EXPECT_EQ(piped.err.find('\r'), std::string::npos) << piped.err;
}

TEST(Cli, DemoWritesEveryFormatAndAnExactnessReport) {
  const fs::path dir = scratch_dir() / "demo";
  fs::remove_all(dir);
  const Result r = run({"demo", "-o", dir.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json report = json::parse(r.out);
  ASSERT_EQ(report["exactness"].size(), 9u);  // 2 trajectories + 1 surface, x JSON, STEP, IGES
  for (const auto& c : report["exactness"]) {
    EXPECT_LE(c["relative_deviation"].get<double>(), 1e-11) << c["file"];
    EXPECT_TRUE(c["weights_positive"].get<bool>());
    EXPECT_TRUE(fs::exists(dir / c["file"].get<std::string>()));
  }
  for (const char* f :
       {"motion.json", "demo.svg", "report.json", "surface_parabola.step", "surface_parabola.igs"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  // The figure by the renderer: five numbered key poses, two trajectories, the swept
  // parabola.
  const std::string svg = slurp(dir / "demo.svg");
  auto count = [&](const std::string& needle) {
    std::size_t n = 0;
    for (auto p = svg.find(needle); p != std::string::npos; p = svg.find(needle, p + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("class=\"key-marker\""), 5u);
  EXPECT_EQ(count("class=\"trajectory\""), 2u);
  EXPECT_GT(count("class=\"surface\""), 100u);
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_NE(e.path().filename().string().rfind(".qmotion", 0), 0u);
}

TEST(Cli, DemoWritesAllItsFilesOrNone) {
  // A folder where the demo must write a file: exit 2, and the folder holds what it held.
  const fs::path dir = scratch_dir() / "demo_blocked";
  fs::remove_all(dir);
  fs::create_directories(dir / "surface_parabola.step");
  std::ofstream(dir / "mine.txt") << "the user's";
  const Result r = run({"demo", "-o", dir.string()});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("surface_parabola.step"), std::string::npos) << r.err;
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"mine.txt", "surface_parabola.step"}));
  for (const auto& e : fs::directory_iterator(scratch_dir()))
    EXPECT_EQ(e.path().filename().string().find(".qmotion-demo"), std::string::npos);
  // Into a folder that exists, with a trailing slash: every file, the user's kept.
  fs::remove_all(dir / "surface_parabola.step");
  ASSERT_EQ(run({"demo", "-o", dir.string() + "/"}).status, 0);
  EXPECT_TRUE(fs::exists(dir / "mine.txt"));
  EXPECT_TRUE(fs::exists(dir / "surface_parabola.step"));
}

}  // namespace
}  // namespace qmotion::test
