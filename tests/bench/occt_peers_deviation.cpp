// tests/bench/occt_peers_deviation.cpp: see occt_peers_deviation.hpp.
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <boost/iterator/counting_iterator.hpp>
#include <functional>
#include <memory>
#include <qmotion/sweep/surface_eval.hpp>

// CGAL before OpenCASCADE: OpenCASCADE's `Handle` macro breaks CGAL headers after it.
// clang-format off
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/property_map.h>

#include "occt_peers_deviation.hpp"
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>
// clang-format on

namespace qmotion::bench {
namespace {

// ---- deviation: dense samples both ways, nearest seeds from a k-d tree, Gauss-Newton -----

using Kernel = CGAL::Simple_cartesian<double>;
using Pt = Kernel::Point_3;
using TreeTraits = CGAL::Search_traits_adapter<std::size_t, CGAL::Pointer_property_map<Pt>::type,
                                               CGAL::Search_traits_3<Kernel>>;
using Search = CGAL::Orthogonal_k_neighbor_search<TreeTraits>;

/// Dense samples of a surface with their (face, u, v), and a k-d tree over them.
struct Samples {
  mutable std::vector<Pt> pts;  // mutable: CGAL's distance adapter takes a non-const map
  std::vector<std::array<double, 3>> where;  // face, u, v
  std::unique_ptr<Search::Tree> tree;

  void add(int face, double u, double v, const V3& p) {
    pts.emplace_back(p.x(), p.y(), p.z());
    where.push_back({double(face), u, v});
  }
  void build() {
    tree = std::make_unique<Search::Tree>(
        boost::counting_iterator<std::size_t>(0), boost::counting_iterator<std::size_t>(pts.size()),
        Search::Tree::Splitter(), TreeTraits(CGAL::make_property_map(pts)));
    tree->build();  // now, not lazily inside a (concurrent) query
  }
  std::vector<std::size_t> nearest(const V3& x, unsigned k) const {
    Search::Distance d(CGAL::make_property_map(pts));
    Search s(*tree, Pt(x.x(), x.y(), x.z()), k, 0, true, d);
    std::vector<std::size_t> out;
    for (auto it = s.begin(); it != s.end(); ++it) out.push_back(it->first);
    return out;
  }
};

/// Distance from x to the face near (u, v): Gauss-Newton on |S - x|^2 in the UV box.
double face_distance(const OcctFace& f, const V3& x, double u, double v) {
  double best = HUGE_VAL;
  for (int it = 0; it <= 12; ++it) {
    gp_Pnt P;
    gp_Vec Su, Sv;
    f.s->D1(u, v, P, Su, Sv);
    const V3 S(P.X(), P.Y(), P.Z()), su(Su.X(), Su.Y(), Su.Z()), sv(Sv.X(), Sv.Y(), Sv.Z());
    const V3 r = x - S;
    best = std::min(best, r.norm());
    Eigen::Matrix2d J;
    J << su.dot(su), su.dot(sv), su.dot(sv), sv.dot(sv);
    if (!(J.determinant() > 1e-30 * J.squaredNorm())) break;
    const Eigen::Vector2d d = J.ldlt().solve(Eigen::Vector2d(su.dot(r), sv.dot(r)));
    u = std::clamp(u + d(0), f.u0, f.u1);
    v = std::clamp(v + d(1), f.v0, f.v1);
    if (d.norm() < 1e-16) break;
  }
  return best;
}

/// Sample counts along u and v of a surface over [u0, u1] x [v0, v1] so that neighbouring
/// samples are at most h apart (the longest of three iso-curves in each direction, measured
/// as polylines of `probe` points), at least 16 and at most 4000.
std::pair<int, int> counts_for(const std::function<V3(double, double)>& S, double u0, double u1,
                               double v0, double v1, double h, int probe) {
  auto longest = [&](bool along_u) {
    double L = 0;
    for (double f : {0.0, 0.5, 1.0}) {
      double l = 0;
      V3 prev;
      for (int i = 0; i <= probe; ++i) {
        const double a = double(i) / probe;
        const V3 p = along_u ? S(u0 + (u1 - u0) * a, v0 + (v1 - v0) * f)
                             : S(u0 + (u1 - u0) * f, v0 + (v1 - v0) * a);
        if (i) l += (p - prev).norm();
        prev = p;
      }
      L = std::max(L, l);
    }
    return std::clamp(static_cast<int>(L / h) + 1, 16, 4000);
  };
  return {longest(true), longest(false)};
}

}  // namespace

std::vector<OcctFace> faces_of(const TopoDS_Shape& shape) {
  std::vector<OcctFace> out;
  for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
    const TopoDS_Face& f = TopoDS::Face(e.Current());
    OcctFace o;
    o.s = BRep_Tool::Surface(f);
    BRepTools::UVBounds(f, o.u0, o.u1, o.v0, o.v1);
    out.push_back(o);
  }
  return out;
}

