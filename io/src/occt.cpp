// io/src/occt.cpp: the only place OpenCASCADE appears (STYLE §4).
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

#include "isolated.hpp"
#include "occt_unchecked.hpp"

namespace qmotion::io {
namespace {

/// Our unit names -> STEP (write.step.unit) and IGES (unit name) spellings, and the size
/// of the unit in millimetres.
struct UnitNames {
  const char* step;
  const char* iges;
  double mm;
};

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

Handle(TCollection_HAsciiString) hstr(const std::string& s) {
  return new TCollection_HAsciiString(s.c_str());
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

/// A full knot vector as OpenCASCADE's distinct knots and their multiplicities.
struct OcctKnots {
  TColStd_Array1OfReal knots;
  TColStd_Array1OfInteger mults;
};

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

/// OpenCASCADE's progress, forwarded to io::report_progress under a stage name (ended with
/// fraction 1 when the indicator goes).
class SinkIndicator : public Message_ProgressIndicator {
 public:
  explicit SinkIndicator(std::string stage) : stage_(std::move(stage)) {}
  ~SinkIndicator() override { report_progress(stage_, 1.0); }
  void Show(const Message_ProgressScope&, const Standard_Boolean) override {
    report_progress(stage_, std::min(GetPosition(), 0.999));
  }

 private:
  std::string stage_;
};

void write_step_shape(const std::string& path, const TopoDS_Shape& shape, const ExportInfo& info) {
  quiet_occt();
  const UnitNames u = unit_names(info.units);
  STEPControl_Controller::Init();
  // Set the units for every transfer: a writer can carry the unit of an earlier one.
  Interface_Static::SetCVal("xstep.cascade.unit", u.step);
  Interface_Static::SetCVal("write.step.unit", u.step);
  Interface_Static::SetCVal("write.step.schema", "AP214IS");
  Interface_Static::SetCVal("write.step.product.name", info.product.c_str());
  // OpenCASCADE 7.6 keeps the unit of the shape data in a global and in the model, besides
  // the static: set all, every time, so the numbers are written as given, in that unit.
  UnitsMethods::SetCasCadeLengthUnit(u.mm);
  STEPControl_Writer writer;
  writer.Model(Standard_True)->SetLocalLengthUnit(u.mm);
  writer.Model()->SetWriteLengthUnit(u.mm);
  const Handle(SinkIndicator) progress = new SinkIndicator("STEP translation");
  if (writer.Transfer(shape, STEPControl_AsIs, Standard_True, progress->Start()) !=
      IFSelect_RetDone)
    throw Error(Errc::export_failed,
                path + ": OpenCASCADE could not translate the geometry to STEP");
  APIHeaderSection_MakeHeader header(writer.Model());
  header.SetName(hstr(std::filesystem::path(path).filename().string()));
  header.SetOriginatingSystem(hstr(std::string("qmotion ") + version_string));
  header.SetAuthorValue(1, hstr("qmotion"));
  header.SetOrganizationValue(1, hstr("qmotion"));
  header.SetDescriptionValue(1, hstr(info.description.empty() ? info.product : info.description));
  StepData_StepWriter sw(writer.Model());
  sw.FloatWriter().SetFormat("%.17E");  // round-trip precision (default prints ~12 digits)
  sw.SendModel(Handle(StepData_Protocol)::DownCast(writer.WS()->Protocol()));
  AtomicOutput out(path);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    if (!f || !sw.Print(f)) throw Error(Errc::invalid_input, path + ": cannot write the STEP file");
    f.close();  // flushed and checked before the rename: a full disk leaves no truncated file
    if (f.fail())
      throw Error(Errc::invalid_input, path + ": writing the STEP file failed (disk full?)");
  }
  out.commit();
}

/// Writes one geometry entity (`geom`), or a shape as IGES B-rep entities (`shape`).
void write_iges_model(const std::string& path, const Handle(Standard_Transient) & geom,
                      const TopoDS_Shape* shape, const ExportInfo& info) {
  quiet_occt();
  const UnitNames u = unit_names(info.units);
  IGESControl_Controller::Init();
  Interface_Static::SetCVal("xstep.cascade.unit", u.step);
  Interface_Static::SetCVal("write.iges.unit", u.iges);
  UnitsMethods::SetCasCadeLengthUnit(u.mm);
  IGESControl_Writer writer(u.iges, shape ? 1 : 0);  // 1: B-rep (shells, solids)
  {  // the model's own record of the unit the shape data is in (7.6): no rescaling
    IGESData_GlobalSection gs = writer.Model()->GlobalSection();
    gs.SetCascadeUnit(u.mm);
    writer.Model()->SetGlobalSection(gs);
  }
  const Handle(SinkIndicator) progress = new SinkIndicator("IGES translation");
  if (shape ? !writer.AddShape(*shape, progress->Start()) : !writer.AddGeom(geom))
    throw Error(Errc::export_failed,
                path + ": OpenCASCADE could not translate the geometry to IGES");
  writer.ComputeModel();
  IGESData_GlobalSection gs = writer.Model()->GlobalSection();
  gs.SetFileName(hstr(std::filesystem::path(path).filename().string()));
  gs.SetSendName(hstr(info.product));
  gs.SetSystemId(hstr(std::string("qmotion ") + version_string));
  gs.SetAuthorName(hstr("qmotion"));
  gs.SetMaxDigitsDouble(17);
  writer.Model()->SetGlobalSection(gs);
  IGESData_IGESWriter iw(writer.Model());
  iw.FloatWriter().SetFormat("%.17E");
  iw.SendStartLine(
      ("qmotion: " + (info.description.empty() ? info.product : info.description)).c_str());
  iw.SendModel(IGESSelect_WorkLibrary::DefineProtocol());
  AtomicOutput out(path);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    if (!f || !iw.Print(f)) throw Error(Errc::invalid_input, path + ": cannot write the IGES file");
    f.close();  // flushed and checked before the rename: a full disk leaves no truncated file
    if (f.fail())
      throw Error(Errc::invalid_input, path + ": writing the IGES file failed (disk full?)");
  }
  out.commit();
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

/// A wire through the curves in order (each an edge on its whole curve).
TopoDS_Wire make_wire(const std::vector<sweep::NurbsCurve<double>>& curves, const std::string& path,
                      const std::string& what) {
  BRepBuilderAPI_MakeWire w;
  for (const auto& c : curves) {
    w.Add(BRepBuilderAPI_MakeEdge(make_curve(c)).Edge());
    if (!w.IsDone())
      throw Error(Errc::export_failed,
                  path + ": OpenCASCADE could not join the " + what + " into a wire");
  }
  return w.Wire();
}

/// The faces sewn into one shell, or with caps into one closed, outward-oriented solid.
TopoDS_Shape make_shell(const sweep::NurbsShell<double>& s, const std::string& path) {
  if (s.faces.empty()) throw Error(Errc::internal, "a shell without faces");
  if (s.faces.size() == 1 && s.cap_start.empty()) {
    return BRepBuilderAPI_MakeFace(make_surface(s.faces.front()), 1e-9).Face();
  }
  // Neighbouring faces share their boundary poles exactly; the tolerance only absorbs
  // OpenCASCADE's own rounding of the boundary curves.
  BRepBuilderAPI_Sewing sewing(std::max(1e-7, 1e-9 * sweep::diagonal(s)));
  for (const auto& f : s.faces) sewing.Add(BRepBuilderAPI_MakeFace(make_surface(f), 1e-9).Face());
  if (!s.cap_start.empty()) {
    for (const auto* cap : {&s.cap_start, &s.cap_end}) {
      BRepBuilderAPI_MakeFace face(make_wire(*cap, path, "cap's boundary curves"),
                                   Standard_True /*only a plane*/);
      if (!face.IsDone())
        throw Error(Errc::export_failed,
                    path + ": OpenCASCADE found no plane through a cap's boundary");
      sewing.Add(face.Face());
    }
  }
  sewing.Perform();
  const TopoDS_Shape sewn = sewing.SewedShape();
  if (sewn.IsNull())
    throw Error(Errc::export_failed, path + ": OpenCASCADE could not sew the faces");
  if (s.cap_start.empty()) return sewn;
  TopExp_Explorer e(sewn, TopAbs_SHELL);
  if (!e.More()) throw Error(Errc::export_failed, path + ": the sewn faces form no shell");
  const TopoDS_Shell shell = TopoDS::Shell(e.Current());
  e.Next();
  if (e.More() || sewing.NbFreeEdges() > 0)
    throw Error(Errc::export_failed, path + ": the swept faces and caps do not close (" +
                                         std::to_string(sewing.NbFreeEdges()) +
                                         " free edges after sewing)");
  BRepBuilderAPI_MakeSolid solid(shell);
  if (!solid.IsDone()) throw Error(Errc::export_failed, path + ": OpenCASCADE made no solid");
  TopoDS_Solid result = solid.Solid();
  BRepLib::OrientClosedSolid(result);
  if (!BRepCheck_Analyzer(result).IsValid())
    throw Error(Errc::export_failed, path + ": OpenCASCADE finds the swept solid invalid");
  return result;
}

template <typename F>
void guarded(const std::string& path, F&& f) {
  try {
    f();
  } catch (const Standard_Failure& e) {
    throw Error(Errc::export_failed, path + ": OpenCASCADE: " + e.GetMessageString());
  }
}

}  // namespace

int occt_max_degree() { return Geom_BSplineCurve::MaxDegree(); }

void knots_to_distinct(const std::vector<double>& full, std::vector<double>& distinct,
                       std::vector<int>& mults) {
  distinct.clear();
  mults.clear();
  for (double k : full) {
    if (!distinct.empty() && distinct.back() == k) {
      ++mults.back();
    } else {
      distinct.push_back(k);
      mults.push_back(1);
    }
  }
}

std::vector<double> knots_from_distinct(const std::vector<double>& distinct,
                                        const std::vector<int>& mults) {
  std::vector<double> full;
  for (std::size_t i = 0; i < distinct.size(); ++i)
    full.insert(full.end(), static_cast<std::size_t>(mults[i]), distinct[i]);
  return full;
}

void write_step(const std::string& path, const sweep::NurbsSurface<double>& s,
                const ExportInfo& info) {
  guarded(path, [&] {
    write_step_shape(path, BRepBuilderAPI_MakeFace(make_surface(s), 1e-9).Face(), info);
  });
}

void write_step(const std::string& path, const sweep::NurbsCurve<double>& c,
                const ExportInfo& info) {
  guarded(path,
          [&] { write_step_shape(path, BRepBuilderAPI_MakeEdge(make_curve(c)).Edge(), info); });
}

void write_iges(const std::string& path, const sweep::NurbsSurface<double>& s,
                const ExportInfo& info) {
  guarded(path, [&] { write_iges_model(path, make_surface(s), nullptr, info); });
}

void write_iges(const std::string& path, const sweep::NurbsCurve<double>& c,
                const ExportInfo& info) {
  guarded(path, [&] { write_iges_model(path, make_curve(c), nullptr, info); });
}

void write_step(const std::string& path, const sweep::NurbsShell<double>& s,
                const ExportInfo& info) {
  guarded(path, [&] { write_step_shape(path, make_shell(s, path), info); });
}

void write_iges(const std::string& path, const sweep::NurbsShell<double>& s,
                const ExportInfo& info) {
  guarded(path, [&] {
    if (s.faces.size() == 1 && s.cap_start.empty()) {
      write_iges_model(path, make_surface(s.faces.front()), nullptr, info);
      return;
    }
    const TopoDS_Shape shape = make_shell(s, path);
    write_iges_model(path, Handle(Standard_Transient)(), &shape, info);
  });
}

std::vector<FaceMesh> mesh_shell(const sweep::NurbsShell<double>& s, double deflection,
                                 double angle, const std::string& path) {
  std::vector<FaceMesh> out;
  guarded(path, [&] {
    const TopoDS_Shape shape = make_shell(s, path);
    IMeshTools_Parameters params;
    params.Deflection = deflection;
    params.Angle = angle;
    params.InParallel = Standard_True;
    const Handle(SinkIndicator) progress = new SinkIndicator("meshing");
    BRepMesh_IncrementalMesh mesher(shape, params, progress->Start());
    if (!mesher.IsDone()) throw Error(Errc::export_failed, path + ": OpenCASCADE's mesher failed");
    for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
      const TopoDS_Face& face = TopoDS::Face(e.Current());
      TopLoc_Location loc;
      const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
      if (tri.IsNull() || !tri->HasUVNodes())
        throw Error(Errc::export_failed,
                    path + ": OpenCASCADE's mesher left a face untriangulated");
      FaceMesh fm;
      const gp_Trsf t = loc.Transformation();
      for (int i = 1; i <= tri->NbNodes(); ++i) {
        const gp_Pnt p = tri->Node(i).Transformed(t);
        const gp_Pnt2d q = tri->UVNode(i);
        fm.nodes.emplace_back(p.X(), p.Y(), p.Z());
        fm.uv.emplace_back(q.X(), q.Y());
      }
      const bool reversed = face.Orientation() == TopAbs_REVERSED;
      for (int i = 1; i <= tri->NbTriangles(); ++i) {
        int a = 0, b = 0, c = 0;
        tri->Triangle(i).Get(a, b, c);
        fm.triangles.push_back(reversed ? std::array<int, 3>{a - 1, c - 1, b - 1}
                                        : std::array<int, 3>{a - 1, b - 1, c - 1});
      }
      const Handle(Geom_Surface) surf = BRep_Tool::Surface(face);
      if (const Handle(Geom_Plane) plane = Handle(Geom_Plane)::DownCast(surf); !plane.IsNull()) {
        const gp_Pln pl = plane->Pln().Transformed(t);
        fm.plane_point = Eigen::Vector3d(pl.Location().X(), pl.Location().Y(), pl.Location().Z());
        const gp_Dir n = pl.Axis().Direction();
        fm.plane_normal = Eigen::Vector3d(n.X(), n.Y(), n.Z());
      } else {
        // The shell's face this one is: every (sampled) node inside its parameter
        // rectangle and on its surface at the node's (u, v), the best fit of them (sewing
        // keeps the surfaces and their parameters).
        double best = HUGE_VAL;
        const std::size_t step = std::max<std::size_t>(1, fm.nodes.size() / 32);
        for (std::size_t k = 0; k < s.faces.size(); ++k) {
          const auto& f = s.faces[k];
          const double du = 1e-9 * (f.knots_u.back() - f.knots_u.front()),
                       dv = 1e-9 * (f.knots_v.back() - f.knots_v.front());
          double worst = 0;
          for (std::size_t i = 0; i < fm.nodes.size() && worst < best; i += step) {
            const Eigen::Vector2d q = fm.uv[i];
            if (q(0) < f.knots_u.front() - du || q(0) > f.knots_u.back() + du ||
                q(1) < f.knots_v.front() - dv || q(1) > f.knots_v.back() + dv) {
              worst = HUGE_VAL;
              break;
            }
            worst = std::max(
                worst, (sweep::evaluate(f, std::clamp(q(0), f.knots_u.front(), f.knots_u.back()),
                                        std::clamp(q(1), f.knots_v.front(), f.knots_v.back())) -
                        fm.nodes[i])
                           .norm());
          }
          if (worst < best) {
            best = worst;
            fm.face = static_cast<int>(k);
          }
        }
        if (fm.face < 0)
          throw Error(Errc::internal, path + ": a meshed face matches no face of the shell");
      }
      out.push_back(std::move(fm));
    }
  });
  return out;
}

