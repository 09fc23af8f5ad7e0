// Swept volumes in every build, with or without CGAL (so under the sanitizers too): a small
// enclosing mesh is closed and consistently oriented, and holds sampled points of the swept
// volume by the winding number (tests/api/volume_test.cpp checks more, with CGAL).
#include <gtest/gtest.h>

#include <map>
#include <qmotion/io/bodies.hpp>
#include <qmotion/qmotion.hpp>
#include <random>

#include "io_test_util.hpp"

namespace qmotion {
namespace {

TEST(SweptVolumePlain, ClosedOrientedAndHoldsSamples) {
  auto poses = io::read_poses(test::test_data("helix_10.json"));
  poses.poses.resize(3);
  QSplineOptions q;
  q.scheme = "kks";
  for (const Motion& m : {interpolate(poses, {}).motion, qspline(poses, q).motion}) {
    for (const char* spec : {"sphere:3", "box:4,6,8"}) {
      const sweep::Body body = io::read_body(spec);
      const SweptVolume v = swept_volume(m, body, 2.0);
      ASSERT_GT(v.triangles.size(), 100u) << spec;
      EXPECT_LE(v.distance_bound, 2.0) << spec;
      std::map<std::pair<int, int>, int> directed;
      for (const auto& t : v.triangles)
        for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
      for (const auto& [e, n] : directed) {
        ASSERT_EQ(n, 1) << spec;
        ASSERT_EQ(directed.count({e.second, e.first}), 1u) << spec;
      }
      sweep::TriangleMesh mesh{v.vertices, v.triangles};
      const auto corners = sweep::triangulate(body, 0.1).vertices;
      std::mt19937 g(7);
      std::uniform_real_distribution<double> u(0, 1);
      for (int i = 0; i < 40; ++i) {
        const double t = m.a() + (m.b() - m.a()) * u(g);
        const Eigen::Vector3d x =
            m.place(t, corners[static_cast<std::size_t>(u(g) * corners.size()) % corners.size()]);
        EXPECT_LT(sweep::detail::mesh_distance(mesh, x), 0) << spec << " at t = " << t;
      }
    }
  }
}

}  // namespace
}  // namespace qmotion
