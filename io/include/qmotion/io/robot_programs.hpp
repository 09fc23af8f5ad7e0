// <qmotion/io/robot_programs.hpp>: the poses a robot program moves through, as a pose file
// (docs/formats.md, "Robot programs"; docs/fitting.md, "Robot programs as pose files").
#pragma once
#include <optional>
#include <qmotion/io/poses.hpp>
#include <string>

namespace qmotion::io {

/// How a robot program's frames are read (the CLI's --robot-config, --tool, --base and
/// --skip-unknown). With the defaults, a program whose moves use one tool and one base gives
/// its targets as written, and one that uses more is refused naming the lines.
struct RobotOptions {
  /// KUKA: a `$config.dat` (its `TOOL_DATA[n]` and `BASE_DATA[n]`). The text wins over the
  /// path; read_poses reads the path into the text.
  std::string config_path;
  std::optional<std::string> config_text;
  /// The TCP every pose is expressed for: a KUKA tool number (0 the flange) with a config, an
  /// ABB tooldata declared in the module (or tool0). Empty: the program's own, if only one.
  std::string tool;
  /// KUKA with a config: the base the poses are expressed in (0 or empty: the world).
  std::string base;
  /// Statements the reader does not know become warnings (PoseSet::warnings) naming the line,
  /// instead of refusals. Moves it cannot place stay refused.
  bool skip_unknown = false;

  bool given() const {
    return !config_path.empty() || config_text || !tool.empty() || !base.empty();
  }
};

/// The Cartesian targets of a KUKA KRL program (.src), in the order of its PTP, LIN and CIRC
/// instructions (CIRC: the auxiliary point, then the end point): inline aggregates
/// {X, Y, Z, A, B, C} or names declared (DECL E6POS / POS / FRAME) in the program or in
/// `dat_text`, its .dat. Millimetres; R = Rz(A) Ry(B) Rx(C), degrees. Each move's tool and
/// base come from FDAT_ACT (the FDAT's TOOL_NO, BASE_NO), $TOOL / $BASE and BAS(#TOOL / #BASE).
/// Every statement is a construct the reader knows, or refused (Errc::invalid_input) naming the
/// file, line and construct.
PoseSet parse_krl(const std::string& text, const std::string& source,
                  const std::optional<std::string>& dat_text = std::nullopt,
                  const std::string& dat_source = {}, const RobotOptions& options = {});

/// The robtargets of an ABB RAPID module (.mod, .prg), in the order of the MoveJ, MoveL and
/// MoveC instructions that name them (MoveC: the circle point, then the end point):
/// [[x, y, z], [q1, q2, q3, q4], ...] with q1 the scalar part, unit within 1e-6. Millimetres.
/// A \WObj declared as wobjdata in the module is applied (world = uframe · oframe · target);
/// moves with different tooldata need options.tool. Refusals as for parse_krl.
PoseSet parse_rapid(const std::string& text, const std::string& source,
                    const RobotOptions& options = {});

/// The pose targets of a Universal Robots URScript program (.script), in the order of its
/// movel, movej, movep and movec calls (movec: the via pose, then the end pose): pose literals
/// p[x, y, z, rx, ry, rz] (metres, rotation vector in radians) or variables assigned one.
/// Positions come out in millimetres. set_tcp is applied: every pose is expressed for the TCP
/// of the first move. Refusals as for parse_krl.
PoseSet parse_urscript(const std::string& text, const std::string& source,
                       const RobotOptions& options = {});

/// read_poses (poses.hpp) with the options for robot programs: .src (with its .dat beside it),
/// .mod, .prg and .script are read as programs; other files refuse the options.
PoseSet read_poses(const std::string& path, const RobotOptions& options);

}  // namespace qmotion::io
