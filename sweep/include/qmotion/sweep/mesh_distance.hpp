// <qmotion/sweep/mesh_distance.hpp>: the signed distance to a closed, oriented triangle mesh:
// by a scan of every triangle with the winding number's sign, or through an index (a
// bounding-box tree and angle-weighted pseudonormals) in logarithmic time
// (docs/geometry.md, "Swept volumes").
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

namespace qmotion::sweep {

/// A closed triangle mesh: counter-clockwise seen from outside.
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
};

namespace detail {

/// The closest point to x on the triangle (a, b, c) (Ericson, Real-Time Collision
/// Detection, 5.1.5). `where`, when given, is set to the feature it lies on: 0, 1, 2 the
/// vertex a, b, c; 3, 4, 5 the edge ab, bc, ca; 6 the face.
inline Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& x, const Eigen::Vector3d& a,
                                           const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                           int* where = nullptr) {
  int at = 6;
  auto done = [&](int w, const Eigen::Vector3d& p) {
    at = w;
    if (where) *where = at;
    return p;
  };
  const Eigen::Vector3d ab = b - a, ac = c - a, ax = x - a;
  const double d1 = ab.dot(ax), d2 = ac.dot(ax);
  if (d1 <= 0 && d2 <= 0) return done(0, a);
  const Eigen::Vector3d bx = x - b;
  const double d3 = ab.dot(bx), d4 = ac.dot(bx);
  if (d3 >= 0 && d4 <= d3) return done(1, b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return done(3, a + d1 / (d1 - d3) * ab);
  const Eigen::Vector3d cx = x - c;
  const double d5 = ab.dot(cx), d6 = ac.dot(cx);
  if (d6 >= 0 && d5 <= d6) return done(2, c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return done(5, a + d2 / (d2 - d6) * ac);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return done(4, b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b));
  const double den = 1 / (va + vb + vc);
  return done(6, a + ab * (vb * den) + ac * (vc * den));
}

/// Halves order[a, b), triangles of m, at the median of their centroids along the longest
/// axis of the centroids' box: order[a, mid) then holds the lower half (nth_element), and
/// mid = (a + b) / 2 is returned. The trees over a mesh's triangles (MeshIndex, and
/// HullPieces' parts) split this way.
inline std::size_t split_at_median(const TriangleMesh& m, std::vector<int>& order, std::size_t a,
                                   std::size_t b) {
  auto p = [&](int v) -> const Eigen::Vector3d& { return m.vertices[static_cast<std::size_t>(v)]; };
  Eigen::AlignedBox3d centres;
  for (std::size_t i = a; i < b; ++i) {
    const auto& tr = m.triangles[static_cast<std::size_t>(order[i])];
    centres.extend(Eigen::Vector3d((p(tr[0]) + p(tr[1]) + p(tr[2])) / 3));
  }
  Eigen::Index axis = 0;
  centres.sizes().maxCoeff(&axis);
  const std::size_t mid = (a + b) / 2;
  auto key = [&](int t) {
    const auto& tr = m.triangles[static_cast<std::size_t>(t)];
    return p(tr[0])(axis) + p(tr[1])(axis) + p(tr[2])(axis);
  };
  std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(a),
                   order.begin() + static_cast<std::ptrdiff_t>(mid),
                   order.begin() + static_cast<std::ptrdiff_t>(b),
                   [&](int s, int t) { return key(s) < key(t); });
  return mid;
}

/// The signed distance from x to a closed, outward-oriented triangle mesh: the distance to
/// its nearest triangle, negative where the winding number (the solid angles' sum over 4 pi,
/// Van Oosterom and Strackee) is above one half. Linear in the mesh's size.
inline double mesh_distance(const TriangleMesh& m, const Eigen::Vector3d& x) {
  double d2 = HUGE_VAL, omega = 0;
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    d2 = std::min(d2, (closest_on_triangle(x, a, b, c) - x).squaredNorm());
    const Eigen::Vector3d p = a - x, q = b - x, r = c - x;
    const double lp = p.norm(), lq = q.norm(), lr = r.norm();
    const double num = p.dot(q.cross(r));
    const double den = lp * lq * lr + p.dot(q) * lr + q.dot(r) * lp + r.dot(p) * lq;
    omega += 2 * std::atan2(num, den);
  }
  const double d = std::sqrt(d2);
  return omega > 2 * 3.14159265358979323846 ? -d : d;
}

