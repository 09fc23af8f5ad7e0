// api/src/volume_lattice.cpp: the lattice route of the enclosing mesh of `volume`, for
// bodies that are not convex (detail::lattice_mesh; docs/geometry.md, "Swept volumes").
//
// A lower bound F of the distance to V at the vertices of a cubic lattice (a branch and
// bound over sweep::SweptVolumeTree), its piecewise-linear interpolant g over the six Kuhn
// tetrahedra of every cube, and the surface g = tau (marching tetrahedra) with tau above the
// tetrahedra's circumradius h sqrt(3) / 2:
// - for q in V inside a tetrahedron with vertices v_i and barycentric weights l_i,
//   g(q) = sum l_i F(v_i) <= sum l_i f(v_i) <= sum l_i |v_i - q| <= sqrt(sum l_i |v_i - q|^2)
//   <= the circumradius (f is 1-Lipschitz and 0 on V; the last sum is R^2 - |q - centre|^2),
//   so V lies in { g < tau }: the mesh encloses V;
// - a level set of a piecewise-linear function at a value no vertex takes is a closed
//   2-manifold, and its pieces lie in disjoint tetrahedra: no self-intersection;
// - each output vertex's distance to V is bounded by placing the body at one parameter (an
//   upper bound of f); the largest is the certified distance bound, and the lattice is made
//   finer until it is within the tolerance.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <qmotion/api/volume.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/swept_volume.hpp>
#include <string>
#include <utility>
#include <vector>

#include "edge_index.hpp"
#include "volume_detail.hpp"

namespace qmotion::detail {
namespace {

constexpr int kBlock = 8;  // lattice vertices per block edge
static_assert(kBlock == 8, "fill takes octants of 4^3 vertices, and their cubes of 2^3");
/// How far below the exact minimum over a batch's leaves a vertex's bound may stop, in tau.
constexpr double kSlack = 0.05;
constexpr double kSqrt3 = 1.7320508075688772;
constexpr double kPi = 3.14159265358979323846;

/// The lattice: vertices origin + h (i, j, k), 0 <= i < n[0], ...; blocks of 8^3 vertices.
class Lattice {
 public:
  enum class Kind : std::uint8_t { far, deep, near };
  struct Block {
    Kind kind = Kind::near;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double lower = 0, depth = 0;  // at the centre
    int node = -1;                // the tree's best placement for the centre
    std::vector<double> value;    // near: F at the 512 vertices
    std::vector<float> depth_at;  // near: certified depth inside V (0 outside)
    std::vector<int> node_at;     // near: the tree's best placement found for the vertex
  };

  /// eps: how far from tau a vertex's value is kept (at least 1e-7 h).
  Lattice(const sweep::SweptVolumeTree& tree, const Eigen::AlignedBox3d& box, double h, double tau,
          double eps)
      : tree_(tree),
        box_(box),
        h_(h),
        tau_(tau),
        eps_(std::max(1e-7 * h, eps)),
        far_(tau + kSqrt3 * h + tree.largest_leaf_delta() + kSlack * tau + 2 * eps_),
        stop_depth_(1.01 * kSqrt3 * h) {
    const double pad = tau + 3 * h;
    origin_ = box.min() - Eigen::Vector3d::Constant(pad);
    for (int a = 0; a < 3; ++a) {
      const double n = std::ceil((box.max()(a) - box.min()(a) + 2 * pad) / h) + 1;
      if (!(n < 1e6))
        throw Error(Errc::numerical_failure, "volume: the tolerance is too fine for a lattice");
      n_[a] = static_cast<long>(n);
      nb_[a] = (n_[a] + kBlock - 1) / kBlock;
    }
    const double blocks = static_cast<double>(nb_[0]) * nb_[1] * nb_[2];
    if (blocks > 8e6)
      throw Error(Errc::numerical_failure,
                  "volume: the tolerance is too fine: the lattice would have " +
                      kernel::detail::format_double(blocks) + " blocks");
    blocks_.resize(static_cast<std::size_t>(blocks));
  }

