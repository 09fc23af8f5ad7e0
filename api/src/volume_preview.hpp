// api/src/volume_preview.hpp: the swept volume that `render --body` and `view --volume` draw.
#pragma once
#include <optional>
#include <qmotion/api/volume.hpp>
#include <string>

namespace qmotion::detail {

/// The body of a preview (render --body, view --volume) and its mesh, at tol (--body-tol) or
/// by default at 1e-2 of the sampled box's diagonal; the body read goes to body_out if given.
SweptVolume preview_volume(const Motion& motion, const std::string& body_spec,
                           std::optional<double> tol, sweep::Body* body_out);

}  // namespace qmotion::detail
