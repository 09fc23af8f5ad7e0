// tests/io/step_size_test.cpp mirrors io::control_points and the floors kStepPoleBytes and
// kIgesPoleBytes (io/occt.hpp): floors on the bytes of a STEP or IGES file, checked against the
// files OpenCASCADE writes, and the refusal they allow before anything is built.
#include <filesystem>
#include <fstream>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <string>

#include "io_test_util.hpp"
#include "surface_util.hpp"

namespace qmotion::test {
namespace {
namespace fs = std::filesystem;

/// A clamped rational surface of nu x nv poles, degree 3 x 2, even knots, random poles.
sweep::NurbsSurface<double> clamped_surface(int nu, int nv, unsigned seed) {
  auto clamped = [](int n, int p) {
    std::vector<double> k(static_cast<std::size_t>(p + 1), 0.0);
    for (int i = 1; i < n - p; ++i) k.push_back(double(i) / (n - p));
    k.insert(k.end(), static_cast<std::size_t>(p + 1), 1.0);
    return k;
  };
  return random_surface(3, clamped(nu, 3), 2, clamped(nv, 2), seed);
}

/// The peak resident memory of this process so far (VmHWM), in bytes.
std::uintmax_t peak_rss() {
  std::ifstream f("/proc/self/status");
  std::string key;
  std::uintmax_t kb = 0;
  while (f >> key)
    if (key == "VmHWM:") {
      f >> kb;
      return kb * 1024;
    }
  return 0;
}

TEST(StepSize, TheFloorIsBelowEveryFileWritten) {
  const auto small = clamped_surface(6, 4, 1), large = clamped_surface(60, 40, 2);
  const auto arc = sweep::arc(7.0 / 3.0, 10.0, 300.0);
  sweep::NurbsShell<double> shell;
  shell.faces = {large};
  const std::vector<sweep::NurbsCurve<double>> wire{arc};
  EXPECT_EQ(io::control_points(large), 2400u);
  EXPECT_EQ(io::control_points(shell), 2400u);
  EXPECT_EQ(io::control_points(wire), arc.points.size());
  const auto p = [](const std::string& n) { return scratch_path("step_size", n).string(); };
  const auto at_least = [&](const std::string& file, std::uintmax_t poles, std::uintmax_t bytes) {
    EXPECT_LE(poles * bytes, fs::file_size(p(file))) << file;
  };
  io::write_step(p("small.step"), small, {});
  io::write_step(p("large.step"), large, {});
  io::write_step(p("arc.step"), arc, {});
  io::write_step(p("shell.step"), shell, {});
  io::write_step(p("wire.step"), wire, {});
  io::write_iges(p("small.igs"), small, {});
  io::write_iges(p("large.igs"), large, {});
  io::write_iges(p("arc.igs"), arc, {});
  io::write_iges(p("shell.igs"), shell, {});
  for (const std::string f : {"small", "large", "shell"}) {
    at_least(f + ".step", io::control_points(f == "small" ? small : large), io::kStepPoleBytes);
    at_least(f + ".igs", io::control_points(f == "small" ? small : large), io::kIgesPoleBytes);
  }
  at_least("arc.step", io::control_points(arc), io::kStepPoleBytes);
  at_least("wire.step", io::control_points(wire), io::kStepPoleBytes);
  at_least("arc.igs", io::control_points(arc), io::kIgesPoleBytes);
  // Tight enough to matter: a file of many poles is under twice its floor, so what is refused
  // only after writing was never more than twice the limit.
  EXPECT_LE(fs::file_size(p("large.step")), 2 * 2400 * io::kStepPoleBytes);
  EXPECT_LE(fs::file_size(p("large.igs")), 2 * 2400 * io::kIgesPoleBytes);
}

TEST(StepSize, AnExportOverTheLimitIsRefusedBeforeMemoryGrows) {
  // 5.52 million poles: a floor of 552 MB, over the 512 MiB limit (the surface itself holds
  // 177 MB here; OpenCASCADE would hold its text and entities several times over).
  auto s = clamped_surface(2400, 2300, 3);
  ASSERT_GT(io::control_points(s) * io::kStepPoleBytes, io::kMaxFileBytes);
  ASSERT_GT(io::control_points(s) * io::kIgesPoleBytes, io::kMaxFileBytes);
  const auto out = scratch_path("step_size", "huge.step");
  const std::uintmax_t before = peak_rss();
  EXPECT_TRUE(throws_error([&] { io::write_step(out.string(), s, {}); }, Errc::invalid_input,
                           {"huge.step", "5520000 control points", "refused before it is built"}));
  EXPECT_TRUE(
      throws_error([&] { io::write_iges(scratch_path("step_size", "huge.igs").string(), s, {}); },
                   Errc::invalid_input, {"huge.igs", "IGES", "refused before it is built"}));
  EXPECT_LT(peak_rss() - before, std::uintmax_t(16) << 20);  // nothing built
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(scratch_path("step_size", "huge.igs")));
  sweep::NurbsShell<double> shell;
  shell.faces.push_back(std::move(s));  // no second copy
  EXPECT_TRUE(throws_error([&] { io::write_step(out.string(), shell, {}); }, Errc::invalid_input,
                           {"refused before it is built"}));
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace qmotion::test
