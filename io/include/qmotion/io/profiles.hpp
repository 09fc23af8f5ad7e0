// <qmotion/io/profiles.hpp>
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <qmotion/sweep/nurbs.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <string>

namespace qmotion::io {

/// A profile of the moving space (docs/formats.md), one or more edges in order: a JSON
/// nurbs_curve file or a JSON array of them (a wire), all edges of the first wire of a
/// STEP or IGES file (converted to NURBS, exactly for lines, conics and B-splines; the
/// first edge's curve when the file has no wire), or a shorthand: `segment:x0,y0,z0:x1,y1,z1`,
/// `polyline:x,y,z:x,y,z:...`, `rect:w,h` (closed, centred at the moving origin in the
/// moving x-y plane), `circle:r` (exact rational circle in the moving x-y plane from
/// (r,0,0), counter-clockwise), `arc:r,a0,a1` (degrees). Lengths of STEP/IGES profiles are
/// converted to `units`. Consecutive edges must join (within 1e-9 of the profile's size).
/// Throws Errc::invalid_input naming the profile and what is wrong.
sweep::Profile<double> read_profile(const std::string& spec, const std::string& units = "mm");

/// The profile of a JSON document as a .json profile file holds it: one nurbs_curve, or an
/// array of them in order (a wire whose edges must join). Errc::invalid_input naming `where`.
sweep::Profile<double> profile_from_json(const nlohmann::json& doc, const std::string& where);

}  // namespace qmotion::io
