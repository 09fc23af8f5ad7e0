// api/src/export_fitted.cpp: non-rational motions (docs/geometry.md): a quaternion spline's
// rigid maps fitted once on one knot vector (sweep::fit_frames); its trajectories and surfaces
// are that matrix spline applied to points.
#include <cmath>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/fit.hpp>
#include <qmotion/sweep/solid.hpp>
#include <qmotion/sweep/surface.hpp>

#include "export_detail.hpp"

namespace qmotion::detail {
using json = nlohmann::json;
namespace {

/// The fit for the given points (Cartesian, the motion's unit), with the tolerance used.
struct QSplineFit {
  sweep::FrameFit fit;
  double tol = 0;
};

QSplineFit fit_qspline(const Motion& m, const std::vector<Eigen::Vector3d>& pts,
                       const ExportOptions& opt, Format f) {
  check_max_degree(opt, f);
  const kernel::QuaternionSpline& s = m.spline();
  sweep::FrameFitOptions fo;
  fo.degree = opt.max_degree > 0 ? opt.max_degree : kQSplineFitDegree;
  if (opt.tol > 0) {
    fo.tol = opt.tol;
  } else {  // 1e-6 of the bounding-box diagonal of the points' trajectories
    std::vector<Eigen::Vector3d> samples;
    for (int i = 0; i <= 400; ++i) {
      const double t = s.a() + (s.b() - s.a()) * i / 400;
      const auto q = s.rotation(t);
      const Eigen::Vector3d p = s.position(t);
      for (const auto& x : pts) samples.push_back(kernel::rotate(q, x) + p);
    }
    fo.tol = 1e-6 * std::max(diagonal(samples), 1e-300);
  }
  return {sweep::fit_frames(m, pts, fo), fo.tol};
}

/// The approximation record of a fitted export (tolerance and deviation in the declared
/// unit).
json fit_json(const QSplineFit& q, const ExportResult& r) {
  return json{
      {"method", "least-squares fit of the rigid maps on one knot vector (docs/geometry.md)"},
      {"tolerance", q.tol * r.unit_factor},
      {"measured_deviation", q.fit.max_deviation * r.unit_factor},
      {"max_deviation", q.fit.max_deviation_bound * r.unit_factor},
      {"max_deviation_proof",
       "the largest sampled deviation plus M h^2/8, M bounding its second derivative"},
      {"degree", q.fit.matrix.degree()},
      {"poles_per_curve", q.fit.matrix.ctrl().size()},
      {"spans", q.fit.spans},
      {"check_samples", q.fit.check_samples},
      {"continuity", r.continuity_u}};
}

void record_fit(const QSplineFit& q, ExportResult& r) {
  r.approx_deviation = q.fit.max_deviation * r.unit_factor;
  r.approx_bound = q.fit.max_deviation_bound * r.unit_factor;
  r.approx_tolerance = q.tol * r.unit_factor;
  r.approx_spans = q.fit.spans;
}

}  // namespace

Computed<sweep::NurbsCurve<double>> fitted_trajectory(const Motion& m, const Eigen::Vector3d& point,
                                                      const ExportOptions& opt, Format f,
                                                      ExportResult& r) {
  resolve_units(m.units(), opt, r);
  const QSplineFit q = fit_qspline(m, {point}, opt, f);
  sweep::NurbsCurve<double> c = sweep::to_nurbs(
      sweep::apply(q.fit.matrix, sweep::Vec4<double>(1, point(0), point(1), point(2))));
  scale_points(c, r.unit_factor);
  record_fit(q, r);
  r.degree_u = c.degree;
  r.continuity_u = sweep::min_continuity(c.knots, c.degree);
  r.poles = static_cast<int>(c.points.size());
  r.min_weight = min_weight(c.weights);
  json approximation = fit_json(q, r);
  return {std::move(c), std::move(approximation)};
}

Computed<std::vector<sweep::NurbsSurface<double>>> fitted_surfaces(
    const Motion& m, const sweep::Profile<double>& profile, const std::string& profile_name,
    const ExportOptions& opt, Format f, ExportResult& r) {
  resolve_units(m.units(), opt, r);
  if (f == Format::step || f == Format::iges)
    for (const auto& e : profile.edges) check_degree(e.degree, "the profile", f, ExportOptions{});
  std::vector<Eigen::Vector3d> pts;
  for (const auto& e : profile.edges) pts.insert(pts.end(), e.points.begin(), e.points.end());
  if (pts.empty())
    throw Error(Errc::invalid_input, "the profile " + profile_name + " has no edges");
  const QSplineFit q = fit_qspline(m, pts, opt, f);
  const kernel::QuaternionSpline& s = m.spline();
  const auto& M = q.fit.matrix;
  sweep_checks(
      profile, profile_name, opt, r,
      [&](const sweep::PlanarRegion& region) {  // on the fitted surface that is written
        std::vector<kernel::BSpline<Eigen::Vector4d>> cols;
        for (const auto& X : sweep::homogeneous_points(profile)) cols.push_back(sweep::apply(M, X));
        return sweep::find_backsweep(
            cols, sweep::apply(
                      M, Eigen::Vector4d(0, region.normal(0), region.normal(1), region.normal(2))));
      },
      [&](const sweep::PlanarRegion& region) {  // of the motion itself: A |integral n . c'|
        return region.area * std::abs(sweep::detail::integrate(
                                 s.knots,
                                 [&](double t) {
                                   return kernel::rotate(s.rotation(t), region.normal)
                                       .dot(s.point_velocity(t, region.centroid));
                                 },
                                 64));
      },
      self_intersection_check(m, profile));
  std::vector<sweep::NurbsSurface<double>> surfaces;
  for (const auto& e : profile.edges) {
    sweep::HomogeneousSurface<double> hs{M.degree(), e.degree, M.knots(), e.knots, {}};
    hs.poles.assign(M.ctrl().size(), std::vector<sweep::Vec4<double>>(e.points.size()));
    for (std::size_t j = 0; j < e.points.size(); ++j) {
      const sweep::Vec4<double> X(e.weights[j], e.weights[j] * e.points[j](0),
                                  e.weights[j] * e.points[j](1), e.weights[j] * e.points[j](2));
      for (std::size_t i = 0; i < M.ctrl().size(); ++i) hs.poles[i][j] = M.ctrl()[i] * X;
    }
    surfaces.push_back(sweep::to_nurbs(hs));
    scale_points(surfaces.back(), r.unit_factor);
  }
  record_fit(q, r);
  summarize_surfaces(surfaces, r);
  json approximation = fit_json(q, r);
  return {std::move(surfaces), std::move(approximation)};
}

}  // namespace qmotion::detail
