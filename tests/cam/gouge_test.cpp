// tests/cam/gouge_test.cpp: <qmotion/cam/gouge.hpp> and <qmotion/cam/program.hpp>: a move's
// gouge against the depth worked out by hand, and its bound against independent sampling
// of the cutter over the move, with the part's depth computed from its profile, not its mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <qmotion/cam/gouge.hpp>
#include <qmotion/io/bodies.hpp>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "io_test_util.hpp"
#include "sanitized_size.hpp"

namespace qmotion::test {
namespace {

using Kind = cam::Move::Kind;

/// The part bump.obj by its definition: the profile below, in (x, z), extruded over
/// |y| <= 50. Its signed distance: the profile's in 2-D combined with the ends'.
const std::vector<std::array<double, 2>> kBump = {{-50, -21}, {50, -21}, {50, -1}, {5, -1},
                                                  {5, 0},     {-5, 0},   {-5, -1}, {-50, -1}};

double segment_distance(double x, double z, const std::array<double, 2>& a,
                        const std::array<double, 2>& b) {
  const double ux = b[0] - a[0], uz = b[1] - a[1];
  const double s = std::clamp(((x - a[0]) * ux + (z - a[1]) * uz) / (ux * ux + uz * uz), 0.0, 1.0);
  return std::hypot(x - a[0] - s * ux, z - a[1] - s * uz);
}

/// plate.obj by its definition, in the same way.
const std::vector<std::array<double, 2>> kPlate = {{-50, -20}, {50, -20}, {50, 0}, {-50, 0}};

double prism_signed_distance(const std::vector<std::array<double, 2>>& poly,
                             const Eigen::Vector3d& p) {
  double d = HUGE_VAL;
  bool inside = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    d = std::min(d, segment_distance(p.x(), p.z(), poly[j], poly[i]));
    const auto &a = poly[i], &b = poly[j];
    if ((a[1] > p.z()) != (b[1] > p.z()) &&
        p.x() < (b[0] - a[0]) * (p.z() - a[1]) / (b[1] - a[1]) + a[0])
      inside = !inside;
  }
  const double ey = std::abs(p.y()) - 50;
  if (inside && ey < 0) return -std::min(d, -ey);
  const double out = inside ? 0.0 : d;
  return std::hypot(out, std::max(ey, 0.0));
}

double bump_signed_distance(const Eigen::Vector3d& p) { return prism_signed_distance(kBump, p); }

sweep::Body cutter(const std::string& spec) {
  sweep::Body c = io::read_body(spec);
  sweep::validate(c);
  return c;
}

cam::Move line(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  cam::Move m;
  m.kind = Kind::feed;
  m.from = a;
  m.to = b;
  return m;
}

/// The largest depth into the bump of `n` points of the cutter, at random t and random
/// points of its solid (and of its tip's disc and axis, where the deepest points lie).
double sampled_depth(const cam::Move& m, const sweep::Body& c, int n, std::mt19937& rng,
                     const std::vector<std::array<double, 2>>& poly) {
  std::uniform_real_distribution<double> u(0, 1);
  const double R = c.D / 2;
  double worst = -HUGE_VAL;
  for (int i = 0; i < n;) {
    const double t = u(rng);
    Eigen::Vector3d y(R * (2 * u(rng) - 1), R * (2 * u(rng) - 1), c.L * u(rng));
    if (i % 3 == 0) y.z() = c.kind == sweep::Body::Kind::flat_cutter ? 0 : y.z() * 0.1;
    if (sweep::signed_distance(c, y) > 0) continue;
    worst = std::max(worst, -prism_signed_distance(poly, cam::position(m, t) + y));
    ++i;
  }
  return worst;
}

TEST(Gouge, ADipBetweenTheEndsOfOneBlock) {
  // dip.ngc's feed: 0.5 mm above the plate at both ends, through the ridge between them.
  const sweep::Body part = io::read_body(test_data("verify/bump.obj"));
  const cam::Move m = line({-40, 0, -0.5}, {40, 0, -0.5});
  // (A bull nose's corner reaches the ridge's inner corners, where the part is not locally
  // convex; its interval there stays wider than 0.001: see NeverBelowWhatSampling.)
  for (const std::string spec : {"cutter:ball,6,30", "cutter:flat,8,30"}) {
    const sweep::Body c = cutter(spec);
    // At the block's ends the cutter clears the part: stamping there finds nothing.
    for (const Eigen::Vector3d& end : {m.from, m.to})
      EXPECT_GT(bump_signed_distance(end), 0.49) << spec;
    for (double tol : steps({0.01, 0.001})) {
      const cam::Gouge g = cam::move_gouge(m, c, part, tol);
      EXPECT_TRUE(g.settled) << spec;
      EXPECT_LE(g.lower, 0.5) << spec;
      EXPECT_GE(g.upper, 0.5) << spec;
      EXPECT_LE(g.upper - g.lower, tol) << spec;
      // The deepest point found is a point of the cutter at its t, that deep.
      const Eigen::Vector3d local = g.point - cam::position(m, g.t);
      EXPECT_LE(sweep::signed_distance(c, local), 1e-9) << spec;
      EXPECT_NEAR(-bump_signed_distance(g.point), g.lower, 1e-9) << spec;
    }
  }
}

TEST(Gouge, NeverBelowWhatSamplingFindsOnRandomMoves) {
  // The ball end over bump.obj, whose inner corners its core cannot bound well (so its
  // search also runs over the ball's solid); the flat and bull ends over plate.obj.
  const sweep::Body bump = io::read_body(test_data("verify/bump.obj"));
  const sweep::Body plate = io::read_body(test_data("verify/plate.obj"));
  std::mt19937 rng(20261207);
  std::uniform_real_distribution<double> u(-1, 1);
  const std::vector<std::string> specs = {"cutter:ball,6,30", "cutter:flat,8,30",
                                          "cutter:bull,10,2,30"};
  int deep = 0, clear = 0;
  for (int k = 0; k < 24; ++k) {
    const sweep::Body c = cutter(specs[static_cast<std::size_t>(k % 3)]);
    cam::Move m;
    if (k % 2 == 0) {
      m = line({20 * u(rng), 20 * u(rng), u(rng) - 0.6}, {20 * u(rng), 20 * u(rng), u(rng) - 0.6});
    } else {  // an arc in one of the three planes
      m.kind = Kind::arc;
      m.plane = 17 + k % 3;
      const auto [a, b, w] = cam::plane_axes(m.plane);
      m.centre = Eigen::Vector3d(10 * u(rng), 10 * u(rng), 3 + u(rng));
      const double r = 2 + 3 * std::abs(u(rng)), a0 = 3 * u(rng), a1 = 3 * u(rng);
      m.from = m.centre;
      m.from(a) += r * std::cos(a0);
      m.from(b) += r * std::sin(a0);
      m.to = m.centre;
      m.to(a) += r * std::cos(a1);
      m.to(b) += r * std::sin(a1);
      m.to(w) += u(rng);
      m.turns = u(rng) < 0 ? -1 : 1;
    }
    const double tol = 0.01;
    const bool ball = c.kind == sweep::Body::Kind::ball_cutter;
    const sweep::Body& part = ball ? bump : plate;
    const auto& poly = ball ? kBump : kPlate;
    const cam::Gouge g = cam::move_gouge(m, c, part, tol);
    EXPECT_TRUE(g.settled) << k;
    EXPECT_LE(g.upper - g.lower, tol) << k;
    const double sampled = sampled_depth(m, c, 2000, rng, poly);
    EXPECT_LE(sampled, g.upper + 1e-9) << k;
    // What the search reports as reached is reached: a point of the cutter that deep.
    EXPECT_LE(sweep::signed_distance(c, g.point - cam::position(m, g.t)), 1e-9) << k;
    EXPECT_NEAR(-prism_signed_distance(poly, g.point), g.found, 1e-9) << k;
    if (g.clear) {
      EXPECT_LT(sampled, 0) << k;
      ++clear;
    }
    if (g.lower > 0.1) ++deep;
  }
  // Both outcomes occur among these moves, so both sides were tested.
  EXPECT_GT(deep, 5);
  EXPECT_GT(clear, 3);
}

TEST(Program, PositionsAndSpeedBound) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 30; ++k) {
    cam::Move m;
    m.kind = Kind::arc;
    m.plane = 17 + k % 3;
    const auto [a, b, w] = cam::plane_axes(m.plane);
    m.centre = Eigen::Vector3d(u(rng), u(rng), u(rng));
    const double r0 = 1 + std::abs(u(rng)), r1 = r0 * (1 + 1e-3 * u(rng));
    const double a0 = 3 * u(rng), a1 = 3 * u(rng);
    m.from = m.to = m.centre;
    m.from(a) += r0 * std::cos(a0);
    m.from(b) += r0 * std::sin(a0);
    m.to(a) += r1 * std::cos(a1);
    m.to(b) += r1 * std::sin(a1);
    m.to(w) += u(rng);
    m.turns = (k % 4 == 0 ? 2 : 1) * (u(rng) < 0 ? -1 : 1);
    EXPECT_NEAR((cam::position(m, 0) - m.from).norm(), 0, 1e-12);
    EXPECT_NEAR((cam::position(m, 1) - m.to).norm(), 0, 1e-12);
    // The bound holds every chord of a fine sampling; the turns are all walked.
    const double bound = cam::speed_bound(m);
    double length = 0;
    const int n = 4000;
    for (int i = 0; i < n; ++i) {
      const double chord = (cam::position(m, (i + 1.0) / n) - cam::position(m, i * 1.0 / n)).norm();
      EXPECT_LE(chord, bound / n * (1 + 1e-9));
      length += chord;
    }
    const double turns = std::abs(m.turns) - 1;
    EXPECT_GT(length, 2 * 3.14159265358979323846 * r0 * turns);
  }
}

}  // namespace
}  // namespace qmotion::test
