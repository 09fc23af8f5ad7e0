// sweep/src/volume_adaptive.cpp: the adaptive enclosing mesh of `volume` (docs/guide/volume.md,
// "The adaptive mesh"; volume_detail.hpp).
//
// The surface is the level tau of the piecewise-linear interpolant g, over the octree's
// conforming tetrahedra (volume_octree.hpp), of phi: at every tetrahedron's corner, the
// signed distance to the body at the best placement the tree's search finds (an upper bound
// of the signed distance to V). It is closed, 2-manifold, oriented and embedded: a level of a
// piecewise-linear function over a complex, at a value no corner takes. The proof that it
// encloses V is triangle by triangle: each is certified clear of V (sweep::HullPieces). V is
// connected and meets no triangle, so it lies in one component of the space off the surface:
// the one of a corner inside V (phi < 0 < tau there), inside the surface. A mesh body's
// triangles are certified clear of what its boundary sweeps; each connected sheet of them
// is then outside V when one of its points is outside the body at the start (finish()).
// Every vertex is
// bounded within the tolerance by a placement. A leaf whose triangles or vertices fail is
// split, and the tree balanced again, until none fails.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/hull_pieces.hpp>
#include <qmotion/sweep/swept_volume.hpp>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "volume_detail.hpp"
#include "volume_octree.hpp"
#include "volume_tets.hpp"

namespace qmotion::sweep::mesher {
namespace {

/// The level, in T: the triangles may sag by about T - tau towards V between vertices at tau
/// (so the higher the fewer), and a vertex's bound is its level plus the search's gap and
/// the interpolation's error (at most T). 0.85 made the fewest triangles on the helix
/// (0.5: 449 250 at T = 0.05 mm, 0.8: 239 874, 0.88: 219 584, 0.94: 224 402).
constexpr double kLevel = 0.85;
/// A vertex is placed within kLevelSlack T of the level, by at most kPlaceQueries queries of
/// the time tree along its edge (place_vertices).
constexpr double kLevelSlack = 0.02;
constexpr int kPlaceQueries = 4;

/// A point's certified distance to V from its query: the placement's, with rounding (relative
/// 1e-12 of the scene).
double certified_distance(const sweep::VolumeDistance& d, double scale) {
  return std::max(d.signed_upper, 0.0) + 1e-12 * scale;
}

struct Leaf {
  OctKey key = 0;
  std::vector<Tri> tris;     ///< this round's
  std::vector<Tri> checked;  ///< the triangles last certified (all of them passed)
  bool ok = false;
  double inside = 0;  ///< volume of its tetrahedra certified inside V
};

/// A vertex of the surface and what its query found there.
struct Bound {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();  ///< the vertex
  sweep::VolumeDistance d;
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
};

class Mesher {
 public:
  /// eps: how far from tau a corner's value is kept.
  Mesher(const qmotion::Motion& motion, const sweep::SweptVolumeTree& tree,
         const sweep::HullPieces& hulls, const Eigen::AlignedBox3d& box, double T, double tau,
         double e, double eps)
      : motion_(motion),
        tree_(tree),
        hulls_(hulls),
        T_(T),
        tau_(tau),
        e_(e),
        eps_(eps),
        scale_(box.diagonal().norm()),
        octree_(make_octree(box, T)) {}

  EnclosingMesh run() {
    EnclosingMesh out;
    std::vector<OctKey> fresh;
    for (const auto& [k, c] : octree_.leaves()) fresh.push_back(k);
    for (out.rounds = 1;; ++out.rounds) {
      octree_.balance(fresh);
      classify();
      // Only the leaves whose tetrahedra may have changed are made again: new ones, and
      // those next to a split cell (Octree::touching).
      std::vector<Leaf*> dirty = dirty_leaves(fresh);
      evaluate(dirty);
      for_each(dirty, [&](Leaf& L) { L.tris = triangles(L); });
      std::size_t count = 0;
      for (const auto& [k, L] : leaves_) count += L.tris.size();
      refuse_size(motion_, T_, count);
      place_vertices(dirty);
      for_each(dirty, [&](Leaf& L) { certify(L); });
      std::vector<OctKey> failed;
      for (Leaf* L : dirty)
        if (!L->ok) failed.push_back(L->key);
      if (failed.empty()) {
        finish(out);
        return out;
      }
      fresh.clear();
      for (const OctKey c : failed) {
        if (Octree::level(c) >= Octree::kFinest)
          throw Error(Errc::numerical_failure,
                      "volume: a cell of the finest level could not be certified (the tolerance " +
                          kernel::detail::format_double(T_) + " is too fine for the scene)");
        octree_.split(c, &fresh);
      }
      if (out.rounds > 40)  // never seen: each round splits, and the finest level ends it
        throw Error(Errc::numerical_failure, "volume: the adaptive mesh did not converge");
    }
  }