void write_step(const std::string& path, const std::vector<sweep::NurbsCurve<double>>& wire,
                const ExportInfo& info) {
  guarded(path, [&] { write_step_shape(path, make_wire(wire, path, "curves"), info); });
}

namespace {
/// Checks an IGES file's structure before OpenCASCADE parses it. OpenCASCADE 7.6 crashes
/// on two kinds of damage:
/// - a rational B-spline entity (126/128) whose parameter record is cut short;
/// - parameter lines with no directory entry before them. Its C parser keeps the last
///   entry of the previous IGES file it read in a static pointer, freed with that file,
///   and files its parameters under it (a use after free: only a second read in one
///   process can crash, as a library user or the Python module does).
/// So every record must be what OpenCASCADE's line reader takes whole: 80 columns (it
/// cuts longer lines in 80-column pieces, and skips a short first line), printable
/// characters, its section letter in column 73 and its sequence number in 74-80. The
/// sections come in the order S, G, D, P, T (OpenCASCADE skips a line out of order),
/// parameter lines only after a directory, and each directory entry has its two lines
/// (OpenCASCADE leaves the second half of a lone one uninitialised).
/// Every directory entry must point at parameter lines that exist, and every 126/128
/// record must hold all the numbers its K and M announce (within bounds that keep the
/// work finite). Files declaring other delimiters than ',' and ';' are checked with theirs.
void check_iges_structure(const std::string& path) {
  const std::string text = read_text_file(path);
  std::vector<std::string> d, p;
  std::string g;
  std::size_t line_start = 0;
  int last_section = 0;  // index in "SGDPT", 0 before the first record
  for (int number = 1; line_start < text.size(); ++number) {
    // Lines end in LF, CR LF or CR alone (OpenCASCADE reads all three).
    std::size_t line_end = text.find_first_of("\r\n", line_start);
    if (line_end == std::string::npos) line_end = text.size();
    const std::string_view line(text.data() + line_start, line_end - line_start);
    line_start = line_end + 1;
    if (line_end + 1 < text.size() && text[line_end] == '\r' && text[line_end + 1] == '\n')
      ++line_start;
    if (line.find_first_not_of(" \t") == std::string_view::npos) continue;
    auto damaged_line = [&](const std::string& what) {
      throw Error(Errc::invalid_input, path + ": a damaged IGES file (line " +
                                           std::to_string(number) + ": " + what + ")");
    };
    if (line.size() != 80)
      damaged_line("a record of " + std::to_string(line.size()) + " columns, not 80");
    for (const char c : line)
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e)
        damaged_line("a character that is not printable ASCII");
    const auto section = std::string_view("SGDPT").find(line[72]);
    if (section == std::string_view::npos)
      damaged_line("no section letter S, G, D, P or T in column 73");
    const std::string_view seq = line.substr(73);
    const auto digits = seq.find_first_not_of(' ');
    if (digits == std::string_view::npos ||
        seq.find_first_not_of("0123456789", digits) != std::string_view::npos)
      damaged_line("no sequence number in columns 74-80");
    const int order = static_cast<int>(section) + 1;
    if (order < last_section)
      damaged_line(std::string("a ") + line[72] + " line after the " + "SGDPT"[last_section - 1] +
                   " section");
    if (line[72] == 'P' && d.empty()) damaged_line("parameter lines before any directory entry");
    last_section = order;
    if (line[72] == 'G') g += line.substr(0, 72);
    if (line[72] == 'D') d.emplace_back(line);
    if (line[72] == 'P') p.emplace_back(line);
  }
  if (d.size() % 2 != 0)
    throw Error(Errc::invalid_input,
                path + ": a damaged IGES file (the last directory entry has one line of its two)");
  char delim = ',', rec = ';';
  if (g.size() >= 3 && g.compare(0, 2, "1H") == 0) delim = g[2];
  {
    const std::size_t at = g.size() >= 3 && g.compare(0, 2, "1H") == 0 ? 4 : 1;
    if (g.size() >= at + 3 && g.compare(at, 2, "1H") == 0) rec = g[at + 2];
  }
  auto damaged = [&](std::size_t entry, const std::string& what) {
    throw Error(Errc::invalid_input, path + ": a damaged IGES file (directory entry " +
                                         std::to_string(2 * entry + 1) + ": " + what + ")");
  };
  auto field = [](const std::string& l, int k) {  // 8-column field k (0-based) of a D line
    const std::string f = l.substr(static_cast<std::size_t>(8 * k), 8);
    const auto b = f.find_first_not_of(' ');
    if (b == std::string::npos) return 0L;
    char* end = nullptr;
    const long v = std::strtol(f.c_str() + b, &end, 10);
    return (end && *end == '\0') ||
                   (end && std::string(end).find_first_not_of(' ') == std::string::npos)
               ? v
               : -1L;
  };
  for (std::size_t e = 0; e + 1 < d.size(); e += 2) {
    const long type = field(d[e], 0), start = field(d[e], 1), count = field(d[e + 1], 3);
    if (type < 0 || start < 1 || count < 1 || start + count - 1 > static_cast<long>(p.size()))
      damaged(e / 2, "its parameter lines are missing");
    std::string data;
    for (long k = start - 1; k < start - 1 + count; ++k)
      data += p[static_cast<std::size_t>(k)].substr(0, 64);
    const auto end = data.find(rec);
    if (end == std::string::npos) damaged(e / 2, "its parameter record is cut short");
    if (type != 126 && type != 128) continue;
    std::vector<double> v;
    std::size_t pos = 0;
    const std::string rec_data = data.substr(0, end);
    while (pos <= rec_data.size()) {
      const auto next = std::min(rec_data.find(delim, pos), rec_data.size());
      std::string f = rec_data.substr(pos, next - pos);
      f.erase(0, f.find_first_not_of(' '));
      f.erase(f.find_last_not_of(' ') + 1);
      for (auto& c : f)
        if (c == 'D' || c == 'd') c = 'E';  // Fortran double exponent
      char* stop = nullptr;
      const double x = std::strtod(f.c_str(), &stop);
      v.push_back(!f.empty() && stop && *stop == '\0' && std::isfinite(x) ? x : std::nan(""));
      pos = next + 1;
    }
    auto count_ok = [&](double need) { return static_cast<double>(v.size()) >= need; };
    auto numbers_ok = [&](std::size_t need) {
      for (std::size_t k = 1; k < need; ++k)
        if (std::isnan(v[k])) return false;
      return true;
    };
    if (type == 126) {
      if (!count_ok(3)) damaged(e / 2, "a B-spline curve without its degree");
      const double K = v[1], M = v[2];
      if (!(M >= 1 && M <= 25 && K >= M && K <= 1e6 && K == std::floor(K) && M == std::floor(M)))
        damaged(e / 2, "a B-spline curve with impossible K, M");
      const double need = 7 + (K + M + 2) + 4 * (K + 1) + 5;
      if (!count_ok(need) || !numbers_ok(static_cast<std::size_t>(need)))
        damaged(e / 2, "a B-spline curve with missing or non-numeric data");
    } else {
      if (!count_ok(5)) damaged(e / 2, "a B-spline surface without its degrees");
      const double K1 = v[1], K2 = v[2], M1 = v[3], M2 = v[4];
      if (!(M1 >= 1 && M2 >= 1 && M1 <= 25 && M2 <= 25 && K1 >= M1 && K2 >= M2 &&
            (K1 + 1) * (K2 + 1) <= 1e7 && K1 == std::floor(K1) && K2 == std::floor(K2) &&
            M1 == std::floor(M1) && M2 == std::floor(M2)))
        damaged(e / 2, "a B-spline surface with impossible K, M");
      const double need = 10 + (K1 + M1 + 2) + (K2 + M2 + 2) + 4 * (K1 + 1) * (K2 + 1) + 4;
      if (!count_ok(need) || !numbers_ok(static_cast<std::size_t>(need)))
        damaged(e / 2, "a B-spline surface with missing or non-numeric data");
    }
  }
}

