// io/cli/commands.cpp
#include "io/cli/commands.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <sstream>

#include "io/atomic_file.hpp"
#ifdef QMOTION_WITH_CGAL
#include "io/exact_number.hpp"
#endif
#include "io/json_number.hpp"
#include "io/motion_json.hpp"
#include "io/occt_info.hpp"
#include "io/poses.hpp"
#include "kernel/error.hpp"
#include "kernel/interpolation.hpp"
#include "kernel/motion.hpp"
#include "kernel/order.hpp"
#include "kernel/parametrization.hpp"

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

/// The recorded input poses of a motion file's method, if any.
std::optional<io::PoseSet> recorded_poses(const io::MotionFile& f) {
  if (!f.method.is_object() || !f.method.contains("input_poses")) return std::nullopt;
  return io::parse_poses_json_value(f.method["input_poses"], f.source + ": method.input_poses");
}

/// Residual of the motion at every recorded pose (null when a parameter is missing). Exact
/// Scalar: 0 where Q(t_i) is exactly proportional to P_i, else the double residual.
template <typename Scalar>
json interpolation_residuals(const kernel::QMotion<Scalar>& m,
                             const std::vector<kernel::Pose<Scalar>>& P, const io::MotionFile& f,
                             Scalar /*tag*/) {
  json res = json::array();
  const json& params = f.method.contains("parameters") ? f.method["parameters"] : json();
  for (std::size_t i = 0; i < P.size(); ++i) {
    std::optional<Scalar> t = P[i].t;
    if (params.is_array() && i < params.size()) {
      const io::Number n =
          io::read_number(params[i], f.source + ": method.parameters[" + std::to_string(i) + "]");
#ifdef QMOTION_WITH_CGAL
      if constexpr (kernel::is_exact_v<Scalar>) {
        t = io::exact_from_text(n.text);
      } else {
        t = n.value;
      }
#else
      t = n.value;
#endif
    }
    if (!t) return nullptr;
    const auto q = kernel::evaluate(m, *t);
    const auto p = P[i].dual_quaternion();
    bool proportional = kernel::is_exact_v<Scalar>;
    if constexpr (kernel::is_exact_v<Scalar>)
      for (int c = 0; c < 8; ++c)
        for (int d = c + 1; d < 8; ++d) proportional = proportional && q[c] * p[d] == q[d] * p[c];
    if (proportional) {
      res.push_back(0.0);
      continue;
    }
    kernel::DualQuaternion<double> qd, pd;
    for (int c = 0; c < 8; ++c) {
      qd[c] = kernel::to_double(q[c]);
      pd[c] = kernel::to_double(p[c]);
    }
    res.push_back(kernel::pose_residual(qd, pd));
  }
  return res;
}

/// The order a recorded interpolation method guarantees (kernel::construction_order).
std::optional<int> recorded_order(const json& method) {
  if (!method.is_object() || !method.contains("rotation_degree") ||
      !method.contains("translation") || !method.contains("translation_degree"))
    return std::nullopt;
  const json& k = method["rotation_degree"];
  const json& l = method["translation_degree"];
  const json& tr = method["translation"];
  if (!k.is_number_integer() || !tr.is_string()) return std::nullopt;
  if (tr == "trt" && l.is_array() && l.size() == 2 && l[0].is_number_integer() &&
      l[1].is_number_integer())
    return kernel::construction_order(kernel::TranslationMethod::trt, k.get<int>(), l[0].get<int>(),
                                      l[1].get<int>());
  if (!l.is_number_integer()) return std::nullopt;
  if (tr == "tr")
    return kernel::construction_order(kernel::TranslationMethod::tr, k.get<int>(), l.get<int>());
  if (tr == "minimal")
    return kernel::construction_order(kernel::TranslationMethod::minimal, k.get<int>(),
                                      l.get<int>());
  return std::nullopt;
}

