// io/src/occt_loader.cpp: the functions of <qmotion/io/occt.hpp>, in libqmotion: each calls
// its implementation in libqmotion_occt, loaded on first use (io/src/occt_plugin.hpp).
#include <dlfcn.h>

#include <cmath>
#include <filesystem>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/kernel/error.hpp>
#include <string>

#include "occt_plugin.hpp"
#include "occt_unchecked.hpp"

namespace qmotion::io {
namespace {

constexpr const char* kPluginName = "libqmotion_occt.so";

/// libqmotion_occt beside this library (its directory from dladdr), else by the loader's
/// search. Errc::export_failed, with the loader's message, when it cannot be loaded.
const plugin::Table* load_table() {
  std::string here_dir;
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&load_table), &info) && info.dli_fname)
    here_dir = std::filesystem::path(info.dli_fname).parent_path().string();
  void* handle = nullptr;
  std::string why;
  for (const std::string& candidate :
       {here_dir.empty() ? std::string() : here_dir + "/" + kPluginName,
        std::string(kPluginName)}) {
    if (candidate.empty()) continue;
    handle = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle) break;
    const char* e = dlerror();
    why = e ? e : "unknown error";
  }
  if (!handle)
    throw Error(Errc::export_failed,
                std::string("OpenCASCADE's part of qmotion (") + kPluginName +
                    ") could not be loaded, so STEP, IGES and meshes are unavailable: " + why);
  using Entry = const plugin::Table* (*)();
  const auto entry = reinterpret_cast<Entry>(dlsym(handle, "qmotion_occt_table"));
  const plugin::Table* t = entry ? entry() : nullptr;
  if (!t || t->abi != plugin::kTableAbi)
    throw Error(Errc::export_failed, std::string(kPluginName) +
                                         " is from another build of qmotion (its table does "
                                         "not match); reinstall qmotion");
  return t;
}

/// The table, loaded once: a static's initialisation is thread-safe, and one that throws is
/// tried again at the next call.
const plugin::Table& table() {
  static const plugin::Table* const loaded = load_table();
  return *loaded;
}

/// Errc::invalid_input, before anything is built, when the file's floor is over the limit.
template <typename Geometry>
void refuse_large(const std::string& path, const Geometry& g, const char* format,
                  std::uintmax_t pole_bytes) {
  const std::uintmax_t n = io::control_points(g);  // not a unity neighbour's helper
  if (n > kMaxFileBytes / pole_bytes)
    throw Error(Errc::invalid_input,
                path + ": the " + format + " file would be at least " +
                    std::to_string(n * pole_bytes) + " bytes (" + std::to_string(n) +
                    " control points), more than " + std::to_string(kMaxFileBytes) +
                    " (the limit of a file qmotion reads or writes, which bounds memory): "
                    "refused before it is built");
}
template <typename Geometry>
void refuse_large_step(const std::string& path, const Geometry& g) {
  refuse_large(path, g, "STEP", kStepPoleBytes);
}
template <typename Geometry>
void refuse_large_iges(const std::string& path, const Geometry& g) {
  refuse_large(path, g, "IGES", kIgesPoleBytes);
}

}  // namespace

std::uintmax_t control_points(const sweep::NurbsCurve<double>& c) { return c.points.size(); }
std::uintmax_t control_points(const sweep::NurbsSurface<double>& s) {
  std::uintmax_t n = 0;
  for (const auto& row : s.points) n += row.size();
  return n;
}
std::uintmax_t control_points(const sweep::NurbsShell<double>& s) {
  std::uintmax_t n = 0;
  for (const auto& f : s.faces) n += control_points(f);
  for (const auto* cap : {&s.cap_start, &s.cap_end})
    for (const auto& c : *cap) n += control_points(c);
  return n;
}
std::uintmax_t control_points(const std::vector<sweep::NurbsCurve<double>>& wire) {
  std::uintmax_t n = 0;
  for (const auto& c : wire) n += control_points(c);
  return n;
}

int occt_max_degree() { return table().occt_max_degree(); }

void write_step(const std::string& path, const sweep::NurbsSurface<double>& s,
                const ExportInfo& info) {
  refuse_large_step(path, s);
  table().write_step_surface(path, s, info);
}
void write_step(const std::string& path, const sweep::NurbsCurve<double>& c,
                const ExportInfo& info) {
  refuse_large_step(path, c);
  table().write_step_curve(path, c, info);
}
void write_iges(const std::string& path, const sweep::NurbsSurface<double>& s,
                const ExportInfo& info) {
  refuse_large_iges(path, s);
  table().write_iges_surface(path, s, info);
}
void write_iges(const std::string& path, const sweep::NurbsCurve<double>& c,
                const ExportInfo& info) {
  refuse_large_iges(path, c);
  table().write_iges_curve(path, c, info);
}
void write_step(const std::string& path, const sweep::NurbsShell<double>& s,
                const ExportInfo& info) {
  refuse_large_step(path, s);
  table().write_step_shell(path, s, info);
}
void write_iges(const std::string& path, const sweep::NurbsShell<double>& s,
                const ExportInfo& info) {
  refuse_large_iges(path, s);
  table().write_iges_shell(path, s, info);
}
void write_step(const std::string& path, const std::vector<sweep::NurbsCurve<double>>& wire,
                const ExportInfo& info) {
  refuse_large_step(path, wire);
  table().write_step_wire(path, wire, info);
}
std::vector<FaceMesh> mesh_shell(const sweep::NurbsShell<double>& s, double deflection,
                                 double angle, const std::string& path) {
  return table().mesh_shell(s, deflection, angle, path);
}
CadGeometry read_cad(const std::string& path, bool want_surface, const std::string& units) {
  return table().read_cad(path, want_surface, units);
}
CadGeometry read_cad_unchecked(const std::string& path, bool want_surface,
                               const std::string& units) {
  return table().read_cad_unchecked(path, want_surface, units);
}
std::vector<std::array<Eigen::Vector3d, 3>> read_stl(const std::string& path) {
  return table().read_stl(path);
}
CadMesh mesh_cad(const std::string& path, double deflection, const std::string& units) {
  if (!(deflection > 0) || !std::isfinite(deflection))
    throw Error(Errc::internal, path + ": mesh_cad needs a positive deflection");
  return table().mesh_cad(path, deflection, units);
}

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

}  // namespace qmotion::io
