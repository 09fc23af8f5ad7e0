// io/occt.cpp: the only place OpenCASCADE appears (STYLE §4).
#include "io/occt.hpp"

#include <APIHeaderSection_MakeHeader.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRep_Tool.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
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
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <UnitsMethods.hxx>
#include <XSControl_WorkSession.hxx>
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/atomic_file.hpp"
#include "kernel/error.hpp"

namespace qmotion::io {
namespace {

/// Our unit names -> STEP (write.step.unit) and IGES (unit name) spellings, and the size
/// of the unit in millimetres.
struct UnitNames {
  const char* step;
  const char* iges;
  double mm;
};

UnitNames unit_names(const std::string& u) {
  if (u == "mm") return {"MM", "MM", 1.0};
  if (u == "cm") return {"CM", "CM", 10.0};
  if (u == "m") return {"M", "M", 1000.0};
  if (u == "in") return {"INCH", "IN", 25.4};
  if (u == "ft") return {"FT", "FT", 304.8};
  if (u == "um") return {"UM", "UM", 0.001};
  throw Error(Errc::invalid_input,
              "unknown length unit '" + u + "' (expected mm, cm, m, in, ft, um)");
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

void fill_knots(const std::vector<double>& full, TColStd_Array1OfReal& k,
                TColStd_Array1OfInteger& m) {
  std::vector<double> d;
  std::vector<int> mu;
  knots_to_distinct(full, d, mu);
  k.Resize(1, static_cast<int>(d.size()), false);
  m.Resize(1, static_cast<int>(d.size()), false);
  for (std::size_t i = 0; i < d.size(); ++i) {
    k.SetValue(static_cast<int>(i) + 1, d[i]);
    m.SetValue(static_cast<int>(i) + 1, mu[i]);
  }
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
  TColStd_Array1OfReal ku(1, 1), kv(1, 1);
  TColStd_Array1OfInteger mu(1, 1), mv(1, 1);
  fill_knots(s.knots_u, ku, mu);
  fill_knots(s.knots_v, kv, mv);
  return new Geom_BSplineSurface(poles, weights, ku, kv, mu, mv, s.degree_u, s.degree_v);
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
  TColStd_Array1OfReal k(1, 1);
  TColStd_Array1OfInteger m(1, 1);
  fill_knots(c.knots, k, m);
  return new Geom_BSplineCurve(poles, weights, k, m, c.degree);
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

std::string extension(const std::string& path) {
  return lower(std::filesystem::path(path).extension().string());
}

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
  if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone)
    throw Error(Errc::export_failed,
                path + ": OpenCASCADE could not translate the geometry to STEP");
  APIHeaderSection_MakeHeader header(writer.Model());
  header.SetName(hstr(std::filesystem::path(path).filename().string()));
  header.SetOriginatingSystem(hstr("qmotion 0.1.0"));
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
  }
  out.commit();
}

void write_iges_geom(const std::string& path, const Handle(Standard_Transient) & geom,
                     const ExportInfo& info) {
  quiet_occt();
  const UnitNames u = unit_names(info.units);
  IGESControl_Controller::Init();
  Interface_Static::SetCVal("xstep.cascade.unit", u.step);
  Interface_Static::SetCVal("write.iges.unit", u.iges);
  UnitsMethods::SetCasCadeLengthUnit(u.mm);
  IGESControl_Writer writer(u.iges, 0);
  {  // the model's own record of the unit the shape data is in (7.6): no rescaling
    IGESData_GlobalSection gs = writer.Model()->GlobalSection();
    gs.SetCascadeUnit(u.mm);
    writer.Model()->SetGlobalSection(gs);
  }
  if (!writer.AddGeom(geom))
    throw Error(Errc::export_failed,
                path + ": OpenCASCADE could not translate the geometry to IGES");
  writer.ComputeModel();
  IGESData_GlobalSection gs = writer.Model()->GlobalSection();
  gs.SetFileName(hstr(std::filesystem::path(path).filename().string()));
  gs.SetSendName(hstr(info.product));
  gs.SetSystemId(hstr("qmotion 0.1.0"));
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
  }
  out.commit();
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
  guarded(path, [&] { write_iges_geom(path, make_surface(s), info); });
}

void write_iges(const std::string& path, const sweep::NurbsCurve<double>& c,
                const ExportInfo& info) {
  guarded(path, [&] { write_iges_geom(path, make_curve(c), info); });
}

CadGeometry read_cad(const std::string& path, bool want_surface, const std::string& units) {
  if (!std::filesystem::is_regular_file(path))
    throw Error(Errc::invalid_input, path + ": cannot open file for reading");
  quiet_occt();
  const std::string ext = extension(path);
  const UnitNames u = unit_names(units);
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
    if (want_surface) {
      TopExp_Explorer e(shape, TopAbs_FACE);
      if (!e.More()) throw Error(Errc::invalid_input, path + ": the file holds no surface (face)");
      const Handle(Geom_Surface) surf = BRep_Tool::Surface(TopoDS::Face(e.Current()));
      Handle(Geom_BSplineSurface) bs = Handle(Geom_BSplineSurface)::DownCast(surf);
      if (bs.IsNull()) bs = GeomConvert::SurfaceToBSplineSurface(surf);
      g.is_surface = true;
      g.surface = from_occt(bs);
      g.value = [bs](double u, double v) {
        const gp_Pnt p = bs->Value(u, v);
        return Eigen::Vector3d(p.X(), p.Y(), p.Z());
      };
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
      Handle(Geom_BSplineCurve) bc = Handle(Geom_BSplineCurve)::DownCast(curve);
      if (bc.IsNull() || first != bc->FirstParameter() || last != bc->LastParameter())
        bc = GeomConvert::CurveToBSplineCurve(new Geom_TrimmedCurve(curve, first, last));
      g.curve = from_occt(bc);
      g.value = [bc](double t, double) {
        const gp_Pnt p = bc->Value(t);
        return Eigen::Vector3d(p.X(), p.Y(), p.Z());
      };
    }
  } catch (const Standard_Failure& e) {
    throw Error(Errc::invalid_input,
                path + ": OpenCASCADE could not read it: " + e.GetMessageString());
  }
  return g;
}

}  // namespace qmotion::io