/// Refuses a file in which OpenCASCADE's reader found failed entities (a damaged or
/// truncated file): transferring one can dereference a missing entity and crash.
void refuse_failed_load(XSControl_Reader& reader, const std::string& path, const char* format) {
  const Interface_CheckIterator checks = reader.WS()->ModelCheckList();
  for (checks.Start(); checks.More(); checks.Next()) {
    const Handle(Interface_Check)& c = checks.Value();
    if (c.IsNull() || !c->HasFailed()) continue;
    std::string what = c->NbFails() > 0 ? c->CFail(1) : "a failed entity";
    const int n = checks.Number();
    throw Error(Errc::invalid_input, path + ": a damaged " + format + " file" +
                                         (n > 0 ? " (entity " + std::to_string(n) + ": " : " (") +
                                         what + ")");
  }
}

/// read_cad's work, run in the child process: the counts, flags and units, which faces are
/// planes, and the profile's wire; the B-splines OpenCASCADE made go to `surfaces` (one per
/// face that is not a plane) and `curve_out`, for the calling process to convert.
CadGeometry read_cad_here(const std::string& path, bool want_surface, const std::string& ext,
                          const UnitNames& u, bool prechecks,
                          std::vector<Handle(Geom_BSplineSurface)>& surfaces,
                          Handle(Geom_BSplineCurve) & curve_out) {
  quiet_occt();
  CadGeometry g;
  TopoDS_Shape shape;
  try {
    if (ext == ".step" || ext == ".stp") {
      STEPControl_Controller::Init();
      Interface_Static::SetCVal("xstep.cascade.unit", u.step);
      UnitsMethods::SetCasCadeLengthUnit(u.mm);
      STEPControl_Reader reader;
      if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
        throw Error(Errc::invalid_input, path + ": not a readable STEP file");
      if (prechecks) refuse_failed_load(reader, path, "STEP");
      TColStd_SequenceOfAsciiString len, ang, solid;
      reader.FileUnits(len, ang, solid);
      if (len.Length() > 0) g.file_units = lower(len.First().ToCString());
      reader.TransferRoots();
      shape = reader.OneShape();
    } else if (ext == ".igs" || ext == ".iges") {
      IGESControl_Controller::Init();
      Interface_Static::SetCVal("xstep.cascade.unit", u.step);
      UnitsMethods::SetCasCadeLengthUnit(u.mm);
      Interface_Static::SetIVal("read.iges.bspline.continuity", 0);  // keep C0 B-splines whole
      IGESControl_Reader reader;
      if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
        throw Error(Errc::invalid_input, path + ": not a readable IGES file");
      if (prechecks) refuse_failed_load(reader, path, "IGES");
      const auto model = Handle(IGESData_IGESModel)::DownCast(reader.Model());
      if (!model.IsNull() && !model->GlobalSection().UnitName().IsNull())
        g.file_units = lower(model->GlobalSection().UnitName()->ToCString());
      reader.TransferRoots();
      shape = reader.OneShape();
    } else {
      throw Error(Errc::invalid_input, path + ": expected a .step, .stp, .igs or .iges file");
    }
    if (shape.IsNull()) throw Error(Errc::invalid_input, path + ": the file holds no geometry");
    g.valid = BRepCheck_Analyzer(shape).IsValid();
    for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) ++g.faces;
    for (TopExp_Explorer e(shape, TopAbs_EDGE); e.More(); e.Next()) ++g.edges;
    for (TopExp_Explorer e(shape, TopAbs_SHELL); e.More(); e.Next()) ++g.shells;
    for (TopExp_Explorer e(shape, TopAbs_SOLID); e.More(); e.Next()) ++g.solids;
    {  // closed: every edge (but degenerate ones) bounds exactly two faces
      TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
      TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
      g.closed = edge_faces.Extent() > 0;
      for (int i = 1; i <= edge_faces.Extent(); ++i)
        if (!BRep_Tool::Degenerated(TopoDS::Edge(edge_faces.FindKey(i))) &&
            edge_faces.FindFromIndex(i).Extent() != 2)
          g.closed = false;
    }
    if (g.solids > 0) {
      GProp_GProps props;
      BRepGProp::VolumeProperties(shape, props, 1e-9, Standard_True);
      g.volume = props.Mass();
    }
    if (want_surface) {
      for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
        const Handle(Geom_Surface) surf = BRep_Tool::Surface(TopoDS::Face(e.Current()));
        if (surf.IsNull()) throw Error(Errc::invalid_input, path + ": a face has no surface");
        CadFace face;
        if (!Handle(Geom_Plane)::DownCast(surf).IsNull()) {
          face.is_plane = true;
          g.face_list.push_back(std::move(face));
          continue;
        }
        Handle(Geom_BSplineSurface) bs = Handle(Geom_BSplineSurface)::DownCast(surf);
        if (bs.IsNull()) bs = GeomConvert::SurfaceToBSplineSurface(surf);
        surfaces.push_back(bs);
        g.face_list.push_back(std::move(face));
      }
      if (surfaces.empty())
        throw Error(Errc::invalid_input, path + ": the file holds no surface (face)");
      g.is_surface = true;
    } else {
      TopExp_Explorer e(shape, TopAbs_EDGE);
      if (!e.More()) throw Error(Errc::invalid_input, path + ": the file holds no curve (edge)");
      double first = 0, last = 0;
      const Handle(Geom_Curve) curve = BRep_Tool::Curve(TopoDS::Edge(e.Current()), first, last);
      if (curve.IsNull())
        throw Error(Errc::invalid_input, path + ": the first edge has no 3D curve");
      // Readers split a curve at its C0 knots into edges on the same curve: take the whole
      // range of the curve the first edge lies on.
      for (e.Next(); e.More(); e.Next()) {
        double f2 = 0, l2 = 0;
        if (BRep_Tool::Curve(TopoDS::Edge(e.Current()), f2, l2) != curve) continue;
        first = std::min(first, f2);
        last = std::max(last, l2);
      }
      curve_out = whole_curve(curve, first, last);
      g.wire = profile_edges(shape);  // empty: the calling process takes the curve
    }
  } catch (const Standard_Failure& e) {
    throw Error(Errc::invalid_input,
                path + ": OpenCASCADE could not read it: " + e.GetMessageString());
  }
  return g;
}

