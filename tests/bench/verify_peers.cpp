// `qmotion verify` against what a CAM programmer has without it (issue 53; docs/guide/
// verify.md). Each table is printed as Markdown; tests/bench/bench_page.py puts them into
// docs/benchmarks.md.
// - Gouges: the cutter stamped at N instants of every block, at the peer's best: the ball's
//   depth at each stamp is exact (its radius less its centre's signed distance to the part),
//   one query a stamp. (A voxel grid of the part at T, OpenVDB's route, would hold 10^8
//   voxels for the 100 x 100 mm part; the stamps are the only error left here.)
// - Stock left: OpenVDB's in-process stock, the stock's level set less a ball's level set at
//   N stamps spread evenly along the program (csgDifference), sampled on the part's top.
// - Collisions: FCL's continuous collision detection (verify_peers_fcl.cpp).
// --smoke runs one short case of each (CTest). The exit status is 1 when a certified
// interval of qmotion's misses the truth or a stamp finds more than qmotion's upper bound.
#include "verify_peers.hpp"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Composite.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/MeshToVolume.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <qmotion/io/bodies.hpp>
#include <qmotion/io/gcode.hpp>
#include <qmotion/qmotion.hpp>
#include <string>
#include <vector>

#include "finishing_scene.hpp"

namespace qmotion::peers {
namespace {

using V3 = Eigen::Vector3d;
namespace fs = std::filesystem;

fs::path scratch() {
  return fs::temp_directory_path() / ("qmotion_verify_peers_" + std::to_string(::getpid()));
}

struct Scene {
  std::string name, program, part;
};

/// The largest depth of the ball (radius r) in the part over stamps at n even instants of
/// every feed block (both ends included).
double stamped_gouge(const cam::Program& p, const sweep::Body& part, double r, int n) {
  double worst = -HUGE_VAL;
  for (const cam::Move& m : p.moves) {
    if (m.kind == cam::Move::Kind::traverse) continue;
    for (int k = 0; k < n; ++k) {
      const V3 c = cam::position(m, double(k) / (n - 1)) + V3(0, 0, r);
      worst = std::max(worst, r - sweep::signed_distance(part, c));
    }
  }
  return std::max(0.0, worst);
}

int gouge_table(const std::vector<Scene>& scenes, const std::vector<int>& stamps, std::FILE* out) {
  int wrong = 0;
  std::fprintf(out,
               "\nGouges, ball cutter D 6, T = 0.01 mm: qmotion's certified depth against the "
               "cutter stamped at N instants of every block, the ball's depth at each exact:\n\n"
               "| program | method | time (s) | gouge (mm) | short of qmotion's lower bound by "
               "(mm) | time / qmotion's |\n| --- | --- | --- | --- | --- | --- |\n");
  for (const Scene& s : scenes) {
    VerifyOptions o;
    o.program = s.program;
    o.part = s.part;
    o.tool = "cutter:ball,6,30";
    o.tol = 0.01;
    const auto t0 = std::chrono::steady_clock::now();
    const VerifyReport r = verify(o);
    const double tq = seconds_since(t0);
    std::fprintf(out, "| %s | qmotion `verify`%s | %.3f | [%.4f, %.4f] | | 1.00 |\n",
                 s.name.c_str(), r.settled ? " (certified)" : " (not settled)", tq, r.gouge_lower,
                 r.gouge_upper);
    const cam::Program p = io::read_gcode(s.program);
    const sweep::Body part = io::read_body(s.part);
    for (int n : stamps) {
      const auto t1 = std::chrono::steady_clock::now();
      const double g = stamped_gouge(p, part, 3, n);
      const double ts = seconds_since(t1);
      if (g > r.gouge_upper + 1e-9) ++wrong;
      std::fprintf(out, "| %s | %d stamps a block%s | %.3f | %.4f | %.4f | %.3f |\n",
                   s.name.c_str(), n, n == 2 ? " (its ends)" : "", ts, g,
                   std::max(0.0, r.gouge_lower - g), ts / tq);
    }
  }
  return wrong;
}

/// The scallop scene of the tests: passes along x at y = -13 ... 13 (stepover 1), the tip on
/// the plate's top z = 0; the stock [-5, 5]^2 x [-5, 1] over it.
std::string scallop_program(const fs::path& dir) {
  const fs::path p = dir / "scallop.ngc";
  std::FILE* f = std::fopen(p.string().c_str(), "w");
  std::fprintf(f, "G21 G90 G17\nG0 Z10\nG0 X-14 Y-13\nG1 Z0 F1000\n");
  int x = -14;
  for (int y = -13; y <= 13; ++y) {
    if (y > -13) std::fprintf(f, "G1 Y%d\n", y);
    x = -x;
    std::fprintf(f, "G1 X%d\n", x);
  }
  std::fprintf(f, "G0 Z10\nM2\n");
  std::fclose(f);
  return p.string();
}

void write_box(const fs::path& p, const V3& lo, const V3& hi) {
  std::FILE* f = std::fopen(p.string().c_str(), "w");
  for (int k = 0; k < 8; ++k)
    std::fprintf(f, "v %g %g %g\n", k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(),
                 k & 4 ? hi.z() : lo.z());
  const int faces[12][3] = {{1, 3, 4}, {1, 4, 2}, {5, 6, 8}, {5, 8, 7}, {1, 2, 6}, {1, 6, 5},
                            {3, 7, 8}, {3, 8, 4}, {1, 5, 7}, {1, 7, 3}, {2, 4, 8}, {2, 8, 6}};
  for (const auto& t : faces) std::fprintf(f, "f %d %d %d\n", t[0], t[1], t[2]);
  std::fclose(f);
}

struct Left {
  double max = 0, mean = 0;
};

/// The stock left on the plate's top [-5, 5]^2 by the stock's level set at voxel h less
/// the ball at n stamps spread evenly along the feed moves, sampled at 400 x 400 points.
Left openvdb_stock_left(const cam::Program& p, double h, int n) {
  const float band = static_cast<float>(std::ceil(0.1 / h) + 2);
  const auto xform = openvdb::math::Transform::createLinearTransform(h);
  std::vector<openvdb::Vec3s> pts;
  for (int k = 0; k < 8; ++k)
    pts.emplace_back(k & 1 ? 5.f : -5.f, k & 2 ? 5.f : -5.f, k & 4 ? 1.f : -5.f);
  const std::vector<openvdb::Vec4I> quads = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  auto stock = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(
      *xform, pts, std::vector<openvdb::Vec3I>{}, quads, band);
  double length = 0;
  for (const cam::Move& m : p.moves)
    if (m.kind != cam::Move::Kind::traverse) length += (m.to - m.from).norm();
  double at = 0;
  std::size_t k = 0;
  for (const cam::Move& m : p.moves) {
    if (m.kind == cam::Move::Kind::traverse) continue;
    const double l = (m.to - m.from).norm();
    for (; k < static_cast<std::size_t>(n) && k * length / (n - 1) <= at + l + 1e-9; ++k) {
      const double t = l > 0 ? std::min(1.0, (k * length / (n - 1) - at) / l) : 1;
      const V3 c = cam::position(m, t) + V3(0, 0, 3);
      if (std::abs(c.x()) > 8.1 || std::abs(c.y()) > 8.1) continue;  // far from the stock
      auto ball = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
          3.f, openvdb::Vec3f(float(c.x()), float(c.y()), float(c.z())), float(h), band);
      openvdb::tools::csgDifference(*stock, *ball);
    }
    at += l;
  }
  const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> at_grid(*stock);
  Left out;
  const int q = 400;
  for (int i = 0; i < q; ++i)
    for (int j = 0; j < q; ++j) {
      const double x = -5 + 10 * (i + 0.5) / q, y = -5 + 10 * (j + 0.5) / q;
      const double s = std::max(0.0, -double(at_grid.wsSample(openvdb::Vec3R(x, y, 0))));
      out.max = std::max(out.max, s);
      out.mean += s / (double(q) * q);
    }
  return out;
}

int stock_table(const std::vector<std::pair<double, int>>& runs, std::FILE* out) {
  const fs::path dir = scratch();
  const std::string program = scallop_program(dir);
  write_box(dir / "plate.obj", V3(-10, -10, -5), V3(10, 10, 0));
  VerifyOptions o;
  o.program = program;
  o.part = (dir / "plate.obj").string();
  o.tool = "cutter:ball,6,20";
  o.tol = 0.01;
  o.stock = "box:-5,-5,-5,5,5,1";
  const auto t0 = std::chrono::steady_clock::now();
  const VerifyReport r = verify(o);
  const double tq = seconds_since(t0);
  // The truth (tests/cli/verify_stock_test.cpp): sqrt(r^2 + s^2 / 4) - r at the ridges.
  const double truth = std::sqrt(9.25) - 3;
  // The mean over the top's middle, by the midpoint rule (as the test integrates it).
  double mean = 0;
  for (int i = 0; i < 2000; ++i)
    for (int j = 0; j < 2000; ++j) {
      const double px = -5 + 10 * (i + 0.5) / 2000, py = -5 + 10 * (j + 0.5) / 2000;
      const double f = std::abs(py - std::round(py));
      mean += std::min({px + 5, 5 - px, py + 5, 5 - py, 1.0, std::sqrt(9 + f * f) - 3}) / 4e6;
    }
  int wrong = truth < r.stock->max_lower - 1e-12 || truth > r.stock->max_upper + 1e-12;
  std::fprintf(out,
               "\nStock left by a ball cutter D 6 at stepover 1 mm over a plate (27 passes, "
               "the stock 10 x 10 x 6 mm), T = 0.01 mm; the largest is sqrt(r^2 + s^2/4) - r "
               "= %.5f mm, the mean %.5f mm:\n\n| method | time (s) | largest (mm) | its error "
               "(mm) | mean (mm) | "
               "time / qmotion's |\n| --- | --- | --- | --- | --- | --- |\n",
               truth, mean);
  std::fprintf(out, "| qmotion `verify`%s | %.3f | [%.4f, %.4f] | %.4f | [%.4f, %.4f] | 1.00 |\n",
               r.stock->max_settled ? " (certified)" : " (not settled)", tq, r.stock->max_lower,
               r.stock->max_upper, r.stock->max_upper - r.stock->max_lower, r.stock->mean_lower,
               r.stock->mean_upper);
  const cam::Program p = io::read_gcode(program);
  for (const auto& [h, n] : runs) {
    std::fprintf(stderr, "verify_peers: OpenVDB, voxel %g, %d stamps\n", h, n);
    const auto t1 = std::chrono::steady_clock::now();
    const Left l = openvdb_stock_left(p, h, n);
    const double ts = seconds_since(t1);
    std::fprintf(out, "| OpenVDB, voxel %g mm, %d stamps | %.3f | %.4f | %.4f | %.4f | %.2f |\n", h,
                 n, ts, l.max, std::abs(l.max - truth), l.mean, ts / tq);
  }
  fs::remove_all(dir);
  return wrong;
}

}  // namespace
}  // namespace qmotion::peers

