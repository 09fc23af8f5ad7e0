// io/profiles.hpp
#pragma once
#include <string>

#include "sweep/nurbs.hpp"

namespace qmotion::io {

/// A profile curve of the moving space (SPEC §5): a JSON nurbs_curve file, the first edge
/// of a STEP or IGES file (converted to NURBS, exactly for lines, conics and B-splines), or
/// a shorthand: `segment:x0,y0,z0:x1,y1,z1`, `circle:r` (exact rational circle in the
/// moving x-y plane from (r,0,0), counter-clockwise), `arc:r,a0,a1` (degrees). Lengths of
/// STEP/IGES profiles are converted to `units`. Throws Errc::invalid_input naming the
/// profile and what is wrong.
sweep::NurbsCurve<double> read_profile(const std::string& spec, const std::string& units = "mm");

}  // namespace qmotion::io
