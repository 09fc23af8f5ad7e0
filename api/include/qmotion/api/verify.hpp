// <qmotion/api/verify.hpp>: `qmotion verify`: whether a machining program gouges a part,
// certified between its blocks, not only at them (docs/guide/verify.md).
#pragma once
#include <Eigen/Core>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <qmotion/cam/gouge.hpp>
#include <qmotion/cam/program.hpp>
#include <string>
#include <vector>

namespace qmotion {

struct VerifyOptions {
  std::string program;  ///< G-code (.ngc, .nc, .gcode, .tap, .cnc)
  std::string tool;     ///< cutter:flat,D,L, cutter:ball,D,L or cutter:bull,D,rc,L (mm)
  /// The part in the program's frame (mm): a closed .stl, .obj or .ply mesh, or a STEP or
  /// IGES solid (meshed by OpenCASCADE within T / 4).
  std::string part;
  std::optional<double> tol;  ///< mm; default 0.01
  std::string output;         ///< the report (.json); empty: none written
  /// The raw stock: box:x0,y0,z0,x1,y1,z1 (two opposite corners, mm) or a closed mesh;
  /// empty: no stock figures.
  std::string stock;
  /// The part coloured by stock left and gouge: .ply (vertex colours), .svg or .png (a view
  /// from above); needs the stock. Empty: none.
  std::string map;
  /// The tool holder (mm): cylinder:r,h, radius r from the cutter's length up h; or
  /// holder:r1,h1,r2,h2,..., cylinders stacked upwards from the cutter's length (a collet
  /// nut, then the chuck's body); empty: none checked.
  std::string holder;
  /// Fixtures (clamps, vices): as the stock, box:x0,y0,z0,x1,y1,z1 or a closed mesh; never
  /// cut, checked against the cutter and the holder.
  std::vector<std::string> fixtures;
};

/// What the program leaves of the stock on the part (docs/guide/verify.md, "Stock left"):
/// at a point p of the part's surface, the distance from p to the nearest point that is
/// not remaining stock (cut by the cutter, or outside the raw stock); 0 where the cutter
/// reaches p. Each figure an interval that holds it over the whole surface.
struct StockLeft {
  double max_lower = 0, max_upper = 0;              ///< the largest stock left
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< where max_lower is reached
  /// The move that comes nearest to `point` (none when the raw stock's face is nearer:
  /// the stock there was never cut), its line and t.
  std::optional<std::size_t> block;
  int line = 0;
  double t = 0;
  /// The mean over the part's surface inside the raw stock, and its estimate from the
  /// cells' centres (a sample, beside the interval).
  double mean_lower = 0, mean_upper = 0, mean_estimate = 0;
  double area_in_stock = 0;  ///< mm^2 (the estimate's)
  std::size_t cells = 0, queries = 0;
  bool max_settled = false;   ///< max_upper - max_lower <= the tolerance
  bool mean_settled = false;  ///< the mean's interval no wider than the tolerance
  /// Per vertex of the part's mesh (the map's colours): min(depth in the raw stock,
  /// distance to the swept cutter), negative where the cutter enters the part.
  std::vector<double> vertex_values;
};

/// One move's certified gouge, where it is.
struct MoveGouge {
  std::size_t block = 0;  ///< the move's index in the program (0-based)
  int line = 0;
  cam::Move::Kind kind = cam::Move::Kind::feed;
  cam::Gouge gouge;
};

struct VerifyReport {
  std::string program;
  std::size_t moves = 0, feeds = 0, traverses = 0, arcs = 0;
  double tolerance = 0;
  /// Over the whole program: no point of the cutter at any t lies deeper in the part than
  /// gouge_upper; gouge_lower is reached at `deepest` (0: no point found inside).
  double gouge_lower = 0, gouge_upper = 0;
  std::optional<MoveGouge> deepest;
  /// The moves that certainly enter the part (lower > 0), in program order.
  std::vector<MoveGouge> gouges;
  /// Every move proven clear of the part (it clears it by more than the tolerance).
  bool clear = true;
  bool settled = true;             ///< every move's interval within the tolerance
  std::optional<StockLeft> stock;  ///< with VerifyOptions::stock
  /// With VerifyOptions::holder: each move's first contact of the holder with the stock as
  /// cut so far and with the part (docs/guide/verify.md, "Collisions"), as reported.
  std::optional<nlohmann::json> holder;
  /// With VerifyOptions::stock: the rapid moves (G0) whose cutter enters the stock as cut
  /// so far, each with its first contact, as reported.
  std::optional<nlohmann::json> rapids_through_stock;
  /// With VerifyOptions::fixtures: each move's first contact of the cutter or the holder with
  /// each fixture, as reported.
  std::optional<nlohmann::json> fixtures;
  /// When the part, the stock or a fixture is a STEP or IGES solid: the deflection (T / 4)
  /// within which OpenCASCADE meshed it; the figures above are certified for the mesh.
  std::optional<double> cad_deflection;
  std::size_t queries = 0;
  double seconds = 0;
  nlohmann::json report() const;
};

/// Reads the program and the bodies, and bounds how deep the cutter enters the part over
/// every move (cam::move_gouge, the moves in parallel), each move to within the tolerance.
/// Errc::invalid_input (no report written) naming the file, line or body for a program the
/// G-code reader refuses, a program that turns a rotary axis (5-axis verification is not
/// there yet), a tool that is not a cutter, a part that is neither a closed mesh nor a STEP
/// or IGES solid (io::mesh_cad), and a bad tolerance; a stock that is neither a box, a
/// closed mesh nor such a solid, a map without a stock or
/// of another format, a holder that is neither a cylinder nor a stack of them, and a fixture
/// as a bad stock is.
VerifyReport verify(const VerifyOptions& options);

}  // namespace qmotion
