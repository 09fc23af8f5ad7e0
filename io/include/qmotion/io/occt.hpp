// <qmotion/io/occt.hpp>
#pragma once
// STEP and IGES through OpenCASCADE. No OpenCASCADE type appears here: handles, 1-based
// arrays and knot/multiplicity pairs stay in occt.cpp (STYLE §4, §9).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <qmotion/sweep/nurbs.hpp>
#include <qmotion/sweep/shell.hpp>
#include <string>
#include <vector>

namespace qmotion::io {

/// Metadata written into STEP/IGES headers.
struct ExportInfo {
  std::string units = "mm";  ///< mm, cm, m, in, ft, um: declared in the file, numbers in it
  std::string product = "qmotion";
  std::string description;  ///< e.g. the motion file the geometry came from
};

/// Maximum B-spline degree OpenCASCADE stores (Geom_BSplineCurve::MaxDegree()).
int occt_max_degree();

/// Writes one face bounded by the surface's natural boundary (AP214), every real with 17
/// significant digits, the declared unit `info.units`. Atomic (docs/formats.md). Throws
/// Errc::export_failed when OpenCASCADE refuses the geometry.
void write_step(const std::string& path, const sweep::NurbsSurface<double>& s,
                const ExportInfo& info);
/// Writes the curve as one edge.
void write_step(const std::string& path, const sweep::NurbsCurve<double>& c,
                const ExportInfo& info);
/// IGES 5.3: entity 128 (rational B-spline surface), full precision, declared unit.
void write_iges(const std::string& path, const sweep::NurbsSurface<double>& s,
                const ExportInfo& info);
/// IGES 5.3: entity 126 (rational B-spline curve).
void write_iges(const std::string& path, const sweep::NurbsCurve<double>& c,
                const ExportInfo& info);

/// A shell of faces (split at C0 knots, several profile edges) sewn along their shared
/// edges; with `closed` and caps, the planar caps are added and the whole written as one
/// closed solid (STEP MANIFOLD_SOLID_BREP; IGES 5.3 B-rep entities 186/514/510). Throws
/// Errc::export_failed when OpenCASCADE cannot sew or close it.
void write_step(const std::string& path, const sweep::NurbsShell<double>& s,
                const ExportInfo& info);
void write_iges(const std::string& path, const sweep::NurbsShell<double>& s,
                const ExportInfo& info);
/// A wire: the curves in order, joined end to start (a profile of several edges).
void write_step(const std::string& path, const std::vector<sweep::NurbsCurve<double>>& wire,
                const ExportInfo& info);

/// The control points a STEP or IGES file of the geometry holds at least: every pole of every
/// face and curve (a shell's cap edges once: a face's boundary may share them).
std::uintmax_t control_points(const sweep::NurbsSurface<double>& s);
std::uintmax_t control_points(const sweep::NurbsCurve<double>& c);
std::uintmax_t control_points(const sweep::NurbsShell<double>& s);
std::uintmax_t control_points(const std::vector<sweep::NurbsCurve<double>>& wire);

/// Floors on the bytes a control point takes in the files write_step and write_iges write,
/// every real at 17 significant digits (at least 23 characters; OpenCASCADE does not shorten
/// zeros). STEP: a CARTESIAN_POINT entity of three reals with its name and brackets. IGES: three
/// reals in the parameter section, two to an 80-column record. The writers refuse geometry
/// whose control points times its floor pass kMaxFileBytes before OpenCASCADE builds anything:
/// the file would be refused anyway, after OpenCASCADE held it several times over in memory.
inline constexpr std::uintmax_t kStepPoleBytes = 100;
inline constexpr std::uintmax_t kIgesPoleBytes = 120;

/// One face of a shell as OpenCASCADE's mesher (BRepMesh_IncrementalMesh) triangulated it.
struct FaceMesh {
  int face = -1;  ///< the shell's face (index into faces) it lies on; -1: a planar cap
  std::vector<Eigen::Vector3d> nodes;
  std::vector<Eigen::Vector2d> uv;            ///< the nodes' (u, v) on that face's surface
  std::vector<std::array<int, 3>> triangles;  ///< 0-based, counter-clockwise seen from outside
  Eigen::Vector3d plane_point, plane_normal;  ///< a cap's plane
};

/// The shell (built as write_step builds it: sewn faces, with caps one oriented solid)
/// triangulated within `deflection` (absolute) and `angle` (radians) by BRepMesh.
/// Triangles follow the faces' orientation in the shape. Throws Errc::export_failed naming
/// path when OpenCASCADE fails.
std::vector<FaceMesh> mesh_shell(const sweep::NurbsShell<double>& s, double deflection,
                                 double angle, const std::string& path);

/// One face read back: its surface as NURBS, or a plane (a solid's cap).
struct CadFace {
  bool is_plane = false;
  sweep::NurbsSurface<double> surface;  ///< (not is_plane)
  /// Evaluation by OpenCASCADE itself (Geom_BSplineSurface::Value).
  std::function<Eigen::Vector3d(double, double)> value;
};

/// Geometry read back from a STEP or IGES file through OpenCASCADE.
struct CadGeometry {
  bool is_surface = false;
  sweep::NurbsSurface<double> surface;  ///< first face's surface as NURBS (is_surface)
  sweep::NurbsCurve<double> curve;      ///< first edge's curve as NURBS (otherwise)
  /// The first wire's edges in order (each whole curve; otherwise the first edge's curve).
  std::vector<sweep::NurbsCurve<double>> wire;
  std::vector<CadFace> face_list;  ///< every face (is_surface)
  /// Evaluation by OpenCASCADE itself (Geom_BSplineSurface/Curve::Value): (u, v) or (t, -).
  std::function<Eigen::Vector3d(double, double)> value;
  int faces = 0, solids = 0, shells = 0;
  int edges = 0;           ///< distinct edges (one shared by two faces counts once)
  bool valid = false;      ///< BRepCheck_Analyzer on the whole shape
  bool closed = false;     ///< every edge of the shape bounds two faces (a closed shell)
  double volume = 0;       ///< of the solids, by BRepGProp's adaptive integration (1e-9)
  std::string file_units;  ///< the length unit the file declares (lower case, e.g. "mm")
};

/// Reads a STEP (.step/.stp) or IGES (.igs/.iges) file, converting lengths to `units`.
/// With `want_surface`, every face (and the first face's surface); else the first wire's
/// edges and the first edge's curve. Curves and surfaces of other types are converted to
/// NURBS (exactly for lines, conics and B-splines). Throws Errc::invalid_input naming the
/// file when it cannot be read or holds no such geometry.
///
/// OpenCASCADE reads the file in a child process (fork; io/isolated.hpp): its parsers crash
/// on some damaged files, and the crash becomes Errc::invalid_input ("OpenCASCADE's reader
/// crashed on it") while this process goes on. CadGeometry::value evaluates, in this
/// process, the B-spline OpenCASCADE made in the child, rebuilt from its poles and knots.
/// As with any fork, a multithreaded caller must not hold locks OpenCASCADE needs.
CadGeometry read_cad(const std::string& path, bool want_surface, const std::string& units = "mm");

/// The solids of a STEP or IGES file as OpenCASCADE's mesher (BRepMesh_IncrementalMesh)
/// triangulates them: every node on the file's surfaces, every triangle within `deflection`
/// of its face (absolute, in `units`) by the mesher's own measure, and counter-clockwise
/// seen from outside. Planar faces are exact.
struct CadMesh {
  std::vector<std::array<Eigen::Vector3d, 3>> triangles;
  double deflection = 0;  ///< the largest a curved face's triangulation reports (0: none)
  int solids = 0, faces = 0, planar_faces = 0;
  std::string file_units;  ///< the length unit the file declares
};

/// Reads and meshes a STEP or IGES solid in a child process (as read_cad). Errc::invalid_input
/// naming the file when it cannot be read, holds no solid, is not closed or is invalid by
/// OpenCASCADE's checker, or when a face stays farther than `deflection` from its triangles.
CadMesh mesh_cad(const std::string& path, double deflection, const std::string& units = "mm");

/// Full clamped knot vector <-> distinct knots and multiplicities (the OpenCASCADE/STEP/
/// IGES convention); one conversion each way (STYLE §9).
void knots_to_distinct(const std::vector<double>& full, std::vector<double>& distinct,
                       std::vector<int>& mults);
std::vector<double> knots_from_distinct(const std::vector<double>& distinct,
                                        const std::vector<int>& mults);

/// The triangles of an STL file (ASCII or binary, OpenCASCADE's reader), in the file's
/// coordinates. Errc::invalid_input naming the file when it is missing or unreadable.
std::vector<std::array<Eigen::Vector3d, 3>> read_stl(const std::string& path);

}  // namespace qmotion::io
