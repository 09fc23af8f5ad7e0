// io/cli/commands.cpp
#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/cli/commands.hpp>
#include <qmotion/io/export.hpp>
#include <qmotion/io/interpolate.hpp>
#include <qmotion/io/motion_info.hpp>
#include <sstream>
#ifdef QMOTION_WITH_CGAL
#include <qmotion/io/exact_number.hpp>
#endif
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/occt_info.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/io/profiles.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/kernel/order.hpp>
#include <qmotion/kernel/parametrization.hpp>
#include <qmotion/kernel/spline_interpolation.hpp>

namespace qmotion::cli {
namespace {

using json = nlohmann::json;

int cmd_info(const std::string& path, bool exact) {
  std::cout << io::motion_info(io::read_motion(path), exact).dump(2) << '\n';
  return 0;
}

int cmd_eval(const std::string& path, const std::string& t_text, const std::string& point_text) {
  const io::MotionFile f = io::read_motion(path);
  const double t = io::parse_number_text(t_text, "--t").value;
  const Eigen::Vector3d x =
      point_text.empty() ? Eigen::Vector3d::Zero() : io::parse_point(point_text, "--point");
  std::string warning;
  const json out = io::motion_eval(f, t, x, &warning, t_text);
  if (!warning.empty()) std::cerr << "qmotion: warning: " << path << " " << warning << "\n";
  std::cout << out.dump(2) << '\n';
  return 0;
}

int cmd_interpolate(const std::string& poses_path, const std::string& output,
                    const io::InterpolateOptions& opt) {
  const io::PoseSet set = io::read_poses(poses_path);
  const io::InterpolatedMotion r = io::interpolate(set, opt);
  if (!r.poles.empty()) {
    std::ostringstream os;
    os.precision(10);
    for (double p : r.poles) os << " " << p;
    std::cerr << "qmotion: warning: the motion has a pole (zero rotational part) at t =" << os.str()
              << ": trajectories are unbounded there and cannot be exported\n";
  }
  io::write_file_atomic(output, r.document.dump(1) + "\n");
  std::cerr << "qmotion: wrote " << output << " (" << r.summary << ")\n";
  return 0;
}

int cmd_poses(const std::string& path, const std::string& out_path) {
  const io::PoseSet set = io::read_poses(path);
  const json doc = io::poses_to_json(set);
  if (!out_path.empty()) {
    io::write_file_atomic(out_path, doc.dump(1) + "\n");
    std::cerr << "qmotion: wrote " << set.poses.size() << " poses to " << out_path << "\n";
  } else {
    json summary{{"source", path},
                 {"poses", set.poses.size()},
                 {"units", set.units},
                 {"has_t", set.has_t()}};
    std::cout << summary.dump(2) << '\n';
  }
  return 0;
}

/// The five sample poses of the demo (the shared five_positions.json).
constexpr const char* kDemoPoses = R"({"units":"mm","poses":[
 {"t":0.0,"position":[0,0,0],"rotation":{"quaternion":[1,0,0,0]}},
 {"t":0.25,"position":[40,10,5],"rotation":{"axis_angle":{"axis":[0,0,1],"angle_deg":45}}},
 {"t":0.5,"position":[70,40,20],"rotation":{"axis_angle":{"axis":[1,1,0],"angle_deg":80}}},
 {"t":0.75,"position":[90,80,10],"rotation":{"quaternion":[0.5,0.162937633978,0.81468816989,0.244406450967]}},
 {"t":1.0,"position":[120,100,0],"rotation":{"axis_angle":{"axis":[0,1,1],"angle_deg":150}}}]})";