/// The signed distance to a closed, consistently oriented 2-manifold triangle mesh in
/// logarithmic time: the nearest point p by a tree of bounding boxes (branch and bound on
/// the boxes' distance), and the sign of (x - p) . N with N the angle-weighted pseudonormal
/// of the feature p lies on (the face's normal, the sum of an edge's two face normals, or the
/// angle-weighted sum about a vertex): for such meshes that sign is the inside-outside test
/// (Baerentzen and Aanaes 2005). The distance is the scan's; the sign agrees with the winding
/// number's away from the surface.
class MeshIndex {
 public:
  explicit MeshIndex(const TriangleMesh& m) : m_(m) {
    const std::size_t n = m.triangles.size();
    face_.resize(n);
    edge_.resize(n);
    std::vector<Eigen::Vector3d> vertex(m.vertices.size(), Eigen::Vector3d::Zero());
    std::map<std::pair<int, int>, Eigen::Vector3d> edges;
    for (std::size_t t = 0; t < n; ++t) {
      const auto& tri = m.triangles[t];
      const Eigen::Vector3d nrm = (p(tri[1]) - p(tri[0])).cross(p(tri[2]) - p(tri[0])).normalized();
      face_[t] = nrm.allFinite() ? nrm : Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) {
        const int a = tri[static_cast<std::size_t>(k)],
                  b = tri[static_cast<std::size_t>((k + 1) % 3)],
                  c = tri[static_cast<std::size_t>((k + 2) % 3)];
        const Eigen::Vector3d u = (p(b) - p(a)).normalized(), v = (p(c) - p(a)).normalized();
        const double angle = std::acos(std::clamp(u.dot(v), -1.0, 1.0));
        if (std::isfinite(angle)) vertex[static_cast<std::size_t>(a)] += angle * face_[t];
        edges.try_emplace({std::min(a, b), std::max(a, b)}, Eigen::Vector3d::Zero())
            .first->second += face_[t];
      }
    }
    vertex_ = std::move(vertex);
    for (std::size_t t = 0; t < n; ++t)
      for (int k = 0; k < 3; ++k) {
        const int a = m.triangles[t][static_cast<std::size_t>(k)],
                  b = m.triangles[t][static_cast<std::size_t>((k + 1) % 3)];
        edge_[t][static_cast<std::size_t>(k)] = edges[{std::min(a, b), std::max(a, b)}];
      }
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0);
    if (n > 0) {
      nodes_.emplace_back();
      build(0, 0, n);
    }
  }

  /// The signed distance from x: negative inside. `nearest`, when given, is set to the
  /// mesh's point nearest x. With a cap, only triangles nearer than it are searched, and
  /// HUGE_VAL says that there are none (|distance| >= cap, of either sign). `triangle`, when
  /// given, is set to the nearest triangle's index (-1 when none).
  double signed_distance(const Eigen::Vector3d& x, Eigen::Vector3d* nearest = nullptr,
                         double cap = HUGE_VAL, int* triangle = nullptr) const {
    double best = cap * cap;
    int tri = -1, where = 6;
    Eigen::Vector3d near = x;
    // Each node popped pushes at most its two children: the stack holds at most the tree's
    // depth plus one (build() halves, so a log2 of the size; kStack is far above).
    std::pair<int, double> stack[kStack];
    int top = 0;
    if (!nodes_.empty()) stack[top++] = {0, box_distance(x, nodes_[0].box)};
    while (top > 0) {
      const auto [at, d2box] = stack[--top];
      if (d2box >= best) continue;
      const Node& nd = nodes_[static_cast<std::size_t>(at)];
      if (nd.count > 0) {
        for (int i = nd.first; i < nd.first + nd.count; ++i) {
          const int t = order_[static_cast<std::size_t>(i)];
          const auto& tr = m_.triangles[static_cast<std::size_t>(t)];
          int w = 6;
          const Eigen::Vector3d q = closest_on_triangle(x, p(tr[0]), p(tr[1]), p(tr[2]), &w);
          const double d2 = (q - x).squaredNorm();
          if (d2 < best) {
            best = d2;
            tri = t;
            where = w;
            near = q;
          }
        }
        continue;
      }
      // The nearer child (by its box) last, so that it is searched first; a child whose box
      // is already beyond the best is not pushed.
      const double dl = box_distance(x, nodes_[static_cast<std::size_t>(nd.left)].box),
                   dr = box_distance(x, nodes_[static_cast<std::size_t>(nd.left + 1)].box);
      const bool left_first = dl < dr;
      const std::pair<int, double> first{left_first ? nd.left : nd.left + 1, left_first ? dl : dr},
          second{left_first ? nd.left + 1 : nd.left, left_first ? dr : dl};
      if (second.second < best) stack[top++] = second;
      if (first.second < best) stack[top++] = first;
    }
    if (triangle) *triangle = tri;
    if (tri < 0) return HUGE_VAL;
    const auto t = static_cast<std::size_t>(tri);
    const auto& tr = m_.triangles[t];
    Eigen::Vector3d N;
    if (where < 3)
      N = vertex_[static_cast<std::size_t>(tr[static_cast<std::size_t>(where)])];
    else if (where < 6)
      N = edge_[t][static_cast<std::size_t>(where - 3)];
    else
      N = face_[t];
    const double d = std::sqrt(best);
    if (nearest) *nearest = near;
    return (x - near).dot(N) < 0 ? -d : d;
  }

  /// The indexed mesh.
  const TriangleMesh& mesh() const { return m_; }

  /// The triangles nearer x than r, at most `limit` of them: false when there are more.
  bool triangles_within(const Eigen::Vector3d& x, double r, std::size_t limit,
                        std::vector<int>& out) const {
    out.clear();
    std::vector<int> stack;
    if (!nodes_.empty()) stack.push_back(0);
    const double r2 = r * r;
    while (!stack.empty()) {
      const Node& nd = nodes_[static_cast<std::size_t>(stack.back())];
      stack.pop_back();
      if (box_distance(x, nd.box) >= r2) continue;
      if (nd.count == 0) {
        stack.push_back(nd.left);
        stack.push_back(nd.left + 1);
        continue;
      }
      for (int i = nd.first; i < nd.first + nd.count; ++i) {
        const int t = order_[static_cast<std::size_t>(i)];
        const auto& tr = m_.triangles[static_cast<std::size_t>(t)];
        if ((closest_on_triangle(x, p(tr[0]), p(tr[1]), p(tr[2])) - x).squaredNorm() >= r2)
          continue;
        if (out.size() == limit) return false;
        out.push_back(t);
      }
    }
    return true;
  }

 private:
  static constexpr int kStack = 128;
  /// The squared distance from x to the box.
  static double box_distance(const Eigen::Vector3d& x, const Eigen::AlignedBox3d& b) {
    return (x - x.cwiseMax(b.min()).cwiseMin(b.max())).squaredNorm();
  }
  struct Node {
    Eigen::AlignedBox3d box;
    int left = -1;  ///< children left and left + 1, or -1 for a leaf
    int first = 0, count = 0;
  };
  const Eigen::Vector3d& p(int v) const { return m_.vertices[static_cast<std::size_t>(v)]; }

  /// Fills node `at` over order_[a, b): its box, then halves at the median of the centroids
  /// along their box's longest axis into two new nodes, down to four triangles.
  void build(int at, std::size_t a, std::size_t b) {
    Eigen::AlignedBox3d box;
    for (std::size_t i = a; i < b; ++i)
      for (int v : m_.triangles[static_cast<std::size_t>(order_[i])]) box.extend(p(v));
    nodes_[static_cast<std::size_t>(at)].box = box;
    if (b - a <= 4) {
      nodes_[static_cast<std::size_t>(at)].first = static_cast<int>(a);
      nodes_[static_cast<std::size_t>(at)].count = static_cast<int>(b - a);
      return;
    }
    const std::size_t mid = split_at_median(m_, order_, a, b);
    const int left = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    nodes_.emplace_back();
    nodes_[static_cast<std::size_t>(at)].left = left;
    build(left, a, mid);
    build(left + 1, mid, b);
  }

  TriangleMesh m_;  ///< a copy: the index outlives no body it was made for
  std::vector<Eigen::Vector3d> face_, vertex_;
  std::vector<std::array<Eigen::Vector3d, 3>> edge_;  ///< by triangle: ab, bc, ca
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

}  // namespace detail
}  // namespace qmotion::sweep