  /// Classifies every block, then evaluates the near ones. A block is deep when a query
  /// finds its cells inside V, far when its vertices' bounds reach far_ (so none is a
  /// neighbour of an inside vertex: the surface's vertices interpolate evaluated values
  /// only), and near otherwise. Regions of 8^3 blocks are settled by one query at
  /// their centre when they are all deep or all far, else their octants, down to one block.
  void evaluate(std::atomic<std::size_t>& queries) {
    constexpr long kRegion = 8;  // blocks per region edge
    const long nr[3] = {(nb_[0] + kRegion - 1) / kRegion, (nb_[1] + kRegion - 1) / kRegion,
                        (nb_[2] + kRegion - 1) / kRegion};
    tbb::parallel_for(std::size_t(0), static_cast<std::size_t>(nr[0] * nr[1] * nr[2]),
                      [&](std::size_t g) {
                        const long l = static_cast<long>(g);
                        classify(l / (nr[1] * nr[2]) * kRegion, (l / nr[2]) % nr[1] * kRegion,
                                 l % nr[2] * kRegion, kRegion, queries);
                      });
    std::size_t near = 0;
    for (const auto& B : blocks_) near += B.kind == Kind::near;
    if (near > 100000)
      throw Error(Errc::numerical_failure,
                  "volume: the tolerance is too fine for the memory: " + std::to_string(near) +
                      " lattice blocks of 512 vertices near the surface");
    tbb::parallel_for(std::size_t(0), blocks_.size(), [&](std::size_t b) {
      Block& B = blocks_[b];
      if (B.kind != Kind::near) return;
      B.value.resize(kBlock * kBlock * kBlock);
      B.depth_at.resize(kBlock * kBlock * kBlock);
      B.node_at.resize(kBlock * kBlock * kBlock);
      const auto [bi, bj, bk] = block_index(b);
      std::size_t asked = 0;
      // The block's own query (above) found it neither deep nor far: its octants next.
      constexpr int half = kBlock / 2;
      for (int o = 0; o < 8; ++o)
        fill(B, bi * kBlock + (o & 1) * half, bj * kBlock + (o >> 1 & 1) * half,
             bk * kBlock + (o >> 2 & 1) * half, asked);
      queries += asked;
    });
  }

  /// Classifies the blocks (bi, bj, bk) + [0, size)^3 by a query at the centre of their
  /// vertices (see evaluate()): each block's bounds are the centre's, less its distance.
  void classify(long bi, long bj, long bk, long size, std::atomic<std::size_t>& queries) {
    if (bi >= nb_[0] || bj >= nb_[1] || bk >= nb_[2]) return;
    const double r = 0.5 * (kBlock - 1) * kSqrt3 * h_;        // block centre to its vertex
    const double r_cells = 0.5 * (kBlock + 1) * kSqrt3 * h_;  // block centre to a cell's corner
    const double spread = 0.5 * static_cast<double>((size - 1) * kBlock) * kSqrt3 * h_;
    const Eigen::Vector3d c =
        position(bi * kBlock, bj * kBlock, bk * kBlock) +
        Eigen::Vector3d::Constant(0.5 * static_cast<double>(size * kBlock - 1) * h_);
    const auto d = tree_.query(c, -(spread + r_cells));
    ++queries;
    const double lower = std::max(d.lower, box_distance(c));
    const double depth = d.signed_upper < 0 ? -d.signed_upper : 0;
    if (size == 1 || depth >= spread + r_cells || lower - spread - r >= far_) {
      for (long a = bi; a < std::min(bi + size, nb_[0]); ++a)
        for (long b = bj; b < std::min(bj + size, nb_[1]); ++b)
          for (long e = bk; e < std::min(bk + size, nb_[2]); ++e) {
            Block& B = blocks_[static_cast<std::size_t>((a * nb_[1] + b) * nb_[2] + e)];
            B.centre = position(a * kBlock, b * kBlock, e * kBlock) +
                       Eigen::Vector3d::Constant(0.5 * (kBlock - 1) * h_);
            const double to = (B.centre - c).norm();
            B.lower = lower - to;
            B.depth = std::max(0.0, depth - to);
            B.node = d.node;
            if (B.depth >= r_cells)
              B.kind = Kind::deep;
            else if (B.lower - r >= far_)
              B.kind = Kind::far;
            else
              B.kind = Kind::near;
          }
      return;
    }
    const long half = size / 2;
    for (int o = 0; o < 8; ++o)
      classify(bi + (o & 1) * half, bj + (o >> 1 & 1) * half, bk + (o >> 2 & 1) * half, half,
               queries);
  }

