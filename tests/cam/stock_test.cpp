// tests/cam/stock_test.cpp: <qmotion/cam/stock.hpp>: the cutter's distance against its
// profile in the (rho, z) half-plane, and the swept cutter's certified distance against
// dense sampling of the moves.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <qmotion/cam/stock.hpp>
#include <qmotion/io/bodies.hpp>
#include <random>
#include <vector>

#include "sanitized_size.hpp"

namespace qmotion::test {
namespace {

using Kind = cam::Move::Kind;

double clamp_distance(double v, double lo, double hi) { return std::max({lo - v, v - hi, 0.0}); }

/// The distance from (rho, z) to the cutter's profile, from its definition: flat, a
/// rectangle; ball, a half-disc below a rectangle; bull, two rectangles and the corner's
/// quarter disc. Outside only (0 inside).
double profile_distance(const sweep::Body& c, double rho, double z) {
  const double R = c.D / 2;
  auto rect = [&](double r1, double z0, double z1) {
    return std::hypot(clamp_distance(rho, -1, r1), clamp_distance(z, z0, z1));
  };
  auto disc = [&](double cr, double cz, double r) {
    return std::max(std::hypot(rho - cr, z - cz) - r, 0.0);
  };
  using K = sweep::Body::Kind;
  if (c.kind == K::flat_cutter) return rect(R, 0, c.L);
  if (c.kind == K::ball_cutter)  // the capsule: the axis from R to max(R, L), grown by R
    return std::max(std::hypot(rho, clamp_distance(z, R, std::max(R, c.L))) - R, 0.0);
  return std::min({rect(R - c.rc, 0, c.L), rect(R, c.rc, c.L), disc(R - c.rc, c.rc, c.rc)});
}

TEST(Stock, CutterDistanceIsTheProfilesOutsideAndNegativeInside) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-12, 12), h(-6, 30);
  for (const char* spec : {"cutter:flat,10,20", "cutter:ball,6,20", "cutter:bull,10,2,20"}) {
    const sweep::Body c = io::read_body(spec);
    const auto cores = cam::detail::cores_of(c);
    for (int i = 0; i < 4000; ++i) {
      const Eigen::Vector3d y(u(rng), u(rng), h(rng));
      const double d = cam::cutter_distance(cores, y);
      const double p = profile_distance(c, std::hypot(y.x(), y.y()), y.z());
      if (y.z() > c.L) continue;  // above the cutting length the cores may reach further
      if (p > 0)
        EXPECT_NEAR(d, p, 1e-12) << spec << " at " << y.transpose();
      else
        EXPECT_LE(d, 1e-12) << spec << " at " << y.transpose();
    }
  }
}

cam::Move straight(Eigen::Vector3d a, Eigen::Vector3d b) {
  cam::Move m;
  m.kind = Kind::feed;
  m.from = a;
  m.to = b;
  return m;
}

cam::Program random_program(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-10, 10), z(-2, 2);
  cam::Program p;
  Eigen::Vector3d at(0, 0, 0);
  for (int i = 0; i < 12; ++i) {
    const Eigen::Vector3d to(u(rng), u(rng), z(rng));
    if (i % 3 == 2) {  // a quarter-ish arc in XY about a centre beside the chord
      cam::Move m = straight(at, at);
      m.kind = Kind::arc;
      m.plane = 17;
      m.centre = at + Eigen::Vector3d(3, 0, 0);
      m.to = m.centre + Eigen::Vector3d(0, 3, to.z() - at.z());
      m.to.z() = to.z();
      m.turns = 1;
      p.moves.push_back(m);
      at = m.to;
    } else {
      p.moves.push_back(straight(at, to));
      at = to;
    }
  }
  return p;
}

/// The least cutter distance over 20 000 samples of every move: at least the true least.
double sampled(const cam::Program& p, const sweep::Body& cutter, const Eigen::Vector3d& x,
               bool clipped) {
  const auto cores = cam::detail::cores_of(cutter);
  double best = HUGE_VAL;
  for (const cam::Move& m : p.moves)
    for (int k = 0; k <= 20000; ++k) {
      const double d = cam::cutter_distance(cores, x - cam::position(m, k / 20000.0));
      best = std::min(best, clipped ? std::max(d, 0.0) : d);
    }
  return best;
}

