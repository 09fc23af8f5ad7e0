// <qmotion/io/gcode.hpp>: reading G-code that any CAM system wrote, as LinuxCNC's
// interpreter reads it (docs/formats.md, "G-code read by verify").
#pragma once
#include <qmotion/cam/program.hpp>
#include <string>

namespace qmotion::io {

/// The canonical moves of a G-code program, the tool starting at the origin as LinuxCNC's
/// interpreter starts. Read: G0, G1, G2, G3 (centre by I/J/K from the start, or by R; P full
/// turns), G17/G18/G19, G20/G21, G90/G91, G93/G94, F, X/Y/Z and A/B/C, line numbers (N),
/// comments in parentheses or after ';', and M2/M30, which end it. Errc::invalid_input naming
/// `label`, the line and the word for anything else (another G or M code, S, T, parameters,
/// expressions, block delete), a number that is not one, an axis word with no motion mode,
/// a feed move with no feed rate (under G93 on its own block), an arc with no centre, with
/// the centre on its end, or whose radius differs from start to end by more than LinuxCNC
/// accepts, and a program with no move.
cam::Program parse_gcode(const std::string& text, const std::string& label);

/// parse_gcode of a file (at most kMaxFileBytes), named by its path.
cam::Program read_gcode(const std::string& path);

/// Whether `path` names G-code by its extension: .ngc, .nc, .gcode, .tap, .cnc.
bool is_gcode_path(const std::string& path);

}  // namespace qmotion::io
