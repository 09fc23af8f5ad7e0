// The proof that a sphere's pipe does not overlap itself (sweep/pipe_reach.hpp), on paths
// whose answer is known from their own geometry: exact circular arcs (rational quadratic
// pieces, curvature 1/R everywhere) and helices. A pipe is accepted exactly when r is below
// the radius of curvature and no far part of the path comes within 2 r; otherwise the
// refusal names the radius of curvature, or the two places on the path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/pipe.hpp>
#include <qmotion/sweep/pipe_reach.hpp>
#include <random>
#include <string>
#include <vector>

namespace qmotion {
namespace pipe_reach_tests {  // named: the unity build merges test files

using Path = kernel::BSpline<Eigen::Vector4d>;
const double kPi = 3.14159265358979323846;

/// `quarters` quarter circles of radius R about the origin in the xy plane, from (R, 0, 0)
/// counter-clockwise, as rational quadratic pieces (weights 1, sqrt(2)/2, 1), one per unit
/// of t: an exact circle, tangent-continuous at the joints.
Path arc(double R, int quarters) {
  std::vector<double> T{0, 0, 0};
  for (int q = 1; q < quarters; ++q) T.insert(T.end(), {double(q), double(q)});
  T.insert(T.end(), {double(quarters), double(quarters), double(quarters)});
  std::vector<Eigen::Vector4d> P;
  const double w = std::sqrt(0.5);
  auto at = [&](double a) { return Eigen::Vector3d(R * std::cos(a), R * std::sin(a), 0); };
  for (int q = 0; q < quarters; ++q) {
    const double a = q * kPi / 2;
    const Eigen::Vector3d p0 = at(a), corner = at(a) + at(a + kPi / 2);
    P.emplace_back(1, p0(0), p0(1), p0(2));
    P.emplace_back(w, w * corner(0), w * corner(1), w * corner(2));
  }
  const Eigen::Vector3d end = at(quarters * kPi / 2);
  P.emplace_back(1, end(0), end(1), end(2));
  return Path::make(2, T, P);
}

/// A cubic B-spline whose control points lie on a helix of radius R and pitch p, 12 per
/// turn: a helix-like path whose turns lie about p apart.
Path helix(double R, double p, double turns) {
  const int n = static_cast<int>(12 * turns) + 1;
  std::vector<double> T(4, 0.0);
  for (int i = 1; i < n - 3; ++i) T.push_back(i);
  T.insert(T.end(), 4, double(n - 3));
  std::vector<Eigen::Vector4d> P;
  for (int i = 0; i < n; ++i) {
    const double a = i * kPi / 6;
    P.emplace_back(1, R * std::cos(a), R * std::sin(a), p * a / (2 * kPi));
  }
  return Path::make(3, T, P);
}

::testing::AssertionResult refused(const Path& c, double r, const std::vector<std::string>& names) {
  try {
    sweep::pipe_overlap_free(c, r, "path");
  } catch (const Error& e) {
    const std::string m = e.what();
    if (e.code() != Errc::invalid_input)
      return ::testing::AssertionFailure() << "not invalid input: " << m;
    for (const auto& n : names)
      if (m.find(n) == std::string::npos)
        return ::testing::AssertionFailure() << "'" << n << "' not in: " << m;
    std::cout << m << "\n";
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "accepted";
}

TEST(PipeReach, CircleArcsAcceptedBelowTheirRadius) {
  // A quarter circle of radius 5: its ends are 7.07 apart, under 2 r = 8, yet no part of
  // the pipe of radius 4 overlaps another (the chord only grows along the arc).
  for (int quarters : {1, 2}) {
    const auto reach = sweep::pipe_overlap_free(arc(5, quarters), 4, "arc");
    EXPECT_GT(reach.pieces, 0u);
    EXPECT_LE(reach.curvature_radius, 5 * (1 + 1e-9));  // a lower bound of the true 5
    EXPECT_GT(reach.curvature_radius, 4);
    EXPECT_NEAR(reach.sampled_min_radius, 5, 1e-9);
  }
  // The half circle's ends are 10 apart, beyond 2 r = 9.8: accepted just below R.
  EXPECT_NO_THROW(sweep::pipe_overlap_free(arc(5, 2), 4.9, "arc"));
}

TEST(PipeReach, RefusesARadiusAboveTheCurvatureRadius) {
  EXPECT_TRUE(refused(arc(5, 1), 5.5, {"radius of curvature", "below the radius", "t = "}));
  EXPECT_TRUE(refused(helix(3, 2, 2), 4, {"radius of curvature", "below the radius", "t = "}));
}

TEST(PipeReach, RefusesAPathThatComesBack) {
  // Three quarters of a circle of radius 5: the ends are 7.07 apart; with r = 4 both caps
  // hold the point between them, so the shell overlaps itself.
  EXPECT_TRUE(refused(arc(5, 3), 4, {"overlaps itself", "comes back within", "t = "}));
  // A whole circle and a bit more: the path returns onto itself.
  EXPECT_TRUE(refused(arc(5, 5), 1, {"overlap", "comes back within"}));
  // A helix whose turns lie 5 apart, under 2 r = 6; at r = 2 (4 < 5) it is accepted.
  EXPECT_TRUE(
      refused(helix(10, 5, 2), 3, {"overlap", "comes back within", "twice the radius is 6"}));
  const auto ok = sweep::pipe_overlap_free(helix(10, 5, 2), 2, "helix");
  EXPECT_GT(ok.pairs, 0u);
  EXPECT_GT(ok.curvature_radius, 2);
}

/// The volume of { x : dist(x, c) <= r } by Monte Carlo in the box about the path: n points,
/// each against a polyline of 4000 segments on the path; and the standard error. Each point
/// is tested against the segments listed in its cell of a grid of side r, which lists every
/// segment whose box, grown by r, meets the cell: the others lie farther than r.
std::pair<double, double> monte_carlo_volume(const Path& c, double r, int n) {
  std::vector<Eigen::Vector3d> poly;
  Eigen::AlignedBox3d box;
  for (int i = 0; i <= 4000; ++i) {
    const Eigen::Vector4d y = kernel::evaluate(c, c.a() + (c.b() - c.a()) * i / 4000);
    poly.emplace_back(y.tail<3>() / y(0));
    box.extend(poly.back());
  }
  box.min().array() -= r;
  box.max().array() += r;
  const Eigen::Array3i cells = (box.sizes().array() / r).ceil().cast<int>().max(1);
  const auto cell = [&](const Eigen::Vector3d& x) {
    const Eigen::Array3i k =
        ((x - box.min()).array() / r).floor().cast<int>().max(0).min(cells - 1);
    return k;
  };
  std::vector<std::vector<int>> grid(static_cast<std::size_t>(cells.prod()));
  const auto index = [&](const Eigen::Array3i& k) {
    return static_cast<std::size_t>((k(2) * cells(1) + k(1)) * cells(0) + k(0));
  };
  for (std::size_t i = 0; i + 1 < poly.size(); ++i) {
    Eigen::AlignedBox3d sb(poly[i]);
    sb.extend(poly[i + 1]);
    const Eigen::Array3i lo = cell(sb.min().array() - r), hi = cell(sb.max().array() + r);
    for (int z = lo(2); z <= hi(2); ++z)
      for (int y = lo(1); y <= hi(1); ++y)
        for (int x = lo(0); x <= hi(0); ++x)
          grid[index(Eigen::Array3i(x, y, z))].push_back(static_cast<int>(i));
  }
  std::mt19937 g(11);
  std::uniform_real_distribution<double> u(0, 1);
  int inside = 0;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d x =
        box.min() + box.sizes().cwiseProduct(Eigen::Vector3d(u(g), u(g), u(g)));
    for (const int i : grid[index(cell(x))]) {
      const Eigen::Vector3d d = poly[i + 1] - poly[i];
      const double s = std::clamp((x - poly[i]).dot(d) / d.squaredNorm(), 0.0, 1.0);
      if ((poly[i] + s * d - x).squaredNorm() <= r * r) {
        ++inside;
        break;
      }
    }
  }
  const double p = double(inside) / n, vol = box.volume();
  return {p * vol, std::sqrt(p * (1 - p) / n) * vol};
}

/// Why the refusal matters: the shell of an overlapping pipe encloses its overlap twice, so
/// its volume exceeds the sweep's (Monte Carlo); an accepted pipe's volume is the sweep's.
TEST(PipeReach, OverlapWouldMiscountTheVolume) {
  for (double r : {3.0, 2.0}) {
    const Path c = helix(10, 5, 2);
    const double shell = sweep::pipe_shell(c, r, "helix").volume;
    const auto [mc, se] = monte_carlo_volume(c, r, 60000);
    std::cout << "r = " << r << ": shell " << shell << ", sweep " << mc << " +- " << se << "\n";
    if (r == 3.0)
      EXPECT_GT(shell, mc + 6 * se);  // refused above
    else
      EXPECT_NEAR(shell, mc, 4 * se);  // accepted above
  }
}

/// Random smooth paths with small balls: accepted, and the curvature bound lies below
/// every radius of curvature sampled along the path.
TEST(PipeReach, CurvatureBoundIsALowerBound) {
  std::mt19937 g(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 6; ++k) {
    std::vector<double> T(4, 0.0);
    const int n = 8;
    for (int i = 1; i < n - 3; ++i) T.push_back(i);
    T.insert(T.end(), 4, double(n - 3));
    std::vector<Eigen::Vector4d> P;
    for (int i = 0; i < n; ++i) {
      const double w = 1 + 0.3 * u(g);
      const Eigen::Vector3d x(10.0 * i, 4 * u(g), 4 * u(g));
      P.emplace_back(w, w * x(0), w * x(1), w * x(2));
    }
    const Path c = Path::make(3, T, P);
    const auto reach = sweep::pipe_overlap_free(c, 0.2, "random");
    double least = HUGE_VAL;
    for (int i = 0; i <= 20000; ++i) {
      const double t = c.a() + (c.b() - c.a()) * i / 20000;
      // Curvature from derivatives of the homogeneous curve by central differences of
      // the point (h small against the path's scale).
      const double h = 1e-4;
      auto pt = [&](double s) {
        const Eigen::Vector4d y = kernel::evaluate(c, std::clamp(s, c.a(), c.b()));
        return Eigen::Vector3d(y.tail<3>() / y(0));
      };
      const double s = std::clamp(t, c.a() + h, c.b() - h);
      const Eigen::Vector3d d1 = (pt(s + h) - pt(s - h)) / (2 * h),
                            d2 = (pt(s + h) - 2 * pt(s) + pt(s - h)) / (h * h);
      least = std::min(least, std::pow(d1.norm(), 3) / d1.cross(d2).norm());
    }
    EXPECT_LE(reach.curvature_radius, least * (1 + 1e-5)) << "path " << k;
    EXPECT_GT(reach.curvature_radius, 0.2) << "path " << k;
  }
}

}  // namespace pipe_reach_tests
}  // namespace qmotion
