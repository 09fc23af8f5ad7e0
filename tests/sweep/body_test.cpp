// Tests of <qmotion/sweep/body.hpp>: every body's triangulation is closed and oriented, lies
// on the body, encloses no more than it and approaches its volume; sizes are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <qmotion/io/bodies.hpp>
#include <qmotion/sweep/body.hpp>
#include <qmotion/sweep/swept_volume.hpp>
#include <random>

#include "io_test_util.hpp"

namespace qmotion {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Case {
  const char* spec;
  double volume;  // of the body itself, by formula
};

TEST(Body, TriangulationsAreClosedOrientedAndApproachTheVolume) {
  const double R = 3, L = 20, rc = 1;
  const Case cases[] = {
      {"sphere:2", 4 * kPi * 8 / 3},
      {"box:1,2,3", 6},
      {"cylinder:2,5", kPi * 4 * 5},
      {"cutter:flat,6,20", kPi * R * R * L},
      {"cutter:ball,6,20", kPi * R * R * (L - R) + 2 * kPi * R * R * R / 3},
      // Bottom: radius (R - rc) + sqrt(rc^2 - (rc - z)^2) for z in [0, rc]; then the shank.
      {"cutter:bull,6,1,20",
       kPi * ((R - rc) * (R - rc) * rc + (R - rc) * kPi * rc * rc / 2 + 2 * rc * rc * rc / 3) +
           kPi * R * R * (L - rc)},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.spec);
    const sweep::Body body = io::read_body(c.spec);
    double last = 0;
    for (double tol : {1e-2, 1e-3}) {
      const auto m = sweep::triangulate(body, tol);
      EXPECT_NO_THROW(io::require_closed_oriented(m, c.spec));
      const double v = test::enclosed_volume(m);
      // Inscribed: never more than the body, and within the tolerance times its area.
      EXPECT_LE(v, c.volume * (1 + 1e-12));
      EXPECT_GT(v, c.volume * (1 - 40 * tol));
      EXPECT_GE(v, last);  // finer is closer
      last = v;
      double far = 0;
      for (const auto& x : m.vertices) far = std::max(far, x.norm());
      EXPECT_LE(far, sweep::radius(body) * (1 + 1e-12));
      EXPECT_GT(far, sweep::radius(body) * (1 - 1e-3));
    }
  }
}

TEST(Body, VerticesLieOnTheBody) {
  for (const auto& x : sweep::triangulate(io::read_body("sphere:2"), 1e-3).vertices)
    EXPECT_NEAR(x.norm(), 2, 1e-12);
  for (const auto& x : sweep::triangulate(io::read_body("cylinder:2,5"), 1e-3).vertices) {
    const double r = std::hypot(x.x(), x.y());
    EXPECT_TRUE(std::abs(r - 2) < 1e-12 || r < 1e-12);
    EXPECT_TRUE(std::abs(x.z()) < 1e-15 || std::abs(x.z() - 5) < 1e-15);
  }
  for (const auto& x : sweep::triangulate(io::read_body("cutter:ball,6,20"), 1e-3).vertices) {
    if (x.z() <= 3)
      EXPECT_NEAR((x - Eigen::Vector3d(0, 0, 3)).norm(), 3, 1e-12);  // the ball
    else
      EXPECT_TRUE(std::abs(std::hypot(x.x(), x.y()) - 3) < 1e-12 || std::abs(x.z() - 20) < 1e-15);
  }
}

TEST(Body, BadSizesAreRefusedNamingTheBody) {
  for (const char* spec : {"sphere:0", "sphere:-1", "box:1,0,1", "box:1,2", "cylinder:1,-2",
                           "cutter:flat,0,10", "cutter:bull,6,4,10", "cutter:ball,6,2",
                           "cutter:taper,6,10", "blob:3", "sphere:x", "sphere:inf"}) {
    EXPECT_TRUE(test::throws_error([&] { io::read_body(spec); }, Errc::invalid_input, {spec}))
        << spec;
  }
}

/// The indexed signed distance of a mesh body (a tree of boxes, the sign by pseudonormals)
/// against the scan of every triangle with the winding number's sign: the same distance,
/// and the same sign away from the surface, for a convex tetrahedron, the non-convex
/// bracket, and a holder-like solid of revolution of 10^4 triangles.
TEST(MeshIndex, AgreesWithTheScanAndTheWindingNumber) {
  const std::vector<std::pair<double, double>> holder = {
      {0, 0}, {3, 0}, {3, 20}, {5, 22}, {8, 22}, {8, 30}, {12, 34}, {12, 50}, {0, 50}};
  std::vector<sweep::Body> bodies = {io::read_body(test::test_data("bodies/tetra.obj")),
                                     io::read_body(test::test_data("bodies/bracket.obj"))};
  sweep::Body revolved;
  revolved.kind = sweep::Body::Kind::mesh;
  revolved.mesh = sweep::detail::revolve(holder, 720);
  sweep::index_mesh(revolved);
  bodies.push_back(revolved);
  ASSERT_GE(bodies.back().mesh.triangles.size(), 10000u);
  std::mt19937 g(17);
  for (const auto& b : bodies) {
    ASSERT_TRUE(b.index);
    Eigen::AlignedBox3d box;
    for (const auto& v : b.mesh.vertices) box.extend(v);
    std::uniform_real_distribution<double> u(0, 1);
    const double size = box.diagonal().norm();
    int inside = 0;
    for (int i = 0; i < 2000; ++i) {
      const Eigen::Vector3d x = box.min() - 0.2 * box.sizes() +
                                1.4 * box.sizes().cwiseProduct(Eigen::Vector3d(u(g), u(g), u(g)));
      const double fast = sweep::signed_distance(b, x),
                   scan = sweep::detail::mesh_distance(b.mesh, x);
      ASSERT_NEAR(std::abs(fast), std::abs(scan), 1e-12 * size)
          << b.spec << " at " << x.transpose();
      if (std::abs(scan) > 1e-9 * size) {
        ASSERT_EQ(fast < 0, scan < 0) << b.spec << " at " << x.transpose();
      }
      inside += scan < 0;
    }
    EXPECT_GT(inside, 50) << b.spec;  // the sample meets both sides
  }
}

}  // namespace
}  // namespace qmotion
