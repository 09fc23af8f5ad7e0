// io/src/occt_write.cpp: NURBS curves, surfaces, shells and solids written as STEP and IGES
// through OpenCASCADE, and shells tessellated for meshes.
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
#include "occt_convert.hpp"
#include "occt_plugin.hpp"

namespace qmotion::io {
using namespace detail;  // NOLINT: this module's own conversions
namespace {

Handle(TCollection_HAsciiString) hstr(const std::string& s) {
  return new TCollection_HAsciiString(s.c_str());
}

/// Writes a translated model to `path` through `print` (a STEP or IGES writer's Print) into a
/// temporary file, flushed and checked before the rename: a full disk leaves no truncated file.
template <typename Print>
void print_atomically(const std::string& path, const char* format, Print print) {
  AtomicOutput out(path);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    if (!f || !print(f))
      throw Error(Errc::invalid_input, path + ": cannot write the " + format + " file");
    f.close();
    if (f.fail())
      throw Error(Errc::invalid_input,
                  path + ": writing the " + format + " file failed (disk full?)");
  }
  out.commit();
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
  init_step_translator();
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
  print_atomically(path, "STEP", [&sw](std::ostream& f) { return sw.Print(f); });
}

/// Writes one geometry entity (`geom`), or a shape as IGES B-rep entities (`shape`).
void write_iges_model(const std::string& path, const Handle(Standard_Transient) & geom,
                      const TopoDS_Shape* shape, const ExportInfo& info) {
  quiet_occt();
  const UnitNames u = unit_names(info.units);
  init_iges_translator();
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
  print_atomically(path, "IGES", [&iw](std::ostream& f) { return iw.Print(f); });
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
  if (s.cap_start.empty() && !s.closed) {  // an open shell: its shared edges by equality
    const TopoDS_Shape direct = shared_edge_shell(s.faces);
    if (!direct.IsNull()) return direct;
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
  // A solid: planar caps added above, or (closed without them) faces that close by
  // themselves, such as a pipe with its half-sphere caps.
  if (s.cap_start.empty() && !s.closed) return sewn;
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

namespace plugin {

int occt_max_degree() { return Geom_BSplineCurve::MaxDegree(); }

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

}  // namespace plugin
}  // namespace qmotion::io
