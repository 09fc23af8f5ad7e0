// cli/command.hpp: one subcommand of the qmotion executable: its CLI11 parser and what
// it runs. Each add_<command>() (cli/<command>.cpp) declares its options and returns
// both; the command parses, calls the library and prints.
#pragma once
#include <CLI/CLI.hpp>
#include <functional>
#include <iostream>
#include <qmotion/api/export.hpp>
#include <qmotion/io/robot_programs.hpp>
#include <sstream>
#include <string>

namespace qmotion::cli {

struct Command {
  CLI::App* app;             ///< the subcommand (true when it was given)
  std::function<int()> run;  ///< runs it; returns the exit status, throws qmotion::Error
};

/// The options of trajectory and sweep that shape the exported geometry: --max-degree,
/// --tol, --units.
inline void add_geometry_options(CLI::App* sub, qmotion::ExportOptions& o) {
  sub->add_option("--max-degree", o.max_degree,
                  "Approximate along the motion (measured, within --tol) above degree D; for a "
                  "quaternion-spline motion, the degree of its fitted geometry (default 5)");
  sub->add_option("--tol", o.tol,
                  "Approximation tolerance in the motion's length unit (default 1e-6 of the "
                  "bounding-box diagonal)");
  sub->add_option("--units", o.units,
                  "Convert the numbers from the motion's unit into U and declare U: mm, cm, m, "
                  "um, in, ft (default: the motion's)");
}

/// The POSES argument and the options for robot programs (--robot-config, --tool, --base,
/// --skip-unknown) of every command that reads poses.
inline void add_poses_argument(CLI::App* sub, std::string& path, io::RobotOptions& robot) {
  sub->add_option("POSES", path,
                  "Pose file (.json, .csv) or robot program (KUKA KRL .src, ABB RAPID .mod/.prg, "
                  "URScript .script)")
      ->required();
  sub->add_option("--robot-config", robot.config_path,
                  "KUKA: a $config.dat whose TOOL_DATA and BASE_DATA map every move into one "
                  "frame");
  sub->add_option("--tool", robot.tool,
                  "Robot programs: the TCP every pose is expressed for (a KUKA tool number, an "
                  "ABB tooldata); needed when the moves use more than one tool");
  sub->add_option("--base", robot.base,
                  "KUKA with --robot-config: the base the poses are given in (default 0, the "
                  "world)");
  sub->add_flag("--skip-unknown", robot.skip_unknown,
                "Robot programs: skip statements the reader does not know, with a warning "
                "naming each line, instead of refusing the program");
}

/// The poses of a file or robot program, its warnings printed on standard error.
inline io::PoseSet read_poses_argument(const std::string& path, const io::RobotOptions& robot) {
  io::PoseSet set = io::read_poses(path, robot);
  for (const std::string& w : set.warnings) std::cerr << "qmotion: warning: " << w << "\n";
  return set;
}

/// ", approximated: [deviation at most B (proven), ]measured deviation D within tolerance T"
/// when the export approximated, else "".
inline std::string approximation_note(const qmotion::ExportResult& r) {
  if (!r.approx_deviation) return std::string();
  std::ostringstream os;
  os.precision(3);
  os << ", approximated: ";
  if (r.approx_bound) os << "deviation at most " << *r.approx_bound << " (proven), ";
  os << "measured deviation " << *r.approx_deviation;
  if (r.approx_tolerance) os << " within tolerance " << *r.approx_tolerance;
  return os.str();
}

Command add_info(CLI::App& app);
Command add_eval(CLI::App& app);
Command add_interpolate(CLI::App& app);
Command add_fit(CLI::App& app);
Command add_poses(CLI::App& app);
Command add_trajectory(CLI::App& app);
Command add_sweep(CLI::App& app);
Command add_check(CLI::App& app);
Command add_demo(CLI::App& app);
Command add_qspline(CLI::App& app);
Command add_compare(CLI::App& app);
Command add_toolpath(CLI::App& app);
Command add_render(CLI::App& app);
Command add_plot(CLI::App& app);
Command add_animate(CLI::App& app);
Command add_view(CLI::App& app);
Command add_volume(CLI::App& app);
Command add_verify(CLI::App& app);

/// Runs the qmotion command line; returns the exit status of docs/formats.md. Throws
/// qmotion::Error for user-facing failures (main maps them to their exit status).
int run(int argc, char** argv);

}  // namespace qmotion::cli
