// api/src/exact_check.cpp
#include <CGAL/Polynomial.h>
#include <CGAL/Polynomial_traits_d.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <qmotion/api/exact_check.hpp>
#include <qmotion/api/export.hpp>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/api/motion_info.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/kernel/motion.hpp>

namespace qmotion {
using namespace io;  // NOLINT: the formats this call reads and writes
namespace {

using json = nlohmann::json;
using kernel::Rational;
using Poly = CGAL::Polynomial<Rational>;
using Integer = CGAL::Fraction_traits<Rational>::Numerator_type;
using IntPoly = CGAL::Polynomial<Integer>;

/// The Bernstein polynomial sum c_i C(n,i) s^i (1-s)^(n-i) in the power basis of s, times
/// the common denominator of its coefficients (a polynomial over the integers).
IntPoly integer_power_form(const std::vector<Rational>& c) {
  const int n = static_cast<int>(c.size()) - 1;
  const Poly s(Rational(0), Rational(1)), one_minus_s(Rational(1), Rational(-1));
  std::vector<Poly> sp{Poly(Rational(1))}, op{Poly(Rational(1))};
  for (int i = 1; i <= n; ++i) {
    sp.push_back(sp.back() * s);
    op.push_back(op.back() * one_minus_s);
  }
  Poly p(Rational(0));
  Rational binom(1);
  for (int i = 0; i <= n; ++i) {
    p += Poly(c[static_cast<std::size_t>(i)] * binom) * sp[static_cast<std::size_t>(i)] *
         op[static_cast<std::size_t>(n - i)];
    binom = binom * Rational(n - i) / Rational(i + 1);
  }
  CGAL::Fraction_traits<Poly>::Numerator_type out;
  CGAL::Fraction_traits<Poly>::Denominator_type den;
  CGAL::Fraction_traits<Poly>::Decompose()(p, out, den);
  return out;
}

/// Degree of a piece of a homogeneous trajectory after dividing its four coordinates by
/// their greatest common divisor, exactly (CGAL's Polynomial package, modular gcd over the
/// integers). g = gcd(y0, y1 + a2 y2 + a3 y3) is the gcd of all four for all but finitely
/// many (a2, a3); that g divides y1, y2 and y3 is checked, else all four are combined.
int gcd_reduced_degree(const kernel::Bernstein<Eigen::Matrix<Rational, 4, 1>>& piece) {
  const auto gcd = CGAL::Polynomial_traits_d<IntPoly>::Gcd_up_to_constant_factor();
  std::vector<IntPoly> y;
  for (int k = 0; k < 4; ++k) {
    std::vector<Rational> c;
    for (const auto& v : piece.coeffs()) c.push_back(v(k));
    y.push_back(integer_power_form(c));
  }
  int top = 0;
  for (const auto& p : y)
    if (!CGAL::is_zero(p)) top = std::max(top, p.degree());
  if (CGAL::is_zero(y[0]))
    throw Error(Errc::numerical_failure,
                "check --exact: the trajectory's weight vanishes "
                "identically on a segment (the motion is degenerate)");
  const IntPoly combo = y[1] + IntPoly(Integer(3)) * y[2] - IntPoly(Integer(5)) * y[3];
  IntPoly g = CGAL::is_zero(combo) ? y[0] : gcd(y[0], combo);
  const auto divides = [&](const IntPoly& p) {
    if (CGAL::is_zero(p)) return true;
    IntPoly q, r;
    Integer d;
    CGAL::Polynomial_traits_d<IntPoly>::Pseudo_division()(p, g, q, r, d);
    return CGAL::is_zero(r);
  };
  if (!(divides(y[1]) && divides(y[2]) && divides(y[3])))
    for (int k = 1; k < 4; ++k)
      if (!CGAL::is_zero(y[static_cast<std::size_t>(k)]))
        g = gcd(g, y[static_cast<std::size_t>(k)]);
  return top - g.degree();
}

/// The denominator of x in lowest terms.
Integer denominator(const Rational& x) {
  CGAL::Fraction_traits<Rational>::Numerator_type num;
  CGAL::Fraction_traits<Rational>::Denominator_type den;
  CGAL::Fraction_traits<Rational>::Decompose()(x, num, den);
  return den;
}

/// The same projective motion with integer control points: the motion times the least
/// common multiple of its coordinates' denominators. The exact products below (Plucker
/// polynomial, trajectories) then work on integers and skip most rational gcds.
kernel::QMotion<Rational> integral(const kernel::QMotion<Rational>& m) {
  Integer lcm(1);
  for (const auto& q : m.curve.ctrl())
    for (const auto* part : {&q.real(), &q.dual()})
      for (const Rational& v : {part->w(), part->x(), part->y(), part->z()}) {
        const Integer den = denominator(v);
        lcm = lcm / CGAL::gcd(lcm, den) * den;
      }
  std::vector<kernel::DualQuaternion<Rational>> ctrl;
  for (const auto& q : m.curve.ctrl()) ctrl.push_back(q * Rational(lcm));
  return kernel::QMotion<Rational>{m.basis,
                                   kernel::BSpline<kernel::DualQuaternion<Rational>>::make(
                                       m.curve.degree(), m.curve.knots(), std::move(ctrl))};
}

/// max |a_i - lambda b_i| / max |a_i| over all coordinates, lambda the least-squares scale
/// of b onto a (the file's numbers a, the exact recomputation's b, both in double).
double relative_deviation(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return std::numeric_limits<double>::infinity();
  double ab = 0, bb = 0, amax = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ab += a[i] * b[i];
    bb += b[i] * b[i];
    amax = std::max(amax, std::abs(a[i]));
  }
  if (bb == 0 || amax == 0) return std::numeric_limits<double>::infinity();
  const double lambda = ab / bb;
  double dev = 0;
  for (std::size_t i = 0; i < a.size(); ++i) dev = std::max(dev, std::abs(a[i] - lambda * b[i]));
  return dev / amax;
}

std::vector<double> coordinates(const kernel::QMotion<double>& m) {
  std::vector<double> out;
  for (const auto& q : m.curve.ctrl())
    for (const auto* part : {&q.real(), &q.dual()})
      for (double v : {part->w(), part->x(), part->y(), part->z()}) out.push_back(v);
  return out;
}

/// The options `interpolate` was given, as the provenance records them.
InterpolateOptions recorded_options(const kernel::Provenance<double>& p) {
  InterpolateOptions o;
  o.rotation = kernel::to_string(p.rotation);
  o.translation = kernel::to_string(p.translation);
  o.form = kernel::to_string(p.form);
  o.param = p.param;
  if (p.form != kernel::Form::bezier) {
    o.degree = p.rotation_degree;
    o.translation_degree = p.translation_degree;
  } else if (p.translation == kernel::TranslationMethod::trt) {
    o.trt_degrees =
        std::to_string(p.translation_degree) + "," + std::to_string(p.translation_degree2);
  }
  return o;
}

}  // namespace

