// <qmotion/io/gltf.hpp>: glTF 2.0 files (docs/formats.md, "glTF"): one mesh node moved by a
// keyframe animation (LINEAR samplers), under a root node that turns qmotion's z-up frame
// into glTF's y-up one. Binary .glb or text .gltf with the buffer inlined.
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace qmotion::io {

/// Everything in glTF's 32-bit floats and in metres, as the file holds it.
struct GltfAnimation {
  std::string name = "qmotion";
  std::vector<std::array<float, 3>> positions;  ///< the body's mesh, in the moving frame
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<float> times;                        ///< seconds, strictly increasing
  std::vector<std::array<float, 3>> translations;  ///< one per time
  std::vector<std::array<float, 4>> rotations;     ///< unit quaternions (x, y, z, w)
  nlohmann::json extras;                           ///< the asset's extras (the report)
};

/// Writes the animation to path by its extension, .glb or .gltf, atomically. Errc::invalid_input
/// for another extension, mismatched lengths, times that do not increase, or an empty mesh.
void write_gltf(const std::string& path, const GltfAnimation& a);

/// Whether path names a glTF file (.glb or .gltf).
bool is_gltf_path(const std::string& path);

}  // namespace qmotion::io
