// api/src/demo.cpp
#include <unistd.h>

#include <filesystem>
#include <qmotion/api/demo.hpp>
#include <qmotion/api/export.hpp>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/render/render.hpp>
#include <vector>

namespace qmotion {
using namespace io;  // NOLINT: the formats this call reads and writes
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

/// The five sample poses of the demo (the shared five_positions.json).
constexpr const char* kDemoPoses = R"({"units":"mm","poses":[
 {"t":0.0,"position":[0,0,0],"rotation":{"quaternion":[1,0,0,0]}},
 {"t":0.25,"position":[40,10,5],"rotation":{"axis_angle":{"axis":[0,0,1],"angle_deg":45}}},
 {"t":0.5,"position":[70,40,20],"rotation":{"axis_angle":{"axis":[1,1,0],"angle_deg":80}}},
 {"t":0.75,"position":[90,80,10],"rotation":{"quaternion":[0.5,0.162937633978,0.81468816989,0.244406450967]}},
 {"t":1.0,"position":[120,100,0],"rotation":{"axis_angle":{"axis":[0,1,1],"angle_deg":150}}}]})";

/// Moves every file of `from` into `to`: all of them, or (undoing the moves done) none.
/// A folder in the way is found before anything moves.
void publish(const fs::path& from, const fs::path& to) {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(from)) {
    if (fs::is_directory(to / e.path().filename()))
      throw Error(Errc::invalid_input, "-o " + to.string() + ": " + e.path().filename().string() +
                                           " is a folder; the demo writes a file of that name");
    files.push_back(e.path());
  }
  std::vector<fs::path> moved;
  for (const auto& f : files) {
    std::error_code ec;
    fs::rename(f, to / f.filename(), ec);
    if (ec) {
      const std::string why = ec.message();
      for (const auto& m : moved) fs::remove(m, ec);
      throw Error(Errc::invalid_input, "-o " + to.string() + ": cannot write the demo (" + why +
                                           "); nothing was written");
    }
    moved.push_back(to / f.filename());
  }
}

}  // namespace

json write_demo(const std::string& dir) {
  std::error_code ec;
  fs::path out = fs::absolute(fs::path(dir), ec).lexically_normal();
  if (out.filename().empty()) out = out.parent_path();  // "dir/"
  const bool existed = fs::is_directory(out, ec);
  fs::create_directories(out.parent_path(), ec);
  // Build everything in a scratch folder beside the output: a failure leaves nothing behind.
  const fs::path tmp = out.parent_path() / (".qmotion-demo-" + std::to_string(::getpid()) + "-" +
                                            out.filename().string());
  fs::remove_all(tmp, ec);
  if (!fs::create_directories(tmp, ec) || ec)
    throw Error(Errc::invalid_input, "-o " + dir + ": cannot create the output folder");
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code e;
      fs::remove_all(p, e);
    }
  } cleanup{tmp};

  const PoseSet set = parse_poses_json(kDemoPoses, "embedded demo poses");
  InterpolateOptions opt;  // elliptic + TR (Algorithm 1), the poses' own t
  opt.form = "bezier";
  const InterpolatedMotion interpolated = interpolate(set, opt);
  const std::string& summary = interpolated.summary;
  interpolated.save((tmp / "motion.json").string());
  kernel::Motion<double> named = interpolated.motion.rational();
  named.name = "motion.json";  // what the files' headers cite
  const Motion lm(std::move(named));
  // The paper's Figure 5 idea: a parabola of the moving space swept by the motion.
  const sweep::NurbsCurve<double> parabola{
      2, {0, 0, 0, 1, 1, 1}, {{-10, 0, 10}, {0, 0, -10}, {10, 0, 10}}, {1, 1, 1}};
  write_curve_json((tmp / "parabola.json").string(), parabola);

  json report = json::array();
  for (const std::string ext : {".json", ".step", ".igs"}) {
    for (const auto& [name, point] :
         {std::make_pair(std::string("trajectory_origin"), Eigen::Vector3d(0, 0, 0)),
          std::make_pair(std::string("trajectory_0_0_1"), Eigen::Vector3d(0, 0, 1))}) {
      ExportOptions go;
      go.output = (tmp / (name + ext)).string();
      const auto r = export_trajectory(lm, point, go);
      json c = check_geometry(go.output, lm, std::nullopt, point);
      c["file"] = name + ext;
      c["degree"] = r.degree_u;
      report.push_back(c);
    }
    ExportOptions go;
    go.output = (tmp / ("surface_parabola" + ext)).string();
    export_surface(lm, sweep::single_edge(parabola), "a parabola", go);
    json c = check_geometry(go.output, lm, sweep::single_edge(parabola), std::nullopt);
    c["file"] = "surface_parabola" + ext;
    report.push_back(c);
  }
  {  // The figure: the five poses, the motion, two trajectories and the swept parabola.
    render::RenderOptions ro;
    ro.frames = 0;
    ro.points = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 20)};
    ro.profile = sweep::single_edge(parabola);
    ro.object_size = 6;
    ro.title = "qmotion demo: " + summary;
    render::render_figure(lm, ro).write((tmp / "demo.svg").string());
  }
  const json doc{{"motion", {{"file", "motion.json"}, {"summary", summary}}},
                 {"exactness", report}};
  write_file_atomic((tmp / "report.json").string(), doc.dump(2) + "\n");
  if (!existed) {
    // A new folder appears whole: one rename.
    fs::rename(tmp, out, ec);
    if (ec)
      throw Error(Errc::invalid_input,
                  "-o " + dir + ": cannot create the output folder (" + ec.message() + ")");
  } else {
    publish(tmp, out);
  }
  return doc;
}

}  // namespace qmotion
