// Tests for <qmotion/kernel/motion_fit.hpp>: dense, noisy pose streams fitted by lean
// B-spline Q-motions, measured here independently of the fit's own report.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <qmotion/kernel/motion_fit.hpp>
#include <random>

#include "fit_streams.hpp"

namespace qmotion::kernel {
namespace {

using Q = Quaternion<double>;
using test::noisy_stream;
using test::perturb;
using test::smooth_pose;
using test::Stream;

/// The deviations measured here: the moving origin through the 4x4 matrix of the motion
/// (to_matrix4), the angle through the rotation matrices' relative rotation.
std::pair<double, double> measured(const QMotion<double>& m, const Pose<double>& p, double t) {
  const Eigen::Matrix4d M = to_matrix4(evaluate(m, t));
  const Eigen::Vector3d origin = M.block<3, 1>(1, 0) / M(0, 0);
  const Eigen::Matrix3d R = M.block<3, 3>(1, 1) / M(0, 0);
  const Eigen::Quaterniond pr(p.rotation.w(), p.rotation.x(), p.rotation.y(), p.rotation.z());
  const Eigen::AngleAxisd rel(Eigen::Matrix3d(pr.normalized().toRotationMatrix().transpose() * R));
  return {(origin - p.position).norm(), std::abs(rel.angle()) * 180 / M_PI};
}

/// Every property the fit promises, measured independently.
void expect_fit(const FittedMotion& f, const Stream& s, double tol, double deg) {
  const auto& m = f.motion.curve;
  double worst_pos = 0, worst_ang = 0;
  for (std::size_t i = 0; i < s.poses.size(); ++i) {
    const auto [d, a] = measured(m, s.poses[i], s.t[i]);
    ASSERT_LE(d, tol) << "pose " << i;
    ASSERT_LE(a, deg) << "pose " << i;
    worst_pos = std::max(worst_pos, d);
    worst_ang = std::max(worst_ang, a);
  }
  // The report's worst deviations are the ones measured here.
  EXPECT_NEAR(f.report.worst_position, worst_pos, 1e-9 * (1 + worst_pos));
  EXPECT_NEAR(f.report.worst_angle_deg, worst_ang, 1e-7);
  EXPECT_LE(plucker_residual(m), 1e-12);
  // At least C1 at every interior knot: multiplicity at most degree - 1, and the first
  // derivative of the curve agrees from both sides.
  const auto d1 = derivative(m.curve);
  for (double x : m.curve.breakpoints()) {
    if (x == m.a() || x == m.b()) continue;
    EXPECT_LE(m.curve.multiplicity(x), m.degree() - 2) << "knot " << x;
    const double h = 1e-9 * (m.b() - m.a());
    const auto l = evaluate(d1, x - h), r = evaluate(d1, x + h);
    for (int c = 0; c < 8; ++c) EXPECT_NEAR(l[c], r[c], 1e-4 * (1 + std::abs(l[c])));
  }
  ASSERT_TRUE(f.motion.provenance);
  EXPECT_EQ(f.motion.provenance->form, Form::fit);
  EXPECT_EQ(f.motion.provenance->tolerance, tol);
}

TEST(MotionFit, DenseNoisyNonRationalMotionFitsWithATenthOfTheControlPoints) {
  for (const auto& [n, tol, deg] :
       {std::tuple<std::size_t, double, double>{2000, 0.01, 0.05}, {10000, 0.001, 0.01}}) {
    const Stream s = noisy_stream(n, tol / 3.5, deg / 3.5, 7);
    FitOptions o;
    o.tol = tol;
    o.angle_tol_deg = deg;
    const FittedMotion f = fit_bspline(s.poses, s.t, o);
    expect_fit(f, s, tol, deg);
    EXPECT_LE(f.motion.curve.curve.ctrl().size() * 10, n) << n << " poses";
  }
}

/// The B-spline Q-motion interpolate makes through ten poses of smooth_pose at evenly spaced
/// parameters, and n samples of it, each perturbed within dist and deg.
std::pair<Motion<double>, Stream> sampled_source(int n, double dist, double deg) {
  std::vector<Pose<double>> keys;
  std::vector<double> tk;
  for (int i = 0; i < 10; ++i) {
    keys.push_back(smooth_pose(i / 9.0));
    tk.push_back(i / 9.0);
  }
  Motion<double> source = interpolate_bspline(keys, tk, SplineOptions{});
  std::mt19937 rng(3);
  Stream s;
  for (int i = 0; i < n; ++i) {
    const double u = i / (n - 1.0);
    const auto q = evaluate(source.curve, u);
    Pose<double> p;
    p.position = translation_vector(q);
    p.rotation = normalized(q.real());
    if (dist > 0 || deg > 0) perturb(p, rng, dist, deg);
    s.poses.push_back(p);
    s.t.push_back(u);
  }
  return {std::move(source), std::move(s)};
}

TEST(MotionFit, DenseNoisySamplesOfARationalMotion) {
  const Stream s = sampled_source(3000, 0.01 / 3.5, 0.05 / 3.5).second;
  FitOptions o;
  o.tol = 0.01;
  o.angle_tol_deg = 0.05;
  const FittedMotion f = fit_bspline(s.poses, s.t, o);
  expect_fit(f, s, 0.01, 0.05);
  EXPECT_LE(f.motion.curve.curve.ctrl().size() * 10, s.poses.size());
}

TEST(MotionFit, NoiseFreeSamplesOfABSplineMotionComeBackNoLarger) {
  const auto [source, s] = sampled_source(1000, 0, 0);
  for (double tol : {1e-2, 1e-4, 1e-7}) {
    FitOptions o;
    o.tol = tol;
    o.angle_tol_deg = 1e-5;
    const FittedMotion f = fit_bspline(s.poses, s.t, o);
    expect_fit(f, s, tol, 1e-5);
    EXPECT_LE(f.motion.curve.curve.ctrl().size(), source.curve.curve.ctrl().size()) << tol;
  }
}

TEST(MotionFit, TighteningTheToleranceNeverLoosensTheResult) {
  const Stream s = noisy_stream(3000, 0.0002, 0.0003, 11);  // below T/3 throughout
  double last_pos = INFINITY, last_ang = INFINITY;
  std::size_t last_count = 0;
  for (double tol : {0.1, 0.03, 0.01, 0.003, 0.001}) {
    FitOptions o;
    o.tol = tol;
    o.angle_tol_deg = tol;  // degrees, tightened together
    const FittedMotion f = fit_bspline(s.poses, s.t, o);
    expect_fit(f, s, tol, tol);
    EXPECT_LE(f.report.worst_position, last_pos) << tol;
    EXPECT_LE(f.report.worst_angle_deg, last_ang) << tol;
    EXPECT_GE(f.motion.curve.curve.ctrl().size(), last_count) << tol;
    last_pos = f.report.worst_position;
    last_ang = f.report.worst_angle_deg;
    last_count = f.motion.curve.curve.ctrl().size();
  }
}

TEST(MotionFit, ImpossibleStreamsAreRefusedWithTheReason) {
  const Stream noisy = noisy_stream(500, 0.05, 0.01, 5);
  FitOptions o;
  o.tol = 0.001;  // below the noise
  try {
    fit_bspline(noisy.poses, noisy.t, o);
    FAIL() << "noise above the tolerance was fitted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), Errc::numerical_failure);
    EXPECT_NE(std::string(e.what()).find("cannot be met"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("pose "), std::string::npos) << e.what();
  }
  Stream half = noisy_stream(20, 0, 0, 1);
  half.poses[10].rotation = half.poses[9].rotation * Q(0, 1, 0, 0);  // a half-turn apart
  o.tol = 0.01;
  try {
    fit_bspline(half.poses, half.t, o);
    FAIL() << "a half-turn between neighbours was fitted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), Errc::numerical_failure);
    EXPECT_NE(std::string(e.what()).find("poses 9 and 10"), std::string::npos) << e.what();
  }
  o.tol = 0;
  EXPECT_THROW(fit_bspline(noisy.poses, noisy.t, o), Error);
  o.tol = 0.01;
  o.k = 1;
  EXPECT_THROW(fit_bspline(noisy.poses, noisy.t, o), Error);
}

}  // namespace
}  // namespace qmotion::kernel