json check_exact(const std::string& motion_path, const std::optional<Eigen::Vector3d>& point) {
  const MotionFile f = read_motion(motion_path);
  const kernel::Motion<double> file_motion = to_motion(f);
  if (!file_motion.provenance)
    throw Error(Errc::invalid_input,
                f.source +
                    ": check --exact recomputes the motion from the poses and method its "
                    "method block records; this file records none (a hand-written "
                    "motion: use `qmotion info --exact` for its own exact residuals)");
  const auto& prov = *file_motion.provenance;
  if (prov.form == kernel::Form::c1)
    throw Error(Errc::invalid_input,
                f.source +
                    ": check --exact: a c1 motion's velocities are estimated with square "
                    "roots and logarithms; it has no exact recomputation");
  if (prov.form == kernel::Form::fit)
    throw Error(Errc::invalid_input,
                f.source +
                    ": check --exact: a fitted motion comes from a floating-point least-squares "
                    "solve near its poses, not through them; it has no exact recomputation "
                    "(use `qmotion check` for its deviations)");
  if (file_motion.degree() > kMaxExactInfoDegree ||
      file_motion.segments() > kMaxExactInfoSegments || prov.poses.size() > kMaxExactCheckPoses)
    throw Error(
        Errc::invalid_input,
        f.source + ": check --exact works on motions up to degree " +
            std::to_string(kMaxExactInfoDegree) + ", " + std::to_string(kMaxExactInfoSegments) +
            " segments and " + std::to_string(kMaxExactCheckPoses) + " poses (this one: degree " +
            std::to_string(file_motion.degree()) + ", " + std::to_string(file_motion.segments()) +
            " segments, " + std::to_string(prov.poses.size()) + " poses)");

  std::vector<std::size_t> rounded;
  const PoseSet recorded = *recorded_input_poses(f);  // the provenance records them
  const PoseSet set = with_quaternion_rotations(recorded, &rounded);
  const kernel::Motion<Rational> exact = interpolate_exact(set, recorded_options(prov));
  const auto& ep = *exact.provenance;

  json out;
  out["motion"] = f.source;
  json from = {{"poses", set.poses.size()}};
  json r = json::array();
  for (auto i : rounded) r.push_back(i);
  from["rotations_from_double"] = r;  // poses whose rotation had no exact quaternion text
  out["recomputed_from"] = from;
  out["form"] = kernel::to_string(ep.form);
  out["rotation"] = kernel::to_string(ep.rotation);
  out["translation"] = kernel::to_string(ep.translation);
  out["param"] = ep.param;
  out["degree"] = exact.degree();
  out["segments"] = exact.segments();

  // Plucker condition of the exact motion: its polynomial is zero coefficient by coefficient.
  double plucker_max = 0;
  const kernel::QMotion<Rational> whole = integral(exact.curve);
  const auto plucker = kernel::plucker_spline(whole);
  for (const auto& c : plucker.ctrl())
    plucker_max = std::max(plucker_max, std::abs(CGAL::to_double(c)));
  const bool plucker_zero = plucker_max == 0.0;
  out["plucker"] = {{"exact_zero", plucker_zero},
                    {"exact_max_abs", plucker_max},
                    {"file_residual", kernel::plucker_residual(file_motion.curve)}};

  // Interpolation: the exact motion at every exact parameter, against the exact pose.
  bool interp_zero = true;
  for (double x : ep.residuals) interp_zero = interp_zero && x == 0.0;
  out["interpolation"] = {{"exact_zero", interp_zero},
                          {"exact_residuals", ep.residuals},
                          {"file_max_residual", prov.max_residual()}};

  // The file against the exact recomputation.
  const kernel::Motion<double> exact_d = kernel::to_double(exact);
  bool same_knots = exact_d.curve.curve.knots().size() == file_motion.curve.curve.knots().size();
  double knot_dev = 0;
  if (same_knots)
    for (std::size_t i = 0; i < exact_d.curve.curve.knots().size(); ++i)
      knot_dev = std::max(
          knot_dev, std::abs(exact_d.curve.curve.knots()[i] - file_motion.curve.curve.knots()[i]));
  const double span = std::abs(file_motion.b() - file_motion.a());
  const double coeff_dev =
      same_knots && exact_d.degree() == file_motion.degree()
          ? relative_deviation(coordinates(file_motion.curve), coordinates(exact_d.curve))
          : std::numeric_limits<double>::infinity();
  double param_dev = 0;
  for (std::size_t i = 0; i < prov.parameters.size() && i < ep.parameters.size(); ++i)
    param_dev =
        std::max(param_dev, std::abs(prov.parameters[i] - CGAL::to_double(ep.parameters[i])));
  const double knot_rel =
      same_knots ? knot_dev / (span > 0 ? span : 1.0) : std::numeric_limits<double>::infinity();
  const double param_rel = param_dev / (span > 0 ? span : 1.0);
  auto finite_or_null = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  out["file_deviation"] = {{"control_points", finite_or_null(coeff_dev)},
                           {"knots", finite_or_null(knot_rel)},
                           {"parameters", param_rel},
                           {"tolerance", kExactCheckAgreement}};
  const bool agrees = coeff_dev <= kExactCheckAgreement && knot_rel <= kExactCheckAgreement &&
                      param_rel <= kExactCheckAgreement;

  // Trajectory order: exact gcd per Bezier piece, against what `trajectory` writes.
  const Eigen::Vector3d x = point ? *point : Eigen::Vector3d(0.37, -0.58, 0.72);
  Eigen::Matrix<Rational, 4, 1> xh(Rational(1), Rational(x(0)), Rational(x(1)), Rational(x(2)));
  for (int k = 1; k < 4; ++k)  // homogeneous: integer coordinates, the same point
    xh *= Rational(denominator(xh(k)));
  int gcd_order = 0;
  for (const auto& piece : kernel::bezier_pieces(kernel::homogeneous_trajectory(whole, xh)))
    gcd_order = std::max(gcd_order, gcd_reduced_degree(piece));
  const int written = trajectory_nurbs(file_motion, x).degree;
  const int guaranteed =
      kernel::construction_order(ep.translation, ep.rotation_degree, ep.translation_degree,
                                 std::max(ep.translation_degree2, 0));
  out["order"] = {{"point", {x(0), x(1), x(2)}},
                  {"gcd", gcd_order},
                  {"trajectory_degree", written},
                  {"construction", guaranteed},
                  {"matches", gcd_order == written}};
  out["verified"] = plucker_zero && interp_zero && agrees && gcd_order == written;
  return out;
}

}  // namespace qmotion
