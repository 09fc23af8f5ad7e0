// <qmotion/io/robot_programs.hpp>: the poses a robot program moves through, as a pose file
// (docs/formats.md, "Robot programs").
#pragma once
#include <optional>
#include <qmotion/io/poses.hpp>
#include <string>

namespace qmotion::io {

/// The Cartesian targets of a KUKA KRL program (.src), in the order of its PTP, LIN and CIRC
/// instructions (CIRC: the auxiliary point, then the end point): inline aggregates
/// {X, Y, Z, A, B, C} or names declared (DECL E6POS / POS / FRAME) in the program or in
/// `dat_text`, its .dat. Millimetres; R = Rz(A) Ry(B) Rx(C), degrees. Statements that do not
/// move the tool or change no pose (FOLD comments, $VEL, $ACC, $APO, BAS, PDAT_ACT, ...) pass;
/// anything else is refused (Errc::invalid_input) naming the file, line and construct.
PoseSet parse_krl(const std::string& text, const std::string& source,
                  const std::optional<std::string>& dat_text = std::nullopt,
                  const std::string& dat_source = {});

/// The robtargets of an ABB RAPID module (.mod, .prg), in the order of the MoveJ, MoveL and
/// MoveC instructions that name them (MoveC: the circle point, then the end point):
/// [[x, y, z], [q1, q2, q3, q4], ...] with q1 the scalar part, unit within 1e-6. Millimetres.
/// Refusals as for parse_krl.
PoseSet parse_rapid(const std::string& text, const std::string& source);

}  // namespace qmotion::io