void put_nurbs(ByteWriter& w, const sweep::NurbsCurve<double>& c) {
  w.put(c.degree);
  w.put_vector(c.knots);
  w.put(c.points.size());
  for (const auto& p : c.points) w.put(std::array<double, 3>{p.x(), p.y(), p.z()});
  w.put_vector(c.weights);
}

sweep::NurbsCurve<double> get_nurbs_curve(ByteReader& r) {
  sweep::NurbsCurve<double> c;
  c.degree = r.get<int>();
  c.knots = r.get_vector<double>();
  for (const auto& p : r.get_vector<std::array<double, 3>>())
    c.points.emplace_back(p[0], p[1], p[2]);
  c.weights = r.get_vector<double>();
  return c;
}

// OpenCASCADE's own B-splines as the child read them (periodic or not, unclamped or not),
// rebuilt in this process: from_occt converts them to our clamped NURBS here, and
// CadGeometry::value stays OpenCASCADE's evaluation of the file's object.
template <typename Array>
std::vector<double> reals(const Array& a) {
  return std::vector<double>(a.begin(), a.end());
}

template <typename Array>
std::vector<int> ints(const Array& a) {
  return std::vector<int>(a.begin(), a.end());
}

void put_occt(ByteWriter& w, const Handle(Geom_BSplineCurve) & c) {
  w.put(c->Degree());
  w.put(static_cast<char>(c->IsPeriodic()));
  w.put_vector(reals(c->Knots()));
  w.put_vector(ints(c->Multiplicities()));
  std::vector<std::array<double, 4>> poles;
  for (int i = 1; i <= c->NbPoles(); ++i) {
    const gp_Pnt p = c->Pole(i);
    poles.push_back({p.X(), p.Y(), p.Z(), c->Weight(i)});
  }
  w.put_vector(poles);
}

