// api/src/export_exact.cpp: a rational motion's trajectories and kinematic surfaces as exact
// NURBS at their minimal degree (or approximated above --max-degree).
#include <algorithm>
#include <cmath>
#include <qmotion/io/units.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/approximate.hpp>
#include <qmotion/sweep/surface.hpp>
#include <qmotion/sweep/trajectory.hpp>

#include "export_detail.hpp"

namespace qmotion::detail {
using json = nlohmann::json;
namespace {

/// The JSON record of an approximation (tolerance and deviation in the declared unit).
json approximation_json(const ExportOptions& opt, const ExportResult& r, double tol) {
  return json{{"max_degree", opt.max_degree},
              {"tolerance", tol * r.unit_factor},
              {"degree", r.degree_u},
              {"measured_deviation", *r.approx_deviation},
              {"max_deviation", *r.approx_deviation},
              {"continuity", r.continuity_u}};
}

/// The exact (or --max-degree approximated) surface of one profile edge, in the motion's
/// unit; `tol_used` receives the approximation tolerance.
sweep::NurbsSurface<double> edge_surface(const kernel::Motion<double>& lm,
                                         const sweep::NurbsCurve<double>& profile,
                                         const ExportOptions& opt, Format f, ExportResult& r,
                                         double& tol_used) {
  if (opt.max_degree > 0) {
    std::vector<sweep::Vec4<double>> X;
    for (std::size_t j = 0; j < profile.points.size(); ++j)
      X.emplace_back(profile.weights[j], profile.weights[j] * profile.points[j](0),
                     profile.weights[j] * profile.points[j](1),
                     profile.weights[j] * profile.points[j](2));
    const auto cols = sweep::trajectories(lm, X);
    if (cols.front().degree() > opt.max_degree) {
      double diag = 0;
      for (const auto& c : cols) diag = std::max(diag, diagonal(curve_samples(c, 100)));
      const double tol = opt.tol > 0 ? opt.tol : 1e-6 * diag;
      tol_used = tol;
      // The columns are fitted within a tolerance; the surface between them is measured at
      // 6 x 6 points in every span of its knots and held to 0.9 of the tolerance, like the
      // columns, tightening the columns' tolerance by halves up to five times.
      const auto params = [](const std::vector<double>& knots) {
        std::vector<double> x;
        for (std::size_t k = 0; k + 1 < knots.size(); ++k)
          if (knots[k + 1] > knots[k])
            for (int i = 0; i < 6; ++i) x.push_back(knots[k] + (knots[k + 1] - knots[k]) * i / 6);
        x.push_back(knots.back());
        return x;
      };
      const std::vector<double> vs = params(profile.knots);
      std::vector<Eigen::Vector3d> section(vs.size());
      for (std::size_t j = 0; j < vs.size(); ++j) section[j] = sweep::evaluate(profile, vs[j]);
      double dev = HUGE_VAL, col_tol = tol;
      sweep::NurbsSurface<double> s;
      for (int attempt = 0; attempt < 6 && !(dev <= 0.9 * tol); ++attempt, col_tol /= 2) {
        const auto approx = sweep::approximate_homogeneous(cols, opt.max_degree, col_tol);
        sweep::HomogeneousSurface<double> hs{approx.curves.front().degree(),
                                             profile.degree,
                                             approx.curves.front().knots(),
                                             profile.knots,
                                             {}};
        hs.poles.assign(approx.curves.front().ctrl().size(),
                        std::vector<sweep::Vec4<double>>(cols.size()));
        for (std::size_t j = 0; j < cols.size(); ++j)
          for (std::size_t i = 0; i < hs.poles.size(); ++i)
            hs.poles[i][j] = approx.curves[j].ctrl()[i];
        s = sweep::to_nurbs(hs);
        dev = 0;
        for (const double u : params(s.knots_u)) {
          const auto m = kernel::evaluate(lm.curve, u);
          for (std::size_t j = 0; j < vs.size(); ++j)
            dev = std::max(
                dev, (sweep::evaluate(s, u, vs[j]) - kernel::apply_point(m, section[j])).norm());
        }
      }
      if (!(dev <= tol))
        throw Error(Errc::numerical_failure,
                    "--max-degree " + std::to_string(opt.max_degree) +
                        ": the approximated surface deviates by " + std::to_string(dev) +
                        ", more than the tolerance " + std::to_string(tol));
      r.approx_deviation = std::max(r.approx_deviation.value_or(0.0), dev);
      return s;
    }
  }
  auto s = sweep::kinematic_nurbs(lm, profile);
  check_degree(s.degree_u, "the surface (along the motion)", f, opt);
  return s;
}

}  // namespace

Computed<sweep::NurbsCurve<double>> exact_trajectory(const kernel::Motion<double>& lm,
                                                     const Eigen::Vector3d& point,
                                                     const ExportOptions& opt, Format f,
                                                     ExportResult& r) {
  double tol = 0;
  check_max_degree(opt, f);
  sweep::refuse_poles(lm);
  resolve_units(lm.units, opt, r);
  // The homogeneous curve lives only in here: it is not held beside the NURBS (a
  // 10^4-pose motion's is 2 MB).
  sweep::NurbsCurve<double> c = [&] {
    auto h = sweep::point_trajectory(lm, point);
    if (opt.max_degree > 0 && h.degree() > opt.max_degree) {
      tol = opt.tol > 0 ? opt.tol : 1e-6 * std::max(diagonal(curve_samples(h, 200)), 1e-300);
      auto approx = sweep::approximate_homogeneous({h}, opt.max_degree, tol);
      h = std::move(approx.curves.front());
      r.approx_deviation = approx.max_deviation * r.unit_factor;
      r.approx_tolerance = tol * r.unit_factor;
    } else {
      check_degree(h.degree(), "the trajectory", f, opt);
      const auto extra = sweep::knots_for_positive_weights(h);
      r.inserted_knots = static_cast<int>(extra.size());
      if (!extra.empty()) h = sweep::insert_knots(h, extra);
    }
    return sweep::to_nurbs(h);
  }();
  scale_points(c, r.unit_factor);
  r.degree_u = c.degree;
  r.continuity_u = sweep::min_continuity(c.knots, c.degree);
  r.poles = static_cast<int>(c.points.size());
  r.min_weight = min_weight(c.weights);
  json approximation = r.approx_deviation ? approximation_json(opt, r, tol) : json();
  return {std::move(c), std::move(approximation)};
}

Computed<std::vector<sweep::NurbsSurface<double>>> exact_surfaces(
    const Motion& m, const sweep::Profile<double>& profile, const std::string& profile_name,
    const ExportOptions& opt, Format f, ExportResult& r) {
  const kernel::Motion<double>& lm = m.rational();
  double tol = 0;
  check_max_degree(opt, f);
  sweep::refuse_poles(lm);
  resolve_units(lm.units, opt, r);
  if (f == Format::step || f == Format::iges)
    for (const auto& e : profile.edges) check_degree(e.degree, "the profile", f, ExportOptions{});
  sweep_checks(
      profile, profile_name, opt, r,
      [&](const sweep::PlanarRegion& region) { return sweep::find_backsweep(lm, profile, region); },
      [&](const sweep::PlanarRegion& region) { return sweep::swept_volume(lm, region); },
      self_intersection_check(m, profile));
  std::vector<sweep::NurbsSurface<double>> surfaces;
  for (const auto& e : profile.edges) {
    surfaces.push_back(edge_surface(lm, e, opt, f, r, tol));
    scale_points(surfaces.back(), r.unit_factor);
  }
  if (r.approx_deviation) {
    *r.approx_deviation *= r.unit_factor;
    r.approx_tolerance = tol * r.unit_factor;
  }
  summarize_surfaces(surfaces, r);
  json approximation = r.approx_deviation ? approximation_json(opt, r, tol) : json();
  return {std::move(surfaces), std::move(approximation)};
}

}  // namespace qmotion::detail
