// api/src/toolpath_gcode.cpp: the G1 program of `qmotion toolpath` in the controller's
// dialect, with the path mode its certificate assumes (docs/cam.md).
#include "toolpath_detail.hpp"

namespace qmotion::toolpath_detail {

void write_gcode(const Toolpath& tp, const std::vector<std::pair<double, int>>& feeds,
                 int axis_digits, cam::Dialect d, const cam::PathMode& mode,
                 std::ostringstream& os) {
  const bool inverse = tp.feed_mode == "inverse-time";
  const std::optional<cam::Machine>& machine = tp.machine;
  std::string head = "qmotion toolpath: " + std::to_string(tp.samples.size()) +
                     " points, chord tolerance " + num(tp.chord_tol, 6) + " " + tp.units;
  if (machine) {
    head += ", machine " + machine->name + ", axes " + machine->axes[0].name +
            machine->axes[1].name + ", linear interpolation of the machine axes certified";
    for (const auto& [w, v] : tp.axis_limits) head += ", " + std::string(1, w) + " <= " + num(v, 4);
  }
  os << cam::comment(d, head) << "\n";
  os << cam::comment(d, mode.assumption) << "\n";
  os << cam::units_word(d, tp.units == "in") << " G90 G17 " << (inverse ? "G93" : "G94") << "\n";
  os << mode.words << "\n";
  if (!inverse) os << "F" << num(tp.feed, 4) << "\n";
  for (std::size_t i = 0; i < tp.samples.size(); ++i) {
    std::string words;
    if (machine) {
      const cam::MachineAxes& q = tp.machine_axes[i];
      words = " X" + num(q[0]) + " Y" + num(q[1]) + " Z" + num(q[2]);
      // The rotary words in alphabetical order, as controllers list them.
      const int first = machine->axes[0].name < machine->axes[1].name ? 0 : 1;
      for (int r : {first, 1 - first})
        words += std::string(" ") + machine->axes[static_cast<std::size_t>(r)].name +
                 num(q[static_cast<std::size_t>(3 + r)], axis_digits);
    } else {
      const Eigen::Vector3d& p = tp.samples[i].written.point;
      words = " X" + num(p(0)) + " Y" + num(p(1)) + " Z" + num(p(2));
    }
    os << (i == 0 ? "G0" : "G1") << words;
    if (inverse && i > 0) os << " F" << num(feeds[i - 1].first, feeds[i - 1].second);
    os << "\n";
  }
  if (inverse) os << "G94\n";
  os << "M2\n";
}

}  // namespace qmotion::toolpath_detail
