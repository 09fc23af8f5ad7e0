// io/src/occt_mesh_read.cpp: the solids of a STEP or IGES file as a triangle mesh, for
// `verify`'s parts, stocks and fixtures (docs/formats.md, "Solids read by verify"): read and
// meshed by OpenCASCADE in a child process (isolated.hpp), as read_cad reads.
#include <BRepCheck_Analyzer.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Tool.hxx>
#include <Geom_Plane.hxx>
#include <IMeshTools_Parameters.hxx>
#include <Poly_Triangulation.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <filesystem>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/kernel/error.hpp>

#include "isolated.hpp"
#include "occt_convert.hpp"
#include "occt_plugin.hpp"

namespace qmotion::io {
using namespace detail;  // NOLINT: this module's own conversions

namespace {

/// The child's work: the file's solids meshed within `deflection`, every face's triangles
/// turned counter-clockwise seen from outside (a reversed face's reversed).
void mesh_here(const std::string& path, const std::string& ext, double deflection,
               const UnitNames& u, std::string& out) {
  std::string file_units;
  const TopoDS_Shape shape = read_shape(path, ext, u, true, file_units);
  if (shape.IsNull()) throw Error(Errc::invalid_input, path + ": the file holds no geometry");
  int solids = 0;
  for (TopExp_Explorer e(shape, TopAbs_SOLID); e.More(); e.Next()) ++solids;
  if (solids == 0) throw Error(Errc::invalid_input, path + ": the file holds no solid");
  if (!closed_shape(shape))
    throw Error(Errc::invalid_input, path + ": the solid is not closed (an edge bounds one face)");
  if (!BRepCheck_Analyzer(shape).IsValid())
    throw Error(Errc::invalid_input, path + ": OpenCASCADE finds the solid invalid");
  IMeshTools_Parameters params;
  params.Deflection = deflection;
  params.Angle = 0.5;
  BRepMesh_IncrementalMesh mesher(shape, params);
  if (!mesher.IsDone()) throw Error(Errc::invalid_input, path + ": OpenCASCADE's mesher failed");
  std::vector<std::array<double, 9>> triangles;
  std::array<int, 2> faces{0, 0};  // faces, planes among them
  double worst = 0;
  for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
    const TopoDS_Face& face = TopoDS::Face(e.Current());
    TopLoc_Location loc;
    const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
    ++faces[0];
    if (tri.IsNull())
      throw Error(Errc::invalid_input, path + ": OpenCASCADE's mesher left face " +
                                           std::to_string(faces[0]) + " untriangulated");
    if (!Handle(Geom_Plane)::DownCast(BRep_Tool::Surface(face)).IsNull())
      ++faces[1];
    else
      worst = std::max(worst, tri->Deflection());
    const gp_Trsf t = loc.Transformation();
    const bool reversed = face.Orientation() == TopAbs_REVERSED;
    for (int i = 1; i <= tri->NbTriangles(); ++i) {
      int n[3];
      tri->Triangle(i).Get(n[0], n[1], n[2]);
      if (reversed) std::swap(n[1], n[2]);
      std::array<double, 9> v;
      for (std::size_t k = 0; k < 3; ++k) {
        const gp_Pnt p = tri->Node(n[k]).Transformed(t);
        v[3 * k] = p.X();
        v[3 * k + 1] = p.Y();
        v[3 * k + 2] = p.Z();
      }
      triangles.push_back(v);
    }
  }
  ByteWriter w(out);
  w.put(solids);
  w.put(faces);
  w.put(worst);
  w.put_string(file_units);
  w.put_vector(triangles);
}

}  // namespace

namespace plugin {

CadMesh mesh_cad(const std::string& path, double deflection, const std::string& units) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error(Errc::invalid_input, path + ": cannot open file for reading");
  if (std::filesystem::file_size(path, ec) > kMaxFileBytes) refuse_file_size(path, kMaxFileBytes);
  const std::string ext = lower_extension(path);
  const bool step = ext == ".step" || ext == ".stp";
  if (!step && ext != ".igs" && ext != ".iges")
    throw Error(Errc::invalid_input, path + ": expected a .step, .stp, .igs or .iges file");
  const UnitNames u = unit_names(units);
  const std::string answer = run_isolated(path, step ? "STEP" : "IGES", [&](std::string& out) {
    try {
      mesh_here(path, ext, deflection, u, out);
    } catch (const Standard_Failure& e) {
      throw Error(Errc::invalid_input,
                  path + ": OpenCASCADE could not read or mesh it: " + e.GetMessageString());
    }
  });
  ByteReader in(answer);
  CadMesh m;
  m.solids = in.get<int>();
  const auto faces = in.get<std::array<int, 2>>();
  m.faces = faces[0];
  m.planar_faces = faces[1];
  m.deflection = in.get<double>();
  m.file_units = in.get_string();
  for (const auto& t : in.get_vector<std::array<double, 9>>())
    m.triangles.push_back({Eigen::Vector3d(t[0], t[1], t[2]), Eigen::Vector3d(t[3], t[4], t[5]),
                           Eigen::Vector3d(t[6], t[7], t[8])});
  if (!in.done()) throw Error(Errc::internal, path + ": an isolated reader's answer is garbled");
  if (m.deflection > deflection)
    throw Error(Errc::invalid_input, path + ": OpenCASCADE's mesher left a face " +
                                         kernel::detail::format_double(m.deflection) +
                                         " from its triangles, more than the " +
                                         kernel::detail::format_double(deflection) + " asked");
  return m;
}

}  // namespace plugin
}  // namespace qmotion::io
