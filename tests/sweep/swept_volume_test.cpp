// tests/sweep/swept_volume_test.cpp mirrors sweep/swept_volume.hpp: the tree's bounds of the
// distance f(x) from a point to the swept volume by branch and bound (query), against f
// measured by a search on t of the test's own (dense samples, then golden sections), with and
// without a first guess, and built span by span in any order; and the
// subgradient of a convex body's signed distance (sweep/body.hpp) that the adaptive mesh
// tries as a separating direction.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <functional>
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
  const char* body;  ///< a body spec, or @ and a file under tests/data
  bool rational;
};

qmotion::sweep::Body body_of(const char* spec) {
  return qmotion::io::read_body(spec[0] == '@' ? qmotion::test::test_data(spec + 1) : spec);
}

class TreeBounds : public ::testing::TestWithParam<Case> {};

// Points about the volume's boundary: a placed point of the body pushed out by up to 2 T, and
// the 4^3 lattice points of step h about it. For every point x:
// - the lower bound is below f(x), and within the leaves' radius of it;
// - the upper bound is an actual placement (the node it names places the body that far from
//   x), no lower than f(x), and within the leaves' radius above it (the leaf holding the best
//   t is opened, or a bound already proved f reached).
TEST_P(TreeBounds, BracketTheMeasuredDistance) {
  const Case c = GetParam();
  const Motion m = helix(c.rational);
  const auto body = body_of(c.body);
  const double rho = qmotion::sweep::radius(body), T = 0.05 * rho, leaf = 0.1 * T;
  const qmotion::sweep::SweptVolumeTree tree(m, body, leaf);
  const double h = 0.8 * T;
  const auto mesh = qmotion::sweep::triangulate(body, 1e-3 * rho);
  std::mt19937 g(31);
  std::uniform_real_distribution<double> u(0, 1);
  // eps: rounding; slop: the measured f's excess over the true minimum, besides.
  const double eps = 1e-9 * rho, slop = 1e-6 * rho;
  int outside = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const double t = m.a() + (m.b() - m.a()) * u(g);
    const V3 v =
        mesh.vertices[static_cast<std::size_t>(u(g) * mesh.vertices.size()) % mesh.vertices.size()];
    const V3 out = (v - V3(0, 0, 0.5 * rho)).normalized();
    const V3 centre = m.place(t, v + 2 * T * u(g) * out);
    for (int i = 0; i < 64; ++i) {
      const V3 x = centre + h * V3(i % 4 - 1.5, i / 4 % 4 - 1.5, i / 16 - 1.5);
      const double f = measured_distance(m, body, x);
      const auto full = tree.query(x, -HUGE_VAL);
      SCOPED_TRACE(std::string(c.body) + " trial " + std::to_string(trial) + " point " +
                   std::to_string(i) + " f " + std::to_string(f));
      EXPECT_LE(full.lower, f + eps);
      EXPECT_GE(full.lower, f - leaf - slop);
      EXPECT_GE(std::max(full.signed_upper, 0.0), f - eps);
      EXPECT_LE(full.signed_upper, f + leaf + eps);
      ASSERT_GE(full.node, 0);
      EXPECT_NEAR(tree.node_distance(x, full.node), full.signed_upper, eps);
      // A first guess (any node) changes the order of the search, not its best placement,
      // and the lower bound stays a bound.
      const int hint = static_cast<int>(u(g) * static_cast<double>(tree.nodes().size()));
      const auto guessed = tree.query(x, -HUGE_VAL, hint);
      EXPECT_EQ(guessed.signed_upper, full.signed_upper);
      EXPECT_LE(guessed.lower, f + eps);
      EXPECT_GE(guessed.lower, f - leaf - slop);
      // With stop_above at f (about half of these points lie above it, half below): a
      // placement below it, the best's distance; else nothing below it and a lower bound
      // within a leaf's Delta of it, still below f.
      const double above = f + (i % 2 ? 0.5 : -0.5) * T;
      const auto capped = tree.query(x, -HUGE_VAL, hint, above);
      EXPECT_LE(capped.lower, f + eps);
      if (capped.signed_upper < above) {
        EXPECT_GE(std::max(capped.signed_upper, 0.0), f - eps);
        EXPECT_NEAR(tree.node_distance(x, capped.node), capped.signed_upper, eps);
      } else {
        EXPECT_GE(capped.lower, above - tree.largest_leaf_delta() - eps);
        EXPECT_LT(above, f + leaf + eps);  // a placement below it would have been found
      }
      outside += f > 0;
    }
  }
  EXPECT_GT(outside, 300);  // most points are outside V, where the bounds are measured
}

