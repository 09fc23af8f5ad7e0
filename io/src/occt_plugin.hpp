// io/src/occt_plugin.hpp: the table through which libqmotion calls OpenCASCADE (private to
// io/). Everything that links OpenCASCADE is in libqmotion_occt, a library of its own that
// libqmotion loads (dlopen) the first time a STEP, IGES or STL file is read or written or a
// shell is meshed, so that commands that never touch one neither load OpenCASCADE's
// toolkits nor pay for their start-up (docs/architecture.md).
#pragma once
#include <qmotion/io/occt.hpp>
#include <string>
#include <vector>

namespace qmotion::io::plugin {

// The implementations behind the functions of <qmotion/io/occt.hpp> of the same names (and
// read_cad_unchecked of occt_unchecked.hpp), in libqmotion_occt.
int occt_max_degree();
void write_step(const std::string& path, const sweep::NurbsSurface<double>& s,
                const ExportInfo& info);
void write_step(const std::string& path, const sweep::NurbsCurve<double>& c,
                const ExportInfo& info);
void write_iges(const std::string& path, const sweep::NurbsSurface<double>& s,
                const ExportInfo& info);
void write_iges(const std::string& path, const sweep::NurbsCurve<double>& c,
                const ExportInfo& info);
void write_step(const std::string& path, const sweep::NurbsShell<double>& s,
                const ExportInfo& info);
void write_iges(const std::string& path, const sweep::NurbsShell<double>& s,
                const ExportInfo& info);
void write_step(const std::string& path, const std::vector<sweep::NurbsCurve<double>>& wire,
                const ExportInfo& info);
std::vector<FaceMesh> mesh_shell(const sweep::NurbsShell<double>& s, double deflection,
                                 double angle, const std::string& path);
CadGeometry read_cad(const std::string& path, bool want_surface, const std::string& units);
CadGeometry read_cad_unchecked(const std::string& path, bool want_surface,
                               const std::string& units);
std::vector<std::array<Eigen::Vector3d, 3>> read_stl(const std::string& path);
CadMesh mesh_cad(const std::string& path, double deflection, const std::string& units);

/// The table libqmotion_occt hands out. `abi` first: a library built from other sources is
/// refused rather than called.
struct Table {
  int abi;
  int (*occt_max_degree)();
  void (*write_step_surface)(const std::string&, const sweep::NurbsSurface<double>&,
                             const ExportInfo&);
  void (*write_step_curve)(const std::string&, const sweep::NurbsCurve<double>&, const ExportInfo&);
  void (*write_iges_surface)(const std::string&, const sweep::NurbsSurface<double>&,
                             const ExportInfo&);
  void (*write_iges_curve)(const std::string&, const sweep::NurbsCurve<double>&, const ExportInfo&);
  void (*write_step_shell)(const std::string&, const sweep::NurbsShell<double>&, const ExportInfo&);
  void (*write_iges_shell)(const std::string&, const sweep::NurbsShell<double>&, const ExportInfo&);
  void (*write_step_wire)(const std::string&, const std::vector<sweep::NurbsCurve<double>>&,
                          const ExportInfo&);
  std::vector<FaceMesh> (*mesh_shell)(const sweep::NurbsShell<double>&, double, double,
                                      const std::string&);
  CadGeometry (*read_cad)(const std::string&, bool, const std::string&);
  CadGeometry (*read_cad_unchecked)(const std::string&, bool, const std::string&);
  std::vector<std::array<Eigen::Vector3d, 3>> (*read_stl)(const std::string&);
  CadMesh (*mesh_cad)(const std::string&, double, const std::string&);
};

/// Changed whenever Table or a type it passes changes.
inline constexpr int kTableAbi = 2;

}  // namespace qmotion::io::plugin

/// The entry point libqmotion looks up in libqmotion_occt.
extern "C" const qmotion::io::plugin::Table* qmotion_occt_table();
