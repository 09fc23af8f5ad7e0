// api/src/interpolate.cpp
#include <qmotion/api/interpolate.hpp>
#include <qmotion/io/atomic_file.hpp>
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

namespace qmotion {
using namespace io;  // NOLINT: the formats this call reads and writes
namespace {

using json = nlohmann::json;

/// Finishes a new motion: parametrisation name and units recorded, the document written
/// with the poses as the user gave them, the summary and the poles.
template <typename Scalar>
InterpolatedMotion finish(kernel::Motion<Scalar> m, const std::string& param, const PoseSet& set) {
  m.units = set.units;
  m.provenance->param = param;
  const auto& p = *m.provenance;
  std::ostringstream os;
  os << kernel::to_string(p.form) << ", degree " << m.degree();
  if (p.form != kernel::Form::bezier) os << ", " << m.segments() << " segments";
  os << ", order "
     << kernel::construction_order(p.translation, p.rotation_degree, p.translation_degree,
                                   std::max(p.translation_degree2, 0))
     << ", max residual " << p.max_residual();
  InterpolatedMotion out{Motion(kernel::to_double(m)), os.str(), kernel::find_poles(m.curve), set,
                         nullptr};
  if constexpr (kernel::is_exact_v<Scalar>)
    out.exact_document = motion_document(m, poses_to_json(set));
  return out;
}

/// The options of `interpolate` checked and resolved against the poses, with the
/// parameters of the rule in double.
struct Resolved {
  kernel::InterpolationOptions opt;
  kernel::SplineOptions sopt;
  kernel::Form form = kernel::Form::bezier;
  kernel::ParamRule rule = kernel::ParamRule::uniform;
  std::vector<double> t;
};

Resolved resolve(const PoseSet& set, const InterpolateOptions& args) {
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
  if (!kernel::form_from_string(form))
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
  const kernel::ParamRule rule = param_rule(set, args.param);
  return Resolved{opt, sopt, *kernel::form_from_string(form), rule,
                  kernel::parametrize(to_poses_double(set), rule)};
}

#ifdef QMOTION_WITH_CGAL
/// The exact motion: poses read exactly from their text, parameters exact for the given
/// and uniform rules (the double rule's values, exactly, for the others).
kernel::Motion<kernel::Rational> run_exact(const PoseSet& set, const Resolved& r) {
  const auto poses_e = to_poses_exact(set);
  const std::size_t count = poses_e.size();
  std::vector<kernel::Rational> te;
  for (std::size_t i = 0; i < count; ++i)
    te.push_back(r.rule == kernel::ParamRule::given ? *poses_e[i].t : kernel::Rational(r.t[i]));
  if (r.rule == kernel::ParamRule::uniform)
    for (std::size_t i = 0; i < count; ++i)
      te[i] =
          kernel::Rational(static_cast<long>(i)) / kernel::Rational(static_cast<long>(count - 1));
  auto m = kernel::interpolate(poses_e, te, r.form, r.opt, r.sopt);
  m.units = set.units;
  m.provenance->param = kernel::to_string(r.rule);
  return m;
}
#endif

}  // namespace

#ifdef QMOTION_WITH_CGAL
kernel::Motion<kernel::Rational> interpolate_exact(const PoseSet& set, InterpolateOptions args) {
  args.exact = true;
  return run_exact(set, resolve(set, args));
}
#endif

kernel::ParamRule param_rule(const PoseSet& set, const std::string& name) {
  const std::string rule_name = !name.empty() ? name : (set.has_t() ? "given" : "uniform");
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
  return *rule;
}

InterpolatedMotion interpolate(const PoseSet& set, const InterpolateOptions& args) {
  const Resolved r = resolve(set, args);
  const std::string rule = kernel::to_string(r.rule);
  if (args.exact) {
#ifdef QMOTION_WITH_CGAL
    return finish(run_exact(set, r), rule, set);
#else
    throw Error(Errc::invalid_input,
                "--exact: this build has no exact arithmetic (QMOTION_WITH_CGAL=OFF)");
#endif
  }
  return finish(kernel::interpolate(to_poses_double(set), r.t, r.form, r.opt, r.sopt), rule, set);
}

json InterpolatedMotion::document() const {
  if (!exact_document.is_null()) return exact_document;
  return motion_document(motion.rational(), poses_to_json(input));
}

std::string InterpolatedMotion::text() const {
  if (!exact_document.is_null()) return exact_document.dump(1) + "\n";
  return motion_json_text(motion.rational(), &input);
}

void InterpolatedMotion::save(const std::string& path) const {
  const auto& m = motion.rational();
  if (exact_document.is_null()) return write_motion_json(path, m, &input);
  check_motion_limits(m.degree(), m.curve.curve.ctrl().size(), path);
  write_file_atomic(path, text());
}

}  // namespace qmotion
