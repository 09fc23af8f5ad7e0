// tests/sweep/fit_test.cpp mirrors sweep/fit.hpp
#include <cmath>
#include <qmotion/kernel/qspline.hpp>
#include <qmotion/sweep/fit.hpp>
#include <random>

#include "qspline_util.hpp"
#include "sanitized_size.hpp"
#include "test_util.hpp"

namespace qmotion::test {
namespace {
using V3 = Eigen::Vector3d;
using V4 = Eigen::Vector4d;
using kernel::Quaternion;
using kernel::QuaternionSpline;

/// The largest deviation of the fitted trajectories of `pts` from the spline's at 3000
/// random parameters: independent of the fit's own grids.
double independent_deviation(const QuaternionSpline& s, const sweep::FrameFit& f,
                             const std::vector<V3>& pts) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(s.a(), s.b());
  double dev = 0;
  for (int i = 0; i < 3000; ++i) {
    const double t = u(rng);
    const Eigen::Matrix4d m = kernel::evaluate(f.matrix, t);
    for (const auto& x : pts) {
      const V3 want = kernel::rotate(s.rotation(t), x) + s.position(t);
      const V4 got = m * V4(1, x(0), x(1), x(2));
      dev = std::max(dev, (got.tail<3>() - want).norm());
    }
  }
  return dev;
}

TEST(FitFrames, EverySchemeIsWithinTheToleranceAndPolesGrowAsItShrinks) {
  const std::vector<V3> pts{V3(0, 0, 0), V3(5, 0, 0), V3(5, 3, 0), V3(0, 3, -1)};
  for (auto scheme : {kernel::QSplineScheme::kks, kernel::QSplineScheme::quintic,
                      kernel::QSplineScheme::quartic}) {
    const QuaternionSpline s = six_key_spline(scheme);
    SCOPED_TRACE(kernel::to_string(s.scheme));
    int last_poles = 0;
    for (double tol : steps({1e-3, 1e-6, 1e-9})) {
      sweep::FrameFitOptions o;
      o.tol = tol;
      const auto f = sweep::fit_frames(s, pts, o);
      EXPECT_LE(f.max_deviation, tol);
      EXPECT_LE(independent_deviation(s, f, pts), tol) << "tol " << tol;
      EXPECT_EQ(f.matrix.degree(), 5);
      const int poles = static_cast<int>(f.matrix.ctrl().size());
      EXPECT_GT(poles, last_poles) << "tol " << tol;
      last_poles = poles;
      // The ends are exact, and every row 0 is (1, 0, 0, 0): the fit acts affinely.
      EXPECT_LE((f.matrix.ctrl().front() - s.frame(s.a())).norm(), 1e-15 * 100);
      EXPECT_LE((f.matrix.ctrl().back() - s.frame(s.b())).norm(), 1e-15 * 100);
      for (const auto& m : f.matrix.ctrl()) EXPECT_EQ(m.row(0), Eigen::RowVector4d(1, 0, 0, 0));
      // The motion's breakpoints are knots of the fit.
      const auto bp = f.matrix.breakpoints();
      for (double k : s.knots)
        EXPECT_TRUE(std::find(bp.begin(), bp.end(), k) != bp.end()) << "knot " << k;
    }
  }
}

/// The largest deviation on a grid of `per_span` points in every span of the fit.
double grid_deviation(const QuaternionSpline& s, const sweep::FrameFit& f,
                      const std::vector<V3>& pts, int per_span) {
  const auto x = f.matrix.breakpoints();
  double dev = 0;
  for (std::size_t k = 0; k + 1 < x.size(); ++k)
    for (int i = 0; i <= per_span; ++i) {
      const double t = x[k] + (x[k + 1] - x[k]) * i / per_span;
      const Eigen::Matrix4d m = kernel::evaluate(f.matrix, t);
      for (const auto& p : pts) {
        const V3 want = kernel::rotate(s.rotation(t), p) + s.position(t);
        dev = std::max(dev, ((m * V4(1, p(0), p(1), p(2))).tail<3>() - want).norm());
      }
    }
  return dev;
}

// The fit's deviation is proven, not sampled: its bound is within the tolerance, above what
// 4096 points per span find, and above the certificate's own samples by at most the share of
// the tolerance its remainder term may take. A 64-point grid per span (the old check) reads
// below the 4096-point one somewhere: sampling alone would have certified too little.
TEST(FitFrames, TheDeviationBoundIsProvenAndTight) {
  const std::vector<V3> pts{V3(0, 0, 0), V3(5, 0, 0), V3(5, 3, 0), V3(0, 3, -1)};
  int under_read = 0;
  for (auto scheme : {kernel::QSplineScheme::kks, kernel::QSplineScheme::quintic,
                      kernel::QSplineScheme::quartic}) {
    const QuaternionSpline s = six_key_spline(scheme);
    for (double tol : steps({1e-3, 1e-6, 1e-9})) {
      SCOPED_TRACE(std::string(kernel::to_string(s.scheme)) + " tol " + std::to_string(tol));
      sweep::FrameFitOptions o;
      o.tol = tol;
      const auto f = sweep::fit_frames(s, pts, o);
      const double dense = grid_deviation(s, f, pts, 4096);
      EXPECT_LE(f.max_deviation_bound, tol);
      EXPECT_LE(dense, f.max_deviation_bound);
      EXPECT_LE(f.max_deviation, f.max_deviation_bound);
      EXPECT_LE(f.max_deviation_bound,
                std::max(dense, f.max_deviation) + sweep::kFitRemainderShare * tol * (1 + 1e-6));
      if (grid_deviation(s, f, pts, 64) < dense * (1 - 1e-3)) ++under_read;
    }
  }
  // The 64-point grid reads low at the finest tolerance, which the sanitized tree skips.
  if (!kSanitized) {
    EXPECT_GT(under_read, 0);
  }
}

// The generic entry point takes the motion's second-derivative bound, and the certificate's
// grid follows it: the spline's own bound asks for more samples than a (false) zero bound.
TEST(FitFrames, TheCertificateUsesTheMotionsBound) {
  const QuaternionSpline s = six_key_spline(kernel::QSplineScheme::kks);
  sweep::FrameFitOptions o;
  o.tol = 1e-6;
  const std::vector<V3> pts{V3(5, 3, 0)};
  const auto zero =
      sweep::fit_frames([&](double t) { return s.frame(t); },
                        [](double, double) { return kernel::FrameSecondDerivativeBound{}; },
                        s.knots, s.interior_continuity(), pts, o);
  const auto real = sweep::fit_frames(s, pts, o);
  EXPECT_GT(real.check_samples, zero.check_samples);  // a finer grid where the motion bends
  EXPECT_LE(grid_deviation(s, real, pts, 4096), real.max_deviation_bound);
}

TEST(FitFrames, KnotMultiplicityFollowsTheMotionsContinuity) {
  const QuaternionSpline q =
      six_key_spline(kernel::QSplineScheme::quintic);  // unequal spans: C0 in u
  sweep::FrameFitOptions o;
  o.tol = 1e-6;
  const auto f = sweep::fit_frames(q, {V3(1, 2, 3)}, o);
  for (std::size_t k = 1; k + 1 < q.knots.size(); ++k)
    EXPECT_EQ(kernel::continuity_at(f.matrix, q.knots[k]), 0) << "key " << k;
  const QuaternionSpline s = six_key_spline(kernel::QSplineScheme::kks);  // C2
  const auto g = sweep::fit_frames(s, {V3(1, 2, 3)}, o);
  for (std::size_t k = 1; k + 1 < s.knots.size(); ++k)
    EXPECT_GE(kernel::continuity_at(g.matrix, s.knots[k]), 2) << "key " << k;
}

TEST(FitFrames, SixthOrderConvergence) {
  // Degree 5: the error falls like h^6, so 1000 times less asks about 10^(1/2) times the spans
  // (not 1000^(1/4) = 5.6 of a cubic). Allow 2x for the adaptivity's granularity.
  const QuaternionSpline s = six_key_spline(kernel::QSplineScheme::kks);
  auto spans = [&](double tol, int degree) {
    sweep::FrameFitOptions o;
    o.tol = tol;
    o.degree = degree;
    return sweep::fit_frames(s, {V3(3, 1, 0)}, o).spans;
  };
  const double r5 = static_cast<double>(spans(1e-9, 5)) / spans(1e-6, 5);
  EXPECT_LE(r5, 2 * std::sqrt(10.0));
  const double r3 = static_cast<double>(spans(1e-8, 3)) / spans(1e-5, 3);
  EXPECT_GE(r3, r5);  // the cubic needs more refinement per decade
}

TEST(FitFrames, RefusesWhatItCannotReach) {
  const QuaternionSpline s = six_key_spline(kernel::QSplineScheme::kks);
  sweep::FrameFitOptions o;
  o.tol = 1e-9;
  o.degree = 1;
  o.max_spans = 64;
  try {
    sweep::fit_frames(s, {V3(1, 0, 0)}, o);
    ADD_FAILURE() << "no refusal";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), Errc::numerical_failure);
    EXPECT_NE(std::string(e.what()).find("above the tolerance"), std::string::npos) << e.what();
  }
  o.tol = -1;
  EXPECT_THROW(sweep::fit_frames(s, {V3(1, 0, 0)}, o), Error);
}

}  // namespace
}  // namespace qmotion::test
