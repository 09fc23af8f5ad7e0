// cli/qspline.cpp: `qmotion qspline`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/qspline.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/poses.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_qspline(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "qspline",
      "Build a non-rational unit-quaternion spline motion through the poses and write "
      "it as a quaternion-spline motion file");
  struct Options {
    std::string poses, output;
    io::RobotOptions robot;
    qmotion::QSplineOptions options;
  };
  auto o = std::make_shared<Options>();
  add_poses_argument(sub, o->poses, o->robot);
  sub->add_option("-o,--output", o->output, "Motion JSON file to write")->required();
  sub->add_option("--scheme", o->options.scheme,
                  "kks (Kim-Kim-Shin C2 B-spline, iterative), quintic (Tan et al., tension, any "
                  "knots), quartic (Xing et al.)")
      ->required();
  sub->add_option("--tension", o->options.tension,
                  "Quintic: A for every key, or a1,...,an one per key (>= 0, default 0.5)");
  sub->add_option("--param", o->options.param,
                  "Parameters: given (default when every pose has t), uniform (default "
                  "otherwise), chordal, star-chordal, centripetal, angular, angular-chordal. KKS "
                  "and the quartic place the keys at uniform knots on the interval");
  return {sub, [o] {
            const qmotion::QSplineResult r =
                qmotion::qspline(read_poses_argument(o->poses, o->robot), o->options);
            r.save(o->output);
            std::cerr << "qmotion: wrote " << o->output << " (" << r.summary << ")\n";
            return 0;
          }};
}

}  // namespace qmotion::cli
