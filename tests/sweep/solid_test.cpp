// tests/sweep/solid_test.cpp mirrors sweep/shell.hpp and sweep/solid.hpp
#include <cmath>
#include <qmotion/io/poses.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/kernel/parametrization.hpp>
#include <qmotion/sweep/factors.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <qmotion/sweep/shell.hpp>
#include <qmotion/sweep/solid.hpp>
#include <qmotion/sweep/surface.hpp>
#include <random>

#include "io_test_util.hpp"
#include "sweep_util.hpp"

namespace qmotion::test {
namespace {
using V3 = Eigen::Vector3d;

/// Elliptic + TR Bezier motion through poses given as (t, position, axis, angle in degrees).
Built motion(const std::vector<std::tuple<double, V3, V3, double>>& poses) {
  std::vector<kernel::Pose<double>> P;
  for (const auto& [t, p, axis, deg] : poses)
    P.push_back(kernel::Pose<double>{t, p, kernel::from_axis_angle(axis, deg * M_PI / 180.0)});
  auto r = kernel::interpolate_bezier(P, kernel::parametrize(P, kernel::ParamRule::given),
                                      kernel::InterpolationOptions{});
  auto f = *r.factors;
  return Built{std::move(r), std::move(f)};
}

TEST(Shell, SplittingAtC0KnotsKeepsTheSurfaceAndItsParameters) {
  const auto P = io::to_poses_double(io::read_poses(test_data("poses/five_positions.json")));
  auto r = kernel::interpolate_bezier(P, kernel::parametrize(P, kernel::ParamRule::given),
                                      kernel::InterpolationOptions{});
  const auto f = *r.factors;
  const auto circle = sweep::circle(3.0);  // quadratic, C0 joints at 1/5, 1/2, 7/10
  const auto whole = sweep::to_nurbs(sweep::kinematic_surface(r, circle));
  const auto faces = sweep::split_c0(whole);
  ASSERT_EQ(faces.size(), 4u);
  EXPECT_EQ(sweep::min_continuity(whole.knots_v, 2), 0);
  std::mt19937 g(3);
  double covered = 0;
  for (const auto& face : faces) {
    EXPECT_TRUE(
        kernel::BSpline<double>::validate(face.degree_u, face.knots_u, face.points.size()).empty());
    EXPECT_TRUE(
        kernel::BSpline<double>::validate(face.degree_v, face.knots_v, face.points.front().size())
            .empty());
    EXPECT_EQ(face.knots_u, whole.knots_u);  // u is still t, unsplit
    EXPECT_GE(sweep::min_continuity(face.knots_v, face.degree_v), 1);
    covered += face.knots_v.back() - face.knots_v.front();
    std::uniform_real_distribution<double> u(face.knots_u.front(), face.knots_u.back()),
        v(face.knots_v.front(), face.knots_v.back());
    for (int k = 0; k < 50; ++k) {
      const double uu = u(g), vv = v(g);
      EXPECT_LT((sweep::evaluate(face, uu, vv) - sweep::evaluate(whole, uu, vv)).norm(), 1e-12);
    }
  }
  EXPECT_DOUBLE_EQ(covered, 1.0);
  // A break (multiplicity degree + 1) and a C0 knot in one curve; curves split the same way.
  const sweep::NurbsCurve<double> c{2,
                                    {0, 0, 0, 1, 1, 2, 2, 2, 3, 3, 3},
                                    {V3(0, 0, 0), V3(1, 1, 0), V3(2, 0, 0), V3(3, 1, 0),
                                     V3(4, 0, 0), V3(5, 5, 0), V3(6, 6, 0), V3(7, 7, 0)},
                                    {1, 2, 1, 0.5, 1, 1, 1, 1}};
  const auto pieces = sweep::split_c0(c);
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[0].knots, (std::vector<double>{0, 0, 0, 1, 1, 1}));
  EXPECT_EQ(pieces[1].knots, (std::vector<double>{1, 1, 1, 2, 2, 2}));
  EXPECT_EQ(pieces[2].knots, (std::vector<double>{2, 2, 2, 3, 3, 3}));
  EXPECT_EQ(pieces[1].points.front(), V3(2, 0, 0));  // shares the C0 pole
  EXPECT_EQ(pieces[2].points.front(), V3(5, 5, 0));  // after the break
  for (double t : {0.3, 1.0, 1.7, 2.5})
    for (const auto& p : pieces) {
      if (p.knots.front() <= t && t < p.knots.back()) {
        EXPECT_LT((sweep::evaluate(p, t) - sweep::evaluate(c, t)).norm(), 1e-14) << t;
      }
    }
}

TEST(Solid, PlanarRegionsAreasAndCentroids) {
  const auto r = sweep::planar_region(sweep::rect(4.0, 2.0));
  EXPECT_NEAR(r.area, 8.0, 1e-13);
  EXPECT_LT(r.centroid.norm(), 1e-13);
  EXPECT_LT((r.normal - V3(0, 0, 1)).norm(), 1e-13);  // counter-clockwise about +z
  const auto c = sweep::planar_region(sweep::single_edge(sweep::circle(3.0)));
  EXPECT_NEAR(c.area, M_PI * 9.0, 1e-12);
  EXPECT_LT(c.centroid.norm(), 1e-12);
  // A clockwise, shifted, tilted triangle: area 1/2 |cross|, centroid the vertex mean.
  const V3 a(1, 2, 3), b(1, 5, 3), d(1, 2, 7);
  const auto t = sweep::planar_region(sweep::polyline<double>({a, b, d, a}));
  EXPECT_NEAR(t.area, 6.0, 1e-12);
  EXPECT_LT((t.centroid - (a + b + d) / 3).norm(), 1e-12);
  EXPECT_LT((t.normal - (b - a).cross(d - a).normalized()).norm(), 1e-12);
  // Bad input: open, not planar, no area.
  EXPECT_TRUE(throws_error(
      [] {
        sweep::planar_region(sweep::polyline<double>({V3(0, 0, 0), V3(1, 0, 0), V3(1, 1, 0)}));
      },
      Errc::invalid_input, {"closed"}));
  EXPECT_TRUE(throws_error(
      [] {
        sweep::planar_region(sweep::polyline<double>(
            {V3(0, 0, 0), V3(1, 0, 0), V3(1, 1, 0.5), V3(0, 1, 0), V3(0, 0, 0)}));
      },
      Errc::invalid_input, {"planar"}));
}

TEST(Solid, VolumeOfAScrewAlongTheNormalIsAreaTimesLength) {
  // Translation by 12 along z with a turn about the z axis through the centroid: every
  // section is the region moved along its normal, V = A * 12 (Cavalieri).
  const V3 z(0, 0, 1);
  const Built m = motion(
      {{0.0, V3(0, 0, 0), z, 0.0}, {0.5, V3(0, 0, 6), z, 40.0}, {1.0, V3(0, 0, 12), z, 80.0}});
  for (const auto& prof : {sweep::rect(4.0, 2.0), sweep::single_edge(sweep::circle(3.0))}) {
    const auto region = sweep::planar_region(prof);
    const auto back = sweep::find_backsweep(m.r, prof, region);
    EXPECT_FALSE(back.t.has_value());
    EXPECT_FALSE(back.flip);
    EXPECT_NEAR(sweep::swept_volume(m.r, region), region.area * 12.0, 1e-10 * region.area * 12.0);
  }
  // Moving against the normal: the same volume, flagged as flipped, not as a back-sweep.
  const Built down = motion({{0.0, V3(0, 0, 0), z, 0.0}, {1.0, V3(0, 0, -5), z, 0.0}});
  const auto rect = sweep::rect(4.0, 2.0);
  const auto back = sweep::find_backsweep(down.r, rect, sweep::planar_region(rect));
  EXPECT_FALSE(back.t.has_value());
  EXPECT_TRUE(back.flip);
  EXPECT_NEAR(sweep::swept_volume(down.r, sweep::planar_region(rect)), 40.0, 1e-10);
}

TEST(Solid, ARegionTurningAboutALineInItsPlaneSweepsBack) {
  // A turn about the x axis, which lies in the rectangle's plane and crosses it: points on
  // either side of the axis move along +n and -n.
  const V3 x(1, 0, 0);
  const Built m = motion(
      {{0.0, V3(0, 0, 0), x, 0.0}, {0.5, V3(0, 0, 0), x, 30.0}, {1.0, V3(0, 0, 0), x, 60.0}});
  const auto rect = sweep::rect(4.0, 2.0);
  const auto back = sweep::find_backsweep(m.r, rect, sweep::planar_region(rect));
  ASSERT_TRUE(back.t.has_value());
  EXPECT_DOUBLE_EQ(*back.t, 0.0);  // from the start
  // Moved off the axis (the region entirely on one side) it sweeps a solid of revolution.
  const auto off =
      sweep::polyline<double>({V3(-2, 3, 0), V3(2, 3, 0), V3(2, 5, 0), V3(-2, 5, 0), V3(-2, 3, 0)});
  const auto region = sweep::planar_region(off);
  const auto ok = sweep::find_backsweep(m.r, off, region);
  EXPECT_FALSE(ok.t.has_value());
  // Pappus: V = A * (distance of the centroid from the axis) * angle, when the turn is
  // uniform; the elliptic interpolant is not uniform in angle but turns by 60 degrees in
  // all, and the volume only depends on the total angle (n.c' dt = r dtheta).
  EXPECT_NEAR(sweep::swept_volume(m.r, region), 8.0 * 4.0 * M_PI / 3.0, 1e-9);
}

}  // namespace
}  // namespace qmotion::test
