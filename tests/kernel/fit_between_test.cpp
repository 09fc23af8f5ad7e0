// Tests for `fit --between` (<qmotion/kernel/fit_between.hpp>): the fitted motion, sampled
// densely here, stays within the proven bounds of the polyline through the stream's positions
// and of the geodesics between its rotations, and the bounds are within the tolerances; on
// three kinds of source motion (a Bezier, a B-spline on uneven parameters, a quaternion
// spline), with noise.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <qmotion/kernel/fit_between.hpp>
#include <qmotion/kernel/motion_fit.hpp>
#include <qmotion/kernel/qspline.hpp>
#include <random>

#include "fit_streams.hpp"

namespace qmotion::kernel {
namespace between_test {

using test::samples;
using test::sources;
using test::Stream;

/// Distance from x to the segment [a, b], written here.
double to_segment(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double s = d.squaredNorm() > 0 ? std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0;
  return (x - a - s * d).norm();
}

TEST(FitBetween, BezierPiecesAreTheSplineOnTheirInterval) {
  const Stream s = samples(sources()[1].second, 400, 0.002, 0.01);
  FitOptions o;
  o.tol = 0.01;
  o.angle_tol_deg = 0.05;
  const FittedMotion f = fit_bspline(s.poses, s.t, o);
  const auto& tr = f.motion.factors->translation;
  const std::vector<double> T = tr.knots();
  Eigen::MatrixXd P(static_cast<Eigen::Index>(tr.ctrl().size()), 3);
  for (std::size_t i = 0; i < tr.ctrl().size(); ++i)
    P.row(static_cast<Eigen::Index>(i)) = tr.ctrl()[i].transpose();
  const int p = tr.degree(), n = static_cast<int>(tr.ctrl().size());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    double u0 = U(rng), u1 = U(rng);
    if (u0 > u1) std::swap(u0, u1);
    const int j = knot_span(T, p, n, u0);
    u1 = std::min(u1, T[static_cast<std::size_t>(j + 1)]);  // inside one span
    const between::Piece B = between::bezier_piece(T, p, P, j, u0, u1);
    for (double s01 : {0.0, 0.3, 0.71, 1.0}) {
      const Eigen::Vector3d want = evaluate(tr, u0 + s01 * (u1 - u0));
      EXPECT_LE((between::bezier_value(B, s01) - want).norm(), 1e-9) << u0 << " " << u1;
    }
  }
}

TEST(FitBetween, TheMotionStaysWithinItsProvenBoundsOfThePolylineAndTheGeodesics) {
  for (const auto& [name, frame] : sources()) {
    const double tol = 0.01, deg = 0.05;
    const std::size_t n = 1500;
    const Stream s = samples(frame, n, tol / 3.5, deg / 3.5);
    FitOptions o;
    o.tol = tol;
    o.angle_tol_deg = deg;
    o.between = true;
    const FittedMotion f = fit_bspline(s.poses, s.t, o);
    const FitReport& r = f.report;
    ASSERT_TRUE(r.between) << name;
    EXPECT_LE(r.between_position_bound, tol) << name;
    EXPECT_LE(r.between_angle_bound_deg, deg) << name;
    EXPECT_LE(r.between_position_sampled, r.between_position_bound) << name;
    EXPECT_LE(r.between_angle_sampled_deg, r.between_angle_bound_deg) << name;
    // Dense samples of the motion as written (the composed curve), against the whole polyline
    // and the geodesics sampled finely with Eigen's slerp.
    double worst_pos = 0, worst_ang = 0;
    std::vector<Eigen::Quaterniond> rot;
    for (const auto& p : s.poses)
      rot.emplace_back(p.rotation.w(), p.rotation.x(), p.rotation.y(), p.rotation.z());
    double slack = 0;  // the slerp samples' spacing: they overestimate the distance by less
    for (std::size_t i = 0; i + 1 < n; ++i)
      slack = std::max(slack, rot[i].angularDistance(rot[i + 1]));
    slack = slack / 64 * 180 / M_PI;
    for (std::size_t i = 0; i + 1 < n; ++i)
      for (int k = 0; k < 12; ++k) {
        const double u = s.t[i] + (s.t[i + 1] - s.t[i]) * (k + 0.5) / 12;
        const Eigen::Matrix4d M = to_matrix4(evaluate(f.motion.curve, u));
        const Eigen::Vector3d x = M.block<3, 1>(1, 0) / M(0, 0);
        const Eigen::Quaterniond q(Eigen::Matrix3d(M.block<3, 3>(1, 1) / M(0, 0)));
        double dp = INFINITY, da = INFINITY;
        for (std::size_t j = 0; j + 1 < n; ++j)
          dp = std::min(dp, to_segment(x, s.poses[j].position, s.poses[j + 1].position));
        for (std::size_t j = (i > 2 ? i - 2 : 0); j + 1 < std::min(n, i + 4); ++j)
          for (int m = 0; m <= 32; ++m)
            da = std::min(da, q.angularDistance(rot[j].slerp(m / 32.0, rot[j + 1])) * 180 / M_PI);
        worst_pos = std::max(worst_pos, dp);
        worst_ang = std::max(worst_ang, da);
      }
    EXPECT_LE(worst_pos, r.between_position_bound + 1e-12) << name;
    EXPECT_LE(worst_ang, r.between_angle_bound_deg + slack + 1e-9) << name;
    EXPECT_GE(worst_pos, 0.2 * r.between_position_bound) << name << ": a loose bound";
  }
}

TEST(FitBetween, TheBoundsHoldOnAFitMadeWithoutThem) {
  // A fit at the poses only, with a coarse tolerance: its factors bounded directly, against
  // the motion sampled densely. The bounds need not be within the tolerance here; they must
  // hold.
  for (const auto& [name, frame] : sources()) {
    const Stream s = samples(frame, 300, 0.01, 0.05);
    FitOptions o;
    o.tol = 0.05;
    o.angle_tol_deg = 0.2;
    const FittedMotion f = fit_bspline(s.poses, s.t, o);
    const auto& fr = f.motion.factors->rotation;
    const auto& ft = f.motion.factors->translation;
    const std::size_t n = s.poses.size();
    Eigen::MatrixXd S(static_cast<Eigen::Index>(n), 3), R(static_cast<Eigen::Index>(n), 4);
    const auto unit = normalized_rotations(s.poses);
    for (std::size_t i = 0; i < n; ++i) {
      S.row(static_cast<Eigen::Index>(i)) = s.poses[i].position.transpose();
      for (int c = 0; c < 4; ++c) R(static_cast<Eigen::Index>(i), c) = unit[i][c];
    }
    Eigen::MatrixXd rot(static_cast<Eigen::Index>(fr.ctrl().size()), 4),
        trans(static_cast<Eigen::Index>(ft.ctrl().size()), 3);
    for (std::size_t i = 0; i < fr.ctrl().size(); ++i)
      for (int c = 0; c < 4; ++c) rot(static_cast<Eigen::Index>(i), c) = fr.ctrl()[i][c];
    for (std::size_t i = 0; i < ft.ctrl().size(); ++i)
      trans.row(static_cast<Eigen::Index>(i)) = ft.ctrl()[i].transpose();
    const std::vector<double> Tr = fr.knots(), Tt = ft.knots();
    const auto b = between::bounds({s.t, S, R, o.tol, o.angle_tol_deg},
                                   {Tr, fr.degree(), rot, Tt, ft.degree(), trans}, true);
    for (std::size_t i = 0; i + 1 < n; ++i)
      for (int k = 0; k <= 8; ++k) {
        const double u = s.t[i] + (s.t[i + 1] - s.t[i]) * k / 8;
        const Eigen::Matrix4d M = to_matrix4(evaluate(f.motion.curve, u));
        const Eigen::Vector3d x = M.block<3, 1>(1, 0) / M(0, 0);
        double dp = INFINITY;
        for (std::size_t j = 0; j + 1 < n; ++j)
          dp = std::min(dp, to_segment(x, s.poses[j].position, s.poses[j + 1].position));
        ASSERT_LE(dp, b.position[i] + 1e-12) << name << " interval " << i;
      }
    EXPECT_LE(b.sampled_position, *std::max_element(b.position.begin(), b.position.end()));
    EXPECT_LE(b.sampled_angle_deg, *std::max_element(b.angle_deg.begin(), b.angle_deg.end()));
  }
}

}  // namespace between_test
}  // namespace qmotion::kernel