// The spans' trees (a KKS spline: one per pair of poses) built in any order (here last
// first, as threads may) make the same tree.
TEST(TreeBuild, TheSpansInAnyOrderMakeTheSameTree) {
  const Motion m = helix(false);
  const auto body = body_of("cutter:ball,6,20");
  const qmotion::sweep::SweptVolumeTree serial(m, body, 0.05);
  const qmotion::sweep::SweptVolumeTree reversed(
      m, body, 0.05, [](std::size_t n, const std::function<void(std::size_t)>& f) {
        for (std::size_t i = n; i-- > 0;) f(i);
      });
  ASSERT_GT(serial.roots().size(), 1u);
  EXPECT_EQ(serial.roots(), reversed.roots());
  EXPECT_EQ(serial.leaves(), reversed.leaves());
  ASSERT_EQ(serial.nodes().size(), reversed.nodes().size());
  for (std::size_t i = 0; i < serial.nodes().size(); ++i) {
    const auto &a = serial.nodes()[i], &b = reversed.nodes()[i];
    EXPECT_EQ(a.t0, b.t0);
    EXPECT_EQ(a.t1, b.t1);
    EXPECT_EQ(a.delta, b.delta);
    EXPECT_EQ(a.child[0], b.child[0]);
    EXPECT_EQ(a.child[1], b.child[1]);
  }
}

INSTANTIATE_TEST_SUITE_P(Bodies, TreeBounds,
                         ::testing::Values(Case{"cutter:ball,6,20", true}, Case{"box:4,6,8", true},
                                           Case{"cylinder:3,10", false},
                                           Case{"cutter:bull,10,2,25", false},
                                           Case{"@bodies/tetra.obj", true}),
                         [](const ::testing::TestParamInfo<Case>& i) {
                           std::string name =
                               i.param.body[0] == '@' ? i.param.body + 8 : i.param.body;
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name + (i.param.rational ? "_rational" : "_kks");
                         });

// The subgradient of a convex body's signed distance: sd(y) >= sd(x) + g . (y - x) for pairs
// of points inside, near and outside the body; |g| <= 1; and g is the gradient (central
// differences) where the distance is smooth, which the random points almost surely are.
class Subgradient : public ::testing::TestWithParam<const char*> {};

TEST_P(Subgradient, SupportsTheSignedDistance) {
  const auto body = qmotion::io::read_body(GetParam());
  ASSERT_TRUE(qmotion::sweep::is_convex(body));
  const double rho = qmotion::sweep::radius(body);
  // Points in the body's bounding box grown by 30 % each side.
  Eigen::AlignedBox3d box;
  for (const auto& v : qmotion::sweep::triangulate(body, 1e-3 * rho).vertices) box.extend(v);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-1.3, 1.3);
  auto point = [&] {
    const V3 s(u(gen), u(gen), u(gen));
    return V3(box.center() + 0.5 * s.cwiseProduct(box.sizes()));
  };
  int inside = 0, smooth = 0;
  for (int i = 0; i < 3000; ++i) {
    const V3 x = point(), y = i % 2 ? point() : x + 0.05 * rho * V3(u(gen), u(gen), u(gen));
    V3 g;
    const double sx = qmotion::sweep::signed_distance(body, x, g);
    SCOPED_TRACE(std::string(GetParam()) + " point " + std::to_string(i));
    EXPECT_NEAR(sx, qmotion::sweep::signed_distance(body, x), 1e-12 * rho);
    EXPECT_LE(g.norm(), 1 + 1e-12);
    EXPECT_GE(qmotion::sweep::signed_distance(body, y), sx + g.dot(y - x) - 1e-12 * rho);
    inside += sx < 0;
    // Central differences: the distance is smooth at x unless x is near a crease of it.
    const double step = 1e-6 * rho;
    V3 fd;
    for (int a = 0; a < 3; ++a) {
      V3 e = V3::Zero();
      e(a) = step;
      fd(a) = (qmotion::sweep::signed_distance(body, x + e) -
               qmotion::sweep::signed_distance(body, x - e)) /
              (2 * step);
    }
    if ((fd - g).norm() < 1e-4) ++smooth;
  }
  EXPECT_GT(inside, 100);
  EXPECT_GT(smooth, 2800);  // all but points within about 1e-6 rho of a crease
}

INSTANTIATE_TEST_SUITE_P(Bodies, Subgradient,
                         ::testing::Values("sphere:3", "box:4,6,8", "cylinder:3,10",
                                           "cutter:flat,6,20", "cutter:ball,6,20",
                                           "cutter:bull,10,2,25"),
                         [](const ::testing::TestParamInfo<const char*>& i) {
                           std::string name = i.param;
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

}  // namespace swept_volume_tests
