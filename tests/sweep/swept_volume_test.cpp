// tests/sweep/swept_volume_test.cpp mirrors sweep/swept_volume.hpp: the tree's bounds of the
// distance f(x) from a point to the swept volume, by a full branch and bound (query) and by a
// batch of points sharing one search (candidates, query_among), against f measured by a
// search on t of the test's own (dense samples, then golden sections).
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <qmotion/io/bodies.hpp>
#include <qmotion/qmotion.hpp>
#include <qmotion/sweep/swept_volume.hpp>
#include <random>
#include <string>

#include "io_test_util.hpp"

namespace swept_volume_tests {

using qmotion::Motion;
using V3 = Eigen::Vector3d;

Motion helix(bool rational) {
  auto poses = qmotion::io::read_poses(qmotion::test::test_data("helix_10.json"));
  poses.poses.resize(5);
  if (rational) return qmotion::interpolate(poses, {}).motion;
  qmotion::QSplineOptions o;
  o.scheme = "kks";
  return qmotion::qspline(poses, o).motion;
}

/// min over t of the body's signed distance from x, placed by the motion at t: 4000 samples,
/// then golden sections about the best. It is f(x) from above, up to the search's error.
double measured_distance(const Motion& m, const qmotion::sweep::Body& body, const V3& x) {
  auto at = [&](double t) {
    const Eigen::Matrix4d f = m.frame(t);
    return qmotion::sweep::signed_distance(
        body, f.block<3, 3>(1, 1).transpose() * (x - f.block<3, 1>(1, 0)));
  };
  const int n = 4000;
  int best = 0;
  double fb = HUGE_VAL;
  for (int i = 0; i <= n; ++i) {
    const double v = at(m.a() + (m.b() - m.a()) * i / n);
    if (v < fb) fb = v, best = i;
  }
  double lo = m.a() + (m.b() - m.a()) * std::max(0, best - 1) / n;
  double hi = m.a() + (m.b() - m.a()) * std::min(n, best + 1) / n;
  for (int it = 0; it < 60; ++it) {
    const double a = lo + 0.381966 * (hi - lo), b = hi - 0.381966 * (hi - lo);
    const double fa = at(a), fbb = at(b);
    fb = std::min({fb, fa, fbb});
    if (fa < fbb)
      hi = b;
    else
      lo = a;
  }
  return std::max(fb, 0.0);
}

struct Case {
  const char* body;
  bool rational;
};

class TreeBounds : public ::testing::TestWithParam<Case> {};

// Points about the volume's boundary: a placed point of the body pushed out by up to 2 T, and
// a batch of cubes of edge h about them. For every point x of a cube:
// - both lower bounds are below f(x), the batch's also when it stops early, and within the leaves'
// radius (plus the batch's slack)
//   of it;
// - both upper bounds are actual placements, no lower than f(x); the full search's is within
//   the leaves' radius above it (the leaf holding the best t is opened, or a bound already
//   proved f reached).
TEST_P(TreeBounds, BracketTheMeasuredDistance) {
  const Case c = GetParam();
  const Motion m = helix(c.rational);
  const auto body = qmotion::io::read_body(c.body);
  const double rho = qmotion::sweep::radius(body), T = 0.05 * rho, leaf = 0.1 * T;
  const qmotion::sweep::SweptVolumeTree tree(m, body, leaf);
  const double h = 0.8 * T, r = 0.5 * std::sqrt(3.0) * h, slack = 0.05 * T;
  const auto mesh = qmotion::sweep::triangulate(body, 1e-3 * rho);
  std::mt19937 g(31);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::pair<int, double>> leaves;
  int outside = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const double t = m.a() + (m.b() - m.a()) * u(g);
    const V3 v =
        mesh.vertices[static_cast<std::size_t>(u(g) * mesh.vertices.size()) % mesh.vertices.size()];
    const V3 out = (v - V3(0, 0, 0.5 * rho)).normalized();
    const V3 centre = m.place(t, v + 2 * T * u(g) * out);
    double rest = 0;
    tree.candidates(centre, r, leaves, rest);
    for (int o = 0; o < 8; ++o) {
      const V3 x = centre + 0.5 * h * V3(o & 1 ? 1 : -1, o & 2 ? 1 : -1, o & 4 ? 1 : -1);
      const double f = measured_distance(m, body, x);
      const auto full = tree.query(x, -HUGE_VAL);
      const auto batch = tree.query_among(x, leaves, rest, slack, HUGE_VAL);
      // eps: rounding; slop: the measured f's excess over the true minimum, besides.
      const double eps = 1e-9 * rho, slop = 1e-6 * rho;
      SCOPED_TRACE(std::string(c.body) + " trial " + std::to_string(trial) + " corner " +
                   std::to_string(o) + " f " + std::to_string(f));
      EXPECT_LE(full.lower, f + eps);
      EXPECT_LE(batch.lower, f + eps);
      // With a wide slack the batch stops after few leaves: still a lower bound.
      EXPECT_LE(tree.query_among(x, leaves, rest, 2 * T, HUGE_VAL).lower, f + eps);
      EXPECT_GE(full.lower, f - leaf - slop);
      EXPECT_GE(batch.lower, f - leaf - slack - slop);
      EXPECT_GE(std::max(full.signed_upper, 0.0), f - eps);
      EXPECT_GE(std::max(batch.signed_upper, 0.0), f - eps);
      EXPECT_LE(full.signed_upper, f + leaf + eps);
      ASSERT_GE(batch.node, 0);
      EXPECT_NEAR(tree.node_distance(x, batch.node), batch.signed_upper, eps);
      outside += f > 0;
    }
  }
  EXPECT_GT(outside, 100);  // most points are outside V, where the bounds are measured
}

INSTANTIATE_TEST_SUITE_P(Bodies, TreeBounds,
                         ::testing::Values(Case{"cutter:ball,6,20", true}, Case{"box:4,6,8", true},
                                           Case{"cylinder:3,10", false},
                                           Case{"cutter:bull,10,2,25", false}),
                         [](const ::testing::TestParamInfo<Case>& i) {
                           std::string name = i.param.body;
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name + (i.param.rational ? "_rational" : "_kks");
                         });

}  // namespace swept_volume_tests