  /// The margin about the box (which holds V) where every value exceeds tau.
  static double pad(const Eigen::AlignedBox3d& box, double T) {
    return 4 * T + 1e-3 * box.diagonal().norm();
  }
  /// The roots' edge: they hold the box and its margin, at most 32 along an axis.
  static double root_edge(const Eigen::AlignedBox3d& box, double T) {
    return (box.sizes() + Eigen::Vector3d::Constant(2 * pad(box, T))).maxCoeff() / 31.5;
  }

 private:
  static Octree make_octree(const Eigen::AlignedBox3d& box, double T) {
    const Eigen::Vector3d size = box.sizes() + Eigen::Vector3d::Constant(2 * pad(box, T));
    const double root = root_edge(box, T);
    std::array<long, 3> n{};
    for (int a = 0; a < 3; ++a)
      n[static_cast<std::size_t>(a)] = std::max(1L, static_cast<long>(std::ceil(size(a) / root)));
    return Octree(box.min() - Eigen::Vector3d::Constant(pad(box, T)), root, n);
  }

  template <typename F>
  static void for_each(const std::vector<Leaf*>& v, const F& f) {
    tbb::parallel_for(std::size_t(0), v.size(), [&](std::size_t i) { f(*v[i]); });
  }

  double half_diagonal(OctKey c) const {
    return 0.5 * std::sqrt(3.0) * static_cast<double>(Octree::size(Octree::level(c))) *
           octree_.unit();
  }
  Eigen::Vector3d centre(OctKey c) const {
    OctPoint p = Octree::corner(c);
    const long h = Octree::size(Octree::level(c)) / 2;
    for (auto& x : p) x += h;
    return octree_.position(p);
  }

  /// Every leaf of unknown kind: far when its bound at the centre, less the half-diagonal,
  /// exceeds tau (every corner's value, an upper bound, does too), deep when a placement
  /// holds the whole cell deeper than the search's gap (every corner's value is below 0).
  void classify() {
    std::vector<OctKey> todo;
    for (const auto& [k, c] : octree_.leaves())
      if (c.kind == Octree::Kind::unknown) todo.push_back(k);
    std::vector<Octree::Kind> kind(todo.size());
    std::vector<int> node(todo.size());
    tbb::parallel_for(std::size_t(0), todo.size(), [&](std::size_t i) {
      const double r = half_diagonal(todo[i]), gap = tree_.largest_leaf_delta();
      // Above tau + eps + r + gap the cell is far whatever the distance is (query()).
      const auto d = tree_.query(centre(todo[i]), -(r + 2 * gap), octree_.leaves().at(todo[i]).node,
                                 tau_ + eps_ + r + 2 * gap);
      node[i] = d.node;
      if (d.lower - r > tau_ + eps_)
        kind[i] = Octree::Kind::far;
      else if (d.signed_upper + r + tree_.largest_leaf_delta() + 1e-12 * scale_ < 0)
        kind[i] = Octree::Kind::deep;
      else
        kind[i] = Octree::Kind::near;
    });
    queries_ += todo.size();
    for (std::size_t i = 0; i < todo.size(); ++i) {
      octree_.cell(todo[i]).kind = kind[i];
      octree_.cell(todo[i]).node = node[i];
      if (kind[i] == Octree::Kind::deep) {
        const double s = static_cast<double>(Octree::size(Octree::level(todo[i]))) * octree_.unit();
        deep_volume_ = kernel::down(deep_volume_ + kernel::down(kernel::down(s * s) * s));
      }
    }
  }

