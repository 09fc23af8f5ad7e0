// tests/sweep/hull_pieces_test.cpp mirrors sweep/hull_pieces.hpp: the support points of the
// convex bodies against points drawn on them, and the certificate that a triangle is clear
// of the swept volume: never given to a triangle through a point of it (placed by the exact
// motion at a random time, a point inside or on the body), and given to triangles far from
// it (farther than the body's reach from the path); for a mesh body that is not convex, the
// same of what its boundary sweeps; a patch of points asked once, then its triangles of
// only what the patch was not cleared of.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <qmotion/io/bodies.hpp>
#include <qmotion/qmotion.hpp>
#include <qmotion/sweep/hull_pieces.hpp>
#include <random>
#include <string>
#include <vector>

#include "io_test_util.hpp"

namespace hull_pieces_tests {

using qmotion::Motion;
using V3 = Eigen::Vector3d;

/// Three poses that turn the body's axis by 25 degrees while it moves 12 mm, as a rational
/// B-spline or a KKS quaternion spline.
Motion tilt(bool rational) {
  auto poses = qmotion::io::read_poses(qmotion::test::test_data("poses/short_tilt.json"));
  if (rational) return qmotion::interpolate(poses, {}).motion;
  qmotion::QSplineOptions o;
  o.scheme = "kks";
  return qmotion::qspline(poses, o).motion;
}

const char* const kBodies[] = {"sphere:1",        "box:1,1.5,2",     "cylinder:0.6,2",
                               "cutter:flat,2,4", "cutter:ball,2,4", "cutter:bull,2,0.4,4"};

TEST(SupportPoint, LiesOnTheBodyAndFarthestAlongItsDirection) {
  std::mt19937 g(5);
  std::normal_distribution<double> n(0, 1);
  for (const char* spec : kBodies) {
    const auto body = qmotion::io::read_body(spec);
    // Points of the body: its triangulation's vertices (on its boundary).
    const auto mesh = qmotion::sweep::triangulate(body, 1e-3);
    for (int i = 0; i < 200; ++i) {
      const V3 u(n(g), n(g), n(g));
      const V3 s = qmotion::sweep::support_point(body, u);
      EXPECT_NEAR(qmotion::sweep::signed_distance(body, s), 0, 1e-12) << spec;
      for (const auto& v : mesh.vertices) ASSERT_LE(u.dot(v), u.dot(s) + 1e-9 * u.norm()) << spec;
    }
  }
}

/// A small triangle about x, turned at random.
std::array<V3, 3> triangle_about(const V3& x, double size, std::mt19937& g) {
  std::normal_distribution<double> n(0, 1);
  const V3 a = V3(n(g), n(g), n(g)).normalized(), b = a.cross(V3(n(g), n(g), n(g))).normalized();
  return {x + size * a, x + size * b, x - size * (a + b)};
}

class Certificate : public ::testing::TestWithParam<bool> {};

TEST_P(Certificate, NeverClearsATriangleThroughTheVolumeAndClearsFarOnes) {
  const Motion m = tilt(GetParam());
  std::mt19937 g(11);
  std::uniform_real_distribution<double> u(0, 1);
  for (const char* spec : kBodies) {
    const auto body = qmotion::io::read_body(spec);
    const qmotion::sweep::HullPieces hulls(m, body, 5e-4);
    EXPECT_GT(hulls.size(), 2u);
    EXPECT_LE(hulls.largest_delta(), 5e-4);
    const auto mesh = qmotion::sweep::triangulate(body, 1e-2);
    int cleared = 0;
    for (int i = 0; i < 3000; ++i) {
      const double t = m.a() + (m.b() - m.a()) * u(g);
      // On the body's boundary, or the middle of two such points (inside: convex).
      const V3 p0 = mesh.vertices[static_cast<std::size_t>(u(g) * mesh.vertices.size()) %
                                  mesh.vertices.size()];
      const V3 p1 = mesh.vertices[static_cast<std::size_t>(u(g) * mesh.vertices.size()) %
                                  mesh.vertices.size()];
      const V3 x = m.place(t, i % 2 ? p0 : V3(0.5 * (p0 + p1)));
      const auto tri = triangle_about(x, 1e-3 + 0.2 * u(g), g);
      V3 nrm = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalized();
      cleared += hulls.clear(tri, {nrm, V3(-nrm)}, 0);
      // A patch about it, asked once (unclear), then the triangle of only what is left.
      std::vector<V3> patch(tri.begin(), tri.end());
      for (int k = 0; k < 5; ++k) patch.push_back(triangle_about(x, 0.3 * u(g), g)[0]);
      cleared += hulls.clear_of(tri, {nrm, V3(-nrm)}, 0, hulls.unclear(patch, {nrm, V3(-nrm)}, 0));
    }
    EXPECT_EQ(cleared, 0) << spec;
    // Far: 10 mm above the highest point the body reaches (the motion stays below z = 3 + 5).
    int far = 0;
    for (int i = 0; i < 200; ++i) {
      const V3 x(12 * u(g), 4 * u(g) - 2, 20 + 5 * u(g));
      far += hulls.clear(triangle_about(x, 0.5, g), {V3(0, 0, 1), V3(0, 0, 1)}, 0);
      std::vector<V3> patch;
      for (int k = 0; k < 4; ++k) patch.push_back(triangle_about(x, 0.5, g)[0]);
      far += hulls.unclear(patch, {V3(0, 0, 1), V3(0, 0, 1)}, 0).empty();
    }
    EXPECT_EQ(far, 400) << spec;
  }
}

/// A mesh body that is not convex (the L-shaped bracket scaled to 2 mm): the pieces cover
/// what its boundary sweeps, so no triangle through a point of it (on a random triangle of the
/// body, placed at a random time) is cleared, and triangles far from it are.
TEST_P(Certificate, CoversWhatAMeshBodysBoundarySweeps) {
  const Motion m = tilt(GetParam());
  auto body = qmotion::io::read_body(qmotion::test::test_data("bodies/bracket.obj"));
  for (auto& v : body.mesh.vertices) v /= 6;
  const qmotion::sweep::HullPieces hulls(m, body, 5e-4);
  // Not convex, so more than one part; its flat faces' triangles share patches.
  EXPECT_GE(hulls.parts(), 2u);
  EXPECT_LT(hulls.parts(), body.mesh.triangles.size());
  // A convex mesh of 12 triangles (a box) is one patch.
  qmotion::sweep::Body box;
  box.kind = qmotion::sweep::Body::Kind::mesh;
  box.mesh = qmotion::sweep::triangulate(qmotion::io::read_body("box:1,1.5,2"), 1e-2);
  ASSERT_EQ(box.mesh.triangles.size(), 12u);
  EXPECT_EQ(qmotion::sweep::HullPieces(m, box, 5e-4).parts(), 1u);
  std::mt19937 g(17);
  std::uniform_real_distribution<double> u(0, 1);
  int cleared = 0;
  for (int i = 0; i < 3000; ++i) {
    const auto& t = body.mesh.triangles[static_cast<std::size_t>(u(g) * 20) % 20];
    double a = u(g), b = u(g);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const V3 p = body.mesh.vertices[t[0]] +
                 a * (body.mesh.vertices[t[1]] - body.mesh.vertices[t[0]]) +
                 b * (body.mesh.vertices[t[2]] - body.mesh.vertices[t[0]]);
    const auto tri =
        triangle_about(m.place(m.a() + (m.b() - m.a()) * u(g), p), 1e-3 + 0.2 * u(g), g);
    const V3 nrm = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalized();
    cleared += hulls.clear(tri, {nrm, V3(-nrm)}, 0);
  }
  EXPECT_EQ(cleared, 0);
  int far = 0;
  for (int i = 0; i < 200; ++i) {
    const V3 x(12 * u(g), 4 * u(g) - 2, 20 + 5 * u(g));
    far += hulls.clear(triangle_about(x, 0.5, g), {V3(0, 0, 1), V3(0, 0, 1)}, 0);
  }
  EXPECT_EQ(far, 200);
}

INSTANTIATE_TEST_SUITE_P(Motions, Certificate, ::testing::Values(true, false),
                         [](const ::testing::TestParamInfo<bool>& i) {
                           return std::string(i.param ? "rational" : "kks");
                         });

}  // namespace hull_pieces_tests
