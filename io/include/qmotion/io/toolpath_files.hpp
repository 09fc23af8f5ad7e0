// <qmotion/io/toolpath_files.hpp>: the file formats of `qmotion toolpath` (docs/cam.md):
// G-code as G1 blocks in a controller's dialect or as Fanuc G06.2 NURBS blocks, APT CL data
// and CSV, written from what the toolpath computed (the api's qmotion::toolpath decides
// what to write and certifies it; these say it in each format's words).
#pragma once
#include <Eigen/Dense>
#include <map>
#include <optional>
#include <ostream>
#include <qmotion/cam/controller.hpp>
#include <qmotion/cam/machine.hpp>
#include <qmotion/cam/toolpath.hpp>
#include <qmotion/kernel/bspline.hpp>
#include <string>
#include <utility>
#include <vector>

namespace qmotion::io {

/// x printed with `digits` decimals, never as "-0".
std::string fixed(double x, int digits = 6);
/// x rounded to `digits` decimals: the value fixed(x, digits) reads back as.
double rounded(double x, int digits);
/// The fewest decimals (at least `least`, at most 17) that print every value of v so that it
/// reads back unchanged.
int exact_decimals(const std::vector<double>& v, int least);

/// Decimals of the NURBS G-code's coordinates and weights.
inline constexpr int kNurbsDigits = 6;

/// What a toolpath file states besides its blocks.
struct ToolpathHeader {
  std::string units = "mm";   ///< the output unit: "mm" or "in" in G-code and APT
  double feed = 0;            ///< units a minute
  double chord_tol = 0;       ///< the certified chord tolerance, stated in G-code's first line
  bool inverse_time = false;  ///< G93: each G1 block's F is 1 / its minutes
  std::optional<cam::Machine> machine;  ///< with a machine, G-code's words are its axes
  std::map<char, double> axis_limits;   ///< inverse time's axis limits, stated in the header
};

/// The G1 program: the header comments (what is certified, the assumption of the path mode),
/// units, the path mode, the feed mode, a G0 to the first sample and a G1 to each other one,
/// M2. With a machine, the blocks are machine_axes (one a sample; the rotary words to
/// `axis_digits` decimals, in alphabetical order), else the samples' written points. Under
/// inverse time, block i's F is feeds[i - 1] (value, decimals), and G94 is restored at the
/// end.
void write_gcode(std::ostream& os, const ToolpathHeader& h,
                 const std::vector<cam::ToolpathSample>& samples,
                 const std::vector<cam::MachineAxes>& machine_axes,
                 const std::vector<std::pair<double, int>>& feeds, int axis_digits,
                 cam::Dialect dialect, const cam::PathMode& mode);

/// APT CL data: PARTNO, UNITS, MULTAX/ON when the tool axis turns, FEDRAT, a GOTO per sample
/// (its written point, and its axis to `axis_digits` decimals under MULTAX), FINI; each
/// statement folded at 72 columns with '$' continuations.
void write_apt(std::ostream& os, const ToolpathHeader& h,
               const std::vector<cam::ToolpathSample>& samples, int axis_digits);

/// CSV: t,x,y,z,i,j,k (and s, the arc length up to the sample, when `arc` is not empty), a
/// row per sample: t to 12 decimals, the written point to `point_digits`, the axis to
/// `axis_digits`, s to 9.
void write_csv(std::ostream& os, const std::vector<cam::ToolpathSample>& samples,
               const std::vector<double>& arc, int point_digits, int axis_digits);

/// What the NURBS program's first comment states of its curve.
struct NurbsHeader {
  std::size_t spans = 0;
  bool exact = false;  ///< the exact trajectory, not a fit
  double bound = 0;    ///< the certified deviation, output unit
};

/// Fanuc G06.2 blocks of `curve` (homogeneous, (w, w x), output unit): the header comments,
/// units, the path mode; a G0 to the first control point; the first block carries G06.2, the
/// order P, the first knot and the feed; every control point its knot (the fewest decimals
/// that read back exactly, at least 9) and weight R; the last `order` knots stand alone; M2.
void write_nurbs_gcode(std::ostream& os, const ToolpathHeader& h,
                       const kernel::BSpline<Eigen::Vector4d>& curve, const NurbsHeader& n,
                       const cam::PathMode& mode);

}  // namespace qmotion::io
