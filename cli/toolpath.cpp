// cli/toolpath.cpp: `qmotion toolpath`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/export.hpp>
#include <qmotion/api/toolpath.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/machine_file.hpp>
#include <qmotion/io/qspline_file.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_toolpath(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "toolpath",
      "Write cutter-location points along the trajectory of --point with the tool axis "
      "R(t)(i,j,k): every chord within --chord-tol of the exact trajectory and every axis within "
      "--angle-tol of the chord's blend, certified from the control points for the numbers as "
      "written and, on a 5-axis machine, for its linear interpolation of its axes (APT, CSV, "
      "G-code)");
  struct Options {
    std::string motion, point, axis = "0,0,1", chord_tol, angle_tol, max_step, feed, limits,
                               controller_tol;
    qmotion::ToolpathOptions options;
  };
  auto o = std::make_shared<Options>();
  sub->add_option("MOTION", o->motion, "Motion JSON file (either kind)")->required();
  sub->add_option("--point", o->point, "Tool reference point x,y,z of the moving space")
      ->required();
  sub->add_option("--axis", o->axis, "Tool axis i,j,k of the moving space (default 0,0,1)");
  sub->add_option("--chord-tol", o->chord_tol,
                  "Largest distance of the exact trajectory from the chords, in the output unit")
      ->required();
  sub->add_option("--angle-tol", o->angle_tol, "Largest axis deviation in degrees (default 0.5)");
  sub->add_option("--max-step", o->max_step, "Longest chord (default: no cap)");
  sub->add_option("--feed", o->feed, "Feed per minute for APT FEDRAT and G-code F (default 1000)");
  sub->add_flag("--arc-length", o->options.arc_length, "CSV: add the arc length s");
  sub->add_option("--rotary", o->options.rotary,
                  "G-code: ac or bc for a table-tilting A/C or B/C machine (Rx(A) Rz(C) or "
                  "Ry(B) Rz(C) takes the tool axis to +Z, pivot at the workpiece origin; the "
                  "branch nearer the previous block, C unwrapped)");
  sub->add_option("--machine", o->options.machine_file,
                  "G-code: a machine file (JSON: two rotary axes on the table or the head, with "
                  "directions and pivots; optional velocity limits, travel and accelerations) "
                  "instead of --rotary");
  sub->add_flag("--c-hold", o->options.c_hold,
                "--rotary/--machine: keep the previous angle of the axis that is undefined where "
                "the tool lies along it (C where the axis is vertical; else refused)");
  sub->add_option("--feed-mode", o->options.feed_mode,
                  "G-code: units-per-minute (G94, default) or inverse-time (G93: an F per block so "
                  "the tool tip moves at --feed along the exact trajectory)");
  sub->add_option("--axis-limits", o->limits,
                  "With inverse-time: velocity limits X=v,Y=v,Z=v,A=v,… (output unit or degrees "
                  "per minute); blocks slow down so that no axis exceeds its limit");
  sub->add_option("--dialect", o->options.dialect,
                  "G-code: the controller's words: linuxcnc (default), fanuc (default with "
                  "--nurbs) or siemens; every program commands its exact-path mode (G61, or "
                  "G60 G601) before the first feed move");
  sub->add_option("--controller-tol", o->controller_tol,
                  "G-code G1, 3-axis: the part of --chord-tol left to the controller's blending "
                  "(LinuxCNC G64 P Q, Siemens G642 CTOL), less than half of it; default 0 "
                  "(exact path)");
  sub->add_flag("--nurbs", o->options.nurbs,
                "G-code: Fanuc-style G06.2 NURBS blocks of degree <= 3 instead of G1 moves: the "
                "exact trajectory where its degree allows, else a cubic fit, within --chord-tol "
                "(certified for the numbers as written; 3-axis)");
  sub->add_option(
      "--units", o->options.units,
      "Write in U and read --chord-tol, --max-step and --feed in U: mm, in (APT, G-code) "
      "or any of mm, cm, m, um, in, ft (CSV); default the motion's (mm for APT and "
      "G-code unless it is in inches)");
  sub->add_option("-o,--output", o->options.output, "Output .apt/.cls, .csv or .nc/.ngc")
      ->required();
  return {sub, [o] {
            auto& opt = o->options;
            opt.point = io::parse_point(o->point, "--point");
            opt.axis = io::parse_point(o->axis, "--axis");
            opt.chord_tol = io::parse_number_text(o->chord_tol, "--chord-tol").value;
            if (!o->angle_tol.empty())
              opt.angle_tol_deg = io::parse_number_text(o->angle_tol, "--angle-tol").value;
            if (!o->max_step.empty())
              opt.max_step = io::parse_number_text(o->max_step, "--max-step").value;
            if (!o->feed.empty()) opt.feed = io::parse_number_text(o->feed, "--feed").value;
            if (!o->controller_tol.empty())
              opt.controller_tol =
                  io::parse_number_text(o->controller_tol, "--controller-tol").value;
            if (!o->limits.empty())
              opt.axis_limits = io::parse_axis_limits(o->limits, "--axis-limits");
            const auto tp = qmotion::toolpath(io::load_motion(o->motion), opt);
            std::cout << tp.report().dump(2) << "\n";
            if (tp.nurbs)
              std::cerr << "qmotion: wrote " << tp.path << " (NURBS of degree "
                        << tp.nurbs->curve.degree() << ", " << tp.nurbs->curve.ctrl().size()
                        << " control points, deviation <= " << tp.nurbs->max_deviation_bound << " "
                        << tp.units << ")\n";
            else
              std::cerr << "qmotion: wrote " << tp.path << " (" << tp.samples.size()
                        << " points, chord deviation <= " << tp.max_chord_bound << " " << tp.units
                        << ")\n";
            return 0;
          }};
}

}  // namespace qmotion::cli