  /// The near leaves among `fresh` and those next to a cell split since the last round;
  /// the leaves of split cells are dropped.
  std::vector<Leaf*> dirty_leaves(const std::vector<OctKey>& fresh) {
    std::vector<OctKey> keys = fresh;
    for (const OctKey x : octree_.take_split()) {
      leaves_.erase(x);
      octree_.touching(x, keys);
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    std::vector<Leaf*> out;
    for (const OctKey k : keys) {
      const auto it = octree_.leaves().find(k);
      if (it == octree_.leaves().end() || it->second.kind != Octree::Kind::near) continue;
      Leaf& L = leaves_[k];
      L.key = k;
      out.push_back(&L);
    }
    return out;
  }

  /// phi at every corner of the near leaves' tetrahedra not yet known.
  void evaluate(const std::vector<Leaf*>& near) {
    // Each corner with the time tree's node of a leaf about it, its search's first guess.
    std::vector<std::vector<std::pair<OctKey, int>>> want(near.size());
    tbb::parallel_for(std::size_t(0), near.size(), [&](std::size_t i) {
      std::vector<Octree::Tet> tets;
      octree_.tets(near[i]->key, tets);
      const int hint = octree_.leaves().at(near[i]->key).node;
      for (const auto& t : tets)
        for (const auto& p : t) {
          const OctKey k = Octree::vertex_key(p);
          if (!value_.count(k)) want[i].push_back({k, hint});
        }
    });
    std::vector<std::pair<OctKey, int>> all;
    for (auto& w : want) all.insert(all.end(), w.begin(), w.end());
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end(),
                          [](const auto& x, const auto& y) { return x.first == y.first; }),
              all.end());
    std::vector<Value> v(all.size());
    tbb::parallel_for(std::size_t(0), all.size(), [&](std::size_t i) {
      const OctPoint p = Octree::vertex_point(all[i].first);
      // Deeper than twice the coarsest cell the corner belongs to, the depth is not needed.
      const double reach = 2 * static_cast<double>(Octree::alignment(p)) * octree_.unit();
      // Far above the level the value only has to be above it: a query that finds no
      // placement below `above` has shown f >= above - gap > tau (query()), and `above`
      // then stands for phi.
      const double above = tau_ + eps_ + std::max(reach, T_) + 2 * tree_.largest_leaf_delta();
      const auto d = tree_.query(octree_.position(p), -reach, all[i].second, above);
      double x = d.signed_upper < HUGE_VAL ? d.signed_upper : above;
      // No corner on the level: within eps of tau it is moved below (the surface's vertices
      // are bounded where they lie, whatever phi is).
      if (std::abs(x - tau_) < eps_) x = tau_ - eps_;
      v[i] = {x, d.t, d.node};
    });
    queries_ += all.size();
    for (std::size_t i = 0; i < all.size(); ++i) value_.emplace(all[i].first, v[i]);
  }

  /// The surface's vertex on edge e (place_vertices).
  const Eigen::Vector3d& on_edge(const EdgeKey& e) const { return bound_.at(e).x; }

  /// Marching tetrahedra over a leaf: each triangle faces from below tau to above. Also sums
  /// the tetrahedra that lie in V (inside_part).
  std::vector<Tri> triangles(Leaf& L) const {
    std::vector<Octree::Tet> tets;
    octree_.tets(L.key, tets);
    std::vector<Tri> out;
    L.inside = 0;
    for (const auto& t : tets) {
      OctKey k[4];
      double v[4], at[4];
      for (int i = 0; i < 4; ++i) {
        k[i] = Octree::vertex_key(t[static_cast<std::size_t>(i)]);
        const Value& x = value_.at(k[i]);
        v[i] = x.v;
        at[i] = x.t;
      }
      if (std::min({v[0], v[1], v[2], v[3]}) < 0) {  // else no part of it is known in V
        Eigen::Vector3d p[4];
        for (int i = 0; i < 4; ++i) p[i] = octree_.position(t[static_cast<std::size_t>(i)]);
        L.inside = kernel::down(L.inside + inside_part(p, v, at, tree_, scale_));
      }
      march(t, k, v, tau_, out);
    }
    return out;
  }

