// tests/fuzz/options_fuzz.cpp: the command line's option and number reading. The first
// byte chooses what reads the rest:
//   0 `qmotion eval MOTION ARGS...`, 1 `qmotion info MOTION ARGS...`,
//   2 `qmotion check CURVE --motion MOTION ARGS...` (ARGS: the rest, one per line; these
//     commands only print), 3 a profile shorthand (`circle:r`, `arc:r,a0,a1`, ...),
//   4 a point "x,y,z" (also as --view and --size), 5 a number, read as double and exactly.
// The motion and curve are written once, at start-up, to a temporary folder.
#include <unistd.h>

#include <filesystem>
#include <qmotion/api/export.hpp>
#include <qmotion/api/interpolate.hpp>
#ifdef QMOTION_WITH_CGAL
#include <qmotion/io/exact_number.hpp>
#endif
#include <qmotion/io/profiles.hpp>
#include <qmotion/render/render.hpp>
#include <sstream>
#include <vector>

#include "command.hpp"
#include "fuzz_util.hpp"

namespace {

std::string g_motion, g_curve;

constexpr const char* kPoses = R"({"units": "mm", "poses": [
  {"t": 0, "position": [0, 0, 0], "rotation": {"quaternion": [1, 0, 0, 0]}},
  {"t": 0.5, "position": [10, 5, 0], "rotation": {"axis_angle": {"axis": [0, 0, 1], "angle_deg": 60}}},
  {"t": 1, "position": [20, 0, 5], "rotation": {"quaternion": [0.5, 0.5, 0.5, 0.5]}}]})";

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  using namespace qmotion;
  const auto dir =
      std::filesystem::temp_directory_path() / ("qmotion-fuzz-options-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  g_motion = (dir / "motion.json").string();
  g_curve = (dir / "curve.json").string();
  const auto made = qmotion::interpolate(io::parse_poses_json(kPoses, "poses"), {});
  made.save(g_motion);
  qmotion::ExportOptions opt;
  opt.output = g_curve;
  qmotion::export_geometry(made.motion, qmotion::Geometry::trajectory(Eigen::Vector3d(1, 2, 3)),
                           opt);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qmotion;
  if (size == 0) return 0;
  const std::string rest = fuzz::text(data + 1, size - 1);
  switch (data[0] % 6) {
    case 0:
    case 1:
    case 2: {
      std::vector<std::string> args{"qmotion"};
      if (data[0] % 6 == 0) args.insert(args.end(), {"eval", g_motion});
      if (data[0] % 6 == 1) args.insert(args.end(), {"info", g_motion});
      if (data[0] % 6 == 2) args.insert(args.end(), {"check", g_curve, "--motion", g_motion});
      std::istringstream lines(rest);
      for (std::string line; args.size() < 12 && std::getline(lines, line);) args.push_back(line);
      std::vector<char*> argv;
      for (auto& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      fuzz::accept_refusals([&] { (void)cli::run(static_cast<int>(args.size()), argv.data()); });
      break;
    }
    case 3:
      fuzz::accept_refusals([&] { (void)io::read_profile(rest, "mm"); });
      break;
    case 4:
      fuzz::accept_refusals([&] { (void)io::parse_point(rest, "--point"); });
      fuzz::accept_refusals([&] { (void)render::parse_view(rest); });
      fuzz::accept_refusals([&] { (void)render::parse_size(rest); });
      break;
    default:
      fuzz::accept_refusals([&] {
        const io::Number n = io::parse_number_text(rest, "--t");
#ifdef QMOTION_WITH_CGAL
        (void)io::exact_from_text(n.text.str());
#endif
      });
  }
  return 0;
}
