// Marching tetrahedra as the adaptive mesh does it (sweep/src/volume_tets.hpp): over a
// balanced octree with cells of three sizes, the triangles form a closed surface that winds
// once about every corner below the level and never about one above it, wherever on its
// edge each vertex lies (docs/geometry.md, "The adaptive mesh"). And the mesh's volume,
// rounded outward (volume_detail.hpp).
#include "../../sweep/src/volume_tets.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <unordered_map>
#include <vector>

#include "../../sweep/src/volume_detail.hpp"
#include "../../sweep/src/volume_octree.hpp"

namespace {

using qmotion::sweep::mesher::EdgeHash;
using qmotion::sweep::mesher::EdgeKey;
using qmotion::sweep::mesher::OctKey;
using qmotion::sweep::mesher::Octree;
using qmotion::sweep::mesher::Tri;

/// The winding number of the closed triangle surface about x: the triangles' solid angles
/// (Van Oosterom and Strackee) over 4 pi.
double winding(const std::vector<std::array<Eigen::Vector3d, 3>>& tris, const Eigen::Vector3d& x) {
  double omega = 0;
  for (const auto& t : tris) {
    const Eigen::Vector3d p = t[0] - x, q = t[1] - x, r = t[2] - x;
    const double lp = p.norm(), lq = q.norm(), lr = r.norm();
    omega += 2 * std::atan2(p.dot(q.cross(r)),
                            lp * lq * lr + p.dot(q) * lr + q.dot(r) * lp + r.dot(p) * lq);
  }
  return omega / (4 * M_PI);
}

TEST(March, ClosedAndOutwardWhereverTheVerticesLieOnTheirEdges) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    std::mt19937 g(seed);
    std::uniform_real_distribution<double> u(0, 1);
    Octree oct(Eigen::Vector3d::Zero(), 1.0, {2, 2, 2});
    // Cells split at random down to level 3, then balanced: faces between sizes.
    for (int round = 0; round < 3; ++round) {
      std::vector<OctKey> keys;
      for (const auto& [k, c] : oct.leaves()) keys.push_back(k);
      std::vector<OctKey> made;
      for (const OctKey k : keys)
        if (u(g) < 0.4) oct.split(k, &made);
      for (const auto& [k, c] : oct.leaves()) made.push_back(k);
      oct.balance(made);
    }
    // phi: the distance from the middle less 0.6, with noise; above 0 on the domain's faces.
    std::unordered_map<OctKey, double> value;
    const Eigen::Vector3d mid(1, 1, 1);
    auto phi = [&](OctKey k) {
      auto [it, fresh] = value.try_emplace(k, 0.0);
      if (fresh)
        it->second =
            (oct.position(Octree::vertex_point(k)) - mid).norm() - 0.6 + 0.2 * (u(g) - 0.5);
      return it->second;
    };
    std::vector<Tri> tris;
    std::set<OctKey> corners;
    for (const auto& [key, cell] : oct.leaves()) {
      std::vector<Octree::Tet> tets;
      oct.tets(key, tets);
      for (const auto& t : tets) {
        OctKey k[4];
        double v[4];
        for (int i = 0; i < 4; ++i) {
          k[i] = Octree::vertex_key(t[static_cast<std::size_t>(i)]);
          v[i] = phi(k[i]);
          corners.insert(k[i]);
        }
        qmotion::sweep::mesher::march(t, k, v, 0.0, tris);
      }
    }
    ASSERT_GT(tris.size(), 100u);
    // Each vertex anywhere inside its edge, near either end included.
    std::unordered_map<EdgeKey, Eigen::Vector3d, EdgeHash> at;
    std::vector<std::array<Eigen::Vector3d, 3>> surface;
    for (const Tri& t : tris) {
      std::array<Eigen::Vector3d, 3> p;
      for (int i = 0; i < 3; ++i) {
        const EdgeKey& e = t[static_cast<std::size_t>(i)];
        auto [it, fresh] = at.try_emplace(e);
        if (fresh) {
          const double s = u(g) < 0.2 ? 1e-3 + 1e-2 * u(g) : 0.02 + 0.96 * u(g);
          const Eigen::Vector3d a = oct.position(Octree::vertex_point(e.a)),
                                b = oct.position(Octree::vertex_point(e.b));
          it->second = a + s * (b - a);
        }
        p[static_cast<std::size_t>(i)] = it->second;
      }
      surface.push_back(p);
    }
    // Closed: every directed edge once, and its reverse once.
    std::map<std::pair<EdgeKey, EdgeKey>, int> directed;
    for (const Tri& t : tris)
      for (int i = 0; i < 3; ++i)
        ++directed[{t[static_cast<std::size_t>(i)], t[static_cast<std::size_t>((i + 1) % 3)]}];
    for (const auto& [e, n] : directed) {
      ASSERT_EQ(n, 1);
      ASSERT_EQ(directed.count({e.second, e.first}), 1u);
    }
    int inside = 0;
    for (const OctKey k : corners) {
      const double w = winding(surface, oct.position(Octree::vertex_point(k)));
      const bool below = value.at(k) < 0;
      inside += below;
      ASSERT_NEAR(w, below ? 1.0 : 0.0, 1e-6) << "seed " << seed;
    }
    EXPECT_GT(inside, 10);
  }
}

// A cube of edge 2^-10 at 2^20 from the point the divergence theorem sums about: its
// coordinates and its volume 2^-30 are exact doubles, the twelve terms are about 2^50 and
// cancel. The interval holds the exact volume where the plain sum misses it by far more than
// any fixed relative margin; about the cube's centre it is also tight.
TEST(EnclosedVolume, HoldsTheExactVolumeWhereAFixedMarginWouldNot) {
  const double o = std::ldexp(1.0, 20), h = std::ldexp(1.0, -10), exact = std::ldexp(1.0, -30);
  std::vector<Eigen::Vector3d> v;
  for (int n = 0; n < 8; ++n)
    v.emplace_back(o + h * (n & 1), o + h * (n >> 1 & 1), o + h * (n >> 2));
  const std::vector<std::array<int, 3>> faces = {{0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5},
                                                 {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},
                                                 {0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}};
  const auto far = qmotion::sweep::mesher::enclosed_volume(v, faces, Eigen::Vector3d::Zero());
  EXPECT_LE(far.lo, exact);
  EXPECT_GE(far.hi, exact);
  double plain = 0;
  for (const auto& t : faces) plain += v[t[0]].dot(v[t[1]].cross(v[t[2]]));
  plain /= 6;
  EXPECT_GT(std::abs(plain - exact), 1e-9 * exact);  // a margin of 1e-9 would not hold it
  const auto near =
      qmotion::sweep::mesher::enclosed_volume(v, faces, Eigen::Vector3d::Constant(o + h / 2));
  EXPECT_LE(near.lo, exact);
  EXPECT_GE(near.hi, exact);
  EXPECT_LT(near.hi - near.lo, 1e-12 * exact);
}

}  // namespace
