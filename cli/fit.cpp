// cli/fit.cpp: `qmotion fit`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/fit.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_fit(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "fit",
      "Fit a lean B-spline Q-motion within tolerances of many (noisy) poses and write it as "
      "motion JSON");
  struct Options {
    std::string poses, output;
    io::RobotOptions robot;
    qmotion::FitOptions options;
  };
  auto o = std::make_shared<Options>();
  add_poses_argument(sub, o->poses, o->robot);
  sub->add_option("-o,--output", o->output, "Motion JSON file to write")->required();
  sub->add_option("--tol", o->options.tol,
                  "Largest distance of the moving origin from a pose's position, in the poses' "
                  "unit")
      ->required();
  sub->add_option("--angle-tol", o->options.angle_tol_deg,
                  "Largest rotation angle from a pose's orientation, degrees (default 0.1)");
  sub->add_option("--degree", o->options.degree, "Degree K of the rotational factor (default 3)");
  sub->add_option("--translation-degree", o->options.translation_degree,
                  "Degree L of the translation (default 3)");
  sub->add_option("--param", o->options.param,
                  "Parameters: given (default when every pose has t), uniform (default "
                  "otherwise), chordal, star-chordal, centripetal, angular, angular-chordal");
  sub->add_flag("--between", o->options.between,
                "Hold the tolerances along the whole motion: the moving origin within --tol of "
                "the polyline through the positions and the rotation within --angle-tol of the "
                "geodesic between neighbouring poses, proven (default: at the poses)");
  return {sub, [o] {
            const qmotion::FitResult r =
                qmotion::fit(read_poses_argument(o->poses, o->robot), o->options);
            r.save(o->output);
            std::cout << r.report_text();
            std::cerr << "qmotion: wrote " << o->output << " (" << r.summary << ")\n";
            return 0;
          }};
}

}  // namespace qmotion::cli