  /// The values of the 4^3 vertices from (i, j, k) on. One query at their centre settles
  /// them all when they are all far out (as blocks are) or all deep inside V. Else one search
  /// of the tree at the centre finds the leaves that can matter to any of them
  /// (SweptVolumeTree::candidates); each cube of 2^3 narrows that list to its own ball
  /// (SweptVolumeTree::narrow), which settles it when it is far or deep, and its vertices
  /// take their bounds from what is left (SweptVolumeTree::query_among).
  void fill(Block& B, long i, long j, long k, std::size_t& asked) const {
    constexpr int s = kBlock / 2;
    const double r = 0.5 * (s - 1) * kSqrt3 * h_;
    const Eigen::Vector3d c = position(i, j, k) + Eigen::Vector3d::Constant(0.5 * (s - 1) * h_);
    const auto d = tree_.query(c, -r);
    ++asked;
    const double lower = std::max(d.lower, box_distance(c));
    const double depth = d.signed_upper < 0 ? -d.signed_upper : 0;
    if (depth >= r || lower - r >= far_) {
      for (long a = i; a < i + s; ++a)
        for (long b = j; b < j + s; ++b)
          for (long e = k; e < k + s; ++e) {
            const double to = (position(a, b, e) - c).norm();
            set(B, a, b, e, depth >= r ? 0.0 : lower - to, depth - to, d.node);
          }
      return;
    }
    thread_local sweep::SweptVolumeTree::Candidates wide, near;
    tree_.candidates(c, r * (1 + 1e-12), wide);
    ++asked;
    // A cube of 2^3 is deep when its vertices lie deeper than a cube's diagonal (so that the
    // inner volume's bound loses nothing).
    const double r2 = 0.5 * kSqrt3 * h_, deep = r2 + stop_depth_;
    for (int o = 0; o < 8; ++o) {
      const long i2 = i + (o & 1) * 2, j2 = j + (o >> 1 & 1) * 2, k2 = k + (o >> 2 & 1) * 2;
      const Eigen::Vector3d c2 = position(i2, j2, k2) + Eigen::Vector3d::Constant(0.5 * h_);
      tree_.narrow(wide, c2, r2, near);
      ++asked;
      const bool settled = near.best <= -deep || near.lower >= far_;
      for (long a = i2; a < i2 + 2; ++a)
        for (long b = j2; b < j2 + 2; ++b)
          for (long e = k2; e < k2 + 2; ++e) {
            const Eigen::Vector3d x = position(a, b, e);
            if (settled) {
              set(B, a, b, e, near.best < 0 ? 0.0 : near.lower, -near.best - (x - c2).norm(),
                  near.best_node);
              continue;
            }
            const auto v = tree_.query_among(x, near, kSlack * tau_, stop_depth_);
            ++asked;
            set(B, a, b, e, std::max(v.lower, box_distance(x)), -v.signed_upper, v.node);
          }
    }
  }

  /// Records a near block's vertex: its lower bound, a depth inside V (kept when positive,
  /// less a relative 1e-6 for the float), and the tree's best placement for it.
  void set(Block& B, long a, long b, long e, double value, double depth, int node) const {
    const int l = local(a, b, e);
    B.value[l] = value;
    B.depth_at[l] = depth > 0 ? static_cast<float>(depth * (1 - 1e-6)) : 0.0f;
    B.node_at[l] = node;
  }

  /// F at a vertex, moved below tau - eps when within eps of tau (lowering keeps it a lower
  /// bound of the distance; no vertex then sits on the level).
  double value(long i, long j, long k) const {
    const Block& B = block(i, j, k);
    double v;
    switch (B.kind) {
      case Kind::deep:
        v = 0;
        break;
      case Kind::far:
        v = B.lower - (position(i, j, k) - B.centre).norm();
        break;
      default:
        v = B.value[local(i, j, k)];
    }
    return v < tau_ + eps_ ? std::min(v, tau_ - eps_) : v;
  }

