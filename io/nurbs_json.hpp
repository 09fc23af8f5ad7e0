// io/nurbs_json.hpp
#pragma once
#include <nlohmann/json.hpp>
#include <qmotion/sweep/nurbs.hpp>
#include <string>

namespace qmotion::io {

/// {"type":"nurbs_curve","degree","knots","control_points","weights"} (SPEC §4).
nlohmann::json curve_to_json(const sweep::NurbsCurve<double>& c);
/// {"type":"nurbs_surface","degree_u","degree_v","knots_u","knots_v","control_points","weights"}.
nlohmann::json surface_to_json(const sweep::NurbsSurface<double>& s);

/// Reads and validates a nurbs_curve (clamped knots, finite poles, positive finite
/// weights); throws Errc::invalid_input naming `where` and the field.
sweep::NurbsCurve<double> curve_from_json(const nlohmann::json& j, const std::string& where);

/// Reads and validates a nurbs_surface (SPEC §4 layout); throws Errc::invalid_input.
sweep::NurbsSurface<double> surface_from_json(const nlohmann::json& j, const std::string& where);

}  // namespace qmotion::io