Handle(Geom_BSplineCurve) get_occt_curve(ByteReader& r) {
  const int degree = r.get<int>();
  const bool periodic = r.get<char>() != 0;
  const auto k = r.get_vector<double>();
  const auto m = r.get_vector<int>();
  const auto poles = r.get_vector<std::array<double, 4>>();
  TColStd_Array1OfReal weights(1, static_cast<int>(poles.size()));
  TColgp_Array1OfPnt points(1, static_cast<int>(poles.size()));
  for (std::size_t i = 0; i < poles.size(); ++i) {
    const auto& p = poles[i];
    points.SetValue(static_cast<int>(i) + 1, gp_Pnt(p[0], p[1], p[2]));
    weights.SetValue(static_cast<int>(i) + 1, p[3]);
  }
  return new Geom_BSplineCurve(points, weights, occt_reals(k), occt_ints(m), degree, periodic);
}

void put_occt(ByteWriter& w, const Handle(Geom_BSplineSurface) & s) {
  w.put(s->UDegree());
  w.put(s->VDegree());
  w.put(static_cast<char>(s->IsUPeriodic()));
  w.put(static_cast<char>(s->IsVPeriodic()));
  w.put_vector(reals(s->UKnots()));
  w.put_vector(ints(s->UMultiplicities()));
  w.put_vector(reals(s->VKnots()));
  w.put_vector(ints(s->VMultiplicities()));
  w.put(s->NbVPoles());
  std::vector<std::array<double, 4>> poles;
  for (int i = 1; i <= s->NbUPoles(); ++i)
    for (int j = 1; j <= s->NbVPoles(); ++j) {
      const gp_Pnt p = s->Pole(i, j);
      poles.push_back({p.X(), p.Y(), p.Z(), s->Weight(i, j)});
    }
  w.put_vector(poles);
}

