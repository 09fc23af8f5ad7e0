// io/src/toolpath_files.cpp: the toolpath's G-code, NURBS G-code, APT and CSV writers
// (toolpath_files.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <qmotion/io/toolpath_files.hpp>
#include <sstream>

namespace qmotion::io {

std::string fixed(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits,
                std::abs(x) < 0.5 * std::pow(10.0, -digits) ? 0.0 : x);
  return buf;
}

double rounded(double x, int digits) {
  const double q = std::pow(10.0, digits);
  return std::round(x * q) / q;
}

int exact_decimals(const std::vector<double>& v, int least) {
  for (int d = least; d < 17; ++d)
    if (std::all_of(v.begin(), v.end(),
                    [&](double x) { return std::strtod(fixed(x, d).c_str(), nullptr) == x; }))
      return d;
  return 17;
}

void write_gcode(std::ostream& os, const ToolpathHeader& h,
                 const std::vector<cam::ToolpathSample>& samples,
                 const std::vector<cam::MachineAxes>& machine_axes,
                 const std::vector<std::pair<double, int>>& feeds, int axis_digits, cam::Dialect d,
                 const cam::PathMode& mode) {
  const std::optional<cam::Machine>& machine = h.machine;
  std::string head = "qmotion toolpath: " + std::to_string(samples.size()) +
                     " points, chord tolerance " + fixed(h.chord_tol, 6) + " " + h.units;
  if (machine) {
    head += ", machine " + machine->name + ", axes " + machine->axes[0].name +
            machine->axes[1].name + ", linear interpolation of the machine axes certified";
    for (const auto& [w, v] : h.axis_limits)
      head += ", " + std::string(1, w) + " <= " + fixed(v, 4);
  }
  os << cam::comment(d, head) << "\n";
  os << cam::comment(d, mode.assumption) << "\n";
  os << cam::units_word(d, h.units == "in") << " G90 G17 " << (h.inverse_time ? "G93" : "G94")
     << "\n";
  os << mode.words << "\n";
  if (!h.inverse_time) os << "F" << fixed(h.feed, 4) << "\n";
  for (std::size_t i = 0; i < samples.size(); ++i) {
    std::string words;
    if (machine) {
      const cam::MachineAxes& q = machine_axes[i];
      words = " X" + fixed(q[0]) + " Y" + fixed(q[1]) + " Z" + fixed(q[2]);
      // The rotary words in alphabetical order, as controllers list them.
      const int first = machine->axes[0].name < machine->axes[1].name ? 0 : 1;
      for (int r : {first, 1 - first})
        words += std::string(" ") + machine->axes[static_cast<std::size_t>(r)].name +
                 fixed(q[static_cast<std::size_t>(3 + r)], axis_digits);
    } else {
      const Eigen::Vector3d& p = samples[i].written.point;
      words = " X" + fixed(p(0)) + " Y" + fixed(p(1)) + " Z" + fixed(p(2));
    }
    os << (i == 0 ? "G0" : "G1") << words;
    if (h.inverse_time && i > 0) os << " F" << fixed(feeds[i - 1].first, feeds[i - 1].second);
    os << "\n";
  }
  if (h.inverse_time) os << "G94\n";
  os << "M2\n";
}

namespace {

/// An APT statement folded at 72 columns with '$' continuations, breaking after commas.
void apt_line(std::ostream& os, const std::string& s) {
  std::string rest = s;
  while (rest.size() > 72) {
    std::size_t cut = rest.rfind(',', 70);
    if (cut == std::string::npos) cut = 70;
    os << rest.substr(0, cut + 1) << "$\n";
    rest = rest.substr(cut + 1);
  }
  os << rest << "\n";
}

}  // namespace

void write_apt(std::ostream& os, const ToolpathHeader& h,
               const std::vector<cam::ToolpathSample>& samples, int axis_digits) {
  bool multax = false;
  for (const auto& s : samples)
    multax = multax || cam::detail::angle_between(s.axis, samples.front().axis) > 1e-12;
  apt_line(os, "PARTNO/QMOTION TOOLPATH");
  apt_line(os, h.units == "in" ? "UNITS/INCHES" : "UNITS/MM");
  if (multax) apt_line(os, "MULTAX/ON");
  apt_line(os, "FEDRAT/" + fixed(h.feed, 4));
  for (const auto& s : samples) {
    const cam::WrittenEnd& w = s.written;
    std::string g = "GOTO/" + fixed(w.point(0)) + "," + fixed(w.point(1)) + "," + fixed(w.point(2));
    if (multax)
      for (int c = 0; c < 3; ++c) g += "," + fixed(w.axis(c), axis_digits);
    apt_line(os, g);
  }
  apt_line(os, "FINI");
}

void write_csv(std::ostream& os, const std::vector<cam::ToolpathSample>& samples,
               const std::vector<double>& arc, int point_digits, int axis_digits) {
  os << "t,x,y,z,i,j,k" << (arc.empty() ? "" : ",s") << "\n";
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto& p = samples[i];
    os << fixed(p.t, 12);
    for (int c = 0; c < 3; ++c) os << "," << fixed(p.written.point(c), point_digits);
    for (int c = 0; c < 3; ++c) os << "," << fixed(p.written.axis(c), axis_digits);
    if (!arc.empty()) os << "," << fixed(arc[i], 9);
    os << "\n";
  }
}

void write_nurbs_gcode(std::ostream& os, const ToolpathHeader& h,
                       const kernel::BSpline<Eigen::Vector4d>& c, const NurbsHeader& nh,
                       const cam::PathMode& mode) {
  const int order = c.degree() + 1, kd = exact_decimals(c.knots(), 9);
  const std::size_t n = c.ctrl().size();
  std::ostringstream head;
  head.precision(3);
  head << "(qmotion toolpath: NURBS of degree " << c.degree() << ", " << n << " control points, "
       << nh.spans << (nh.spans == 1 ? " span, " : " spans, ")
       << (nh.exact ? "the exact trajectory" : "a fit") << ", certified deviation <= " << nh.bound
       << " " << h.units << ")\n";
  os << head.str() << cam::comment(cam::Dialect::fanuc, mode.assumption) << "\n"
     << (h.units == "in" ? "G20" : "G21") << " G90 G17 G94\n"
     << mode.words << "\n";
  auto xyz = [](const Eigen::Vector4d& v) {
    return " X" + fixed(v(1) / v(0)) + " Y" + fixed(v(2) / v(0)) + " Z" + fixed(v(3) / v(0));
  };
  os << "G0" << xyz(c.ctrl().front()) << "\n";
  for (std::size_t i = 0; i < n; ++i)
    os << (i == 0 ? "G06.2 P" + std::to_string(order) + " " : "") << "K" << fixed(c.knots()[i], kd)
       << xyz(c.ctrl()[i]) << " R" << fixed(c.ctrl()[i](0))
       << (i == 0 ? " F" + fixed(h.feed, 4) : "") << "\n";
  for (std::size_t i = n; i < c.knots().size(); ++i) os << "K" << fixed(c.knots()[i], kd) << "\n";
  os << "M2\n";
}

}  // namespace qmotion::io