  /// A certified depth inside V at a vertex (0: none known).
  double depth(long i, long j, long k) const {
    const Block& B = block(i, j, k);
    switch (B.kind) {
      case Kind::deep:
        return B.depth - (position(i, j, k) - B.centre).norm();
      case Kind::far:
        return 0;
      default:
        return B.depth_at[local(i, j, k)];
    }
  }

  /// The tree's node whose placement was nearest a vertex, of those its query saw.
  int node(long i, long j, long k) const {
    const Block& B = block(i, j, k);
    return B.kind == Kind::near ? B.node_at[local(i, j, k)] : B.node;
  }

  Eigen::Vector3d position(long i, long j, long k) const {
    return origin_ + h_ * Eigen::Vector3d(static_cast<double>(i), static_cast<double>(j),
                                          static_cast<double>(k));
  }

  const long* n() const { return n_; }
  const long* blocks_per_axis() const { return nb_; }
  Kind kind(long bi, long bj, long bk) const {
    if (bi >= nb_[0] || bj >= nb_[1] || bk >= nb_[2]) return Kind::far;
    return blocks_[static_cast<std::size_t>((bi * nb_[1] + bj) * nb_[2] + bk)].kind;
  }
  double tau() const { return tau_; }
  double h() const { return h_; }

 private:
  std::array<long, 3> block_index(std::size_t b) const {
    const long l = static_cast<long>(b);
    return {l / (nb_[1] * nb_[2]), (l / nb_[2]) % nb_[1], l % nb_[2]};
  }
  const Block& block(long i, long j, long k) const {
    return blocks_[static_cast<std::size_t>(((i / kBlock) * nb_[1] + j / kBlock) * nb_[2] +
                                            k / kBlock)];
  }
  static int local(long i, long j, long k) {
    return static_cast<int>((i % kBlock) * 64 + (j % kBlock) * 8 + k % kBlock);
  }
  /// The distance from x to the box that holds V: a lower bound of the distance to V.
  double box_distance(const Eigen::Vector3d& x) const {
    return (x - x.cwiseMax(box_.min()).cwiseMin(box_.max())).norm();
  }