/// An isometric SVG of the trajectories and of the profile at nine instants.
std::string demo_svg(const io::LoadedMotion& lm, const sweep::NurbsCurve<double>& profile) {
  auto proj = [](const Eigen::Vector3d& p) {
    return Eigen::Vector2d((p.x() - p.y()) * 0.8660254037844386, -(p.x() + p.y()) * 0.5 - p.z());
  };
  std::vector<std::vector<Eigen::Vector2d>> lines;
  std::vector<std::string> colors;
  for (const Eigen::Vector3d& x :
       std::vector<Eigen::Vector3d>{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 20)}) {
    lines.emplace_back();
    colors.push_back(lines.size() == 1 ? "#c0392b" : "#2471a3");
    for (int i = 0; i <= 200; ++i)
      lines.back().push_back(proj(kernel::apply_point(
          kernel::evaluate(lm.motion, lm.motion.a() + (lm.motion.b() - lm.motion.a()) * i / 200.0),
          x)));
  }
  for (int k = 0; k <= 8; ++k) {
    const auto q =
        kernel::evaluate(lm.motion, lm.motion.a() + (lm.motion.b() - lm.motion.a()) * k / 8.0);
    lines.emplace_back();
    colors.push_back("#555555");
    for (int j = 0; j <= 40; ++j)
      lines.back().push_back(proj(kernel::apply_point(q, sweep::evaluate(profile, j / 40.0))));
  }
  Eigen::Vector2d lo = lines[0][0], hi = lines[0][0];
  for (const auto& l : lines)
    for (const auto& p : l) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  const double pad = 10, scale = std::min(760.0 / std::max(hi.x() - lo.x(), 1e-9),
                                          700.0 / std::max(hi.y() - lo.y(), 1e-9));
  std::ostringstream os;
  os << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\""
     << static_cast<int>((hi.x() - lo.x()) * scale + 2 * pad) << "\" height=\""
     << static_cast<int>((hi.y() - lo.y()) * scale + 2 * pad + 30)
     << "\">\n<text x=\"10\" y=\"18\" font-family=\"sans-serif\" font-size=\"11\">elliptic + TR "
        "motion, five poses. red: origin; "
        "blue: (0,0,20); grey: parabola at t = k/8</text>\n";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    os << "<polyline fill=\"none\" stroke=\"" << colors[i] << "\" stroke-width=\"1.5\" points=\"";
    for (const auto& p : lines[i])
      os << (p.x() - lo.x()) * scale + pad << "," << (p.y() - lo.y()) * scale + pad + 30 << " ";
    os << "\"/>\n";
  }
  os << "</svg>\n";
  return os.str();
}