  /// Each new vertex: the point of its edge where phi crosses tau, found by false position
  /// (Illinois) from the corners' values; its distance to V bounded above by the best
  /// placement of that search, and the direction from that placement of the body to the
  /// vertex (the subgradient of its signed distance): about the surface, the direction that
  /// separates it from V. Any point inside the edge keeps the surface a closed, embedded
  /// manifold (triangles(): each tetrahedron's piece stays a disk in it, and two neighbours
  /// share the vertices on their common edges); on the level of phi rather than of its
  /// interpolant, the vertices sit where the certificate wants them, and the cells can be
  /// larger where phi is far from linear (about the cutters' rims).
  void place_vertices(const std::vector<Leaf*>& dirty) {
    std::vector<EdgeKey> todo;
    for (const Leaf* L : dirty)
      for (const Tri& t : L->tris)
        for (const EdgeKey& e : t)
          if (!bound_.count(e)) todo.push_back(e);
    std::sort(todo.begin(), todo.end());
    todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
    std::vector<Bound> b(todo.size());
    std::vector<int> asked(todo.size());
    tbb::parallel_for(std::size_t(0), todo.size(),
                      [&](std::size_t i) { asked[i] = place(todo[i], b[i]); });
    for (std::size_t i = 0; i < todo.size(); ++i) {
      queries_ += static_cast<std::size_t>(asked[i]);
      bound_.emplace(todo[i], b[i]);
    }
  }

  /// place_vertices for one edge; returns the queries it took.
  int place(const EdgeKey& e, Bound& out) const {
    const Value& A = value_.at(e.a);
    const Value& B = value_.at(e.b);
    const Eigen::Vector3d pa = octree_.position(Octree::vertex_point(e.a)),
                          pb = octree_.position(Octree::vertex_point(e.b));
    // f(s) = phi(pa + s (pb - pa)) - tau, of opposite signs at the ends.
    double s0 = 0, f0 = A.v - tau_, s1 = 1, f1 = B.v - tau_;
    int side = 0, asked = 0;
    double best = HUGE_VAL;
    for (;;) {
      const double s = std::clamp(s0 - f0 * (s1 - s0) / (f1 - f0), 0.0, 1.0);
      const Eigen::Vector3d x = pa + s * (pb - pa);
      // A point above tau + T is no vertex; there only the sign of f is needed (query()).
      const double above = tau_ + T_ + 2 * tree_.largest_leaf_delta();
      const sweep::VolumeDistance d = tree_.query(x, 0, A.node, above);
      ++asked;
      const double f = std::min(d.signed_upper, above) - tau_;
      if (std::abs(f) < best) {
        best = std::abs(f);
        out.x = x;
        out.d = d;
      }
      if (best <= kLevelSlack * T_ || asked == kPlaceQueries) break;
      if ((f < 0) == (f0 < 0)) {
        s0 = s, f0 = f;
        if (side == -1) f1 /= 2;
        side = -1;
      } else {
        s1 = s, f1 = f;
        if (side == 1) f0 /= 2;
        side = 1;
      }
    }
    if (!(out.d.signed_upper < HUGE_VAL)) return asked;  // no vertex: its cell is split
    const Eigen::Matrix4d fr = motion_.frame(out.d.t);
    const Eigen::Matrix3d R = fr.block<3, 3>(1, 1);
    const Eigen::Vector3d local = R.transpose() * (out.x - fr.block<3, 1>(1, 0));
    Eigen::Vector3d g;
    // A mesh's nearest triangle lies within the distance the query found: searched only
    // that far (the direction is a hint for the certificate, not a part of it).
    sweep::signed_distance(tree_.body(), local, g,
                           std::abs(out.d.signed_upper) * (1 + 1e-6) + 1e-9 * scale_);
    out.n = R * g;
    return asked;
  }