  const sweep::SweptVolumeTree& tree_;
  Eigen::AlignedBox3d box_;
  double h_, tau_, eps_;
  /// A vertex whose lower bound is at least far_ is "far": its true distance exceeds tau by
  /// more than a Kuhn edge (h sqrt(3)) plus how far below it a near vertex's bound may lie
  /// (a leaf's radius, and kSlack tau), so no near vertex next to it falls below tau.
  double far_;
  double stop_depth_;  ///< a vertex deeper in V than a cube's diagonal needs no more search
  Eigen::Vector3d origin_;
  long n_[3] = {0, 0, 0}, nb_[3] = {0, 0, 0};
  std::vector<Block> blocks_;
};

/// A volume of V certainly inside a lattice cube of edge h that has a vertex at depth d in V
/// (the ball of radius d about that vertex lies in V): the ball's octant when d <= h, the
/// cube [0, d / sqrt(3)]^3 the ball holds, the whole cube from d >= h sqrt(3).
double inside_part(double d, double h) {
  if (!(d > 0)) return 0;
  const double a = std::min(d, h), b = std::min(d / kSqrt3, h);
  return std::max(kPi / 6 * a * a * a, b * b * b);
}

struct Surface {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 2>> near;  ///< the tree's best nodes for the edge's two ends
  std::vector<std::uint64_t> edge;       ///< the lattice edge a vertex lies on (EdgeIndex key)
  std::vector<std::array<int, 3>> triangles;
  double inside_volume = 0;  ///< of the lattice cubes certified inside V
};

/// Marching tetrahedra over the cubes of the blocks bi in [row0, row1) that the level
/// crosses (six Kuhn tetrahedra per cube, around its diagonal from corner 0 to corner 7).
/// An edge's key is 8 times its lower end's lattice index plus the axes it spans (bits).
Surface extract_rows(const Lattice& L, long row0, long row1) {
  Surface s;
  const long* n = L.n();
  const long* nb = L.blocks_per_axis();
  const double tau = L.tau(), h = L.h();
  EdgeIndex on_edge;
  auto gid = [&](long i, long j, long k) {
    return static_cast<std::uint64_t>((i * n[1] + j) * n[2] + k);
  };
  static const int kuhn[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                                 {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  const double cell = h * h * h;
  std::vector<double> value((kBlock + 1) * (kBlock + 1) * (kBlock + 1)), depth(value.size());
  for (long bi = row0; bi < row1; ++bi)
    for (long bj = 0; bj < nb[1]; ++bj)
      for (long bk = 0; bk < nb[2]; ++bk) {
        const auto own = L.kind(bi, bj, bk);
        bool uniform = own != Lattice::Kind::near;
        for (int c = 1; c < 8 && uniform; ++c)
          uniform = L.kind(bi + (c & 1), bj + (c >> 1 & 1), bk + (c >> 2 & 1)) == own;
        if (uniform) {
          if (own == Lattice::Kind::deep) s.inside_volume += cell * kBlock * kBlock * kBlock;
          continue;
        }
        // The block's vertices and the next ones on its far sides, looked up once.
        constexpr int m = kBlock + 1;
        const long i0 = bi * kBlock, j0 = bj * kBlock, k0 = bk * kBlock;
        const long i1 = std::min(i0 + kBlock, n[0] - 1), j1 = std::min(j0 + kBlock, n[1] - 1),
                   k1 = std::min(k0 + kBlock, n[2] - 1);
        for (long i = i0; i <= i1; ++i)
          for (long j = j0; j <= j1; ++j)
            for (long k = k0; k <= k1; ++k) {
              const int l = static_cast<int>(((i - i0) * m + (j - j0)) * m + (k - k0));
              value[l] = L.value(i, j, k);
              depth[l] = L.depth(i, j, k);
            }
        for (long i = i0; i < i1; ++i)
          for (long j = j0; j < j1; ++j)
            for (long k = k0; k < k1; ++k) {
              double v[8];
              int inside = 0;
              double deepest = 0;
              const int l0 = static_cast<int>(((i - i0) * m + (j - j0)) * m + (k - k0));
              for (int c = 0; c < 8; ++c) {
                const int l = l0 + ((c & 1) * m + (c >> 1 & 1)) * m + (c >> 2 & 1);
                v[c] = value[l];
                inside += v[c] < tau;
                deepest = std::max(deepest, depth[l]);
              }
              s.inside_volume += inside_part(deepest, h);
              if (inside == 0 || inside == 8) continue;
              auto corner = [&](int c) {
                return L.position(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1));
              };
              // The surface's vertex on the edge from corner a to corner b (b's bits hold a's).
              auto vertex = [&](int a, int b) {
                const int lo = (a & b) == a ? a : b, hi = lo == a ? b : a;
                const std::uint64_t key =
                    gid(i + (lo & 1), j + (lo >> 1 & 1), k + (lo >> 2 & 1)) * 8 +
                    static_cast<std::uint64_t>(lo ^ hi);
                const auto [it, fresh] = on_edge.try_emplace(key);
                if (fresh) {
                  const double s0 = (tau - v[lo]) / (v[hi] - v[lo]);
                  *it = static_cast<int>(s.vertices.size());
                  s.vertices.push_back(corner(lo) + s0 * (corner(hi) - corner(lo)));
                  s.near.push_back({L.node(i + (lo & 1), j + (lo >> 1 & 1), k + (lo >> 2 & 1)),
                                    L.node(i + (hi & 1), j + (hi >> 1 & 1), k + (hi >> 2 & 1))});
                  s.edge.push_back(key);
                }
                return *it;
              };
              // Appends (a, b, c), or (a, c, b), whichever faces from `in` towards `out`.
              auto triangle = [&](int a, int b, int c, const Eigen::Vector3d& toward) {
                const Eigen::Vector3d &pa = s.vertices[a], &pb = s.vertices[b], &pc = s.vertices[c];
                if ((pb - pa).cross(pc - pa).dot(toward) >= 0)
                  s.triangles.push_back({a, b, c});
                else
                  s.triangles.push_back({a, c, b});
              };
              for (const auto& t : kuhn) {
                int in[4], out[4], ni = 0, no = 0;
                for (int c : t) (v[c] < tau ? in[ni++] : out[no++]) = c;
                if (ni == 0 || no == 0) continue;
                const Eigen::Vector3d toward = corner(out[0]) - corner(in[0]);
                if (ni == 1) {
                  triangle(vertex(in[0], out[0]), vertex(in[0], out[1]), vertex(in[0], out[2]),
                           toward);
                } else if (ni == 3) {
                  triangle(vertex(in[0], out[0]), vertex(in[1], out[0]), vertex(in[2], out[0]),
                           toward);
                } else {  // a quadrilateral: i0o0, i0o1, i1o1, i1o0 in turn
                  const int a = vertex(in[0], out[0]), b = vertex(in[0], out[1]),
                            c = vertex(in[1], out[1]), d = vertex(in[1], out[0]);
                  const Eigen::Vector3d &pa = s.vertices[a], &pb = s.vertices[b],
                                        &pc = s.vertices[c], &pd = s.vertices[d];
                  const Eigen::Vector3d normal =
                      (pb - pa).cross(pc - pa) + (pc - pa).cross(pd - pa);
                  if (normal.dot(toward) >= 0) {
                    s.triangles.push_back({a, b, c});
                    s.triangles.push_back({a, c, d});
                  } else {
                    s.triangles.push_back({a, c, b});
                    s.triangles.push_back({a, d, c});
                  }
                }
              }
            }
      }
  return s;
}

/// The surface over the whole lattice: rows of blocks in parallel, then joined in order.
/// A vertex on an edge in the plane between two parts' rows is made by both: the later part's
/// copy becomes the earlier one's.
Surface extract(const Lattice& L) {
  const long rows = L.blocks_per_axis()[0];
  const long* n = L.n();
  std::vector<Surface> parts(static_cast<std::size_t>(rows));
  tbb::parallel_for(long(0), rows, [&](long r) {
    parts[static_cast<std::size_t>(r)] = extract_rows(L, r, r + 1);
  });
  // Where each part's vertices go: the next free index, or the earlier part's copy.
  std::vector<std::vector<int>> to(parts.size());
  std::vector<std::size_t> triangles_before(parts.size() + 1, 0);
  int count = 0;
  EdgeIndex shared;  // the previous part's vertices on its last plane, by edge
  for (long r = 0; r < rows; ++r) {
    const Surface& p = parts[static_cast<std::size_t>(r)];
    std::vector<int>& t = to[static_cast<std::size_t>(r)];
    t.resize(p.vertices.size());
    EdgeIndex last;
    for (std::size_t v = 0; v < p.vertices.size(); ++v) {
      const std::uint64_t key = p.edge[v];
      const long i = static_cast<long>(key / 8 / static_cast<std::uint64_t>(n[1] * n[2]));
      const bool in_plane = (key & 1) == 0;  // the edge does not span the first axis
      const int* earlier = r > 0 && in_plane && i == r * kBlock ? shared.find(key) : nullptr;
      t[v] = earlier ? -1 - *earlier : count++;
      if (in_plane && i == (r + 1) * kBlock) *last.try_emplace(key).first = t[v];
    }
    triangles_before[static_cast<std::size_t>(r) + 1] =
        triangles_before[static_cast<std::size_t>(r)] + p.triangles.size();
    shared = std::move(last);
  }
  Surface out;
  out.vertices.resize(static_cast<std::size_t>(count));
  out.near.resize(static_cast<std::size_t>(count));
  out.triangles.resize(triangles_before.back());
  tbb::parallel_for(std::size_t(0), parts.size(), [&](std::size_t r) {
    const Surface& p = parts[r];
    const std::vector<int>& t = to[r];
    auto index = [&](int v) {
      return t[static_cast<std::size_t>(v)] < 0 ? -1 - t[static_cast<std::size_t>(v)]
                                                : t[static_cast<std::size_t>(v)];
    };
    for (std::size_t v = 0; v < p.vertices.size(); ++v)
      if (t[v] >= 0) {
        out.vertices[static_cast<std::size_t>(t[v])] = p.vertices[v];
        out.near[static_cast<std::size_t>(t[v])] = p.near[v];
      }
    std::size_t at = triangles_before[r];
    for (const auto& tr : p.triangles)
      out.triangles[at++] = {index(tr[0]), index(tr[1]), index(tr[2])};
  });
  for (const auto& p : parts) out.inside_volume += p.inside_volume;
  return out;
}

}  // namespace

EnclosingMesh lattice_mesh(const Motion& motion, const sweep::SweptVolumeTree& tree, double T,
                           const VolumeRounding& rounding) {
  EnclosingMesh out;
  const Eigen::AlignedBox3d box = tree.bounds();
  const double scale = box.diagonal().norm();
  std::atomic<std::size_t> queries{0};
  // The vertices sit near the level tau = h sqrt(3) / 2, plus up to twice the leaves' radius
  // (0.1 T) where the lower bound is loose; measured, about 1.2 tau. Start with tau = 0.72 T
  // and make the lattice finer while a vertex's bound exceeds T.
  double h = 2 * 0.72 * T / kSqrt3;
  double eps_factor = 4;  // see float32 below
  for (out.rounds = 1;; ++out.rounds) {
    // Written as float32, a vertex moves by up to e (float32_rounding): the mesh is made to
    // enclose V grown by e (the level rises by e), so that the rounded mesh, every point of
    // which moves by at most e, still winds once around every point of V. eps keeps the
    // vertices' values that far from the level that no two vertices round to one point
    // (docs/guide/volume.md, "What is written is what was certified"); closed_as_written
    // measures it, and a round that fails it is made again with a wider eps.
    const double e = rounding.float32 ? float32_written(box, T, h, rounding) : 0.0;
    const double tau = 0.5 * kSqrt3 * h * (1 + 1e-9) + 1e-12 * scale + e;
    const double eps = eps_factor * e * (2.2 * h + tree.largest_leaf_delta()) / h;
    if (eps > 0.1 * h) refuse_float32(motion, e, T, rounding);
    Lattice lattice(tree, box, h, tau, eps);
    lattice.evaluate(queries);
    Surface s = extract(lattice);
    refuse_size(motion, T, s.triangles.size());
    // The mesh before rounding encloses V and is embedded: its volume bounds V's.
    const double enclosed = enclosed_volume(s.vertices, s.triangles, box.center());
    if (rounding.float32) round_to_float32(s.vertices, rounding.scale);
    const bool closed = closed_as_written(s.vertices, s.triangles);
    if (!closed && rounding.float32 && out.rounds < 4) {
      eps_factor *= 4;
      continue;
    }
    // Each vertex's distance to V, bounded from above by the best placement the tree finds.
    // The placements nearest the edge's ends come first: one within 0.85 T settles the
    // vertex; else the tree is searched.
    std::vector<sweep::VolumeDistance> at(s.vertices.size());
    std::atomic<std::size_t> searched{0};
    tbb::parallel_for(std::size_t(0), s.vertices.size(), [&](std::size_t v) {
      sweep::VolumeDistance& d = at[v];
      for (const int i : s.near[v])
        if (i >= 0) {
          const double sd = tree.node_distance(s.vertices[v], i);
          if (sd < d.signed_upper) {
            d.signed_upper = sd;
            d.node = i;
          }
        }
      if (d.signed_upper <= 0.85 * T) {
        tree.found_at(d, d.node);
      } else {
        d = tree.query(s.vertices[v], -HUGE_VAL);
        ++searched;
      }
    });
    queries += searched;
    double bound = 0;
    for (const auto& d : at) bound = std::max(bound, std::max(d.signed_upper, 0.0));
    // Rounding of the placement and the distance: relative 1e-12 of the scene.
    bound += 1e-12 * scale;
    if (bound <= T || out.rounds == 4) {
      if (bound > T)
        throw Error(Errc::numerical_failure,
                    motion.label() + ": no lattice brought every vertex within the tolerance " +
                        kernel::detail::format_double(T) + " (best " +
                        kernel::detail::format_double(bound) + ")");
      out.vertices = std::move(s.vertices);
      out.triangles = std::move(s.triangles);
      out.at = std::move(at);
      out.distance_bound = bound;
      out.enclosed = enclosed;
      out.inside_volume = s.inside_volume;
      out.rounding = e;
      out.level = tau;
      out.smallest_cell = out.largest_cell = h;
      out.closed = closed;
      out.queries = queries;
      return out;
    }
    h *= 0.85 * std::min(1.0, T / bound);
  }
}

}  // namespace qmotion::detail