Handle(Geom_BSplineSurface) get_occt_surface(ByteReader& r) {
  const int du = r.get<int>(), dv = r.get<int>();
  const bool pu = r.get<char>() != 0, pv = r.get<char>() != 0;
  const auto uk = r.get_vector<double>();
  const auto um = r.get_vector<int>();
  const auto vk = r.get_vector<double>();
  const auto vm = r.get_vector<int>();
  const int nv = r.get<int>();
  const auto poles = r.get_vector<std::array<double, 4>>();
  if (nv < 1 || poles.size() % static_cast<std::size_t>(nv) != 0)
    throw Error(Errc::internal, "an isolated reader's surface is garbled");
  const int nu = static_cast<int>(poles.size() / static_cast<std::size_t>(nv));
  TColgp_Array2OfPnt points(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const auto& p = poles[static_cast<std::size_t>(i * nv + j)];
      points.SetValue(i + 1, j + 1, gp_Pnt(p[0], p[1], p[2]));
      weights.SetValue(i + 1, j + 1, p[3]);
    }
  return new Geom_BSplineSurface(points, weights, occt_reals(uk), occt_reals(vk), occt_ints(um),
                                 occt_ints(vm), du, dv, pu, pv);
}

std::function<Eigen::Vector3d(double, double)> evaluator(Handle(Geom_BSplineSurface) s) {
  return [s](double u, double v) {
    const gp_Pnt p = s->Value(u, v);
    return Eigen::Vector3d(p.X(), p.Y(), p.Z());
  };
}

