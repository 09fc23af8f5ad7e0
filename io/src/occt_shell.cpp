// io/src/occt_shell.cpp: an open shell whose neighbouring faces share their boundary poles
// exactly (a surface cut at its knots), built with those boundaries as shared edges: what
// sewing finds by projecting every edge on its neighbours, found here by equality of the
// data, with the pcurves known (the boundaries are iso-parametric).
#include <BRep_Builder.hxx>
#include <Geom2d_Line.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Precision.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <array>
#include <gp_Dir2d.hxx>
#include <gp_Pnt2d.hxx>
#include <map>
#include <vector>

#include "occt_convert.hpp"

namespace qmotion::io::detail {
namespace {

using Surface = sweep::NurbsSurface<double>;
using Curve = sweep::NurbsCurve<double>;

/// Side k of a face's parameter rectangle, counter-clockwise: 0 v = v0 and 2 v = v1 (curves
/// along u), 1 u = u1 and 3 u = u0 (along v). Each boundary curve runs with its parameter.
Curve boundary(const Surface& s, int side) {
  Curve c;
  if (side % 2 == 0) {
    const std::size_t j = side == 0 ? 0 : s.points.front().size() - 1;
    c.degree = s.degree_u;
    c.knots = s.knots_u;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      c.points.push_back(s.points[i][j]);
      c.weights.push_back(s.weights[i][j]);
    }
  } else {
    const std::size_t i = side == 3 ? 0 : s.points.size() - 1;
    c.degree = s.degree_v;
    c.knots = s.knots_v;
    c.points = s.points[i];
    c.weights = s.weights[i];
  }
  return c;
}

/// The curve's data bit for bit, for finding the same boundary on another face.
std::vector<double> key(const Curve& c) {
  std::vector<double> k(c.knots);
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    k.insert(k.end(), c.points[i].data(), c.points[i].data() + 3);
    k.push_back(c.weights[i]);
  }
  k.push_back(c.degree);
  return k;
}

/// A point's coordinates bit for bit.
std::array<double, 3> point_key(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

/// The line in the face's (u, v) plane that side k lies on, parametrised as its curve.
Handle(Geom2d_Line) side_line(const Surface& s, int side) {
  if (side % 2 == 0)
    return new Geom2d_Line(gp_Pnt2d(0, side == 0 ? s.knots_v.front() : s.knots_v.back()),
                           gp_Dir2d(1, 0));
  return new Geom2d_Line(gp_Pnt2d(side == 3 ? s.knots_u.front() : s.knots_u.back(), 0),
                         gp_Dir2d(0, 1));
}

struct Use {
  std::size_t face;
  int side;
};

}  // namespace

TopoDS_Shape shared_edge_shell(const std::vector<Surface>& faces) {
  const double tol = Precision::Confusion();
  BRep_Builder b;
  std::vector<TopoDS_Face> occt(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) b.MakeFace(occt[f], make_surface(faces[f]), tol);
  // Each boundary, and the sides that have it: two, on opposite sides (one face's top, its
  // neighbour's bottom), or one (the shell's border).
  std::map<std::vector<double>, std::vector<Use>> uses;
  std::vector<std::array<Curve, 4>> curves(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 4; ++k) {
      curves[f][static_cast<std::size_t>(k)] = boundary(faces[f], k);
      const Curve& c = curves[f][static_cast<std::size_t>(k)];
      if (std::all_of(c.points.begin(), c.points.end(),
                      [&](const Eigen::Vector3d& p) { return p == c.points.front(); }))
        return {};  // a degenerate side: left to sewing
      uses[key(c)].push_back({f, k});
    }
  std::map<std::array<double, 3>, TopoDS_Vertex> vertices;
  auto vertex = [&](const Eigen::Vector3d& p) {
    auto [it, fresh] = vertices.try_emplace(point_key(p));
    if (fresh) b.MakeVertex(it->second, gp_Pnt(p.x(), p.y(), p.z()), tol);
    return it->second;
  };
  std::vector<std::array<TopoDS_Edge, 4>> edges(faces.size());
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> free_ends;
  for (const auto& [k, u] : uses) {
    if (u.size() > 2 || (u.size() == 2 && (u[0].side + 2) % 4 != u[1].side)) return {};
    const Curve& c = curves[u[0].face][static_cast<std::size_t>(u[0].side)];
    TopoDS_Edge e;
    b.MakeEdge(e, make_curve(c), tol);
    b.Add(e, vertex(c.points.front()).Oriented(TopAbs_FORWARD));
    b.Add(e, vertex(c.points.back()).Oriented(TopAbs_REVERSED));
    if (u.size() == 2 && u[0].face == u[1].face) {  // a seam: first the forward side's line
      const Use& fwd = u[0].side < 2 ? u[0] : u[1];
      const Use& rev = u[0].side < 2 ? u[1] : u[0];
      b.UpdateEdge(e, side_line(faces[fwd.face], fwd.side), side_line(faces[rev.face], rev.side),
                   occt[fwd.face], tol);
    } else {
      for (const Use& x : u) b.UpdateEdge(e, side_line(faces[x.face], x.side), occt[x.face], tol);
    }
    b.Range(e, c.knots.front(), c.knots.back());
    b.SameParameter(e, Standard_True);
    b.SameRange(e, Standard_True);
    for (const Use& x : u) edges[x.face][static_cast<std::size_t>(x.side)] = e;
    if (u.size() == 1) free_ends.emplace_back(c.points.front(), c.points.back());
  }
  // Borders that meet end to end where faces should have joined (the same boundary written
  // with different rounding): sewing's job, not this one's.
  for (std::size_t i = 0; i < free_ends.size(); ++i)
    for (std::size_t j = i + 1; j < free_ends.size(); ++j) {
      const auto& [a0, a1] = free_ends[i];
      const auto& [b0, b1] = free_ends[j];
      const double same = std::max((a0 - b0).norm(), (a1 - b1).norm());
      const double flipped = std::max((a0 - b1).norm(), (a1 - b0).norm());
      if (std::min(same, flipped) < 100 * tol && (a0 - a1).norm() > 100 * tol) return {};
    }
  TopoDS_Shell shell;
  b.MakeShell(shell);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    TopoDS_Wire w;
    b.MakeWire(w);
    for (int k = 0; k < 4; ++k)  // sides 0 and 1 run with their curves, 2 and 3 against
      b.Add(w, edges[f][static_cast<std::size_t>(k)].Oriented(k < 2 ? TopAbs_FORWARD
                                                                    : TopAbs_REVERSED));
    w.Closed(Standard_True);
    b.Add(occt[f], w);
    b.Add(shell, occt[f]);
  }
  shell.Closed(Standard_False);
  return shell;
}

}  // namespace qmotion::io::detail