int main(int argc, char** argv) {
  using namespace qmotion::peers;
  openvdb::initialize();
  // --smoke, or the tables to run (gouge, stock, fcl; all by default).
  const bool smoke = argc > 1 && std::strcmp(argv[1], "--smoke") == 0;
  auto wanted = [&](const char* table) {
    if (argc < 2 || smoke) return true;
    for (int i = 1; i < argc; ++i)
      if (std::strcmp(argv[i], table) == 0) return true;
    return false;
  };
  const std::string data = QMOTION_TEST_DATA;
  const fs::path dir = scratch();
  fs::create_directories(dir);
  int wrong = 0;
  if (wanted("gouge")) {
    std::vector<Scene> scenes = {
        {"dip.ngc (one G1 through a ridge)", data + "/verify/dip.ngc", data + "/verify/bump.obj"}};
    if (!smoke) {
      qmotion::bench::write_part((dir / "part.obj").string(), 200);
      qmotion::bench::write_program((dir / "finish.ngc").string(), 2, 3);
      scenes.push_back({"finishing, 2 passes (202 G1)", (dir / "finish.ngc").string(),
                        (dir / "part.obj").string()});
      // The same passes in chords of 9 mm, whose sag gouges where the part is concave.
      qmotion::bench::write_program((dir / "chords.ngc").string(), 2, 3, 10);
      scenes.push_back({"9 mm chords, 2 passes (22 G1)", (dir / "chords.ngc").string(),
                        (dir / "part.obj").string()});
    }
    wrong += gouge_table(
        scenes, smoke ? std::vector<int>{2, 10} : std::vector<int>{2, 10, 100, 1000}, stdout);
  }
  if (wanted("stock"))
    wrong += stock_table(smoke ? std::vector<std::pair<double, int>>{{0.05, 50}}
                               : std::vector<std::pair<double, int>>{{0.04, 300},
                                                                     {0.02, 1000},
                                                                     {0.02, 3000},
                                                                     {0.01, 1000}},
                         stdout);
  if (wanted("fcl")) wrong += fcl_holder_table(smoke ? 24 : 240, stdout);
  fs::remove_all(dir);
  if (wrong > 0)
    std::fprintf(stderr, "verify_peers: qmotion's certified answer was wrong %d times\n", wrong);
  return wrong > 0 ? 1 : 0;
}
