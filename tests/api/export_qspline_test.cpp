// tests/api/export_qspline_test.cpp mirrors api/export.hpp for quaternion-spline motions:
// approximated trajectories and sweeps, measured against the motion itself; and the
// self-intersection proof's refusals under --fail-on-self-intersection.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <qmotion/api/export.hpp>
#include <qmotion/api/qspline.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/io/profiles.hpp>
#include <qmotion/sweep/surface.hpp>
#include <random>

#include "io_test_util.hpp"
#include "toolpath_util.hpp"

namespace qmotion::test {
namespace {
namespace fs = std::filesystem;
using V3 = Eigen::Vector3d;

qmotion::Motion motion(const std::string& scheme, const std::string& tension = "") {
  qmotion::QSplineOptions o;
  o.scheme = scheme;
  o.tension = tension;
  return qmotion::qspline(io::read_poses(test_data("helix_10.json")), o).motion;
}

/// Largest distance between the points' trajectories at 401 parameters, their bounding box.
double diagonal(const qmotion::Motion& m, const std::vector<V3>& pts) {
  V3 lo = V3::Constant(HUGE_VAL), hi = -lo;
  for (int i = 0; i <= 400; ++i)
    for (const auto& x : pts) {
      const V3 y = place(m, m.spline().a() + (m.spline().b() - m.spline().a()) * i / 400, x);
      lo = lo.cwiseMin(y);
      hi = hi.cwiseMax(y);
    }
  return (hi - lo).norm();
}

TEST(ExportQSpline, StepSweepsAreWithinTheToleranceOfTheMotionItself) {
  // For 1e-3, 1e-6 and 1e-9 of the size, the STEP read back through OpenCASCADE against the
  // motion evaluated directly (check, not the fit), for every scheme; poles grow as the
  // tolerance shrinks. The pole counts are printed for the README's table.
  const auto profile = io::read_profile("rect:4,2");
  std::vector<V3> corners;
  for (const auto& e : profile.edges)
    corners.insert(corners.end(), e.points.begin(), e.points.end());
  for (const auto& [scheme, tension] : std::vector<std::pair<std::string, std::string>>{
           {"kks", ""}, {"quintic", "0.8"}, {"quartic", ""}}) {
    const auto m = motion(scheme, tension);
    const double diag = diagonal(m, corners);
    int last_poles = 0;
    for (double rel : {1e-3, 1e-6, 1e-9}) {
      SCOPED_TRACE(scheme + " " + std::to_string(rel));
      qmotion::ExportOptions o;
      o.output = scratch(scheme + ".step").string();
      o.tol = rel * diag;
      const auto r = qmotion::export_geometry(m, qmotion::Geometry::sweep(profile, "rect"), o);
      ASSERT_TRUE(r.approx_deviation && r.approx_tolerance);
      EXPECT_LE(*r.approx_deviation, o.tol);
      EXPECT_DOUBLE_EQ(*r.approx_tolerance, o.tol);
      EXPECT_EQ(r.degree_u, 5);
      EXPECT_GE(r.continuity_u, scheme == "quintic" ? 0 : 2);
      EXPECT_GE(r.poles, last_poles);
      last_poles = r.poles;
      const auto c = qmotion::check(o.output, m, qmotion::Geometry::sweep(profile), 21);
      EXPECT_TRUE(c["valid"].get<bool>());
      EXPECT_TRUE(c["faces_cover_profile"].get<bool>());
      EXPECT_TRUE(c["param_range_matches_motion"].get<bool>());
      EXPECT_LE(c["max_deviation"].get<double>(), o.tol) << c.dump();
      ASSERT_TRUE(r.approx_bound);
      EXPECT_LE(c["max_deviation"].get<double>(), *r.approx_bound * (1 + 1e-9)) << c.dump();
      std::cout << "[ poles    ] " << scheme << " tol " << rel << " x diagonal: " << r.poles
                << " poles, " << r.approx_spans << " spans, bound " << *r.approx_bound
                << ", measured " << *r.approx_deviation << ", check "
                << c["max_deviation"].get<double>() << "\n";
    }
  }
}

TEST(ExportQSpline, JsonTrajectoryIsTheFittedCurveWithinTheDefaultTolerance) {
  const auto m = motion("quintic", "0.3");
  const V3 x(1, 2, 3);
  const std::string out = scratch("traj.json").string();
  qmotion::ExportOptions o;
  o.output = out;
  const auto r = qmotion::export_geometry(m, qmotion::Geometry::trajectory(x), o);
  std::ifstream f(out);
  const auto doc = nlohmann::json::parse(f);
  const auto curve = io::curve_from_json(doc, out);
  // The default tolerance is 1e-6 of the trajectory's bounding-box diagonal.
  const double tol = 1e-6 * diagonal(m, {x});
  EXPECT_NEAR(doc["approximation"]["tolerance"].get<double>(), tol, 1e-3 * tol);
  EXPECT_EQ(doc["approximation"]["degree"].get<int>(), 5);
  EXPECT_EQ(doc["approximation"]["poles_per_curve"].get<std::size_t>(), curve.points.size());
  EXPECT_EQ(r.poles, static_cast<int>(curve.points.size()));
  // Evaluated independently at random parameters, and exactly at both ends.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(m.spline().a(), m.spline().b());
  double dev = 0;
  for (int i = 0; i < 2000; ++i) {
    const double t = u(rng);
    dev = std::max(dev, (sweep::evaluate(curve, t) - place(m, t, x)).norm());
  }
  EXPECT_LE(dev, tol);
  // The proven bound covers what these samples find, and is in the file.
  ASSERT_TRUE(r.approx_bound);
  EXPECT_LE(dev, *r.approx_bound);
  EXPECT_LE(*r.approx_bound, tol);
  EXPECT_LE(*r.approx_deviation, *r.approx_bound);
  EXPECT_EQ(doc["approximation"]["max_deviation"].get<double>(), *r.approx_bound);
  EXPECT_EQ(doc["approximation"]["measured_deviation"].get<double>(), *r.approx_deviation);
  for (double t : {m.spline().a(), m.spline().b()})
    EXPECT_LE((sweep::evaluate(curve, t) - place(m, t, x)).norm(), 1e-12 * diagonal(m, {x}));
  for (double w : curve.weights) EXPECT_EQ(w, 1.0);  // polynomial, not rational
}

TEST(ExportQSpline, SolidVolumeFromTheMotionMatchesOpenCascadesAndUnitsConvert) {
  const auto m = motion("kks");
  const auto profile = io::read_profile("circle:1.5");
  qmotion::ExportOptions o;
  o.output = scratch("solid.step").string();
  o.solid = true;
  o.units = "cm";
  const auto r = qmotion::export_geometry(m, qmotion::Geometry::sweep(profile, "circle"), o);
  ASSERT_TRUE(r.volume);
  const auto c = qmotion::check(o.output, m, qmotion::Geometry::sweep(profile), 11);
  EXPECT_EQ(c["solids"].get<int>(), 1);
  EXPECT_TRUE(c["closed"].get<bool>());
  EXPECT_EQ(c["units"].get<std::string>(), "cm");
  // Ours integrates n . c' along the motion; OpenCASCADE measures the fitted solid.
  EXPECT_NEAR(c["volume"].get<double>(), *r.volume, 1e-5 * *r.volume);
  EXPECT_LE(c["max_deviation"].get<double>(), *r.approx_tolerance);
  // 1e-6 of the size (of the control points' trajectories: a little larger than the
  // surface's), reported in cm.
  const double size_cm = c["bbox_diagonal"].get<double>();
  EXPECT_NEAR(*r.approx_tolerance, 1e-6 * size_cm, 0.5 * 1e-6 * size_cm);
}

TEST(ExportQSpline, TheCommonCallsTakeEitherKindOfMotion) {
  qmotion::QSplineOptions qo;
  qo.scheme = "quartic";
  const auto q = qmotion::qspline(io::read_poses(test_data("helix_10.json")), qo);
  const std::string file = scratch("quartic_motion.json").string();
  { std::ofstream(file) << q.document.dump(); }
  const qmotion::Motion any = io::load_motion(file);
  ASSERT_FALSE(any.is_rational());
  EXPECT_EQ(any.units(), "mm");
  EXPECT_EQ(any.name(), file);
  qmotion::ExportOptions o;
  o.output = scratch("any.igs").string();
  const auto r = qmotion::export_geometry(any, qmotion::Geometry::trajectory(V3(0, 1, 0)), o);
  EXPECT_TRUE(r.approx_deviation);
  const auto c = qmotion::check(o.output, any, qmotion::Geometry::trajectory(V3(0, 1, 0)));
  EXPECT_LE(c["max_deviation"].get<double>(), *r.approx_tolerance);
  EXPECT_NE(c["motion"].get<std::string>().find("quaternion-spline quartic"), std::string::npos);
  // A degree the target cannot store, a fit that cannot reach its tolerance.
  o.max_degree = 40;
  EXPECT_TRUE(throws_error(
      [&] { qmotion::export_geometry(any, qmotion::Geometry::trajectory(V3(0, 1, 0)), o); },
      Errc::invalid_input, {"--max-degree 40"}));
  o.max_degree = 1;
  o.tol = 1e-12;
  fs::remove(o.output);
  EXPECT_TRUE(throws_error(
      [&] { qmotion::export_geometry(any, qmotion::Geometry::trajectory(V3(0, 1, 0)), o); },
      Errc::numerical_failure, {file, "above the tolerance"}));
  EXPECT_FALSE(fs::exists(o.output));
}

TEST(ExportSelfIntersection, AnythingNotProvenIsRefusedUnderTheFlag) {
  // A tube along an open coil is proven free of self-intersection; with a budget of 50 patch
  // pairs the proof cannot decide, and --fail-on-self-intersection refuses that as it does a
  // contact (Errc::numerical_failure: exit 3), naming the pair, with nothing written.
  const qmotion::Motion m = rational("self_intersection/coil_open.json");
  const auto tube = qmotion::Geometry::sweep(io::read_profile("circle:3"), "circle:3");
  qmotion::ExportOptions o;
  o.output = scratch("coil_open.step").string();
  o.fail_on_self_intersection = true;
  fs::remove(o.output);
  const auto r = qmotion::export_geometry(m, tube, o);
  ASSERT_TRUE(r.self_intersection_proof);
  EXPECT_TRUE(r.self_intersection_proof->proven());
  EXPECT_TRUE(fs::exists(o.output));
  fs::remove(o.output);
  o.self_intersection_budget = 50;
  EXPECT_TRUE(
      throws_error([&] { qmotion::export_geometry(m, tube, o); }, Errc::numerical_failure,
                   {"--fail-on-self-intersection: the sweep of circle:3 is not proven",
                    "the budget of 50 pairs ran out, undecided between t in [", "profile edge 0"}));
  EXPECT_FALSE(fs::exists(o.output));
}

}  // namespace
}  // namespace qmotion::test
