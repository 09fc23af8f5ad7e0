// io/interpolate.cpp
#include <qmotion/io/interpolate.hpp>
#include <sstream>

#ifdef QMOTION_WITH_CGAL
#include <qmotion/io/exact_number.hpp>
#endif
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/kernel/order.hpp>
#include <qmotion/kernel/parametrization.hpp>
#include <qmotion/kernel/spline_interpolation.hpp>

namespace qmotion::io {
namespace {

using json = nlohmann::json;

template <typename Scalar>
json numbers_json(const std::vector<Scalar>& t) {
  json a = json::array();
  for (const auto& v : t) {
#ifdef QMOTION_WITH_CGAL
    if constexpr (kernel::is_exact_v<Scalar>) {
      a.push_back(exact_to_text(v));
      continue;
    }
#endif
    a.push_back(kernel::to_double(v));
  }
  return a;
}

template <typename Scalar>
void run_interpolation(const std::vector<kernel::Pose<Scalar>>& poses, const std::vector<Scalar>& t,
                       const kernel::InterpolationOptions& opt, json method,
                       const std::string& units, InterpolatedMotion& out) {
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
  std::ostringstream os;
  os << "bezier, degree " << r.motion.degree() << ", order "
     << kernel::construction_order(opt.translation, r.k, r.l1, std::max(r.l2, 0))
     << ", max residual " << worst;
  out.summary = os.str();
  out.poles = kernel::find_poles(r.motion);
  out.document = motion_to_json(r.motion, method, units);
}

/// Rows of numbers for a spline's poles, and its knots, into the method record.
template <typename Scalar, typename Coef, typename Row>
void record_spline(json& method, const std::string& name, const kernel::BSpline<Coef>& s, Row row) {
  json poles = json::array();
  for (const auto& c : s.ctrl()) poles.push_back(numbers_json(row(c)));
  method[name + "_control_points"] = poles;
  method[name + "_knots"] = numbers_json(s.knots());
}

template <typename Scalar>
void run_spline_interpolation(const std::vector<kernel::Pose<Scalar>>& poses,
                              const std::vector<Scalar>& t, const std::string& form,
                              const kernel::SplineOptions& sopt, json method,
                              const std::string& units, InterpolatedMotion& out) {
  kernel::SplineInterpolation<Scalar> r = [&] {
    if constexpr (kernel::is_exact_v<Scalar>) {
      return kernel::interpolate_bspline(poses, t, sopt);
    } else {
      return form == "c1" ? kernel::interpolate_c1(poses, t, sopt.translation, sopt.max_residual)
                          : kernel::interpolate_bspline(poses, t, sopt);
    }
  }();
  method["parameters"] = numbers_json(t);
  method["rotation_degree"] = r.k;
  method["translation_degree"] = r.l;
  double worst = 0;
  for (double x : r.residuals) worst = std::max(worst, x);
  method["max_interpolation_residual"] = worst;
  using V3 = Eigen::Matrix<Scalar, 3, 1>;
  record_spline<Scalar>(method, "rotation", r.factors.rotation,
                        [](const kernel::Quaternion<Scalar>& q) {
                          return std::vector<Scalar>{q.w(), q.x(), q.y(), q.z()};
                        });
  record_spline<Scalar>(method, "translation", r.factors.translation, [](const V3& v) {
    return std::vector<Scalar>{v(0), v(1), v(2)};
  });
  std::ostringstream os;
  os << form << ", degree " << r.motion.degree() << ", " << r.motion.segments()
     << " segments, order " << kernel::construction_order(sopt.translation, r.k, r.l)
     << ", max residual " << worst;
  out.summary = os.str();
  out.poles = kernel::find_poles(r.motion);
  out.document = motion_to_json(r.motion, method, units);
}

}  // namespace

InterpolatedMotion interpolate(const PoseSet& set, const InterpolateOptions& args) {
  const std::size_t count = set.poses.size();
  kernel::InterpolationOptions opt;
  const auto rotation = kernel::rotation_method_from_string(args.rotation);
  if (!rotation)
    throw Error(
        Errc::invalid_input,
        "--rotation: expected elliptic, affine or projective, found '" + args.rotation + "'");
  opt.rotation = *rotation;
  const auto translation = kernel::translation_method_from_string(args.translation);
  if (!translation)
    throw Error(Errc::invalid_input,
                "--translation: expected tr, trt or minimal, found '" + args.translation + "'");
  opt.translation = *translation;
  if (!args.trt_degrees.empty()) {
    if (opt.translation != kernel::TranslationMethod::trt)
      throw Error(Errc::invalid_input, "--trt-degrees needs --translation trt");
    const auto comma = args.trt_degrees.find(',');
    auto to_int = [&](const std::string& s) {
      if (s.empty() || s.size() > 3 || s.find_first_not_of("0123456789") != std::string::npos)
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
  if (form != "bezier" && form != "bspline" && form != "c1")
    throw Error(Errc::invalid_input,
                "--form: expected bezier, bspline or c1, found '" + form + "'");
  const bool spline = form != "bezier";
  const int m = static_cast<int>(count) - 1;
  kernel::SplineOptions sopt;
  sopt.translation = opt.translation;
  if (spline) {
    if (opt.rotation != kernel::RotationMethod::elliptic)
      throw Error(Errc::invalid_input,
                  "--form " + form + " interpolates rotations by the elliptic method; --rotation " +
                      args.rotation + " is for --form bezier");
    if (opt.translation == kernel::TranslationMethod::trt)
      throw Error(
          Errc::invalid_input,
          "--form " + form + ": --translation trt is for --form bezier (use tr or minimal)");
    if (form == "c1" && args.exact)
      throw Error(Errc::invalid_input,
                  "--form c1 estimates velocities with square roots and logarithms: no --exact");
    if (form == "c1" && ((args.degree >= 0 && args.degree != 3) ||
                         (args.translation_degree >= 0 && args.translation_degree != 3)))
      throw Error(Errc::invalid_input,
                  "--form c1 has cubic factors: --degree and --translation-degree are 3");
    if (args.degree == 0 || args.translation_degree == 0 || args.degree > 25 ||
        args.translation_degree > 25)
      throw Error(Errc::invalid_input, "--degree and --translation-degree: expected 1 to 25");
    if (args.degree > 0) sopt.k = args.degree;
    if (args.translation_degree > 0) sopt.l = args.translation_degree;
  } else {
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
  }
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
        set.source +
            ": --param given needs a t for every pose; the file has none (try --param uniform)");
  const auto poses_d = to_poses_double(set);
  const std::vector<double> t = kernel::parametrize(poses_d, *rule);

  json method{{"rotation", args.rotation},
              {"translation", args.translation},
              {"param", kernel::to_string(*rule)},
              {"form", form},
              {"exact", args.exact},
              {"input_poses", poses_to_json(set)}};
  if (opt.translation == kernel::TranslationMethod::trt) {
    const auto d = opt.trt_degrees.value_or(std::make_pair(m - 1, 0));
    method["trt_degrees"] = {d.first, d.second};
  }
  InterpolatedMotion out;
  if (args.exact) {
#ifdef QMOTION_WITH_CGAL
    const auto poses_e = to_poses_exact(set);
    std::vector<kernel::Rational> te;
    for (std::size_t i = 0; i < count; ++i)
      te.push_back(*rule == kernel::ParamRule::given ? *poses_e[i].t : kernel::Rational(t[i]));
    if (*rule == kernel::ParamRule::uniform)
      for (std::size_t i = 0; i < count; ++i)
        te[i] = kernel::Rational(static_cast<long>(i)) / kernel::Rational(static_cast<long>(m));
    if (spline) {
      run_spline_interpolation(poses_e, te, form, sopt, method, set.units, out);
    } else {
      run_interpolation(poses_e, te, opt, method, set.units, out);
    }
#else
    throw Error(Errc::invalid_input,
                "--exact: this build has no exact arithmetic (QMOTION_WITH_CGAL=OFF)");
#endif
  } else {
    if (spline) {
      run_spline_interpolation(poses_d, t, form, sopt, method, set.units, out);
    } else {
      run_interpolation(poses_d, t, opt, method, set.units, out);
    }
  }
  return out;
}

}  // namespace qmotion::io