  /// A leaf passes when every vertex of its triangles is within T (less the rounding e) and
  /// every triangle is clear of V by e. Unchanged triangles that passed are not asked again.
  /// The hull of all its vertices is asked first: the pieces it is clear of, each triangle
  /// in it is too, and the triangles are asked only of the others.
  void certify(Leaf& L) const {
    if (L.ok && L.tris == L.checked) return;
    L.ok = false;
    std::vector<EdgeKey> keys;
    for (const Tri& t : L.tris)
      for (const EdgeKey& e : t) {
        if (!(certified_distance(bound_.at(e).d, scale_) + e_ <= T_)) return;
        keys.push_back(e);
      }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    std::vector<Eigen::Vector3d> pts;
    Eigen::Vector3d m = Eigen::Vector3d::Zero(), n = Eigen::Vector3d::Zero();
    for (const EdgeKey& e : keys) {
      pts.push_back(on_edge(e));
      m += bound_.at(e).n;
    }
    std::vector<std::array<Eigen::Vector3d, 3>> tris(L.tris.size());
    for (std::size_t i = 0; i < tris.size(); ++i) {
      for (int k = 0; k < 3; ++k)
        tris[i][static_cast<std::size_t>(k)] = on_edge(L.tris[i][static_cast<std::size_t>(k)]);
      n += (tris[i][1] - tris[i][0]).cross(tris[i][2] - tris[i][0]);
    }
    const auto unit = [](const Eigen::Vector3d& u, const Eigen::Vector3d& or_else) {
      return u.norm() > 0 ? Eigen::Vector3d(u.normalized()) : or_else;
    };
    n = unit(n, Eigen::Vector3d::UnitZ());
    const auto left = hulls_.unclear(pts, {unit(m, n), n}, e_);
    for (std::size_t i = 0; i < tris.size(); ++i) {
      const auto& p = tris[i];
      const Eigen::Vector3d nt = unit((p[1] - p[0]).cross(p[2] - p[0]), Eigen::Vector3d::UnitZ());
      Eigen::Vector3d mt = Eigen::Vector3d::Zero();
      for (const EdgeKey& e : L.tris[i]) mt += bound_.at(e).n;
      if (!hulls_.clear_of(p, {unit(mt, nt), nt}, e_, left)) return;
    }
    L.checked = L.tris;
    L.ok = true;
  }

  /// The mesh: vertices numbered by their edges in the leaves' order.
  void finish(EnclosingMesh& out) {
    std::unordered_map<EdgeKey, int, EdgeHash> index;
    auto number = [&](const EdgeKey& e) {
      const auto [it, fresh] = index.emplace(e, static_cast<int>(out.vertices.size()));
      if (fresh) {
        out.vertices.push_back(on_edge(e));
        out.at.push_back(bound_.at(e).d);
      }
      return it->second;
    };
    bool inside_point = false;
    out.smallest_cell = HUGE_VAL;
    for (const auto& [k, L] : leaves_) {
      for (const Tri& t : L.tris)
        out.triangles.push_back({number(t[0]), number(t[1]), number(t[2])});
      out.inside_volume = kernel::down(out.inside_volume + L.inside);
      if (L.tris.empty()) continue;
      const double s = static_cast<double>(Octree::size(Octree::level(k))) * octree_.unit();
      out.smallest_cell = std::min(out.smallest_cell, s);
      out.largest_cell = std::max(out.largest_cell, s);
      ++out.cells;
    }
    for (const auto& [k, v] : value_) inside_point = inside_point || v.v < 0;
    if (!sweep::is_convex(tree_.body())) sheets_outside(out);
    if (out.triangles.empty() || !inside_point)
      throw Error(Errc::numerical_failure,
                  "volume: the adaptive mesh found no point of the volume (a body too small "
                  "for the scene?)");
    out.inside_volume = kernel::down(out.inside_volume + deep_volume_);
    out.queries = queries_;
    out.pieces = hulls_.size();
    out.level = tau_;
  }

  /// A mesh body: every triangle is clear of what the body's boundary sweeps, so a point of
  /// one never meets M(t) dB and is inside M(t) B for every t or for none; a connected sheet
  /// of them is outside V when one of its points is outside M(a) B. Each sheet's first
  /// vertex is asked (its distance to the boundary exceeds the certified margin, so the
  /// sign is not a rounding's).
  void sheets_outside(const EnclosingMesh& out) const {
    std::vector<int> root(out.vertices.size());
    for (std::size_t i = 0; i < root.size(); ++i) root[i] = static_cast<int>(i);
    auto find = [&](int v) {
      while (root[static_cast<std::size_t>(v)] != v)
        v = root[static_cast<std::size_t>(v)] =
            root[static_cast<std::size_t>(root[static_cast<std::size_t>(v)])];
      return v;
    };
    for (const auto& t : out.triangles) {
      root[static_cast<std::size_t>(find(t[1]))] = find(t[0]);
      root[static_cast<std::size_t>(find(t[2]))] = find(t[0]);
    }
    for (std::size_t v = 0; v < root.size(); ++v) {
      if (find(static_cast<int>(v)) != static_cast<int>(v)) continue;
      if (!(tree_.placed_distance(out.vertices[v], motion_.a()) > 0))
        throw Error(Errc::numerical_failure,
                    motion_.label() + ": a sheet of the enclosing mesh lies inside the body " +
                        tree_.body().spec + " at the start (its vertex " + std::to_string(v) + ")");
    }
  }

