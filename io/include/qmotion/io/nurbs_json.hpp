// <qmotion/io/nurbs_json.hpp>
#pragma once
#include <nlohmann/json.hpp>
#include <qmotion/sweep/nurbs.hpp>
#include <string>
#include <vector>

namespace qmotion::io {

/// A point or a vector as the JSON array [x, y, z].
inline nlohmann::json point_json(const Eigen::Vector3d& p) { return {p(0), p(1), p(2)}; }

/// {"type":"nurbs_curve","degree","knots","control_points","weights"} (docs/formats.md).
nlohmann::json curve_to_json(const sweep::NurbsCurve<double>& c);
/// {"type":"nurbs_surface","degree_u","degree_v","knots_u","knots_v","control_points","weights"}.
nlohmann::json surface_to_json(const sweep::NurbsSurface<double>& s);

/// The same documents as JSON text, streamed (no tree): each pole on one line, numbers in
/// their shortest round-trip form (std::to_chars), keys in sorted order as the tree writes
/// them. `extra` adds top-level members (units, continuity, an approximation record); a
/// member of `extra` whose key the document already has is refused (Errc::internal).
/// Non-finite numbers are written as null, as nlohmann writes them.
std::string curve_json_text(const sweep::NurbsCurve<double>& c,
                            const nlohmann::json& extra = nlohmann::json::object());
std::string surface_json_text(const sweep::NurbsSurface<double>& s,
                              const nlohmann::json& extra = nlohmann::json::object());
/// {"type":"nurbs_shell","closed","faces":[nurbs_surface...]} plus `extra`.
std::string shell_json_text(const std::vector<sweep::NurbsSurface<double>>& faces, bool closed,
                            const nlohmann::json& extra = nlohmann::json::object());
/// The same documents written to `path` atomically as they are made, never held whole
/// (write_json_atomic); Errc::invalid_input naming the path when it cannot be written.
void write_curve_json(const std::string& path, const sweep::NurbsCurve<double>& c,
                      const nlohmann::json& extra = nlohmann::json::object());
void write_surface_json(const std::string& path, const sweep::NurbsSurface<double>& s,
                        const nlohmann::json& extra = nlohmann::json::object());
void write_shell_json(const std::string& path,
                      const std::vector<sweep::NurbsSurface<double>>& faces, bool closed,
                      const nlohmann::json& extra = nlohmann::json::object());

/// Reads and validates a nurbs_curve (clamped knots, finite poles, positive finite
/// weights); throws Errc::invalid_input naming `where` and the field.
sweep::NurbsCurve<double> curve_from_json(const nlohmann::json& j, const std::string& where);

/// Reads and validates a nurbs_surface (docs/formats.md layout); throws Errc::invalid_input.
sweep::NurbsSurface<double> surface_from_json(const nlohmann::json& j, const std::string& where);

/// A NURBS JSON file (docs/formats.md) as `check` reads it: its units when it states them,
/// and a curve, or the faces of a surface or a shell.
struct NurbsFile {
  std::string units;                               ///< as written; empty when the file states none
  sweep::NurbsCurve<double> curve;                 ///< when read as a curve
  std::vector<sweep::NurbsSurface<double>> faces;  ///< when read as a surface or a shell
};

/// Reads the file at `path` as a curve (nurbs_curve), or as a surface (a nurbs_surface, or
/// each face of a nurbs_shell). The poles, knots and weights are scanned in place, a row at a
/// time, and the text's pages given back as they are read, so a file near the 512 MiB limit
/// is never held beside a tree of it; anything unusual is read through the tree instead,
/// which words the refusal as curve_from_json and surface_from_json do (naming the file, the
/// face and the field).
NurbsFile read_nurbs_file(const std::string& path, bool surface);

}  // namespace qmotion::io
