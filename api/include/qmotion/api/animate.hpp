// <qmotion/api/animate.hpp>: `qmotion animate`: a motion as a glTF 2.0 animation of a body,
// with keyframes certified against the exact motion under the players' own interpolation
// (docs/guide/animate.md).
#pragma once
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <qmotion/motion.hpp>
#include <string>

namespace qmotion {

struct AnimateOptions {
  std::string output;  ///< .glb or .gltf
  /// The body moved (io::read_body's forms); empty: a cube a tenth of the motion's extent
  /// (the bounding-box diagonal of its origin's trajectory).
  std::string body;
  /// Largest distance of any point of the body from where the exact motion puts it, at any
  /// time, in the motion's length unit (> 0); unset: 1e-3 of the bounding-box diagonal of
  /// the space the body sweeps.
  std::optional<double> tol;
  /// Seconds the animation lasts; 0: the motion's parameter range (time = t - a).
  double duration = 0;
};

struct Animation {
  std::string path;
  std::size_t keyframes = 0;
  double tolerance = 0;  ///< in the motion's unit
  /// Certified: no point of the body leaves the exact motion by more, between any two keys,
  /// for spherical-linear (glTF) and for component-wise (Blender) rotation blending.
  double bound = 0;
  /// Sampled beside it: the mesh's vertices at 16 times between every two keys, both blends.
  double measured = 0;
  std::string units;            ///< the motion's length unit (of tolerance, bound, measured)
  double metres_per_unit = 1;   ///< the file is in metres, as glTF requires
  double seconds_per_unit = 1;  ///< animation seconds per unit of the motion's parameter
  double duration = 0;          ///< seconds
  double a = 0, b = 0;          ///< the motion's interval; time 0 is t = a
  std::string body;
  double radius = 0;  ///< the body's largest distance from the moving origin (motion unit)
  std::size_t triangles = 0, vertices = 0;
  std::size_t bound_evaluations = 0;
  double seconds = 0;  ///< time taken
  nlohmann::json report() const;
};

/// Writes the motion (either kind) as a glTF animation of the body to options.output.
/// Errc::invalid_input for a bad output extension, tolerance, duration or body (nothing is
/// written); Errc::numerical_failure for a motion with a pole, or when the tolerance is
/// below what glTF's 32-bit numbers can carry.
Animation animate(const Motion& motion, const AnimateOptions& options);

}  // namespace qmotion
