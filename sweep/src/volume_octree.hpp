// sweep/src/volume_octree.hpp: the balanced octree of the adaptive enclosing mesh and its
// conforming tetrahedra (docs/guide/volume.md, "The adaptive mesh").
//
// Cells are addressed by integers: a root cell is 2^15 units, a cell of level l is 2^(15-l),
// the finest (level 14) 2 units, so every cell's centre and its faces' centres are points of
// the unit lattice. The tree is kept 2:1 balanced across faces, edges and corners, and every
// leaf is cut into tetrahedra from its centre to its faces: a face whose neighbour is finer
// into four squares, else one; each square fanned from its centre to its corners and to the
// midpoints of its sides that are corners of a leaf. A face is cut the same way seen from
// both sides (the squares of two neighbours match, and the midpoints depend only on the
// leaves about them), so the tetrahedra form one complex without hanging vertices. (Kuhn's
// six tetrahedra in leaves whose neighbours are all of their level made more triangles: the
// fans sample phi at the faces' and the cell's centres too, so the cells can be larger.)
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace qmotion::sweep::mesher {

using OctKey = std::uint64_t;
using OctPoint = std::array<long, 3>;

class Octree {
 public:
  static constexpr int kLevels = 15;  ///< a root cell is 2^kLevels units
  static constexpr int kFinest = kLevels - 1;
  enum class Kind : std::uint8_t { unknown, far, deep, near };
  struct Cell {
    Kind kind = Kind::unknown;
    int node = -1;  ///< the time tree's node of its centre's query (its parent's until then)
  };

  /// Roots of edge `root` from `origin`, n[a] of them along each axis (n[a] <= 32).
  Octree(const Eigen::Vector3d& origin, double root, const std::array<long, 3>& n);

  static OctKey cell_key(int level, long i, long j, long k) {
    return (OctKey(level) << 60) | (OctKey(i) << 40) | (OctKey(j) << 20) | OctKey(k);
  }
  static int level(OctKey c) { return static_cast<int>(c >> 60); }
  static long size(int level) { return 1L << (kLevels - level); }
  /// The cell's lowest corner, in units.
  static OctPoint corner(OctKey c) {
    const long s = size(level(c)), m = (1L << 20) - 1;
    return {static_cast<long>(c >> 40 & m) * s, static_cast<long>(c >> 20 & m) * s,
            static_cast<long>(c & m) * s};
  }
  static OctKey vertex_key(const OctPoint& p) {
    return (OctKey(p[0]) << 42) | (OctKey(p[1]) << 21) | OctKey(p[2]);
  }
  /// vertex_key's point.
  static OctPoint vertex_point(OctKey k) {
    const OctKey m = (OctKey(1) << 21) - 1;
    return {static_cast<long>(k >> 42 & m), static_cast<long>(k >> 21 & m),
            static_cast<long>(k & m)};
  }
  Eigen::Vector3d position(const OctPoint& p) const {
    return origin_ + unit_ * Eigen::Vector3d(static_cast<double>(p[0]), static_cast<double>(p[1]),
                                             static_cast<double>(p[2]));
  }
  double unit() const { return unit_; }
  /// The largest power of two (in units, at most a root's edge) that divides p's coordinates.
  static long alignment(const OctPoint& p);

  const std::unordered_map<OctKey, Cell>& leaves() const { return leaves_; }
  Cell& cell(OctKey c) { return leaves_.at(c); }

  static constexpr OctKey kNone = ~OctKey(0);
  /// The leaf holding the unit cube whose lowest corner is p (kNone when p is outside);
  /// `hint`, the level looked at first.
  OctKey find(const OctPoint& p, int hint) const;
  /// Replaces a leaf by its eight children (of the parent's kind when it is far or deep,
  /// else unknown), appended to `made` when given.
  void split(OctKey c, std::vector<OctKey>* made = nullptr);
  /// The cells split since the last call.
  std::vector<OctKey> take_split() { return std::exchange(split_, {}); }
  /// Appends the leaves whose tetrahedra a split of x may change: its children that are
  /// leaves, and the leaves beside it no finer than it (a finer leaf's faces and edges see
  /// only cells of its level or finer, which x's children are not).
  void touching(OctKey x, std::vector<OctKey>& out) const;
  /// Splits leaves until every leaf's 26 neighbours are at most one level coarser, given
  /// that only the leaves in `work` (and those split for them) may be out of balance.
  void balance(std::vector<OctKey> work);

  /// A tetrahedron by its corners, in units.
  using Tet = std::array<OctPoint, 4>;
  /// The tetrahedra of a leaf (see the file's comment), appended to out.
  void tets(OctKey c, std::vector<Tet>& out) const;

 private:
  /// The lowest corner of the cell of edge s beside the one at o in direction d (0 to 26,
  /// 13 the cell itself: d % 3, d / 3 % 3, d / 9 along the axes, 1 for none).
  static OctPoint beside(const OctPoint& o, long s, int d) {
    return {o[0] + (d % 3 - 1) * s, o[1] + (d / 3 % 3 - 1) * s, o[2] + (d / 9 - 1) * s};
  }
  bool inside(const OctPoint& p) const {
    for (int a = 0; a < 3; ++a)
      if (p[a] < 0 || p[a] >= extent_[a]) return false;
    return true;
  }
  /// Whether the leaf about p (see find) is finer than level l.
  bool finer_at(const OctPoint& p, int l) const {
    if (!inside(p)) return false;
    const OctKey c = find(p, l + 1);
    return c != kNone && level(c) > l;
  }

  Eigen::Vector3d origin_;
  double unit_;
  long extent_[3];
  std::unordered_map<OctKey, Cell> leaves_;
  std::vector<OctKey> split_;
};

}  // namespace qmotion::sweep::mesher