TEST(Stock, SweptDistanceEnclosesDenseSampling) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-14, 14), z(-4, 8);
  for (const char* spec : {"cutter:ball,6,20", "cutter:flat,10,20"}) {
    const sweep::Body cutter = io::read_body(spec);
    const cam::Program p = random_program(rng);
    const cam::CutIndex cut(p, cutter);
    for (int i = 0; i < 40; ++i) {
      const Eigen::Vector3d x(u(rng), u(rng), z(rng));
      for (const bool clipped : {false, true}) {
        const double eps = 0.002, limit = 50;
        const cam::CutIndex::Near n = cut.distance(x, eps, limit, clipped);
        const double s = std::min(sampled(p, cutter, x, clipped), limit);
        // Sampling finds at least the least; the step between samples is below 2e-3 mm.
        EXPECT_TRUE(n.settled);
        EXPECT_LE(n.lower, s + 1e-12) << spec << " at " << x.transpose();
        EXPECT_LE(n.upper, s + eps + 1e-12) << spec << " at " << x.transpose();
        EXPECT_GE(n.upper, s - 3e-3) << spec << " at " << x.transpose();
        EXPECT_LE(n.upper - n.lower, eps + 1e-12);
      }
    }
  }
}

/// A straight move's distance is convex in x: over a triangle it is at most its value at
/// the corners (move_upper), which the stock search uses as its bound over a cell.
TEST(Stock, AStraightMovesDistanceIsAtMostItsCornersOverATriangle) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-8, 8), w(0, 1);
  for (const char* spec : {"cutter:ball,6,20", "cutter:flat,10,20", "cutter:bull,10,2,20"}) {
    const sweep::Body cutter = io::read_body(spec);
    cam::Program p;
    p.moves.push_back(straight({-5, -1, 0}, {6, 2, -1}));
    const cam::CutIndex cut(p, cutter);
    const auto cores = cam::detail::cores_of(cutter);
    for (int i = 0; i < sized(60, 10); ++i) {
      const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)),
          c(u(rng), u(rng), u(rng));
      const double top =
          std::max({cut.move_upper(0, a), cut.move_upper(0, b), cut.move_upper(0, c)});
      for (int k = 0; k < 200; ++k) {
        double s = w(rng), t = w(rng);
        if (s + t > 1) s = 1 - s, t = 1 - t;
        const Eigen::Vector3d x = a + s * (b - a) + t * (c - a);
        // The least over t by sampling is at least the true least, which is at most top.
        double least = HUGE_VAL;
        for (int j = 0; j <= 4000; ++j)
          least = std::min(least,
                           cam::cutter_distance(cores, x - cam::position(p.moves[0], j / 4000.0)));
        EXPECT_LE(std::max(least, 0.0), top + 5e-3) << spec;
      }
    }
  }
}

TEST(Stock, ABoxsDepthIsAtMostItsBoundOverATriangle) {
  cam::Stock s;
  s.box = Eigen::AlignedBox3d(Eigen::Vector3d(-10, -5, -20), Eigen::Vector3d(10, 5, 1));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-12, 12), w(0, 1);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)),
        c(u(rng), u(rng), u(rng));
    const double top = s.depth_max(a, b, c);
    for (int k = 0; k < 200; ++k) {
      double p = w(rng), q = w(rng);
      if (p + q > 1) p = 1 - p, q = 1 - q;
      const Eigen::Vector3d x = a + p * (b - a) + q * (c - a);
      EXPECT_LE(s.depth(x), top + 1e-12);
    }
  }
  // On the box's face the depth is 0, and so is the bound: a part lying on the stock's
  // face has no area inside it.
  EXPECT_EQ(s.depth_max({-9, -4, -20}, {9, -4, -20}, {0, 4, -20}), 0.0);
}

}  // namespace
}  // namespace qmotion::test