std::function<Eigen::Vector3d(double, double)> evaluator(Handle(Geom_BSplineCurve) c) {
  return [c](double t, double) {
    const gp_Pnt p = c->Value(t);
    return Eigen::Vector3d(p.X(), p.Y(), p.Z());
  };
}

CadGeometry read_cad_isolated(const std::string& path, bool want_surface, const std::string& units,
                              bool prechecks) {
  if (!std::filesystem::is_regular_file(path))
    throw Error(Errc::invalid_input, path + ": cannot open file for reading");
  if (const auto size = std::filesystem::file_size(path); size > kMaxFileBytes)
    throw Error(Errc::invalid_input, path + ": a file of " + std::to_string(size) +
                                         " bytes (at most " + std::to_string(kMaxFileBytes) + ")");
  const std::string ext = lower_extension(path);
  const bool step = ext == ".step" || ext == ".stp";
  if (!step && ext != ".igs" && ext != ".iges")
    throw Error(Errc::invalid_input, path + ": expected a .step, .stp, .igs or .iges file");
  const UnitNames u = unit_names(units);
  if (!step && prechecks) check_iges_structure(path);
  // OpenCASCADE's STEP and IGES parsers crash on some damaged files and keep state from
  // one file to the next (IGES): they run in a child process, whose death is a refusal.
  const std::string answer = run_isolated(path, step ? "STEP" : "IGES", [&](std::string& out) {
    std::vector<Handle(Geom_BSplineSurface)> surfaces;
    Handle(Geom_BSplineCurve) curve;
    const CadGeometry g = read_cad_here(path, want_surface, ext, u, prechecks, surfaces, curve);
    ByteWriter w(out);
    w.put(static_cast<char>(g.is_surface));
    w.put(std::array<int, 4>{g.faces, g.edges, g.solids, g.shells});
    w.put(static_cast<char>(g.valid));
    w.put(static_cast<char>(g.closed));
    w.put(g.volume);
    w.put_string(g.file_units);
    w.put(g.face_list.size());
    for (const auto& f : g.face_list) w.put(static_cast<char>(f.is_plane));
    for (const auto& s : surfaces) put_occt(w, s);
    if (!want_surface) {
      put_occt(w, curve);
      w.put(g.wire.size());
      for (const auto& c : g.wire) put_nurbs(w, c);
    }
  });
  CadGeometry g;
  ByteReader in(answer);
  try {
    g.is_surface = in.get<char>() != 0;
    const auto counts = in.get<std::array<int, 4>>();
    g.faces = counts[0];
    g.edges = counts[1];
    g.solids = counts[2];
    g.shells = counts[3];
    g.valid = in.get<char>() != 0;
    g.closed = in.get<char>() != 0;
    g.volume = in.get<double>();
    g.file_units = in.get_string();
    g.face_list.resize(in.get<std::size_t>());
    for (auto& f : g.face_list) f.is_plane = in.get<char>() != 0;
    for (auto& f : g.face_list) {
      if (f.is_plane) continue;
      const auto bs = get_occt_surface(in);
      f.surface = from_occt(bs);
      f.value = evaluator(bs);
      if (g.value) continue;
      g.surface = f.surface;  // the first face that is not a plane
      g.value = f.value;
    }
    if (!want_surface) {
      const auto bc = get_occt_curve(in);
      g.curve = from_occt(bc);
      g.value = evaluator(bc);
      g.wire.resize(in.get<std::size_t>());
      for (auto& c : g.wire) c = get_nurbs_curve(in);
      if (g.wire.empty()) g.wire.push_back(g.curve);
    }
  } catch (const Standard_Failure& e) {  // as in the child: from_occt's conversion
    throw Error(Errc::invalid_input,
                path + ": OpenCASCADE could not read it: " + e.GetMessageString());
  }
  if (!in.done()) throw Error(Errc::internal, path + ": an isolated reader's answer is garbled");
  return g;
}

}  // namespace

