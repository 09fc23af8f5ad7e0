// sweep/src/volume_octree.cpp: the balanced octree and its conforming tetrahedra
// (volume_octree.hpp).
#include "volume_octree.hpp"

#include <utility>

namespace qmotion::sweep::mesher {

Octree::Octree(const Eigen::Vector3d& origin, double root, const std::array<long, 3>& n)
    : origin_(origin), unit_(root / static_cast<double>(size(0))) {
  for (int a = 0; a < 3; ++a) extent_[a] = n[static_cast<std::size_t>(a)] * size(0);
  for (long i = 0; i < n[0]; ++i)
    for (long j = 0; j < n[1]; ++j)
      for (long k = 0; k < n[2]; ++k) leaves_.emplace(cell_key(0, i, j, k), Cell{});
}

long Octree::alignment(const OctPoint& p) {
  const unsigned long bits = static_cast<unsigned long>(p[0] | p[1] | p[2]) | (1UL << kLevels);
  return static_cast<long>(bits & (~bits + 1));
}

OctKey Octree::find(const OctPoint& p, int hint) const {
  if (!inside(p)) return kNone;
  auto at = [&](int l) {
    const int shift = kLevels - l;
    const OctKey k = cell_key(l, p[0] >> shift, p[1] >> shift, p[2] >> shift);
    return leaves_.count(k) ? k : kNone;
  };
  for (const int l : {hint, hint + 1, hint - 1})
    if (l >= 0 && l <= kFinest)
      if (const OctKey k = at(l); k != kNone) return k;
  for (int l = 0; l <= kFinest; ++l)
    if (const OctKey k = at(l); k != kNone) return k;
  return kNone;
}

void Octree::split(OctKey c, std::vector<OctKey>* made) {
  const int l = level(c);
  const Cell parent = leaves_.at(c);
  const Kind kind = parent.kind;
  leaves_.erase(c);
  split_.push_back(c);
  const OctPoint o = corner(c);
  const long s = size(l + 1);
  for (int q = 0; q < 8; ++q) {
    const OctKey child =
        cell_key(l + 1, o[0] / s + (q & 1), o[1] / s + (q >> 1 & 1), o[2] / s + (q >> 2 & 1));
    Cell cell;
    cell.kind = kind == Kind::far || kind == Kind::deep ? kind : Kind::unknown;
    cell.node = parent.node;
    leaves_.emplace(child, cell);
    if (made) made->push_back(child);
  }
}

void Octree::touching(OctKey x, std::vector<OctKey>& out) const {
  const int l = level(x);
  const long s = size(l);
  const OctPoint o = corner(x);
  for (int q = 0; q < 8; ++q) {
    const OctKey child = cell_key(l + 1, o[0] / (s / 2) + (q & 1), o[1] / (s / 2) + (q >> 1 & 1),
                                  o[2] / (s / 2) + (q >> 2 & 1));
    if (leaves_.count(child)) out.push_back(child);
  }
  for (int d = 0; d < 27; ++d) {
    if (d == 13) continue;
    const OctKey n = find(beside(o, s, d), l);
    if (n != kNone && level(n) <= l) out.push_back(n);
  }
}

void Octree::balance(std::vector<OctKey> work) {
  while (!work.empty()) {
    const OctKey c = work.back();
    work.pop_back();
    if (!leaves_.count(c)) continue;
    const int l = level(c);
    if (l < 2) continue;
    const long s = size(l);
    const OctPoint o = corner(c);
    for (int d = 0; d < 27; ++d) {
      if (d == 13) continue;  // the cell itself
      const OctKey n = find(beside(o, s, d), l - 1);
      if (n != kNone && level(n) < l - 1) {
        split(n, &work);
        work.push_back(c);
        break;
      }
    }
  }
}

void Octree::tets(OctKey c, std::vector<Tet>& out) const {
  const int l = level(c);
  const long s = size(l), h = s / 2;
  const OctPoint o = corner(c);
  const OctPoint centre{o[0] + h, o[1] + h, o[2] + h};
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const int b = (a + 1) % 3, d = (a + 2) % 3;
      OctPoint f0 = o;
      f0[static_cast<std::size_t>(a)] += side * s;
      // The unit cube across the face at its lowest corner: in the neighbour's quadrant child
      // when the neighbour is split (balance: then all four are leaves one level finer).
      OctPoint across = f0;
      across[static_cast<std::size_t>(a)] =
          side ? o[static_cast<std::size_t>(a)] + s : o[static_cast<std::size_t>(a)] - 1;
      const bool finer = l < kFinest && finer_at(across, l);
      const long z = finer ? h : s;
      for (int sq = 0; sq < (finer ? 4 : 1); ++sq) {
        OctPoint p0 = f0;
        p0[static_cast<std::size_t>(b)] += (sq & 1) * z;
        p0[static_cast<std::size_t>(d)] += (sq >> 1) * z;
        auto at = [&](long u, long v) {
          OctPoint p = p0;
          p[static_cast<std::size_t>(b)] += u;
          p[static_cast<std::size_t>(d)] += v;
          return p;
        };
        const OctPoint fan = at(z / 2, z / 2);
        // The square's corners in turn; a whole face's sides are the cell's edges, whose
        // midpoints are leaf corners when a cell about the edge is split. The four-square
        // faces' sides have no such midpoints (balance).
        const OctPoint corners[4] = {at(0, 0), at(z, 0), at(z, z), at(0, z)};
        OctPoint ring[8];
        int m = 0;
        for (int e = 0; e < 4; ++e) {
          ring[m++] = corners[e];
          if (finer) continue;
          const OctPoint& p = corners[e];
          const OctPoint& q = corners[(e + 1) % 4];
          OctPoint mid{(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2};
          // The edge runs along the axis where p and q differ; g is the face's other axis.
          const int g = p[static_cast<std::size_t>(b)] == q[static_cast<std::size_t>(b)] ? b : d;
          const bool g_high = p[static_cast<std::size_t>(g)] != o[static_cast<std::size_t>(g)];
          // The unit cubes at mid in the three other cells about the edge: across the face
          // (axis a), across the face of axis g, and across both.
          const long F = f0[static_cast<std::size_t>(a)], G = p[static_cast<std::size_t>(g)];
          const long ours_a = side ? F - 1 : F, other_a = side ? F : F - 1;
          const long ours_g = g_high ? G - 1 : G, other_g = g_high ? G : G - 1;
          bool split_about = false;
          for (int r = 1; r < 4 && !split_about; ++r) {
            OctPoint u = mid;
            u[static_cast<std::size_t>(a)] = r & 1 ? other_a : ours_a;
            u[static_cast<std::size_t>(g)] = r & 2 ? other_g : ours_g;
            split_about = finer_at(u, l);
          }
          if (split_about) ring[m++] = mid;
        }
        for (int e = 0; e < m; ++e) out.push_back({centre, fan, ring[e], ring[(e + 1) % m]});
      }
    }
}

}  // namespace qmotion::sweep::mesher