int cmd_info(const std::string& path, bool exact) {
  const io::MotionFile f = io::read_motion(path);
  const kernel::QMotion<double> m = io::to_motion_double(f);
  json out;
  out["type"] = "q-motion";
  out["basis"] = m.basis == kernel::Basis::bezier ? "bezier" : "bspline";
  out["degree"] = m.degree();
  // Order: degree of a general point's trajectory with every common factor removed.
  // --exact: exactly from the file's digits. Otherwise: what the recorded construction
  // guarantees, or, for motions without one, a numerical rank.
  const auto recorded = recorded_order(f.method);
#ifdef QMOTION_WITH_CGAL
  if (exact) {
    out["order"] = kernel::motion_order(io::to_motion_exact(f));
    out["order_source"] = "exact";
  } else
#endif
      if (recorded) {
    out["order"] = *recorded;
    out["order_source"] = "construction";
  } else {
    out["order"] = kernel::motion_order(m);
    out["order_source"] = "numerical";
  }
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
#ifdef QMOTION_WITH_CGAL
    res = exact ? interpolation_residuals(io::to_motion_exact(f), io::to_poses_exact(*poses), f,
                                          kernel::Rational(0))
                : interpolation_residuals(m, io::to_poses_double(*poses), f, 0.0);
#else
    res = interpolation_residuals(m, io::to_poses_double(*poses), f, 0.0);
#endif
  }
  out["interpolation_residual"] = res;
  out["poles"] = kernel::find_poles(m);
  if (!f.method.is_null()) {
    json method = f.method;
    for (const char* bulky : {"input_poses", "rotation_control_points",
                              "translation_control_points", "translation2_control_points"})
      method.erase(bulky);
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

struct InterpolateArgs {
  std::string poses, output, rotation = "elliptic", translation = "tr", trt_degrees, param, form;
  int degree = -1, translation_degree = -1;
  bool exact = false;
};

template <typename Scalar>
json numbers_json(const std::vector<Scalar>& t) {
  json a = json::array();
  for (const auto& v : t) {
#ifdef QMOTION_WITH_CGAL
    if constexpr (kernel::is_exact_v<Scalar>) {
      a.push_back(io::exact_to_text(v));
      continue;
    }
#endif
    a.push_back(kernel::to_double(v));
  }
  return a;
}

template <typename Scalar>
json run_interpolation(const std::vector<kernel::Pose<Scalar>>& poses, const std::vector<Scalar>& t,
                       const kernel::InterpolationOptions& opt, json method,
                       const std::string& units, std::string& summary) {
  const auto r = kernel::interpolate_bezier(poses, t, opt);
  method["parameters"] = numbers_json(t);
  method["rotation_degree"] = r.k;
  method["translation_degree"] =
      opt.translation == kernel::TranslationMethod::trt ? json{r.l1, r.l2} : json(r.l1);
  double worst = 0;
  for (double x : r.residuals) worst = std::max(worst, x);
  method["max_interpolation_residual"] = worst;
  // The factors the motion is the product of, for exact minimal-degree trajectories.
  json rot = json::array();
  for (const auto& c : r.rotation.coeffs())
    rot.push_back(numbers_json(std::vector<Scalar>{c.w(), c.x(), c.y(), c.z()}));
  method["rotation_control_points"] = rot;
  auto rows = [](const kernel::MatX<Scalar>& P) {
    json a = json::array();
    for (Eigen::Index j = 0; j < P.rows(); ++j)
      a.push_back(numbers_json(std::vector<Scalar>{P(j, 0), P(j, 1), P(j, 2)}));
    return a;
  };
  method["translation_control_points"] = rows(r.translation);
  if (opt.translation == kernel::TranslationMethod::trt)
    method["translation2_control_points"] = rows(r.translation2);
  const auto poles = kernel::find_poles(r.motion);
  if (!poles.empty()) {
    std::ostringstream os;
    os.precision(10);
    for (double p : poles) os << " " << p;
    std::cerr << "qmotion: warning: the motion has a pole (zero rotational part) at t =" << os.str()
              << ": trajectories are unbounded there and cannot be exported\n";
  }
  std::ostringstream os;
  os << "bezier, degree " << r.motion.degree() << ", order "
     << kernel::construction_order(opt.translation, r.k, r.l1, std::max(r.l2, 0))
     << ", max residual " << worst;
  summary = os.str();
  return io::motion_to_json(r.motion, method, units);
}

int cmd_interpolate(const InterpolateArgs& args) {
  const io::PoseSet set = io::read_poses(args.poses);
  const std::size_t count = set.poses.size();
  kernel::InterpolationOptions opt;
  if (args.rotation == "elliptic") {
    opt.rotation = kernel::RotationMethod::elliptic;
  } else if (args.rotation == "affine") {
    opt.rotation = kernel::RotationMethod::affine;
  } else if (args.rotation == "projective") {
    opt.rotation = kernel::RotationMethod::projective;
  } else {
    throw Error(
        Errc::invalid_input,
        "--rotation: expected elliptic, affine or projective, found '" + args.rotation + "'");
  }
  if (args.translation == "tr") {
    opt.translation = kernel::TranslationMethod::tr;
  } else if (args.translation == "trt") {
    opt.translation = kernel::TranslationMethod::trt;
  } else if (args.translation == "minimal") {
    opt.translation = kernel::TranslationMethod::minimal;
  } else {
    throw Error(Errc::invalid_input,
                "--translation: expected tr, trt or minimal, found '" + args.translation + "'");
  }
  if (!args.trt_degrees.empty()) {
    if (opt.translation != kernel::TranslationMethod::trt)
      throw Error(Errc::invalid_input, "--trt-degrees needs --translation trt");
    const auto comma = args.trt_degrees.find(',');
    auto to_int = [&](const std::string& s) {
      if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos)
        throw Error(Errc::invalid_input,
                    "--trt-degrees: expected two non-negative integers L1,L2, found '" +
                        args.trt_degrees + "'");
      return std::stoi(s);
    };
    if (comma == std::string::npos)
      throw Error(Errc::invalid_input,
                  "--trt-degrees: expected L1,L2, found '" + args.trt_degrees + "'");
    opt.trt_degrees = std::make_pair(to_int(args.trt_degrees.substr(0, comma)),
                                     to_int(args.trt_degrees.substr(comma + 1)));
  }
  const std::string form = !args.form.empty() ? args.form : (count <= 6 ? "bezier" : "bspline");
  if (form == "bspline" || form == "c1")
    throw Error(Errc::invalid_input,
                "--form " + form +
                    (args.form.empty() ? " (the default for more than six poses)" : "") +
                    ": spline motions are not available yet; use --form bezier to force one Bezier "
                    "motion through all " +
                    std::to_string(count) + " poses");
  if (form != "bezier")
    throw Error(Errc::invalid_input,
                "--form: expected bezier, bspline or c1, found '" + form + "'");
  const int m = static_cast<int>(count) - 1;
  if (args.degree >= 0 && args.degree != kernel::rotation_degree(opt.rotation, m))
    throw Error(Errc::invalid_input,
                "--degree " + std::to_string(args.degree) + ": a Bezier motion through " +
                    std::to_string(count) + " poses has rotational degree " +
                    std::to_string(kernel::rotation_degree(opt.rotation, m)) +
                    " with this method; --degree chooses the degree of B-spline motions");
  if (args.translation_degree >= 0 && args.translation_degree != m &&
      opt.translation != kernel::TranslationMethod::trt)
    throw Error(Errc::invalid_input, "--translation-degree " +
                                         std::to_string(args.translation_degree) +
                                         ": a Bezier motion through " + std::to_string(count) +
                                         " poses has translational degree " + std::to_string(m));
  const std::string rule_name =
      !args.param.empty() ? args.param : (set.has_t() ? "given" : "uniform");
  const auto rule = kernel::param_rule_from_string(rule_name);
  if (!rule)
    throw Error(Errc::invalid_input,
                "--param: expected given, uniform, chordal, star-chordal, centripetal, angular or "
                "angular-chordal, found '" +
                    rule_name + "'");
  if (*rule == kernel::ParamRule::given && !set.has_t())
    throw Error(
        Errc::invalid_input,
        args.poses +
            ": --param given needs a t for every pose; the file has none (try --param uniform)");
  const auto poses_d = io::to_poses_double(set);
  const std::vector<double> t = kernel::parametrize(poses_d, *rule);

  json method{{"rotation", args.rotation},
              {"translation", args.translation},
              {"param", kernel::to_string(*rule)},
              {"form", "bezier"},
              {"exact", args.exact},
              {"input_poses", io::poses_to_json(set)}};
  if (opt.translation == kernel::TranslationMethod::trt) {
    const auto d = opt.trt_degrees.value_or(std::make_pair(m - 1, 0));
    method["trt_degrees"] = {d.first, d.second};
  }
  std::string summary;
  json doc;
  if (args.exact) {
#ifdef QMOTION_WITH_CGAL
    const auto poses_e = io::to_poses_exact(set);
    std::vector<kernel::Rational> te;
    for (std::size_t i = 0; i < count; ++i)
      te.push_back(*rule == kernel::ParamRule::given ? *poses_e[i].t : kernel::Rational(t[i]));
    if (*rule == kernel::ParamRule::uniform)
      for (std::size_t i = 0; i < count; ++i)
        te[i] = kernel::Rational(static_cast<long>(i)) / kernel::Rational(static_cast<long>(m));
    doc = run_interpolation(poses_e, te, opt, method, set.units, summary);
#else
    throw Error(Errc::invalid_input,
                "--exact: this build has no exact arithmetic (QMOTION_WITH_CGAL=OFF)");
#endif
  } else {
    doc = run_interpolation(poses_d, t, opt, method, set.units, summary);
  }
  io::write_file_atomic(args.output, doc.dump(1) + "\n");
  std::cerr << "qmotion: wrote " << args.output << " (" << summary << ")\n";
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

  auto* interp = app.add_subcommand(
      "interpolate",
      "Build a Q-motion through the poses (Juettler's methods) and write it as motion JSON");
  InterpolateArgs ia;
  interp->add_option("POSES", ia.poses, "Pose file (.json or .csv)")->required();
  interp->add_option("-o,--output", ia.output, "Motion JSON file to write")->required();
  interp->add_option("--rotation", ia.rotation,
                     "Rotation interpolation: elliptic (default), affine, projective");
  interp->add_option("--translation", ia.translation,
                     "Translation: tr (default), trt, minimal (minimal order)");
  interp->add_option(
      "--trt-degrees", ia.trt_degrees,
      "TRT degrees L1,L2 with L1 + L2 = m - 1 (default m-1,0; L1 = L2 even is singular)");
  interp->add_option("--param", ia.param,
                     "Parameters: given (default when every pose has t), uniform (default "
                     "otherwise), chordal, star-chordal, "
                     "centripetal, angular, angular-chordal");
  interp->add_option(
      "--form", ia.form,
      "bezier (default up to six poses) | bspline (default beyond; not yet available) | c1");
  interp->add_option(
      "--degree", ia.degree,
      "Rotational degree (B-spline motions; a Bezier motion's is fixed by the method)");
  interp->add_option("--translation-degree", ia.translation_degree,
                     "Translational degree (B-spline motions)");
  interp->add_flag(
      "--exact", ia.exact,
      "Compute in exact rational arithmetic from the file's digits (quaternion rotations only)");

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
  if (*interp) return cmd_interpolate(ia);
  if (*poses) return cmd_poses(poses_path, poses_out);
  if (*demo) return cmd_demo(demo_dir);
  std::cout << app.help();
  return 2;
}

}  // namespace qmotion::cli