int cmd_demo(const std::string& dir) {
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
  const io::LoadedMotion lm = io::load_motion(io::parse_motion(motion_doc, "motion.json"));
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
  io::write_file_atomic((tmp / "demo.svg").string(), demo_svg(lm, parabola));
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

int run(int argc, char** argv) {
  CLI::App app{"qmotion: rational motions from rigid-body poses, exported as exact NURBS",
               "qmotion"};
  app.require_subcommand(0, 1);
  bool version = false;
  app.add_flag("--version", version, "Print the version and the OpenCASCADE version, then exit");
  app.footer(
      "Exit status: 0 success, 2 bad input or usage, 3 numerical failure, 1 internal error.\n"
      "Conventions: quaternions (w,x,y,z); pose P = (2 + eps s) * r; millimetres unless the file "
      "says otherwise.\n");

  auto* info = app.add_subcommand(
      "info", "Describe a motion file as JSON (degree, order, Plucker residual, poles, ...)");
  std::string info_path;
  bool info_exact = false;
  info->add_option("MOTION", info_path, "Motion JSON file")->required();
  info->add_flag(
      "--exact", info_exact,
      "Compute the Plucker residual in exact rational arithmetic from the file's digits");

  auto* eval = app.add_subcommand(
      "eval", "Evaluate a motion at a parameter: position, rotation and an optional point");
  std::string eval_path, eval_t, eval_point;
  eval->add_option("MOTION", eval_path, "Motion JSON file")->required();
  eval->add_option("--t", eval_t,
                   "Parameter value inside the motion's interval (negative values allowed)")
      ->required()
      ->allow_extra_args(false);
  eval->add_option("--point", eval_point,
                   "Point x,y,z of the moving space whose image is reported (default: the origin)");

  auto* interp = app.add_subcommand(
      "interpolate",
      "Build a Q-motion through the poses (Juettler's methods) and write it as motion JSON");
  io::InterpolateOptions ia;
  std::string ia_poses, ia_output;
  interp->add_option("POSES", ia_poses, "Pose file (.json or .csv)")->required();
  interp->add_option("-o,--output", ia_output, "Motion JSON file to write")->required();
  interp->add_option("--rotation", ia.rotation,
                     "Rotation interpolation: elliptic (default), affine, projective (the last two "
                     "for --form bezier)");
  interp->add_option("--translation", ia.translation,
                     "Translation: tr (default), trt, minimal (minimal order)");
  interp->add_option(
      "--trt-degrees", ia.trt_degrees,
      "TRT degrees L1,L2 with L1 + L2 = m - 1 (default m-1,0; L1 = L2 even is singular)");
  interp->add_option("--param", ia.param,
                     "Parameters: given (default when every pose has t), uniform (default "
                     "otherwise), chordal, star-chordal, "
                     "centripetal, angular, angular-chordal");
  interp->add_option("--form", ia.form,
                     "bezier (default up to six poses) | bspline (default beyond: global B-spline, "
                     "linear cost) | c1 (Algorithm 2: local C1 cubic pieces)");
  interp->add_option("--degree", ia.degree,
                     "Rotational degree of B-spline motions (default 3; a Bezier motion's is fixed "
                     "by the method)");
  interp->add_option("--translation-degree", ia.translation_degree,
                     "Translational degree of B-spline motions (default 3)");
  interp->add_flag(
      "--exact", ia.exact,
      "Compute in exact rational arithmetic from the file's digits (quaternion rotations only)");

  auto* poses = app.add_subcommand(
      "poses", "Validate a pose file (JSON or CSV); with -o, write it as canonical pose JSON");
  std::string poses_path, poses_out;
  poses->add_option("POSES", poses_path, "Pose file (.json or .csv)")->required();
  poses->add_option("-o,--output", poses_out, "Write the poses as JSON (SPEC §5) to this file");

  auto* traj = app.add_subcommand(
      "trajectory", "Write the exact rational trajectory of a point as NURBS (JSON, STEP or IGES)");
  std::string traj_motion, traj_point;
  io::ExportOptions traj_opt;
  traj->add_option("MOTION", traj_motion, "Motion JSON file")->required();
  traj->add_option("--point", traj_point, "Point x,y,z of the moving space")->required();
  traj->add_option("-o,--output", traj_opt.output, "Output .json, .step/.stp or .igs/.iges")
      ->required();
  traj->add_option("--max-degree", traj_opt.max_degree,
                   "Approximate (measured, within --tol) when the exact degree is above D");
  traj->add_option(
      "--tol", traj_opt.tol,
      "Approximation tolerance in length units (default 1e-6 of the bounding-box diagonal)");
  traj->add_option("--units", traj_opt.units,
                   "Convert the numbers from the motion's unit into U and declare U: mm, cm, m, "
                   "um, in, ft (default: the motion's)");

  auto* swp = app.add_subcommand(
      "sweep",
      "Write the kinematic surface M(t) x(v) of a profile as NURBS (JSON, STEP, IGES; STL mesh)");
  std::string swp_motion, swp_profile;
  io::ExportOptions swp_opt;
  swp->add_option("MOTION", swp_motion, "Motion JSON file")->required();
  swp->add_option("--profile", swp_profile,
                  "Profile: nurbs_curve .json (or an array of them), .step/.igs (the first "
                  "wire's edges), segment:x0,y0,z0:x1,y1,z1, polyline:x,y,z:x,y,z:..., rect:w,h, "
                  "circle:r, arc:r,a0,a1")
      ->required();
  swp->add_option("-o,--output", swp_opt.output, "Output .json, .step/.stp, .igs/.iges or .stl")
      ->required();
  swp->add_option("--max-degree", swp_opt.max_degree,
                  "Approximate along the motion (measured, within --tol) above degree D");
  swp->add_option(
      "--tol", swp_opt.tol,
      "Approximation tolerance in length units (default 1e-6 of the bounding-box diagonal)");
  swp->add_option("--units", swp_opt.units,
                  "Convert the numbers from the motion's unit into U and declare U: mm, cm, m, "
                  "um, in, ft (default: the motion's)");
  swp->add_flag("--single-face", swp_opt.single_face,
                "STEP/IGES: one face per profile edge instead of a shell of C1 faces split at the "
                "C0 knots");
  swp->add_flag("--solid", swp_opt.solid,
                "Closed planar profile: add planar caps at both ends and write one closed solid");

  auto* chk = app.add_subcommand("check",
                                 "Measure the deviation of a written NURBS (JSON, or STEP/IGES "
                                 "read through OpenCASCADE) from the motion");
  std::string chk_file, chk_motion, chk_profile, chk_point;
  int chk_grid = 41;
  chk->add_option("GEOMETRY", chk_file, "The .json, .step/.stp or .igs/.iges file to check")
      ->required();
  chk->add_option("--motion", chk_motion, "Motion JSON file")->required();
  chk->add_option("--profile", chk_profile, "The profile the surface was swept from");
  chk->add_option("--point", chk_point, "The point whose trajectory the curve is");
  chk->add_option("--grid", chk_grid, "Lattice size per direction (plus 400 random samples)");

  auto* demo = app.add_subcommand("demo", "Run the main job on the embedded five sample poses");
  std::string demo_dir = "demo-out";
  demo->add_option("-o,--output", demo_dir, "Output folder");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::cout << app.help("", CLI::AppFormatMode::All);
    return 0;
  } catch (const CLI::ParseError& e) {
    throw Error(Errc::invalid_input, std::string(e.what()) + " (see qmotion --help)");
  }
  if (version) {
    std::cout << "qmotion 0.1.0 (OpenCASCADE " << io::occt_version() << ")\n";
    return 0;
  }
  if (*info) return cmd_info(info_path, info_exact);
  if (*eval) return cmd_eval(eval_path, eval_t, eval_point);
  if (*interp) return cmd_interpolate(ia_poses, ia_output, ia);
  if (*poses) return cmd_poses(poses_path, poses_out);
  if (*traj) {
    const auto r = io::export_trajectory(io::load_motion(traj_motion),
                                         io::parse_point(traj_point, "--point"), traj_opt);
    std::cerr << "qmotion: wrote " << r.path << " (degree " << r.degree_u << ", C" << r.continuity_u
              << ", " << r.poles << " poles, " << r.units << ", " << r.inserted_knots
              << " knots inserted for positive weights"
              << (r.approx_deviation ? ", approximation with measured deviation " +
                                           std::to_string(*r.approx_deviation)
                                     : std::string(""))
              << ")\n";
    return 0;
  }
  if (*swp) {
    const io::LoadedMotion lm = io::load_motion(swp_motion);
    const auto profile = io::read_profile(swp_profile, lm.file.units);
    const auto r = io::export_surface(lm, profile, swp_profile, swp_opt);
    std::cerr << "qmotion: wrote " << r.path << " (degrees " << r.degree_u << " x " << r.degree_v
              << ", C" << r.continuity_u << " x C" << r.continuity_v << ", " << r.faces
              << (r.faces == 1 ? " face, " : " faces, ") << r.poles << " poles, " << r.units
              << (r.volume ? ", solid of volume " + std::to_string(*r.volume) : std::string(""))
              << (r.approx_deviation ? ", approximation with measured deviation " +
                                           std::to_string(*r.approx_deviation)
                                     : std::string(""))
              << ")\n";
    return 0;
  }
  if (*chk) {
    if (chk_profile.empty() == chk_point.empty())
      throw Error(Errc::invalid_input, "check: give exactly one of --profile and --point");
    const io::LoadedMotion lm = io::load_motion(chk_motion);
    std::optional<sweep::Profile<double>> profile;
    std::optional<Eigen::Vector3d> point;
    if (!chk_profile.empty()) profile = io::read_profile(chk_profile, lm.file.units);
    if (!chk_point.empty()) point = io::parse_point(chk_point, "--point");
    if (chk_grid < 1 || chk_grid > 1000)
      throw Error(Errc::invalid_input, "--grid: expected 1 to 1000");
    std::cout << io::check_geometry(chk_file, lm, profile, point, chk_grid).dump(2) << "\n";
    return 0;
  }
  if (*demo) return cmd_demo(demo_dir);
  std::cout << app.help();
  return 2;
}

}  // namespace qmotion::cli
