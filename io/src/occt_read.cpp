// io/src/occt_read.cpp: STEP, IGES and STL files read through OpenCASCADE: their structure
// checked first, read in a child process (isolated.hpp), NURBS faces and curves returned.
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

}  // namespace

bool detail::closed_shape(const TopoDS_Shape& shape) {
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  bool closed = edge_faces.Extent() > 0;
  for (int i = 1; i <= edge_faces.Extent(); ++i)
    if (!BRep_Tool::Degenerated(TopoDS::Edge(edge_faces.FindKey(i))) &&
        edge_faces.FindFromIndex(i).Extent() != 2)
      closed = false;
  return closed;
}

TopoDS_Shape detail::read_shape(const std::string& path, const std::string& ext, const UnitNames& u,
                                bool prechecks, std::string& file_units) {
  quiet_occt();
  TopoDS_Shape shape;
  if (ext == ".step" || ext == ".stp") {
    init_step_translator();
    Interface_Static::SetCVal("xstep.cascade.unit", u.step);
    UnitsMethods::SetCasCadeLengthUnit(u.mm);
    STEPControl_Reader reader;
    if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
      throw Error(Errc::invalid_input, path + ": not a readable STEP file");
    if (prechecks) refuse_failed_load(reader, path, "STEP");
    TColStd_SequenceOfAsciiString len, ang, solid;
    reader.FileUnits(len, ang, solid);
    if (len.Length() > 0) file_units = lower(len.First().ToCString());
    reader.TransferRoots();
    shape = reader.OneShape();
  } else if (ext == ".igs" || ext == ".iges") {
    init_iges_translator();
    Interface_Static::SetCVal("xstep.cascade.unit", u.step);
    UnitsMethods::SetCasCadeLengthUnit(u.mm);
    Interface_Static::SetIVal("read.iges.bspline.continuity", 0);  // keep C0 B-splines whole
    IGESControl_Reader reader;
    if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
      throw Error(Errc::invalid_input, path + ": not a readable IGES file");
    if (prechecks) refuse_failed_load(reader, path, "IGES");
    const auto model = Handle(IGESData_IGESModel)::DownCast(reader.Model());
    if (!model.IsNull() && !model->GlobalSection().UnitName().IsNull())
      file_units = lower(model->GlobalSection().UnitName()->ToCString());
    reader.TransferRoots();
    shape = reader.OneShape();
  } else {
    throw Error(Errc::invalid_input, path + ": expected a .step, .stp, .igs or .iges file");
  }
  return shape;
}

namespace {

/// read_cad's work, run in the child process: the counts, flags and units, which faces are
/// planes, and the profile's wire; the B-splines OpenCASCADE made go to `surfaces` (one per
/// face that is not a plane) and `curve_out`, for the calling process to convert.
CadGeometry read_cad_here(const std::string& path, bool want_surface, const std::string& ext,
                          const UnitNames& u, bool prechecks,
                          std::vector<Handle(Geom_BSplineSurface)>& surfaces,
                          Handle(Geom_BSplineCurve) & curve_out) {
  CadGeometry g;
  TopoDS_Shape shape;
  try {
    shape = read_shape(path, ext, u, prechecks, g.file_units);
    if (shape.IsNull()) throw Error(Errc::invalid_input, path + ": the file holds no geometry");
    g.valid = BRepCheck_Analyzer(shape).IsValid();
    g.faces = distinct(shape, TopAbs_FACE), g.edges = distinct(shape, TopAbs_EDGE);
    g.shells = distinct(shape, TopAbs_SHELL), g.solids = distinct(shape, TopAbs_SOLID);
    g.closed = closed_shape(shape);
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
  if (std::filesystem::file_size(path) > kMaxFileBytes) refuse_file_size(path, kMaxFileBytes);
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

namespace plugin {

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

}  // namespace plugin
}  // namespace qmotion::io
