// tests/sweep/sweep_test.cpp mirrors sweep/trajectory.hpp, sweep/surface.hpp,
// sweep/weights.hpp, sweep/profiles.hpp, sweep/approximate.hpp
#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/kernel/parametrization.hpp>
#include <qmotion/kernel/spline_interpolation.hpp>
#include <qmotion/sweep/approximate.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <qmotion/sweep/surface.hpp>
#include <random>

#include "io_test_util.hpp"
#include "sweep_util.hpp"
#include "test_util.hpp"

namespace qmotion::test {
namespace {
using kernel::RotationMethod;
using kernel::TranslationMethod;
using V3 = Eigen::Vector3d;

/// A motion without recorded factors (hand-written).
kernel::Motion<double> bare(const kernel::QMotion<double>& m) { return kernel::Motion<double>(m); }

Built build(const std::vector<kernel::Pose<double>>& P, RotationMethod rot, TranslationMethod tr) {
  kernel::InterpolationOptions o;
  o.rotation = rot;
  o.translation = tr;
  auto r = kernel::interpolate_bezier(P, kernel::parametrize(P, kernel::ParamRule::given), o);
  auto f = *r.factors;
  return Built{std::move(r), std::move(f)};
}

double diag(const std::vector<V3>& pts) {
  V3 lo = pts[0], hi = pts[0];
  for (const auto& p : pts) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

/// Largest deviation of the curve from the point's path, relative to the path's size.
double curve_deviation(const sweep::NurbsCurve<double>& c, const kernel::QMotion<double>& m,
                       const V3& x) {
  std::mt19937 g(5);
  std::uniform_real_distribution<double> u(m.a(), m.b());
  std::vector<V3> ref;
  double dev = 0;
  for (int k = 0; k < 400; ++k) {
    const double t = k < 2 ? (k == 0 ? m.a() : m.b()) : u(g);
    const V3 exact = kernel::apply_point(kernel::evaluate(m, t), x);
    ref.push_back(exact);
    dev = std::max(dev, (sweep::evaluate(c, t) - exact).norm());
  }
  return dev / diag(ref);
}

double surface_deviation(const sweep::NurbsSurface<double>& s, const kernel::QMotion<double>& m,
                         const sweep::NurbsCurve<double>& prof) {
  std::mt19937 g(6);
  std::uniform_real_distribution<double> u(m.a(), m.b()), v(prof.knots.front(), prof.knots.back());
  std::vector<V3> ref;
  double dev = 0;
  for (int k = 0; k < 400; ++k) {
    const double uu = u(g), vv = v(g);
    const V3 exact = kernel::apply_point(kernel::evaluate(m, uu), sweep::evaluate(prof, vv));
    ref.push_back(exact);
    dev = std::max(dev, (sweep::evaluate(s, uu, vv) - exact).norm());
  }
  return dev / diag(ref);
}

bool all_positive(const std::vector<double>& w) {
  return std::all_of(w.begin(), w.end(), [](double x) { return x > 0; });
}

const RotationMethod kRot[] = {RotationMethod::elliptic, RotationMethod::affine,
                               RotationMethod::projective};
const TranslationMethod kTr[] = {TranslationMethod::tr, TranslationMethod::trt,
                                 TranslationMethod::minimal};

TEST(Trajectory, ExactAtItsMinimalDegreeForEveryMethod) {
  const auto P = io::to_poses_double(io::read_poses(test_data("poses/five_positions.json")));
  const int m = 4;
  for (auto rot : kRot)
    for (auto tr : kTr) {
      SCOPED_TRACE(std::string(kernel::to_string(rot)) + "+" + kernel::to_string(tr));
      const Built b = build(P, rot, tr);
      ASSERT_TRUE(sweep::factors_match(b.f, b.r.curve));
      const int k = b.r.provenance->rotation_degree;
      for (const V3& x : {V3(0, 0, 0), V3(0, 0, 1), V3(12, -3, 7)}) {
        const auto c = sweep::to_nurbs(sweep::trajectory(b.r, x));
        EXPECT_LE(curve_deviation(c, b.r.curve, x), 1e-11);
        EXPECT_TRUE(all_positive(c.weights));
        EXPECT_EQ(c.knots.front(), b.r.curve.a());  // u is t
        EXPECT_EQ(c.knots.back(), b.r.curve.b());
        int expected = kernel::construction_order(tr, k, b.r.provenance->translation_degree,
                                                  std::max(b.r.provenance->translation_degree2, 0));
        if (tr == TranslationMethod::tr && x.isZero())
          expected = m;  // Proposition 4: the origin's path has degree l
        EXPECT_EQ(c.degree, expected) << x.transpose();
      }
      // Without the factors: the same geometry from the motion alone (degree 2n, elevation
      // stripped). Forming |Q0|^2 = 4 |Q_rot|^6 (minimal order) loses digits where the
      // projective rotation comes near zero, which is why exports use the factors.
      const auto c2 = sweep::to_nurbs(sweep::trajectory(bare(b.r.curve), V3(0, 0, 1)));
      EXPECT_LE(curve_deviation(c2, b.r.curve, V3(0, 0, 1)), 1e-10) << "degree " << c2.degree;
    }
}

#ifdef QMOTION_WITH_CGAL
TEST(Trajectory, ExactlyOnTheMotionInRationalArithmetic) {
  const auto P = io::to_poses_exact(io::read_poses(test_data("poses/rational_exact.json")));
  std::vector<Rational> t;
  for (const auto& p : P) t.push_back(*p.t);
  for (auto tr : kTr) {
    kernel::InterpolationOptions o;
    o.translation = tr;
    o.rotation = RotationMethod::affine;
    const auto r = kernel::interpolate_bezier(P, t, o);
    const auto f = *r.factors;
    ASSERT_TRUE(sweep::factors_match(f, r.curve));
    sweep::Vec4<Rational> X(Rational(2), Rational(3), Rational(-1), Rational(5) / Rational(7));
    const auto y = sweep::trajectory_from_factors(f, X);
    for (int i = 0; i <= 12; ++i) {
      const Rational s = Rational(i) / Rational(12);
      const auto a = kernel::evaluate(y, s);
      const auto e = kernel::apply(kernel::evaluate(r.curve, s), X);
      for (int c = 0; c < 4; ++c)
        for (int d = 0; d < 4; ++d)
          ASSERT_EQ(Rational(a(c) * e(d)), Rational(a(d) * e(c))) << "t = " << s;
    }
  }
}
#endif

#ifdef QMOTION_WITH_CGAL
/// The B-spline motion through the exact poses P at t, rotation factor of degree k,
/// translation factor of degree 2.
auto exact_spline(const std::vector<kernel::Pose<Rational>>& P, const std::vector<Rational>& t,
                  TranslationMethod tr, int k) {
  kernel::SplineOptions o;
  o.translation = tr;
  o.k = k;
  o.l = 2;
  return kernel::interpolate_bspline(P, t, o);
}
#endif

#ifdef QMOTION_WITH_CGAL
TEST(Trajectory, SplineMatrixIsTheMotionWithTheFactorsContinuity) {
  // The matrix spline of a B-spline motion's factors (built span by span, assembled once) is
  // the motion's matrix at every parameter, exactly, and at each interior breakpoint exactly
  // as smooth as the less smooth factor there.
  const auto P = io::to_poses_exact(io::read_poses(test_data("poses/rational_exact.json")));
  std::vector<Rational> t;
  for (const auto& p : P) t.push_back(*p.t);
  for (auto tr : {TranslationMethod::tr, TranslationMethod::minimal})
    for (int k = 1; k <= 2; ++k) {
      const auto r = exact_spline(P, t, tr, k);
      const auto& f = *r.factors;
      const auto M = sweep::matrix_from_factors(f);
      ASSERT_GT(M.breakpoints().size(), 2u);
      for (const Rational& x : M.breakpoints()) {
        if (x == M.a() || x == M.b()) continue;
        EXPECT_EQ(kernel::continuity_at(M, x), std::min(kernel::continuity_at(f.rotation, x),
                                                        kernel::continuity_at(f.translation, x)));
      }
      std::vector<Rational> s = M.breakpoints();
      for (int i = 0; i <= 9; ++i) s.push_back(M.a() + (M.b() - M.a()) * Rational(i) / Rational(9));
      const sweep::Vec4<Rational> X(Rational(3), Rational(1), Rational(-2),
                                    Rational(5) / Rational(7));
      for (const Rational& u : s) {
        const sweep::Vec4<Rational> a = kernel::evaluate(M, u) * X;
        const auto e = kernel::apply(kernel::evaluate(r.curve, u), X);
        for (int c = 0; c < 4; ++c)
          for (int d = 0; d < 4; ++d) ASSERT_EQ(Rational(a(c) * e(d)), Rational(a(d) * e(c)));
      }
    }
}
#endif

#ifdef QMOTION_WITH_CGAL
TEST(Trajectory, PointsMappedSpanBySpanAreTheMatrixSplinesImages) {
  // trajectories_from_factors applies each span's matrix piece to the points as it is made,
  // without the matrix spline: in rational arithmetic its poles and knots are M X's exactly.
  const auto P = io::to_poses_exact(io::read_poses(test_data("poses/rational_exact.json")));
  std::vector<Rational> t;
  for (const auto& p : P) t.push_back(*p.t);
  const std::vector<sweep::Vec4<Rational>> X{
      {Rational(1), Rational(0), Rational(0), Rational(0)},
      {Rational(3), Rational(1), Rational(-2), Rational(5) / Rational(7)},
      {Rational(1, 2), Rational(4), Rational(0), Rational(-1)}};
  const auto expect_images = [&](const kernel::MotionFactors<Rational>& f,
                                 const std::string& what) {
    const auto M = sweep::matrix_from_factors(f);
    const auto y = sweep::trajectories_from_factors(f, X);
    ASSERT_EQ(y.size(), X.size());
    for (std::size_t j = 0; j < X.size(); ++j) {
      const auto e = sweep::apply(M, X[j]);
      EXPECT_EQ(y[j].degree(), e.degree()) << what;
      EXPECT_EQ(y[j].knots(), e.knots()) << what;
      EXPECT_TRUE(y[j].ctrl() == e.ctrl()) << what << " point " << j;
    }
  };
  for (auto tr : {TranslationMethod::tr, TranslationMethod::minimal})
    for (int k = 1; k <= 2; ++k) {
      expect_images(*exact_spline(P, t, tr, k).factors,
                    std::string("B-spline ") + kernel::to_string(tr) + " k = " + std::to_string(k));
    }
  for (auto tr : kTr) {
    kernel::InterpolationOptions o;
    o.translation = tr;
    o.rotation = RotationMethod::affine;
    expect_images(*kernel::interpolate_bezier(P, t, o).factors,
                  std::string("Bezier ") + kernel::to_string(tr));
  }
}
#endif

#ifdef QMOTION_WITH_CGAL
TEST(KinematicSurface, ItsColumnsAreTheProfilePolesTrajectoriesExactly) {
  // With the factors the surface is made from the matrix spline M once (pole (i, j) =
  // M_i X_j): in rational arithmetic each column is trajectories_from_factors' spline of
  // that homogeneous pole, knots and poles, for a rational profile (a circle).
  const auto P = io::to_poses_exact(io::read_poses(test_data("poses/rational_exact.json")));
  std::vector<Rational> t;
  for (const auto& p : P) t.push_back(*p.t);
  const auto profile = sweep::circle(Rational(7));
  std::vector<sweep::Vec4<Rational>> X;
  for (std::size_t j = 0; j < profile.points.size(); ++j) {
    sweep::Vec4<Rational> x;
    x << profile.weights[j], profile.points[j] * profile.weights[j];
    X.push_back(x);
  }
  for (auto tr : {TranslationMethod::tr, TranslationMethod::minimal})
    for (int k = 1; k <= 2; ++k) {
      SCOPED_TRACE(std::string(kernel::to_string(tr)) + " k = " + std::to_string(k));
      const auto r = exact_spline(P, t, tr, k);
      const auto s = sweep::kinematic_surface(r, profile);
      auto y = sweep::trajectories_from_factors(*r.factors, X);
      const auto extra = sweep::knots_for_positive_weights(y.front());
      ASSERT_EQ(s.poles.front().size(), X.size());
      for (std::size_t j = 0; j < X.size(); ++j) {
        y[j] = sweep::insert_knots(std::move(y[j]), extra);
        EXPECT_EQ(s.degree_u, y[j].degree());
        EXPECT_EQ(s.knots_u, y[j].knots());
        ASSERT_EQ(s.poles.size(), y[j].ctrl().size());
        for (std::size_t i = 0; i < s.poles.size(); ++i)
          ASSERT_TRUE(s.poles[i][j] == y[j].ctrl()[i]) << "pole " << i << ", " << j;
      }
      EXPECT_EQ(s.knots_v, profile.knots);
      EXPECT_EQ(s.degree_v, profile.degree);
    }
}
#endif

std::vector<std::pair<std::string, sweep::NurbsCurve<double>>> profiles() {
  return {
      {"parabola.json",
       io::curve_from_json(io::read_json_file(test_data("profiles/parabola.json")), "parabola")},
      {"quarter_circle.json",
       io::curve_from_json(io::read_json_file(test_data("profiles/quarter_circle.json")),
                           "quarter")},
      {"circle:15", sweep::circle(15.0)},
      {"segment", sweep::segment<double>(V3(-5, 2, 0), V3(5, -1, 8))},
      {"arc:8,30,250", sweep::arc(8.0, 30.0, 250.0)}};
}

/// a and b are the same surface, every number equal.
template <typename Scalar>
void expect_same_surface(const sweep::NurbsSurface<Scalar>& a,
                         const sweep::NurbsSurface<Scalar>& b) {
  EXPECT_EQ(a.degree_u, b.degree_u);
  EXPECT_EQ(a.degree_v, b.degree_v);
  EXPECT_TRUE(a.knots_u == b.knots_u);
  EXPECT_TRUE(a.knots_v == b.knots_v);
  EXPECT_TRUE(a.weights == b.weights);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    ASSERT_EQ(a.points[i].size(), b.points[i].size());
    for (std::size_t j = 0; j < a.points[i].size(); ++j)
      ASSERT_TRUE(a.points[i][j] == b.points[i][j]) << "pole " << i << ", " << j;
  }
}

TEST(KinematicSurface, ExactForEveryMethodAndProfileKind) {
  const auto P = io::to_poses_double(io::read_poses(test_data("poses/five_positions.json")));
  for (auto rot : kRot)
    for (auto tr : kTr) {
      const Built b = build(P, rot, tr);
      for (const auto& [name, prof] : profiles()) {
        SCOPED_TRACE(std::string(kernel::to_string(rot)) + "+" + kernel::to_string(tr) + " " +
                     name);
        const auto s = sweep::to_nurbs(sweep::kinematic_surface(b.r, prof));
        EXPECT_LE(surface_deviation(s, b.r.curve, prof), 1e-11);
        // kinematic_nurbs (what sweeps build) skips the homogeneous rows: the same surface
        // bit for bit, through the columns (two or three profile poles), through M (four or
        // more), and from the motion alone.
        expect_same_surface(sweep::kinematic_nurbs(b.r, prof), s);
        expect_same_surface(sweep::kinematic_nurbs(bare(b.r.curve), prof),
                            sweep::to_nurbs(sweep::kinematic_surface(bare(b.r.curve), prof)));
        for (const auto& row : s.weights) EXPECT_TRUE(all_positive(row));
        EXPECT_EQ(s.degree_v, prof.degree);
        EXPECT_EQ(s.degree_u,
                  kernel::construction_order(tr, b.r.provenance->rotation_degree,
                                             b.r.provenance->translation_degree,
                                             std::max(b.r.provenance->translation_degree2, 0)));
        EXPECT_EQ(s.knots_u.front(), b.r.curve.a());
        EXPECT_EQ(s.knots_u.back(), b.r.curve.b());
      }
    }
}

/// A TR motion whose rotational part runs from 1 to -1 + 0.3 i: |Q_rot|^2 = (1-2t)^2 +
/// (0.3 t)^2 > 0, but its middle Bernstein coefficient is 1 . (-1) = -1.
kernel::QMotion<double> negative_weight_motion() {
  using Q = kernel::Quaternion<double>;
  using DQ = kernel::DualQuaternion<double>;
  const kernel::Bernstein<Q> rot({Q(1, 0, 0, 0), Q(-1, 0.3, 0, 0)});
  const kernel::Bernstein<DQ> trans({DQ::translation(V3(0, 0, 0)), DQ::translation(V3(10, 5, 0))});
  return kernel::QMotion<double>{kernel::Basis::bezier,
                                 kernel::BSpline<DQ>::from_bezier(kernel::product(trans, rot))};
}

TEST(PositiveWeights, NegativeBernsteinWeightsAreRefinedAwayWithTheSameGeometry) {
  const auto m = negative_weight_motion();
  const auto w = kernel::weight_spline(m);
  EXPECT_LT(*std::min_element(w.ctrl().begin(), w.ctrl().end()), 0.0);  // the premise
  const V3 x(1, 2, 3);
  const auto raw = sweep::trajectory_from_motion(m, sweep::Vec4<double>(1, 1, 2, 3));
  EXPECT_LT(std::min_element(raw.ctrl().begin(), raw.ctrl().end(),
                             [](auto& a, auto& b) { return a(0) < b(0); })
                ->
                operator()(0),
            0.0);
  const auto c = sweep::to_nurbs(sweep::trajectory(bare(m), x));
  EXPECT_TRUE(all_positive(c.weights));
  EXPECT_GT(c.knots.size(), raw.knots().size());  // knots were inserted
  EXPECT_LE(curve_deviation(c, m, x), 1e-11);     // same geometry, u = t
  const auto s = sweep::to_nurbs(sweep::kinematic_surface(bare(m), sweep::circle(4.0)));
  for (const auto& row : s.weights) EXPECT_TRUE(all_positive(row));
  EXPECT_LE(surface_deviation(s, m, sweep::circle(4.0)), 1e-11);
}

TEST(PositiveWeights, TheMatrixSplinesNegativeWeightsAreRefinedAwayToo) {
  // The same motion with its TR factors: the kinematic surface is made from the matrix
  // spline M, whose weight row |Q_rot|^2 has the Bernstein coefficient -1 too.
  using Q = kernel::Quaternion<double>;
  const auto m = negative_weight_motion();
  const sweep::MotionFactors<double> f{
      TranslationMethod::tr,
      kernel::BSpline<Q>::from_bezier(kernel::Bernstein<Q>({Q(1, 0, 0, 0), Q(-1, 0.3, 0, 0)})),
      kernel::BSpline<V3>::from_bezier(kernel::Bernstein<V3>({V3(0, 0, 0), V3(10, 5, 0)})),
      std::nullopt};
  ASSERT_TRUE(sweep::factors_match(f, m));
  const auto M = sweep::matrix_from_factors(f);
  double least = 1;
  for (const auto& Mi : M.ctrl()) least = std::min(least, Mi(0, 0));
  EXPECT_LT(least, 0.0);  // the premise
  // A circle (nine poles: through M) and a segment (two: each pole's own trajectory).
  for (const auto& profile :
       {sweep::circle(4.0), sweep::segment<double>(V3(1, 2, 3), V3(-4, 0, 2))}) {
    SCOPED_TRACE(profile.points.size());
    const auto s = sweep::to_nurbs(sweep::kinematic_surface(kernel::Motion<double>(m, f), profile));
    for (const auto& row : s.weights) EXPECT_TRUE(all_positive(row));
    EXPECT_EQ(s.degree_u, 3);                       // 2k + l, not the motion's 2n = 4
    EXPECT_GT(s.knots_u.size(), M.knots().size());  // knots were inserted
    expect_same_surface(sweep::kinematic_nurbs(kernel::Motion<double>(m, f), profile), s);
    EXPECT_LE(surface_deviation(s, m, profile), 1e-11);
  }
}

TEST(PositiveWeights, AMotionWithAPoleCannotBeMadePositive) {
  using Q = kernel::Quaternion<double>;
  using DQ = kernel::DualQuaternion<double>;
  const kernel::QMotion<double> m{kernel::Basis::bezier,
                                  kernel::BSpline<DQ>::from_bezier(kernel::product(
                                      kernel::Bernstein<DQ>({DQ::translation(V3(1, 0, 0))}),
                                      kernel::Bernstein<Q>({Q(1, 0, 0, 0), Q(-1, 0, 0, 0)})))};
  EXPECT_TRUE(throws_error([&] { sweep::trajectory(bare(m), V3(1, 1, 1)); },
                           Errc::numerical_failure, {"pole"}));
}

#ifdef QMOTION_WITH_CGAL
TEST(KinematicSurface, KinematicNurbsIsTheSameSurfaceWhereWeightsAreRefinedAndExactly) {
  // kinematic_nurbs as to_nurbs(kinematic_surface) (see ExactForEveryMethodAndProfileKind)
  // with negative Bernstein weights refined away, and in rational arithmetic.
  {
    SCOPED_TRACE("negative Bernstein weights");
    const auto m = bare(negative_weight_motion());
    expect_same_surface(sweep::kinematic_nurbs(m, sweep::circle(4.0)),
                        sweep::to_nurbs(sweep::kinematic_surface(m, sweep::circle(4.0))));
  }
  const auto Pe = io::to_poses_exact(io::read_poses(test_data("poses/rational_exact.json")));
  std::vector<Rational> t;
  for (const auto& p : Pe) t.push_back(*p.t);
  for (const auto& prof : {sweep::circle(Rational(7)),
                           sweep::segment<Rational>(Eigen::Matrix<Rational, 3, 1>(1, 2, 3),
                                                    Eigen::Matrix<Rational, 3, 1>(-2, 0, 5))}) {
    SCOPED_TRACE("rational, " + std::to_string(prof.points.size()) + " profile poles");
    const auto r = exact_spline(Pe, t, TranslationMethod::tr, 2);
    expect_same_surface(sweep::kinematic_nurbs(r, prof),
                        sweep::to_nurbs(sweep::kinematic_surface(r, prof)));
  }
}
#endif

#ifdef QMOTION_WITH_CGAL
TEST(Profiles, TheRationalCircleIsExact) {
  const auto c = sweep::circle(Rational(7));
  const auto h = sweep::to_homogeneous(c);
  for (int i = 0; i <= 40; ++i) {
    const auto y = kernel::evaluate(h, Rational(i) / Rational(40));
    EXPECT_EQ(Rational(y(1) * y(1) + y(2) * y(2)),
              Rational(Rational(49) * y(0) * y(0)));  // x^2 + y^2 = r^2 exactly
    EXPECT_EQ(y(3), Rational(0));
  }
  const auto cd = sweep::circle(7.0);
  EXPECT_EQ(sweep::evaluate(cd, 0.0), V3(7, 0, 0));
  EXPECT_GT(sweep::evaluate(cd, 0.1).y(), 0.0);  // counter-clockwise about +z
  const auto a = sweep::arc(3.0, -45.0, 200.0);
  for (int i = 0; i <= 50; ++i) EXPECT_NEAR(sweep::evaluate(a, i / 50.0).norm(), 3.0, 1e-14);
  EXPECT_NEAR((sweep::evaluate(a, 1.0) -
               V3(3 * std::cos(200 * M_PI / 180), 3 * std::sin(200 * M_PI / 180), 0))
                  .norm(),
              0, 1e-14);
  EXPECT_THROW(sweep::arc(3.0, 10.0, 10.0), Error);
  EXPECT_THROW(sweep::circle(-1.0), Error);
}
#endif

TEST(Approximation, LowerDegreeWithinTheMeasuredTolerance) {
  const auto P = io::to_poses_double(io::read_poses(test_data("poses/five_positions.json")));
  const Built b = build(P, RotationMethod::elliptic, TranslationMethod::tr);
  const auto h = sweep::trajectory_from_factors(b.f, sweep::Vec4<double>(1, 0, 0, 1));
  ASSERT_EQ(h.degree(), 12);
  const auto a = sweep::approximate_homogeneous({h}, 5, 1e-4);
  EXPECT_EQ(a.curves.front().degree(), 5);
  EXPECT_LE(a.max_deviation, 1e-4);
  const auto c = sweep::to_nurbs(a.curves.front());
  EXPECT_TRUE(all_positive(c.weights));
  // An independent measurement agrees with the stated one.
  double dev = 0;
  for (int i = 0; i <= 997; ++i) {
    const double t = i / 997.0;
    dev = std::max(dev, (sweep::evaluate(c, t) -
                         kernel::apply_point(kernel::evaluate(b.r.curve, t), V3(0, 0, 1)))
                            .norm());
  }
  EXPECT_LE(dev, 1e-4);
}

TEST(Approximation, SplineMotionKeepsItsJointsAndBeatsTheExactPoleCount) {
  // A cubic B-spline motion through 40 poses of a helix: its trajectories have degree 9 and
  // only C2 joints, so the exact curve carries a 7-fold knot at each of its 38 joints.
  const auto P = io::to_poses_double(io::read_poses(test_data("poses/helix_40.json")));
  std::vector<double> t;
  for (const auto& p : P) t.push_back(*p.t);
  const auto m = kernel::interpolate_bspline(P, t, kernel::SplineOptions{});
  const auto h = sweep::trajectory_from_factors(*m.factors, sweep::Vec4<double>(1, 1, 0, 2));
  const int p = h.degree();
  std::map<double, int> joint_continuity;
  for (const double x : h.breakpoints())
    if (x > h.a() && x < h.b()) joint_continuity[x] = kernel::continuity_at(h, x);
  ASSERT_GT(joint_continuity.size(), 30u);
  Eigen::AlignedBox3d box;
  const auto exact = [&](double u) {
    const Eigen::Vector4d y = kernel::evaluate(h, u);
    return V3(y.tail<3>() / y(0));
  };
  for (int i = 0; i <= 1000; ++i) box.extend(exact(h.a() + (h.b() - h.a()) * i / 1000));
  for (const int D : {7, 5})
    for (const double rel : {1e-5, 1e-9}) {
      SCOPED_TRACE("degree " + std::to_string(D) + ", tolerance " + std::to_string(rel));
      ASSERT_LT(D, p);
      const double tol = rel * box.diagonal().norm();
      const auto a = sweep::approximate_homogeneous({h}, D, tol);
      const auto& c = a.curves.front();
      EXPECT_EQ(c.degree(), D);
      // Fewer poles than the exact curve itself, or the approximation would be pointless.
      EXPECT_LT(c.ctrl().size(), h.ctrl().size());
      // Never less smooth than the motion: at a joint the fit's continuity is at least the
      // curve's (or D - 1); every other knot is simple.
      for (const double x : c.breakpoints()) {
        if (x == c.a() || x == c.b()) continue;
        const auto it = joint_continuity.find(x);
        if (it == joint_continuity.end())
          EXPECT_EQ(kernel::continuity_at(c, x), D - 1) << x;
        else
          EXPECT_GE(kernel::continuity_at(c, x), std::min(it->second, D - 1)) << x;
      }
      // An independent measurement, denser than the fit's own, agrees with the stated one.
      double dev = 0;
      for (int i = 0; i <= 20011; ++i) {
        const double u = h.a() + (h.b() - h.a()) * i / 20011.0;
        const Eigen::Vector4d y = kernel::evaluate(c, u);
        ASSERT_GT(y(0), 0);
        dev = std::max(dev, (V3(y.tail<3>() / y(0)) - exact(u)).norm());
      }
      EXPECT_LE(dev, tol);
      EXPECT_LE(a.max_deviation, tol);
      EXPECT_GE(a.max_deviation, 0.9 * dev);
    }
}

}  // namespace
}  // namespace qmotion::test
