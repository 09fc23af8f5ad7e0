// sweep/src/volume_mesh.cpp: qmotion::swept_volume, the certified enclosing mesh of `volume`
// (docs/guide/volume.md; the constructions and their proofs are in docs/geometry.md, "Swept
// volumes"). Every body takes the adaptive route (volume_adaptive.cpp), whose triangles
// follow the surface.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/hull_pieces.hpp>
#include <qmotion/sweep/swept_volume.hpp>
#include <string>
#include <utility>
#include <vector>

#include "volume_detail.hpp"

namespace qmotion::sweep {
namespace {

/// The smallest distance from x to the body placed at t in [t0, t1], by golden sections
/// from the tree's best placement.
double refined_distance(const sweep::SweptVolumeTree& tree, const qmotion::Motion& m,
                        const Eigen::Vector3d& x, const sweep::VolumeDistance& d) {
  double lo = std::max(m.a(), d.t0 - (d.t1 - d.t0)), hi = std::min(m.b(), d.t1 + (d.t1 - d.t0));
  const double g = 0.6180339887498949;
  double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
  double fa = tree.placed_distance(x, a), fb = tree.placed_distance(x, b);
  double best = std::min({d.signed_upper, fa, fb});
  for (int it = 0; it < 40; ++it) {
    if (fa < fb) {
      hi = b;
      b = a;
      fb = fa;
      a = hi - g * (hi - lo);
      fa = tree.placed_distance(x, a);
      best = std::min(best, fa);
    } else {
      lo = a;
      a = b;
      fa = fb;
      b = lo + g * (hi - lo);
      fb = tree.placed_distance(x, b);
      best = std::min(best, fb);
    }
  }
  return std::max(best, 0.0);
}

}  // namespace

namespace mesher {

kernel::Interval enclosed_volume(const std::vector<Eigen::Vector3d>& vertices,
                                 const std::vector<std::array<int, 3>>& triangles,
                                 const Eigen::Vector3d& o) {
  // Sums of the triangles' determinants in intervals: terms of either sign cancel, and over
  // 10^7 of them a fixed relative margin would not be a bound.
  kernel::Interval v(0.0);
  for (const auto& t : triangles) {
    auto at = [&](int k) {
      return kernel::difference(vertices[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])],
                                o);
    };
    v += kernel::dot(at(0), kernel::cross(at(1), at(2)));
  }
  return v / kernel::Interval(6.0);
}

void refuse_float32(const qmotion::Motion& motion, double e, double T,
                    const VolumeRounding& rounding) {
  throw Error(Errc::invalid_input, motion.label() +
                                       ": binary STL rounds the coordinates to float32, by up to " +
                                       kernel::detail::format_double(e * rounding.scale) +
                                       " here: too coarse for the tolerance " +
                                       kernel::detail::format_double(T * rounding.scale) +
                                       "; write .ply or .obj (double coordinates), or raise --tol");
}

void refuse_size(const qmotion::Motion& motion, double T, std::size_t triangles) {
  if (triangles > 10'000'000)
    throw Error(Errc::numerical_failure,
                motion.label() + ": the enclosing mesh within the tolerance " +
                    kernel::detail::format_double(T) + " would have more than 10^7 triangles (" +
                    std::to_string(triangles) + "): raise --tol");
}

}  // namespace mesher

Eigen::AlignedBox3d sampled_swept_box(const qmotion::Motion& m, const Body& body) {
  const auto mesh = sweep::triangulate(body, 1e-2 * sweep::radius(body));
  Eigen::AlignedBox3d box;
  const int n = 64 * std::max(1, m.segments());
  for (int i = 0; i <= n; ++i) {
    const Eigen::Matrix4d f = m.frame(m.a() + (m.b() - m.a()) * i / n);
    for (const auto& v : mesh.vertices)
      box.extend(Eigen::Vector3d(f.block<3, 1>(1, 0) + f.block<3, 3>(1, 1) * v));
  }
  return box;
}

SweptVolume swept_volume(const qmotion::Motion& motion, const sweep::Body& body,
                         std::optional<double> tol, const VolumeRounding& rounding) {
  sweep::validate(body);
  if (tol && (!(*tol > 0) || !std::isfinite(*tol)))
    throw Error(Errc::invalid_input, "volume: the tolerance must be a positive length, got " +
                                         kernel::detail::format_double(*tol));
  if (motion.is_rational()) sweep::refuse_poles(motion.rational());
  SweptVolume out;
  const Eigen::AlignedBox3d sampled = sampled_swept_box(motion, body);
  out.tolerance = tol ? *tol : 1e-3 * sampled.diagonal().norm();
  const double T = out.tolerance;
  mesher::refuse_octree(motion, sampled, T);
  const sweep::SweptVolumeTree tree(
      motion, body, 0.1 * T, [](std::size_t n, const std::function<void(std::size_t)>& f) {
        tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) { f(i); });
      });
  out.time_pieces = tree.leaves();
  out.piece_delta = tree.largest_leaf_delta();
  const sweep::HullPieces hulls(motion, body, 0.05 * T);
  mesher::EnclosingMesh m = mesher::adaptive_mesh(motion, tree, hulls, T, rounding);
  out.distance_bound = m.distance_bound;
  out.grid_step = m.smallest_cell;
  out.largest_cell = m.largest_cell;
  out.surface_cells = m.cells;
  out.hull_pieces = m.pieces;
  out.level = m.level;
  out.rounds = m.rounds;
  // Measured beside the bound: up to 20 000 vertices, refined along t.
  const std::size_t stride = std::max<std::size_t>(1, m.vertices.size() / 20000);
  std::vector<double> measured((m.vertices.size() + stride - 1) / stride, 0.0);
  tbb::parallel_for(std::size_t(0), measured.size(), [&](std::size_t i) {
    measured[i] = refined_distance(tree, motion, m.vertices[i * stride], m.at[i * stride]);
  });
  for (double x : measured) out.measured_distance = std::max(out.measured_distance, x);
  out.measured_vertices = measured.size();
  out.rounding = m.rounding;
  out.closed = m.closed;
  out.volume_upper = m.enclosed.hi;
  // V holds the body at every placement, so its volume is at least the body's: for a mesh,
  // the divergence sum over its triangles (the tetrahedra about the box's centre are what a
  // thin body's octree cannot certify).
  double lower = m.inside_volume;
  if (body.kind == sweep::Body::Kind::mesh) {
    Eigen::AlignedBox3d own;
    for (const auto& x : body.mesh.vertices) own.extend(x);
    lower = std::max(
        lower, mesher::enclosed_volume(body.mesh.vertices, body.mesh.triangles, own.center()).lo);
  }
  out.volume_lower = std::min(lower, out.volume_upper);
  out.vertices = std::move(m.vertices);
  out.triangles = std::move(m.triangles);
  out.distance_queries = m.queries;
  return out;
}

}  // namespace qmotion::sweep
