// api/src/self_intersection.cpp
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <map>
#include <qmotion/api/self_intersection.hpp>
#include <qmotion/kernel/error.hpp>
#include <sstream>

namespace qmotion {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
using Face = Mesh::Face_index;
using Vertex = Mesh::Vertex_index;

/// A sample of the profile: edge, parameter, point.
struct ProfileSample {
  std::size_t edge;
  double v;
  Eigen::Vector3d x;
};

}  // namespace

namespace {

/// The tessellation and CGAL's check for the image place(t, x) of the point x at t in
/// [a, b], with `segments` the motion's pieces for the default sampling.
SelfIntersection self_intersections(
    const std::function<Eigen::Vector3d(double, const Eigen::Vector3d&)>& place, double a, double b,
    int segments, const sweep::Profile<double>& profile, int samples_t) {
  SelfIntersection out;
  if (profile.edges.empty()) return out;
  const int nt = samples_t > 0 ? samples_t : std::clamp(16 * segments, 64, 2000);
  // Profile samples, the point shared by consecutive edges taken once.
  std::vector<ProfileSample> prof;
  for (std::size_t e = 0; e < profile.edges.size(); ++e) {
    const auto& c = profile.edges[e];
    const int nv = std::max(16, 8 * c.degree);
    const double v0 = c.knots.front(), v1 = c.knots.back();
    for (int j = (e == 0 ? 0 : 1); j <= nv; ++j) {
      const double v = v0 + (v1 - v0) * j / nv;
      prof.push_back({e, v, sweep::evaluate(c, v)});
    }
  }
  if (profile.closed && prof.size() > 2) prof.pop_back();  // the last point is the first
  const std::size_t np = prof.size();
  out.samples_t = nt + 1;
  out.samples_v = static_cast<int>(np);
  Mesh mesh;
  std::vector<double> ts;
  std::vector<Vertex> vid;
  // Points the surface passes through more than once at the same place (a profile point on
  // a fixed rotation axis) are one vertex: triangles meeting there touch, they do not cross.
  std::map<std::array<double, 3>, Vertex> seen;
  for (int i = 0; i <= nt; ++i) {
    const double t = a + (b - a) * i / nt;
    ts.push_back(t);
    for (const auto& s : prof) {
      const Eigen::Vector3d y = place(t, s.x);
      const std::array<double, 3> key{y(0), y(1), y(2)};
      const auto it = seen.find(key);
      if (it != seen.end()) {
        vid.push_back(it->second);
      } else {
        vid.push_back(mesh.add_vertex(K::Point_3(y(0), y(1), y(2))));
        seen.emplace(key, vid.back());
      }
    }
  }
  // Face -> (t index, profile index) of its lower-left grid corner.
  auto grid = mesh.add_property_map<Face, std::pair<int, std::size_t>>("f:grid").first;
  const std::size_t cols = profile.closed ? np : np - 1;
  auto at = [&](int i, std::size_t j) { return vid[static_cast<std::size_t>(i) * np + j % np]; };
  auto add = [&](Vertex a, Vertex b, Vertex c, int i, std::size_t j) {
    if (a == b || b == c || a == c || CGAL::collinear(mesh.point(a), mesh.point(b), mesh.point(c)))
      return;
    const Face f = mesh.add_face(a, b, c);
    if (f != Mesh::null_face()) grid[f] = {i, j};
  };
  for (int i = 0; i < nt; ++i)
    for (std::size_t j = 0; j < cols; ++j) {
      add(at(i, j), at(i + 1, j), at(i + 1, j + 1), i, j);
      add(at(i, j), at(i + 1, j + 1), at(i, j + 1), i, j);
    }
  std::vector<std::pair<Face, Face>> hits;
  CGAL::Polygon_mesh_processing::self_intersections(mesh, std::back_inserter(hits));
  out.pairs = hits.size();
  if (hits.empty()) return out;
  out.t0 = std::numeric_limits<double>::infinity();
  out.t1 = -out.t0;
  std::vector<std::pair<double, double>> vr(
      profile.edges.size(),
      {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()});
  for (const auto& [f, g] : hits)
    for (const Face h : {f, g}) {
      const auto [i, j] = grid[h];
      out.t0 = std::min(out.t0, ts[static_cast<std::size_t>(i)]);
      out.t1 = std::max(out.t1, ts[static_cast<std::size_t>(i) + 1]);
      for (const std::size_t k : {j % np, (j + 1) % np}) {
        auto& r = vr[prof[k].edge];
        r.first = std::min(r.first, prof[k].v);
        r.second = std::max(r.second, prof[k].v);
      }
    }
  for (std::size_t e = 0; e < vr.size(); ++e)
    if (vr[e].first <= vr[e].second) out.edges.push_back({e, vr[e].first, vr[e].second});
  return out;
}

}  // namespace

SelfIntersection sweep_self_intersections(const Motion& motion,
                                          const sweep::Profile<double>& profile, int samples_t) {
  return self_intersections([&](double t, const Eigen::Vector3d& x) { return motion.place(t, x); },
                            motion.a(), motion.b(), motion.segments(), profile, samples_t);
}

}  // namespace qmotion
