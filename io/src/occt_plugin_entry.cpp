// io/src/occt_plugin_entry.cpp: libqmotion_occt's table (io/src/occt_plugin.hpp).
#include "occt_plugin.hpp"

extern "C" const qmotion::io::plugin::Table* qmotion_occt_table() {
  namespace p = qmotion::io::plugin;
  using Surface = qmotion::sweep::NurbsSurface<double>;
  using Curve = qmotion::sweep::NurbsCurve<double>;
  using Shell = qmotion::sweep::NurbsShell<double>;
  using Info = qmotion::io::ExportInfo;
  using S = const std::string&;
  static const p::Table table{
      p::kTableAbi,
      &p::occt_max_degree,
      static_cast<void (*)(S, const Surface&, const Info&)>(&p::write_step),
      static_cast<void (*)(S, const Curve&, const Info&)>(&p::write_step),
      static_cast<void (*)(S, const Surface&, const Info&)>(&p::write_iges),
      static_cast<void (*)(S, const Curve&, const Info&)>(&p::write_iges),
      static_cast<void (*)(S, const Shell&, const Info&)>(&p::write_step),
      static_cast<void (*)(S, const Shell&, const Info&)>(&p::write_iges),
      static_cast<void (*)(S, const std::vector<Curve>&, const Info&)>(&p::write_step),
      &p::mesh_shell,
      &p::read_cad,
      &p::read_cad_unchecked,
      &p::read_stl,
      &p::mesh_cad};
  return &table;
}
