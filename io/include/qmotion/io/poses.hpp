// <qmotion/io/poses.hpp>
#pragma once
#include <Eigen/Core>
#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <qmotion/io/json_number.hpp>
#include <qmotion/kernel/pose.hpp>
#include <string>
#include <vector>

#ifdef QMOTION_WITH_CGAL
#include <qmotion/kernel/cgal_scalar.hpp>
#endif

namespace qmotion::io {

/// A rotation as the file gave it (docs/formats.md).
struct RotationInput {
  enum class Kind { quaternion, matrix, axis_angle };
  Kind kind = Kind::quaternion;
  /// quaternion: w, x, y, z; matrix: 9 entries row by row; axis_angle: axis x, y, z, angle_deg
  std::vector<Number> values;
};

/// One pose as read, numbers with their source text.
struct PoseInput {
  std::optional<Number> t;
  std::array<Number, 3> position;
  RotationInput rotation;
};

/// Most poses a file may hold (bounded memory; see README's limits).
inline constexpr std::size_t kMaxPoses = 100000;

/// A validated pose file: at least two poses, finite numbers, non-zero rotations, proper
/// rotation matrices, and strictly increasing t when t is given (for all poses or none).
struct PoseSet {
  std::string source;        ///< file name, for messages
  std::string units = "mm";  ///< length unit of the positions
  std::vector<PoseInput> poses;
  /// What a reader let pass with a warning (a robot program read with skip_unknown): each
  /// names the file and line. The CLI prints them on standard error.
  std::vector<std::string> warnings;

  bool has_t() const { return !poses.empty() && poses.front().t.has_value(); }
};

/// A pose in kernel numbers (kernel/pose.hpp).
template <typename Scalar>
using Pose = kernel::Pose<Scalar>;

/// Reads poses from a .json or .csv file (by extension; other names are tried as JSON).
PoseSet read_poses(const std::string& path);
/// Parses pose JSON (docs/formats.md); `source` names the input in messages.
PoseSet parse_poses_json(const std::string& text, const std::string& source);
/// The fast path of parse_poses_json: the file read by simdjson without a document tree
/// (a 10^4-pose file is 10^5 numbers); std::nullopt as soon as anything is unusual (a
/// missing or repeated field, an exact "p/q" number, invalid JSON), for the tree reader to
/// read and word. Throws the set's checks, which both readers share.
std::optional<PoseSet> parse_poses_fast(const std::string& text, const std::string& source);
/// The same for an already parsed document (e.g. the poses a motion file records).
PoseSet parse_poses_json_value(const nlohmann::json& doc, const std::string& source);
/// Parses pose CSV with header t,x,y,z,qw,qx,qy,qz (t optional; blank lines and lines
/// starting with '#' are skipped).
PoseSet parse_poses_csv(const std::string& text, const std::string& source);

/// Poses in double precision (rotations as unit quaternions with the file's sign).
std::vector<Pose<double>> to_poses_double(const PoseSet& set);

#ifdef QMOTION_WITH_CGAL
/// Poses read exactly from their text (decimals and "p/q" alike). Only quaternion
/// rotations have exact rational form in general: matrix and axis-angle rotations are
/// refused (Errc::invalid_input naming the pose). Rotations keep the file's scale.
std::vector<Pose<kernel::Rational>> to_poses_exact(const PoseSet& set);

/// The poses with every matrix and axis-angle rotation replaced by the unit quaternion
/// to_poses_double makes of it, written exactly ("p/q", q a power of two), so that exact
/// mode reads the double pipeline's very numbers; `replaced` receives their indices.
PoseSet with_quaternion_rotations(const PoseSet& set, std::vector<std::size_t>* replaced = nullptr);
#endif

/// The poses as JSON (docs/formats.md), numbers written with their source text.
nlohmann::json poses_to_json(const PoseSet& set);

/// Poses in kernel numbers as pose JSON (docs/formats.md): quaternion rotations, t when set.
nlohmann::json poses_to_json(const std::vector<Pose<double>>& poses, const std::string& units);

class JsonText;
/// poses_to_json(set) streamed into `t` (no tree) at nesting `depth`, one pose a line.
void poses_text(JsonText& t, const PoseSet& set, int depth);
/// poses_to_json(poses, units) streamed likewise.
void poses_text(JsonText& t, const std::vector<Pose<double>>& poses, const std::string& units,
                int depth);

/// Length units accepted in files.
bool is_known_unit(const std::string& unit);

}  // namespace qmotion::io
