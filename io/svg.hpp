// io/svg.hpp: pictures of motions (the demo's figure; the render issue extends it).
#pragma once
#include <qmotion/io/export.hpp>
#include <qmotion/sweep/nurbs.hpp>
#include <string>

namespace qmotion::io {

/// An isometric SVG of the trajectories of the origin and of (0,0,20) and of the profile at
/// nine instants, scaled to fit.
std::string render_demo_svg(const kernel::Motion<double>& motion,
                            const sweep::NurbsCurve<double>& profile);

}  // namespace qmotion::io