CadGeometry read_cad(const std::string& path, bool want_surface, const std::string& units) {
  return read_cad_isolated(path, want_surface, units, true);
}

CadGeometry read_cad_unchecked(const std::string& path, bool want_surface,
                               const std::string& units) {
  return read_cad_isolated(path, want_surface, units, false);
}

std::vector<std::array<Eigen::Vector3d, 3>> read_stl(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error(Errc::invalid_input, "--object " + path + ": no such file");
  // In a child process, as read_cad: OpenCASCADE's parser meets the user's file there.
  const std::string answer = run_isolated("--object " + path, "STL", [&](std::string& out) {
    quiet_occt();
    const Handle(Poly_Triangulation) tri = RWStl::ReadFile(path.c_str());
    if (tri.IsNull() || tri->NbTriangles() == 0)
      throw Error(Errc::invalid_input, "--object " + path + ": not a readable STL mesh");
    std::vector<std::array<double, 9>> triangles;
    triangles.reserve(static_cast<std::size_t>(tri->NbTriangles()));
    for (int i = 1; i <= tri->NbTriangles(); ++i) {
      int n[3];
      tri->Triangle(i).Get(n[0], n[1], n[2]);
      std::array<double, 9> t;
      for (int k = 0; k < 3; ++k) {
        const gp_Pnt p = tri->Node(n[k]);
        t[static_cast<std::size_t>(3 * k)] = p.X();
        t[static_cast<std::size_t>(3 * k + 1)] = p.Y();
        t[static_cast<std::size_t>(3 * k + 2)] = p.Z();
      }
      triangles.push_back(t);
    }
    ByteWriter(out).put_vector(triangles);
  });
  ByteReader in(answer);
  std::vector<std::array<Eigen::Vector3d, 3>> out;
  for (const auto& t : in.get_vector<std::array<double, 9>>())
    out.push_back({Eigen::Vector3d(t[0], t[1], t[2]), Eigen::Vector3d(t[3], t[4], t[5]),
                   Eigen::Vector3d(t[6], t[7], t[8])});
  return out;
}

}  // namespace qmotion::io
