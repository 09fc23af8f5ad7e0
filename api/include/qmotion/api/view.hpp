// <qmotion/api/view.hpp>: `qmotion view`: a motion as one self-contained HTML page that
// animates it, draws its trajectories and exact sweep, and interpolates again in the page
// when a pose is edited (docs/guide/view.md).
#pragma once
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <qmotion/motion.hpp>
#include <string>
#include <vector>

namespace qmotion {

struct ViewOptions {
  std::string output;                   ///< .html
  std::string profile;                  ///< a profile (io::read_profile's forms) swept; empty: none
  std::string body;                     ///< a body (io::read_body's forms) moved; empty: none
  std::vector<Eigen::Vector3d> points;  ///< points of the moving space traced; none: the origin
  /// Also the body's swept volume (needs a body): swept_volume's certified enclosing mesh at
  /// volume_tol (unset: 1e-2 of the volume's diagonal, as `render --body`).
  bool volume = false;
  std::optional<double> volume_tol;
};

struct View {
  std::string path;
  std::size_t bytes = 0;       ///< of the page
  std::size_t wasm_bytes = 0;  ///< of the kernel's WebAssembly module inside it
  std::size_t poses = 0;
  bool editable = false;  ///< the file records its method and poses: the page re-interpolates
  nlohmann::json method;  ///< what the page interpolates with (null when not editable)
  std::size_t profile_edges = 0, body_triangles = 0, points = 0;
  std::size_t volume_triangles = 0;  ///< the swept volume's mesh (0: none asked for)
  double volume_distance_bound = 0;  ///< its certificate: every vertex within it of V
  nlohmann::json report() const;
};

/// The data the page reads (docs/guide/view.md): the motion (a rational curve, or a quaternion
/// spline's keys and control points), its method and poses, the profile's edges, the body's
/// triangles, the traced points, the body's swept volume when asked for. Errc::invalid_input
/// for a bad profile, body, point or volume tolerance, or a volume without a body;
/// Errc::numerical_failure for a rational motion with a pole.
nlohmann::json view_data(const Motion& motion, const ViewOptions& options);

/// Writes the page to options.output (atomically; nothing on failure).
View view(const Motion& motion, const ViewOptions& options);

}  // namespace qmotion
