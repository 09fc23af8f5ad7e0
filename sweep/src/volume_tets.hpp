// sweep/src/volume_tets.hpp: what the adaptive mesh (volume_adaptive.cpp) does in one
// tetrahedron of its octree: the surface's pieces, and the part certainly in V
// (docs/geometry.md, "The adaptive mesh").
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

#include "volume_octree.hpp"

namespace qmotion::sweep {
class SweptVolumeTree;
}

namespace qmotion::sweep::mesher {

/// A vertex of the surface: the tetrahedra's edge it lies on, by its ends' keys (lower first).
struct EdgeKey {
  OctKey a = 0, b = 0;
  bool operator==(const EdgeKey& o) const { return a == o.a && b == o.b; }
  bool operator<(const EdgeKey& o) const { return a < o.a || (a == o.a && b < o.b); }
};
struct EdgeHash {
  std::size_t operator()(const EdgeKey& e) const {
    return static_cast<std::size_t>((e.a * 0x9E3779B97F4A7C15ull) ^ (e.b + (e.a << 6)));
  }
};
using Tri = std::array<EdgeKey, 3>;

/// Marching tetrahedra over t, whose corners have keys k and values v: the surface's
/// triangles, by the edges their vertices lie on, appended to out, each facing from below
/// tau to above wherever on its edge each vertex lies (the orientation comes from t's
/// integer corners alone).
void march(const Octree::Tet& t, const OctKey* k, const double* v, double tau,
           std::vector<Tri>& out);

/// A volume of the tetrahedron with corners p (values v, found at the placements at) that
/// certainly lies in V.
double inside_part(const Eigen::Vector3d* p, const double* v, const double* at,
                   const sweep::SweptVolumeTree& tree, double scale);

}  // namespace qmotion::sweep::mesher
