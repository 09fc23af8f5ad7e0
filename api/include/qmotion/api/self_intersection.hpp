// <qmotion/api/self_intersection.hpp>: does a kinematic sweep intersect itself? (CGAL mesh check)
#pragma once
#include <Eigen/Core>
#include <qmotion/motion.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace qmotion {

/// Where a sweep intersects itself: the triangle pairs of its tessellation that CGAL finds
/// crossing, with the parameter ranges they cover.
struct SelfIntersection {
  std::size_t pairs = 0;  ///< intersecting triangle pairs (0: none found)
  double t0 = 0, t1 = 0;  ///< motion parameters involved
  struct EdgeRange {
    std::size_t edge = 0;   ///< profile edge
    double v0 = 0, v1 = 0;  ///< its parameters involved
  };
  std::vector<EdgeRange> edges;
  int samples_t = 0, samples_v = 0;  ///< the tessellation's size (v: all edges together)

  bool found() const { return pairs > 0; }
  /// "t in [a, b], profile edge 0 v in [c, d], ..." for messages.
  std::string ranges() const {
    std::ostringstream os;
    os.precision(4);
    os << "t in [" << t0 << ", " << t1 << "]";
    for (const auto& e : edges)
      os << ", profile edge " << e.edge << " v in [" << e.v0 << ", " << e.v1 << "]";
    return os.str();
  }
};

/// Tessellates the surface M(t) x(v) that the profile sweeps (one mesh over all edges, the
/// vertices where edges meet shared, a closed profile closed) from the motion itself, and
/// asks CGAL's Polygon_mesh_processing::self_intersections for crossing triangles.
/// Triangles that touch only along a shared edge or vertex do not count; degenerate
/// (zero-area) triangles are skipped. `samples_t` 0 chooses 16 per motion segment, 64 to
/// 2000; each edge gets 8 per degree (at least 16).
/// For a quaternion-spline motion the surface is made from its exact poses, not a fit.
SelfIntersection sweep_self_intersections(const Motion& motion,
                                          const sweep::Profile<double>& profile, int samples_t = 0);

}  // namespace qmotion
