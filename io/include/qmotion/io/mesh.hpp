// <qmotion/io/mesh.hpp>: triangle meshes of swept shells through OpenCASCADE's mesher, measured
// against the exact surfaces (our own evaluation, not OpenCASCADE's), written as STL, OBJ
// or PLY.
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <qmotion/sweep/shell.hpp>
#include <string>
#include <vector>

namespace qmotion::io {

struct MeshOptions {
  double deflection = 0;  ///< largest distance of the mesh from the surfaces (absolute, > 0)
  double angle_deg = 20;  ///< angular deflection of the mesher, in (0, 90] degrees
  bool ascii = false;     ///< STL and PLY: ASCII instead of binary (OBJ is always text)
};

struct Mesh {
  std::vector<Eigen::Vector3d> vertices;      ///< welded across the faces' shared edges
  std::vector<std::array<int, 3>> triangles;  ///< 0-based, counter-clockwise from outside
  double deflection = 0;     ///< what the mesher was last asked for (<= the option)
  double max_deviation = 0;  ///< measured at triangle centroids and edge midpoints
  std::size_t deviation_samples = 0;
  double max_vertex_error = 0;  ///< vertices against the surface at their (u, v)
  int rounds = 0;               ///< meshing rounds until the measurement held
  bool closed = false;          ///< every edge bounds exactly two triangles
  bool oriented = false;        ///< closed, and every directed edge occurs once
  /// Per vertex red, green, blue, written to .ply only (empty: none).
  std::vector<std::array<unsigned char, 3>> colours;
};

/// The shell meshed by BRepMesh_IncrementalMesh and measured: every triangle's centroid and
/// edge midpoints against the exact face it lies on (the distance to the nearest surface
/// point by Gauss-Newton from the sample's (u, v); caps against their plane). Where the
/// measurement exceeds o.deflection the shell is meshed again with a smaller deflection
/// (up to 8 rounds; Errc::numerical_failure beyond). Vertices on shared edges are welded,
/// degenerate triangles dropped. Errc::invalid_input for a non-positive deflection or an
/// angle outside (0, 90].
Mesh mesh_shell_within(const sweep::NurbsShell<double>& shell, const MeshOptions& o,
                       const std::string& path);

/// Writes the mesh by the extension of path: .stl (binary, or ASCII), .obj, .ply (binary
/// little-endian with double coordinates, or ASCII; with the colours when there is one per
/// vertex). Atomic.
void write_mesh(const std::string& path, const Mesh& m, bool ascii);

/// Whether path names a mesh format (.stl, .obj, .ply).
bool is_mesh_path(const std::string& path);

}  // namespace qmotion::io
