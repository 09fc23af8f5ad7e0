// io/src/occt_convert.cpp: qmotion's NURBS as OpenCASCADE's and back, and what the STEP/IGES
// writer and reader share.
#include "occt_convert.hpp"

#include <APIHeaderSection_MakeHeader.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepLib.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Plane.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <IMeshTools_Parameters.hxx>
#include <Interface_Check.hxx>
#include <Interface_CheckIterator.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <Message_ProgressIndicator.hxx>
#include <Message_ProgressScope.hxx>
#include <Poly_Triangulation.hxx>
#include <RWStl.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <StepData_Protocol.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_StepWriter.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <TopoDS_Wire.hxx>
#include <UnitsMethods.hxx>
#include <XSControl_WorkSession.hxx>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gp_Pln.hxx>
#include <limits>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/io/progress.hpp>
#include <qmotion/io/units.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/surface.hpp>
#include <qmotion/version.hpp>
#include <sstream>
#include <string_view>

#if defined(__SANITIZE_ADDRESS__)
#define QMOTION_LEAK_CHECKED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define QMOTION_LEAK_CHECKED 1
#endif
#endif
#ifdef QMOTION_LEAK_CHECKED
#include <sanitizer/lsan_interface.h>
#endif

namespace qmotion::io::detail {

UnitNames unit_names(const std::string& unit) {
  const std::string u = canonical_unit(unit, "length unit");
  const double mm = unit_in_mm(u);
  if (u == "mm") return {"MM", "MM", mm};
  if (u == "cm") return {"CM", "CM", mm};
  if (u == "m") return {"M", "M", mm};
  if (u == "in") return {"INCH", "IN", mm};
  if (u == "ft") return {"FT", "FT", mm};
  return {"UM", "UM", mm};
}

/// OpenCASCADE's translators report statistics through the default messenger, which
/// prints to stdout; qmotion's stdout carries JSON, so the printers go (once).
void quiet_occt() {
  static const bool done = [] {
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
    return true;
  }();
  (void)done;
}

namespace {

/// Runs `init` with LeakSanitizer ignoring what it allocates (a no-op without the sanitizer).
template <class F>
void process_lifetime(F init) {
#ifdef QMOTION_LEAK_CHECKED
  const __lsan::ScopedDisabler lifetime_of_the_process;
#endif
  init();
}

}  // namespace

void init_step_translator() {
  process_lifetime([] { STEPControl_Controller::Init(); });
}

void init_iges_translator() {
  process_lifetime([] { IGESControl_Controller::Init(); });
}

TColStd_Array1OfReal occt_reals(const std::vector<double>& v) {
  TColStd_Array1OfReal a(1, static_cast<int>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) a.SetValue(static_cast<int>(i) + 1, v[i]);
  return a;
}

TColStd_Array1OfInteger occt_ints(const std::vector<int>& v) {
  TColStd_Array1OfInteger a(1, static_cast<int>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) a.SetValue(static_cast<int>(i) + 1, v[i]);
  return a;
}

OcctKnots occt_knots(const std::vector<double>& full) {
  std::vector<double> distinct;
  std::vector<int> mults;
  knots_to_distinct(full, distinct, mults);
  return {occt_reals(distinct), occt_ints(mults)};
}

Handle(Geom_BSplineSurface) make_surface(const sweep::NurbsSurface<double>& s) {
  const int nu = static_cast<int>(s.points.size()), nv = static_cast<int>(s.points.front().size());
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const auto& p = s.points[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
      poles.SetValue(i + 1, j + 1, gp_Pnt(p(0), p(1), p(2)));
      weights.SetValue(i + 1, j + 1,
                       s.weights[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]);
    }
  const OcctKnots ku = occt_knots(s.knots_u), kv = occt_knots(s.knots_v);
  return new Geom_BSplineSurface(poles, weights, ku.knots, kv.knots, ku.mults, kv.mults, s.degree_u,
                                 s.degree_v);
}

Handle(Geom_BSplineCurve) make_curve(const sweep::NurbsCurve<double>& c) {
  const int n = static_cast<int>(c.points.size());
  TColgp_Array1OfPnt poles(1, n);
  TColStd_Array1OfReal weights(1, n);
  for (int i = 0; i < n; ++i) {
    const auto& p = c.points[static_cast<std::size_t>(i)];
    poles.SetValue(i + 1, gp_Pnt(p(0), p(1), p(2)));
    weights.SetValue(i + 1, c.weights[static_cast<std::size_t>(i)]);
  }
  const OcctKnots k = occt_knots(c.knots);
  return new Geom_BSplineCurve(poles, weights, k.knots, k.mults, c.degree);
}

sweep::NurbsSurface<double> from_occt(Handle(Geom_BSplineSurface) g) {
  if (g->IsUPeriodic() || g->IsVPeriodic() || g->UMultiplicity(1) <= g->UDegree() ||
      g->UMultiplicity(g->NbUKnots()) <= g->UDegree() || g->VMultiplicity(1) <= g->VDegree() ||
      g->VMultiplicity(g->NbVKnots()) <= g->VDegree()) {  // back to the clamped form
    double u1 = 0, u2 = 0, v1 = 0, v2 = 0;
    g->Bounds(u1, u2, v1, v2);
    g = Handle(Geom_BSplineSurface)::DownCast(g->Copy());
    if (g->IsUPeriodic()) g->SetUNotPeriodic();
    if (g->IsVPeriodic()) g->SetVNotPeriodic();
    g->Segment(u1, u2, v1, v2);
  }
  sweep::NurbsSurface<double> s;
  s.degree_u = g->UDegree();
  s.degree_v = g->VDegree();
  std::vector<double> d;
  std::vector<int> m;
  for (int i = 1; i <= g->NbUKnots(); ++i) {
    d.push_back(g->UKnot(i));
    m.push_back(g->UMultiplicity(i));
  }
  s.knots_u = knots_from_distinct(d, m);
  d.clear();
  m.clear();
  for (int i = 1; i <= g->NbVKnots(); ++i) {
    d.push_back(g->VKnot(i));
    m.push_back(g->VMultiplicity(i));
  }
  s.knots_v = knots_from_distinct(d, m);
  for (int i = 1; i <= g->NbUPoles(); ++i) {
    s.points.emplace_back();
    s.weights.emplace_back();
    for (int j = 1; j <= g->NbVPoles(); ++j) {
      const gp_Pnt p = g->Pole(i, j);
      s.points.back().emplace_back(p.X(), p.Y(), p.Z());
      s.weights.back().push_back(g->Weight(i, j));
    }
  }
  return s;
}

sweep::NurbsCurve<double> from_occt(Handle(Geom_BSplineCurve) g) {
  // Readers may make a closed curve periodic or unclamped: back to the clamped form on
  // the same parameter range (the function is unchanged).
  if (g->IsPeriodic() || g->Multiplicity(1) <= g->Degree() ||
      g->Multiplicity(g->NbKnots()) <= g->Degree()) {
    const double first = g->FirstParameter(), last = g->LastParameter();
    g = Handle(Geom_BSplineCurve)::DownCast(g->Copy());
    if (g->IsPeriodic()) g->SetNotPeriodic();
    g->Segment(first, last);
  }
  sweep::NurbsCurve<double> c;
  c.degree = g->Degree();
  std::vector<double> d;
  std::vector<int> m;
  for (int i = 1; i <= g->NbKnots(); ++i) {
    d.push_back(g->Knot(i));
    m.push_back(g->Multiplicity(i));
  }
  c.knots = knots_from_distinct(d, m);
  for (int i = 1; i <= g->NbPoles(); ++i) {
    const gp_Pnt p = g->Pole(i);
    c.points.emplace_back(p.X(), p.Y(), p.Z());
    c.weights.push_back(g->Weight(i));
  }
  return c;
}

std::string lower(std::string s) {
  for (auto& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

/// The B-spline of curve on [first, last] (the curve itself when that is its whole range).
Handle(Geom_BSplineCurve) whole_curve(const Handle(Geom_Curve) & curve, double first, double last) {
  Handle(Geom_BSplineCurve) bc = Handle(Geom_BSplineCurve)::DownCast(curve);
  if (bc.IsNull() || first != bc->FirstParameter() || last != bc->LastParameter())
    bc = GeomConvert::CurveToBSplineCurve(new Geom_TrimmedCurve(curve, first, last));
  return bc;
}

/// The profile edges of a shape as NURBS curves in order: the first wire's edges in wire
/// order (reversed edges reversed), or, without a wire, every edge chained end to start
/// (an edge is reversed where that joins it). Consecutive edges on one curve (a reader's
/// split at C0 knots) are joined back into that curve.
std::vector<sweep::NurbsCurve<double>> profile_edges(const TopoDS_Shape& shape) {
  struct Run {
    Handle(Geom_Curve) curve;
    double first, last;
    bool reversed;
  };
  std::vector<Run> runs;
  auto add = [&runs](const TopoDS_Edge& edge) {
    double f = 0, l = 0;
    const Handle(Geom_Curve) c = BRep_Tool::Curve(edge, f, l);
    if (c.IsNull()) return;
    const bool rev = edge.Orientation() == TopAbs_REVERSED;
    if (!runs.empty() && runs.back().curve == c && runs.back().reversed == rev &&
        (rev ? l == runs.back().first : f == runs.back().last)) {
      (rev ? runs.back().first : runs.back().last) = rev ? f : l;
      return;
    }
    runs.push_back({c, f, l, rev});
  };
  TopExp_Explorer we(shape, TopAbs_WIRE);
  if (we.More()) {
    for (BRepTools_WireExplorer e(TopoDS::Wire(we.Current())); e.More(); e.Next()) add(e.Current());
  } else {
    for (TopExp_Explorer e(shape, TopAbs_EDGE); e.More(); e.Next()) add(TopoDS::Edge(e.Current()));
  }
  std::vector<sweep::NurbsCurve<double>> out;
  for (const auto& r : runs) {
    Handle(Geom_BSplineCurve) bc =
        Handle(Geom_BSplineCurve)::DownCast(whole_curve(r.curve, r.first, r.last)->Copy());
    if (r.reversed) bc->Reverse();
    out.push_back(from_occt(bc));
  }
  if (we.More() || out.size() < 2) return out;
  // Chain loose edges: each next edge starts (or, reversed, ends) where the chain ends.
  std::vector<sweep::NurbsCurve<double>> chain{out.front()};
  std::vector<bool> used(out.size(), false);
  used[0] = true;
  for (std::size_t n = 1; n < out.size(); ++n) {
    const Eigen::Vector3d end = chain.back().points.back();
    std::size_t best = out.size();
    bool flip = false;
    double gap = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < out.size(); ++k) {
      if (used[k]) continue;
      const double g0 = (out[k].points.front() - end).norm(),
                   g1 = (out[k].points.back() - end).norm();
      if (std::min(g0, g1) < gap) {
        gap = std::min(g0, g1);
        best = k;
        flip = g1 < g0;
      }
    }
    used[best] = true;
    auto c = out[best];
    if (flip) {  // reversed on the same parameter range: v -> first + last - v
      std::reverse(c.points.begin(), c.points.end());
      std::reverse(c.weights.begin(), c.weights.end());
      const double s = c.knots.front() + c.knots.back();
      std::reverse(c.knots.begin(), c.knots.end());
      for (auto& k : c.knots) k = s - k;
    }
    chain.push_back(std::move(c));
  }
  return chain;
}

int distinct(const TopoDS_Shape& shape, TopAbs_ShapeEnum kind) {
  TopTools_IndexedMapOfShape m;
  TopExp::MapShapes(shape, kind, m);
  return m.Extent();
}

}  // namespace qmotion::io::detail
