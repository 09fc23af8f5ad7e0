// cli/interpolate.cpp: `qmotion interpolate`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/kernel/error.hpp>
#include <sstream>

#include "command.hpp"

namespace qmotion::cli {

Command add_interpolate(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "interpolate",
      "Build a Q-motion through the poses (Juettler's methods) and write it as motion JSON");
  struct Options {
    std::string poses, output;
    io::RobotOptions robot;
    qmotion::InterpolateOptions options;
  };
  auto o = std::make_shared<Options>();

  add_poses_argument(sub, o->poses, o->robot);
  sub->add_option("-o,--output", o->output, "Motion JSON file to write")->required();
  sub->add_option("--rotation", o->options.rotation,
                  "Rotation interpolation: elliptic (default), affine, projective (the last two "
                  "for --form bezier)");
  sub->add_option("--translation", o->options.translation,
                  "Translation: tr (default), trt, minimal (minimal order)");
  sub->add_option(
      "--trt-degrees", o->options.trt_degrees,
      "TRT degrees L1,L2 with L1 + L2 = m - 1 (default m-1,0; L1 = L2 even is singular)");
  sub->add_option("--param", o->options.param,
                  "Parameters: given (default when every pose has t), uniform (default "
                  "otherwise), chordal, star-chordal, "
                  "centripetal, angular, angular-chordal");
  sub->add_option("--form", o->options.form,
                  "bezier (default up to six poses) | bspline (default beyond: global B-spline, "
                  "linear cost) | c1 (Algorithm 2: local C1 cubic pieces)");
  sub->add_option("--degree", o->options.degree,
                  "Rotational degree of B-spline motions (default 3; a Bezier motion's is fixed "
                  "by the method)");
  sub->add_option("--translation-degree", o->options.translation_degree,
                  "Translational degree of B-spline motions (default 3)");
  sub->add_flag(
      "--exact", o->options.exact,
      "Compute in exact rational arithmetic from the file's digits (quaternion rotations only)");
  return {sub, [o] {
            const qmotion::InterpolatedMotion r =
                qmotion::interpolate(read_poses_argument(o->poses, o->robot), o->options);
            if (!r.poles.empty()) {
              std::ostringstream os;
              os.precision(10);
              for (double p : r.poles) os << " " << p;
              std::cerr << "qmotion: warning: the motion has a pole (zero rotational part) at t ="
                        << os.str()
                        << ": trajectories are unbounded there and cannot be exported\n";
            }
            r.save(o->output);
            std::cerr << "qmotion: wrote " << o->output << " (" << r.summary << ")\n";
            return 0;
          }};
}

}  // namespace qmotion::cli
