// tests/kernel/spline_interpolation_test.cpp mirrors kernel/spline_interpolation.hpp
#include <qmotion/io/poses.hpp>
#include <qmotion/kernel/banded.hpp>
#include <qmotion/kernel/spline_interpolation.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <qmotion/sweep/surface.hpp>
#include <random>

#include "io_test_util.hpp"
#include "test_util.hpp"

namespace qmotion::test {
namespace {
using kernel::Pose;
using kernel::TranslationMethod;
using V3 = Eigen::Vector3d;

/// Random poses with random (large) rotations and parameters with uneven steps.
std::vector<Pose<double>> random_poses(unsigned seed, int n, std::vector<double>& t) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u(-1, 1), step(0.5, 2.0);
  std::vector<Pose<double>> P;
  t.clear();
  double s = 0;
  for (int i = 0; i < n; ++i) {
    Pose<double> p;
    p.position = V3(u(g), u(g), u(g)) * 100;
    p.rotation = kernel::from_axis_angle(V3(u(g), u(g), u(g)), 3.0 * u(g));
    P.push_back(p);
    t.push_back(s);
    s += step(g);
  }
  return P;
}

/// Normwise Plucker residual at 2000 samples (kernel::plucker_residual's measure).
double dense_plucker(const kernel::QMotion<double>& m) {
  const auto [r, d] = kernel::coefficient_scales(m);
  double worst = 0;
  for (int i = 0; i <= 2000; ++i) {
    const auto q = kernel::evaluate(m, m.a() + (m.b() - m.a()) * i / 2000.0);
    worst = std::max(worst, std::abs(kernel::plucker(q)) / (r * d));
  }
  return worst;
}

kernel::Motion<double> make(const std::string& form, const std::vector<Pose<double>>& P,
                            const std::vector<double>& t, TranslationMethod tr, int k = 3,
                            int l = 3) {
  if (form == "c1") return kernel::interpolate_c1(P, t, tr);
  kernel::SplineOptions o;
  o.translation = tr;
  o.k = k;
  o.l = l;
  return kernel::interpolate_bspline(P, t, o);
}

TEST(SplineMotion, RandomPosesAreInterpolatedAndPlucker) {
  for (int n : {20, 200, 2000})
    for (const std::string form : {"bspline", "c1"})
      for (auto tr : {TranslationMethod::tr, TranslationMethod::minimal}) {
        SCOPED_TRACE(form + " " + kernel::to_string(tr) + " n=" + std::to_string(n));
        std::vector<double> t;
        const auto P = random_poses(static_cast<unsigned>(n), n, t);
        const auto r = make(form, P, t, tr);
        ASSERT_EQ(r.provenance->residuals.size(), P.size());
        for (std::size_t i = 0; i < P.size(); ++i)  // independent of the function's own check
          ASSERT_LE(kernel::pose_residual(kernel::evaluate(r.curve, t[i]), P[i].dual_quaternion()),
                    1e-10)
              << "pose " << i;
        EXPECT_LE(dense_plucker(r.curve), 1e-12);
        EXPECT_EQ(r.curve.segments(),
                  form == "c1" ? n - 1 : n - 3);  // averaged knots: n - p spans
        EXPECT_EQ(r.curve.degree(), tr == TranslationMethod::tr ? 6 : 9);  // k + l, k + max(2k, l)
        EXPECT_EQ(r.curve.a(), t.front());
        EXPECT_EQ(r.curve.b(), t.back());
      }
}

/// Largest jump of the d-th derivative of the homogeneous trajectory of x across the
/// interior breakpoints, relative to that derivative's size. Each side's polynomial comes
/// from the motion's own segment (its Bezier piece squared through (12)), so the
/// measurement uses no knot multiplicity of the trajectory.
double derivative_jump(const kernel::QMotion<double>& m, const V3& x, int d) {
  const Eigen::Vector4d X(1, x(0), x(1), x(2));
  const auto bp = m.curve.breakpoints();
  std::vector<kernel::Bernstein<Eigen::Vector4d>> pieces;
  for (std::size_t k = 0; k + 1 < bp.size(); ++k) {
    const auto q = kernel::bezier_piece(m.curve, bp[k], bp[k + 1]);
    auto y = kernel::product(q, q, kernel::polar::PointImage<double>{X});
    for (int i = 0; i < d; ++i) y = kernel::derivative(y);
    pieces.push_back(y);
  }
  double jump = 0, size = 0;
  for (std::size_t k = 0; k + 1 < pieces.size(); ++k) {
    const Eigen::Vector4d l = kernel::evaluate(pieces[k], bp[k + 1]),
                          r = kernel::evaluate(pieces[k + 1], bp[k + 1]);
    jump = std::max(jump, (l - r).norm());
    size = std::max(size, std::max(l.norm(), r.norm()));
  }
  return jump / size;
}

TEST(SplineMotion, ContinuityAsStated) {
  std::vector<double> t;
  const auto P = random_poses(7, 30, t);
  const std::vector<V3> points = {V3(0, 0, 0), V3(0, 0, 1), V3(20, -5, 3)};
  struct Case {
    std::string form;
    TranslationMethod tr;
    int k, l, cont;  // guaranteed C^cont = C^(min(k, l) - 1); C^1 for c1
  };
  const std::vector<Case> cases = {{"bspline", TranslationMethod::tr, 3, 3, 2},
                                   {"bspline", TranslationMethod::minimal, 3, 3, 2},
                                   {"bspline", TranslationMethod::tr, 2, 4, 1},
                                   {"bspline", TranslationMethod::tr, 4, 5, 3},
                                   {"bspline", TranslationMethod::minimal, 5, 2, 1},
                                   {"c1", TranslationMethod::tr, 3, 3, 1},
                                   {"c1", TranslationMethod::minimal, 3, 3, 1}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.form + " " + kernel::to_string(c.tr) + " k=" + std::to_string(c.k) +
                 " l=" + std::to_string(c.l));
    const auto r = make(c.form, P, t, c.tr, c.k, c.l);
    for (const auto& x : points) {
      for (int d = 0; d <= c.cont; ++d)
        EXPECT_LE(derivative_jump(r.curve, x, d), 1e-9) << "order " << d << " at " << x.transpose();
      // The next order does jump: the measurement can see a discontinuity.
      EXPECT_GT(derivative_jump(r.curve, x, c.cont + 1), 1e-6) << "order " << c.cont + 1;
    }
  }
}