int sample_count(int spans) { return std::clamp(8 * spans + 24, 24, 1600); }

/// The Hausdorff distance between the shape's faces and the exact surface, both ways: every
/// sample of one (at most 1/resolution of the diagonal apart) against the other, from the
/// best of its four nearest samples there (a k-d tree), by Gauss-Newton. Seeds that close keep
/// the foot point on the right sheet where the surface folds over itself.
double deviation(const Case& c, const std::vector<OcctFace>& faces, int resolution) {
  const sweep::SurfaceEvaluator E(c.exact);
  const double h = c.diagonal / resolution;
  const int probe = 8 * c.spans() + 256;
  constexpr unsigned kSeeds = 4;
  Samples ex;
  const auto [nu, nv] = counts_for([&](double u, double v) { return E(u, v); }, E.u0(), E.u1(),
                                   E.v0(), E.v1(), h, probe);
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j) {
      const double u = E.u0() + (E.u1() - E.u0()) * i / nu, v = E.v0() + (E.v1() - E.v0()) * j / nv;
      ex.add(0, u, v, E(u, v));
    }
  ex.build();
  Samples rt;
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const auto& f = faces[k];
    const auto value = [&](double u, double v) {
      const gp_Pnt p = f.s->Value(u, v);
      return V3(p.X(), p.Y(), p.Z());
    };
    const auto [n1, n2] = counts_for(value, f.u0, f.u1, f.v0, f.v1, h, probe);
    for (int i = 0; i <= n1; ++i)
      for (int j = 0; j <= n2; ++j) {
        const double u = f.u0 + (f.u1 - f.u0) * i / n1, v = f.v0 + (f.v1 - f.v0) * j / n2;
        rt.add(static_cast<int>(k), u, v, value(u, v));
      }
  }
  rt.build();
  // Route -> exact on every core (our evaluator and the built tree are read-only).
  double dev = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, rt.pts.size()), 0.0,
      [&](const tbb::blocked_range<std::size_t>& r, double m) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
          const V3 x(rt.pts[i].x(), rt.pts[i].y(), rt.pts[i].z());
          double d = HUGE_VAL;
          for (std::size_t s : ex.nearest(x, kSeeds))
            d = std::min(d, E.distance(x, ex.where[s][1], ex.where[s][2], 12));
          m = std::max(m, d);
        }
        return m;
      },
      [](double a, double b) { return std::max(a, b); });
  for (std::size_t i = 0; i < ex.pts.size(); ++i) {  // exact -> route
    const V3 x(ex.pts[i].x(), ex.pts[i].y(), ex.pts[i].z());
    double d = HUGE_VAL;
    for (std::size_t s : rt.nearest(x, kSeeds)) {
      const auto& w = rt.where[s];
      d = std::min(d, face_distance(faces[static_cast<std::size_t>(w[0])], x, w[1], w[2]));
    }
    dev = std::max(dev, d);
  }
  return dev;
}

/// The exact route's deviation at equal parameters: the surface read back at (t, s) against
/// M(t) c(s) from the dual quaternion curve (an upper bound of the geometric distance).
double parametric_deviation(const Case& c, const OcctFace& f) {
  double dev = 0;
  const int nu = sample_count(c.spans()), nv = 64;
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j) {
      const double t = c.motion.a() + (c.motion.b() - c.motion.a()) * i / nu, s = double(j) / nv;
      const gp_Pnt p = f.s->Value(t, s);
      dev = std::max(dev, (V3(p.X(), p.Y(), p.Z()) - c.point(t, s)).norm());
    }
  return dev;
}

}  // namespace qmotion::bench
