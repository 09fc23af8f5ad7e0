// io/cli/commands.cpp
#include "io/cli/commands.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/json_number.hpp"
#include "io/motion_json.hpp"
#include "io/occt_info.hpp"
#include "io/poses.hpp"
#include "kernel/error.hpp"
#include "kernel/motion.hpp"

namespace qmotion::cli {
namespace {

using json = nlohmann::json;

/// Parses "x,y,z" given to `flag`.
Eigen::Vector3d parse_point(const std::string& text, const std::string& flag) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string cell;
  while (std::getline(ss, cell, ',')) v.push_back(io::parse_number_text(cell, flag).value);
  if (v.size() != 3)
    throw Error(Errc::invalid_input, flag + ": expected three numbers x,y,z, found '" + text + "'");
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

json vec_json(const Eigen::Vector3d& v) { return json{v(0), v(1), v(2)}; }

/// Residual of Q(t_i) against the pose P_i, scale free: min over the sign of
/// |Q/|Q| -+ P/|P|| (8 components).
double pose_residual(const kernel::DualQuaternion<double>& q,
                     const kernel::DualQuaternion<double>& p) {
  const double nq = std::sqrt(q.real().norm2()), np = std::sqrt(p.real().norm2());
  double plus = 0, minus = 0;
  for (int i = 0; i < 8; ++i) {
    plus = std::max(plus, std::abs(q[i] / nq - p[i] / np));
    minus = std::max(minus, std::abs(q[i] / nq + p[i] / np));
  }
  return std::min(plus, minus);
}

/// The recorded input poses of a motion file's method, if any.
std::optional<io::PoseSet> recorded_poses(const io::MotionFile& f) {
  if (!f.method.is_object() || !f.method.contains("input_poses")) return std::nullopt;
  return io::parse_poses_json_value(f.method["input_poses"], f.source + ": method.input_poses");
}

int cmd_info(const std::string& path, bool exact) {
  const io::MotionFile f = io::read_motion(path);
  const kernel::QMotion<double> m = io::to_motion_double(f);
  json out;
  out["type"] = "q-motion";
  out["basis"] = m.basis == kernel::Basis::bezier ? "bezier" : "bspline";
  out["degree"] = m.degree();
  // Order: degree of a general point's trajectory. Elevation the representation carries
  // is stripped; common polynomial factors are not yet (see README).
  const Eigen::Vector4d generic(1.0, 0.3718, -0.5813, 0.7211);
  int order = 0;
  for (const auto& piece : kernel::bezier_pieces(kernel::homogeneous_trajectory(m, generic)))
    order = std::max(order, kernel::exact_degree(piece, 1e-10));
  out["order"] = order;
  out["segments"] = m.segments();
  out["param_range"] = {m.a(), m.b()};
  out["units"] = f.units;
#ifdef QMOTION_WITH_CGAL
  if (exact) {
    out["plucker_residual"] = kernel::to_double(kernel::plucker_residual(io::to_motion_exact(f)));
    out["exact"] = true;
  } else {
    out["plucker_residual"] = kernel::plucker_residual(m);
  }
#else
  if (exact)
    throw Error(Errc::invalid_input,
                "--exact: this build has no exact arithmetic (QMOTION_WITH_CGAL=OFF)");
  out["plucker_residual"] = kernel::plucker_residual(m);
#endif
  json res = nullptr;
  if (const auto poses = recorded_poses(f)) {
    res = json::array();
    const auto P = io::to_poses_double(*poses);
    const json& params = f.method.contains("parameters") ? f.method["parameters"] : json();
    for (std::size_t i = 0; i < P.size(); ++i) {
      double t = P[i].t ? *P[i].t : std::nan("");
      if (params.is_array() && i < params.size())
        t = io::read_number(params[i], path + ": method.parameters").value;
      if (!std::isfinite(t)) {
        res = nullptr;
        break;
      }
      res.push_back(pose_residual(kernel::evaluate(m, t), P[i].dual_quaternion()));
    }
  }
  out["interpolation_residual"] = res;
  out["poles"] = kernel::find_poles(m);
  if (!f.method.is_null()) {
    json method = f.method;
    method.erase("input_poses");
    out["method"] = method;
  }
  std::cout << out.dump(2) << '\n';
  return 0;
}

int cmd_eval(const std::string& path, const std::string& t_text, const std::string& point_text) {
  const io::MotionFile f = io::read_motion(path);
  const kernel::QMotion<double> m = io::to_motion_double(f);
  const double t = io::parse_number_text(t_text, "--t").value;
  if (t < m.a() || t > m.b()) {
    std::ostringstream os;
    os.precision(17);
    os << "--t " << t_text << " is outside the motion's parameter interval [" << m.a() << ", "
       << m.b() << "]";
    throw Error(Errc::invalid_input, os.str());
  }
  const Eigen::Vector3d x =
      point_text.empty() ? Eigen::Vector3d::Zero() : parse_point(point_text, "--point");
  const auto q = kernel::evaluate(m, t);
  if (q.real().norm2() <= 1e-300)
    throw Error(Errc::numerical_failure,
                "the motion has a pole at t = " + t_text + " (zero rotational part)");
  kernel::Quaternion<double> r = kernel::normalized(q.real());
  if (r.w() < 0) r = -r;
  json out;
  out["t"] = t;
  out["position"] = vec_json(kernel::translation_vector(q));
  out["quaternion"] = {r.w(), r.x(), r.y(), r.z()};
  out["point"] = vec_json(kernel::apply_point(q, x));
  const double pl = kernel::plucker_residual(q);
  if (pl > 1e-9)
    std::cerr << "qmotion: warning: " << path
              << " violates the Plucker condition at t (relative residual " << pl
              << "): not a rigid motion\n";
  std::cout << out.dump(2) << '\n';
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

int cmd_demo(const std::string& dir) {
  std::cout << "qmotion demo: not yet. The demo (five poses -> elliptic + TR motion -> "
               "trajectories and a\n"
               "kinematic surface written as STEP, IGES and JSON) arrives with interpolation and "
               "sweeps.\n"
               "Output folder requested: "
            << dir << " (nothing written).\n";
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

  auto* poses = app.add_subcommand(
      "poses", "Validate a pose file (JSON or CSV); with -o, write it as canonical pose JSON");
  std::string poses_path, poses_out;
  poses->add_option("POSES", poses_path, "Pose file (.json or .csv)")->required();
  poses->add_option("-o,--output", poses_out, "Write the poses as JSON (SPEC §5) to this file");

  auto* demo = app.add_subcommand("demo", "Run the main job on the embedded five sample poses");
  std::string demo_dir = "qmotion-demo";
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
  if (*poses) return cmd_poses(poses_path, poses_out);
  if (*demo) return cmd_demo(demo_dir);
  std::cout << app.help();
  return 2;
}

}  // namespace qmotion::cli