TEST(SplineMotion, AlgorithmTwoIsLocal) {
  std::vector<double> t;
  auto P = random_poses(9, 21, t);
  const auto a = kernel::interpolate_c1(P, t, TranslationMethod::tr);
  P[10].position += V3(5, -3, 2);
  P[10].rotation = kernel::from_axis_angle(V3(1, 1, 0), 0.4) * P[10].rotation;
  const auto b = kernel::interpolate_c1(P, t, TranslationMethod::tr);
  // Estimates at poses 9, 10, 11 use pose 10; segment j uses the estimates at j and j + 1.
  for (int j = 0; j < 20; ++j) {
    const auto pa = kernel::bezier_piece(a.curve.curve, t[static_cast<std::size_t>(j)],
                                         t[static_cast<std::size_t>(j + 1)]);
    const auto pb = kernel::bezier_piece(b.curve.curve, t[static_cast<std::size_t>(j)],
                                         t[static_cast<std::size_t>(j + 1)]);
    // Q and -Q are one motion: the sign rule (24) may flip every later rotation.
    double plus = 0, minus = 0, size = 0;
    for (int i = 0; i <= pa.degree(); ++i) {
      plus = std::max(plus, kernel::max_abs(kernel::DualQuaternion<double>(pa[i] - pb[i])));
      minus = std::max(minus, kernel::max_abs(kernel::DualQuaternion<double>(pa[i] + pb[i])));
      size = std::max(size, kernel::max_abs(pa[i]));
    }
    const double diff = std::min(plus, minus);
    // Untouched segments agree to rounding (reassembly blossoms through neighbours).
    if (j < 8 || j > 11) {
      EXPECT_LE(diff, 1e-13 * size) << "segment " << j << " changed";
    } else {
      EXPECT_GT(diff, 1e-6 * size) << "segment " << j << " did not change";
    }
  }
  // The global B-spline motion is not local: a far segment moves too.
  std::vector<double> t2;
  auto Q = random_poses(9, 21, t2);
  const auto c = kernel::interpolate_bspline(Q, t2, kernel::SplineOptions{});
  Q[10].position += V3(5, -3, 2);
  const auto d = kernel::interpolate_bspline(Q, t2, kernel::SplineOptions{});
  EXPECT_NE(kernel::evaluate(c.curve, 0.5 * (t2[0] + t2[1])),
            kernel::evaluate(d.curve, 0.5 * (t2[0] + t2[1])));
}

#ifdef QMOTION_WITH_CGAL
TEST(SplineMotion, ExactBSplineMotionsAreExact) {
  const auto set = io::read_poses(test_data("poses/rational_exact.json"));
  const auto P = io::to_poses_exact(set);
  std::vector<Rational> t;
  for (const auto& p : P) t.push_back(*p.t);
  for (auto tr : {TranslationMethod::tr, TranslationMethod::minimal})
    for (int k : {1, 2, 3}) {
      kernel::SplineOptions o;
      o.translation = tr;
      o.k = k;
      o.l = 2;
      const auto r = kernel::interpolate_bspline(P, t, o);  // throws unless every pose is exact
      EXPECT_EQ(kernel::plucker_residual(r.curve), Rational(0));
      for (double x : r.provenance->residuals) EXPECT_EQ(x, 0.0);
    }
}
#endif

