// <qmotion/io/machine_file.hpp>: a 5-axis machine described in JSON (`toolpath --machine`):
// its two rotary axes, on the table or on the head, with their directions and pivots, and
// optionally the axes' velocity limits. docs/cam.md gives the format.
#pragma once
#include <map>
#include <qmotion/cam/machine.hpp>
#include <string>

namespace qmotion::io {

/// A machine file's contents.
struct MachineFile {
  cam::Machine machine;
  /// Velocity limits by axis word (X, Y, Z in the machine's unit per minute, rotary axes in
  /// degrees per minute); empty when the file gives none.
  std::map<char, double> velocity;
};

/// Reads a machine file. Errc::invalid_input names the file and the field at fault: not
/// two rotary axes, an axis other than A, B or C, a zero-length or parallel direction, an
/// axis that cannot tilt the tool, an unknown unit, a limit that is not positive.
MachineFile read_machine_file(const std::string& path);
/// The same from text; `source` names it in messages.
MachineFile parse_machine_file(const std::string& text, const std::string& source);

/// Velocity limits "X=20000,Y=20000,A=5400,…" (`--axis-limits`): each word once, each limit
/// positive; Errc::invalid_input naming `where` otherwise. Which words a machine has is
/// checked where the machine is known.
std::map<char, double> parse_axis_limits(const std::string& text, const std::string& where);

}  // namespace qmotion::io