  const qmotion::Motion& motion_;
  const sweep::SweptVolumeTree& tree_;
  const sweep::HullPieces& hulls_;
  double T_, tau_, e_, eps_, scale_;
  Octree octree_;
  struct Value {
    double v = 0;   ///< phi
    double t = 0;   ///< the placement that gave it
    int node = -1;  ///< the time tree's node of that placement
  };
  std::unordered_map<OctKey, Value> value_;
  std::map<OctKey, Leaf> leaves_;
  std::unordered_map<EdgeKey, Bound, EdgeHash> bound_;
  double deep_volume_ = 0;
  std::size_t queries_ = 0;
};

}  // namespace

void refuse_octree(const qmotion::Motion& motion, const Eigen::AlignedBox3d& box, double T) {
  // The finest cell is a root's 2^-14; below about 8 of them the surface has no room.
  const double finest = Mesher::root_edge(box, T) / static_cast<double>(1 << Octree::kFinest);
  if (T < 8 * finest)
    throw Error(Errc::numerical_failure,
                motion.label() + ": the tolerance " + kernel::detail::format_double(T) +
                    " is too fine for the swept volume's extent " +
                    kernel::detail::format_double(box.diagonal().norm()) +
                    " (the octree's finest cell would be " + kernel::detail::format_double(finest) +
                    "): raise --tol");
}

EnclosingMesh adaptive_mesh(const qmotion::Motion& motion, const sweep::SweptVolumeTree& tree,
                            const sweep::HullPieces& hulls, double T,
                            const VolumeRounding& rounding) {
  const Eigen::AlignedBox3d box = tree.bounds();
  const double scale = box.diagonal().norm();
  // Written as float32, a vertex moves by up to e, and so does every point of a triangle
  // (a convex combination of its vertices): the triangles are certified clear of V by e, and
  // the vertices within T - e (docs/guide/volume.md, "What is written is what was
  // certified").
  const double e = rounding.float32 ? float32_written(box, T, rounding) : 0.0;
  if (e > 0.05 * T) refuse_float32(motion, e, T, rounding);
  // Rounded, two vertices of the surface near one corner of a tetrahedron could fall on one
  // point: the corners' values are kept 8 e (then 32 e, 128 e) from the level, which keeps
  // the vertices about that far from the corners; closed_as_written measures it.
  EnclosingMesh m;
  for (int attempt = 0;; ++attempt) {
    const double eps = std::max(1e-6 * T, 8 * e * std::pow(4.0, attempt));
    m = Mesher(motion, tree, hulls, box, T, kLevel * T + e, e, eps).run();
    m.enclosed = enclosed_volume(m.vertices, m.triangles, box.center());
    m.rounding = e;
    if (rounding.float32) {
      round_to_float32(m.vertices, rounding.scale);
      tbb::parallel_for(std::size_t(0), m.vertices.size(),
                        [&](std::size_t v) { m.at[v] = tree.query(m.vertices[v], 0); });
      m.queries += m.vertices.size();
    }
    m.closed = closed_as_written(m.vertices, m.triangles);
    if (m.closed) break;
    if (!rounding.float32 || attempt == 2)
      throw Error(Errc::numerical_failure,
                  motion.label() + ": the adaptive mesh is not closed as written");
  }
  for (const auto& d : m.at)
    m.distance_bound = std::max(m.distance_bound, certified_distance(d, scale));
  if (!(m.distance_bound <= T))
    throw Error(Errc::numerical_failure, motion.label() +
                                             ": a vertex lies farther than the tolerance " +
                                             kernel::detail::format_double(T) + " (" +
                                             kernel::detail::format_double(m.distance_bound) + ")");
  return m;
}

}  // namespace qmotion::sweep::mesher