TEST(SplineMotion, ExportedGeometryIsExact) {
  std::vector<double> t;
  const auto P = random_poses(11, 200, t);
  for (const std::string form : {"bspline", "c1"})
    for (auto tr : {TranslationMethod::tr, TranslationMethod::minimal}) {
      SCOPED_TRACE(form + " " + kernel::to_string(tr));
      const auto r = make(form, P, t, tr);
      const V3 x(3, -2, 5);
      const auto c = sweep::to_nurbs(sweep::trajectory(r, x));
      EXPECT_EQ(c.degree, kernel::construction_order(tr, 3, 3));
      std::mt19937 g(2);
      std::uniform_real_distribution<double> u(r.curve.a(), r.curve.b()), v(0, 1);
      double dev = 0, lo = 1e300, hi = -1e300;
      for (int i = 0; i < 400; ++i) {
        const double s = u(g);
        const V3 e = kernel::apply_point(kernel::evaluate(r.curve, s), x);
        dev = std::max(dev, (sweep::evaluate(c, s) - e).norm());
        lo = std::min(lo, e.minCoeff());
        hi = std::max(hi, e.maxCoeff());
      }
      EXPECT_LE(dev / (hi - lo), 1e-11);
      for (double w : c.weights) EXPECT_GT(w, 0.0);
      const auto prof = sweep::circle(7.0);
      const auto s = sweep::to_nurbs(sweep::kinematic_surface(r, prof));
      double sdev = 0;
      for (int i = 0; i < 400; ++i) {
        const double uu = u(g), vv = v(g);
        sdev = std::max(
            sdev, (sweep::evaluate(s, uu, vv) -
                   kernel::apply_point(kernel::evaluate(r.curve, uu), sweep::evaluate(prof, vv)))
                      .norm());
      }
      EXPECT_LE(sdev / (hi - lo), 1e-11);
    }
}

TEST(Banded, SolvesLikeADenseSolver) {
  std::mt19937 g(4);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = 40, w = 3;
  kernel::BandMatrix<double> A(n, w);
  kernel::MatX<double> D = kernel::MatX<double>::Zero(n, n), B(n, 2);
  for (int i = 0; i < n; ++i) {
    for (int j = std::max(0, i - w); j <= std::min(n - 1, i + w); ++j)
      D(i, j) = A(i, j) = (i == j ? 10.0 : u(g));
    B(i, 0) = u(g);
    B(i, 1) = u(g);
  }
  const kernel::MatX<double> x = kernel::solve_banded(A, B, "test");
  EXPECT_LE((D * x - B).norm(), 1e-12);
  kernel::BandMatrix<double> Z(3, 1);
  EXPECT_THROW(
      kernel::solve_banded(Z, kernel::MatX<double>(kernel::MatX<double>::Ones(3, 1)), "zero"),
      Error);
}

TEST(Banded, LeastSquaresMatchesADenseQr) {
  // B-spline collocation at uniform samples (the degree-capped fit's system), degrees 1-9,
  // with rows that run past the last column and a few exact zeros: the banded Givens QR
  // gives Eigen's dense solution, and a zero column is refused.
  std::mt19937 g(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int w = 1; w <= 9; ++w) {
    const int n = 60, m = 4 * n + 1;
    kernel::MatX<double> rows(m, w + 1), dense = kernel::MatX<double>::Zero(m, n), B(m, 3);
    std::vector<int> first(static_cast<std::size_t>(m));
    for (int r = 0; r < m; ++r) {
      first[static_cast<std::size_t>(r)] = std::min(n - 1, r * (n - w) / (m - 1));
      for (int d = 0; d <= w; ++d) {
        const double v = (r + d) % 11 == 0 ? 0.0 : u(g);
        rows(r, d) = v;
        if (first[static_cast<std::size_t>(r)] + d < n)
          dense(r, first[static_cast<std::size_t>(r)] + d) = v;
      }
      for (int c = 0; c < 3; ++c) B(r, c) = u(g);
    }
    const auto x = kernel::least_squares_banded(n, w, first, rows, B, "test");
    const kernel::MatX<double> ref = dense.colPivHouseholderQr().solve(B);
    EXPECT_LE((x - ref).norm(), 1e-10 * ref.norm()) << "w=" << w;
  }
  kernel::MatX<double> rows = kernel::MatX<double>::Ones(4, 2);
  EXPECT_THROW(kernel::least_squares_banded(4, 1, {0, 0, 1, 1}, rows,
                                            kernel::MatX<double>::Ones(4, 1), "gap"),
               Error);
}

TEST(Bessel, EstimatesAreExactForQuadraticMotion) {
  // Positions on a parabola in t: the Bessel estimates are its exact derivative.
  const std::vector<double> t = {0, 0.5, 1.7, 2.0, 3.1};
  std::vector<V3> D;
  auto f = [](double s) { return V3(s * s, 3 * s - 1, -2 * s * s + s); };
  auto df = [](double s) { return V3(2 * s, 3, -4 * s + 1); };
  for (std::size_t i = 0; i + 1 < t.size(); ++i)
    D.push_back((f(t[i + 1]) - f(t[i])) / (t[i + 1] - t[i]));
  const auto v = kernel::bessel_estimates(D, t);
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_LE((v[i] - df(t[i])).norm(), 1e-12) << i;
}

}  // namespace
}  // namespace qmotion::test
