// io/cli/demo.cpp: `qmotion demo`: the main job on embedded poses.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/cli/command.hpp>
#include <qmotion/io/export.hpp>
#include <qmotion/io/interpolate.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/svg.hpp>
#include <qmotion/kernel/error.hpp>

namespace qmotion::cli {
namespace {

using json = nlohmann::json;

/// The five sample poses of the demo (the shared five_positions.json).
constexpr const char* kDemoPoses = R"({"units":"mm","poses":[
 {"t":0.0,"position":[0,0,0],"rotation":{"quaternion":[1,0,0,0]}},
 {"t":0.25,"position":[40,10,5],"rotation":{"axis_angle":{"axis":[0,0,1],"angle_deg":45}}},
 {"t":0.5,"position":[70,40,20],"rotation":{"axis_angle":{"axis":[1,1,0],"angle_deg":80}}},
 {"t":0.75,"position":[90,80,10],"rotation":{"quaternion":[0.5,0.162937633978,0.81468816989,0.244406450967]}},
 {"t":1.0,"position":[120,100,0],"rotation":{"axis_angle":{"axis":[0,1,1],"angle_deg":150}}}]})";

int run_demo(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw Error(Errc::invalid_input, "-o " + dir + ": cannot create the output folder");
  // Build everything in a scratch folder first: a failure leaves nothing behind.
  const fs::path tmp = fs::path(dir) / (".qmotion-demo-" + std::to_string(::getpid()));
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code e;
      fs::remove_all(p, e);
    }
  } cleanup{tmp};

  const io::PoseSet set = io::parse_poses_json(kDemoPoses, "embedded demo poses");
  io::InterpolateOptions opt;  // elliptic + TR (Algorithm 1), the poses' own t
  opt.form = "bezier";
  const io::InterpolatedMotion interpolated = io::interpolate(set, opt);
  const json& motion_doc = interpolated.document;
  const std::string& summary = interpolated.summary;
  io::write_file_atomic((tmp / "motion.json").string(), motion_doc.dump(1) + "\n");
  kernel::Motion<double> lm = interpolated.motion;
  lm.name = "motion.json";  // what the files' headers cite
  // The paper's Figure 5 idea: a parabola of the moving space swept by the motion.
  const sweep::NurbsCurve<double> parabola{
      2, {0, 0, 0, 1, 1, 1}, {{-10, 0, 10}, {0, 0, -10}, {10, 0, 10}}, {1, 1, 1}};
  io::write_file_atomic((tmp / "parabola.json").string(),
                        io::curve_to_json(parabola).dump(1) + "\n");

  json report = json::array();
  for (const std::string ext : {".json", ".step", ".igs"}) {
    for (const auto& [name, point] :
         {std::make_pair(std::string("trajectory_origin"), Eigen::Vector3d(0, 0, 0)),
          std::make_pair(std::string("trajectory_0_0_1"), Eigen::Vector3d(0, 0, 1))}) {
      io::ExportOptions go;
      go.output = (tmp / (name + ext)).string();
      const auto r = io::export_trajectory(lm, point, go);
      json c = io::check_geometry(go.output, lm, std::nullopt, point);
      c["file"] = name + ext;
      c["degree"] = r.degree_u;
      report.push_back(c);
    }
    io::ExportOptions go;
    go.output = (tmp / ("surface_parabola" + ext)).string();
    io::export_surface(lm, sweep::single_edge(parabola), "a parabola", go);
    json c = io::check_geometry(go.output, lm, sweep::single_edge(parabola), std::nullopt);
    c["file"] = "surface_parabola" + ext;
    report.push_back(c);
  }
  io::write_file_atomic((tmp / "demo.svg").string(), io::render_demo_svg(lm, parabola));
  const json doc{{"motion", {{"file", "motion.json"}, {"summary", summary}}},
                 {"exactness", report}};
  io::write_file_atomic((tmp / "report.json").string(), doc.dump(2) + "\n");
  for (const auto& e : fs::directory_iterator(tmp))
    fs::rename(e.path(), fs::path(dir) / e.path().filename());
  std::cout << doc.dump(2) << "\n";
  std::cerr
      << "qmotion: demo written to " << dir
      << " (motion.json, trajectories and surface as JSON/STEP/IGES, demo.svg, report.json)\n";
  return 0;
}

}  // namespace

Command add_demo(CLI::App& app) {
  auto* sub = app.add_subcommand("demo", "Run the main job on the embedded five sample poses");
  auto dir = std::make_shared<std::string>("demo-out");
  sub->add_option("-o,--output", *dir, "Output folder");
  return {sub, [dir] { return run_demo(*dir); }};
}

}  // namespace qmotion::cli
