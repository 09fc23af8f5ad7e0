// cli/eval.cpp: `qmotion eval`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/motion_info.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/point_text.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_eval(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "eval", "Evaluate a motion at a parameter: position, rotation and an optional point");
  struct Options {
    std::string path, t, point;
  };
  auto o = std::make_shared<Options>();
  sub->add_option("MOTION", o->path, "Motion JSON file")->required();
  sub->add_option("--t", o->t,
                  "Parameter value inside the motion's interval (negative values allowed)")
      ->required()
      ->allow_extra_args(false);
  sub->add_option("--point", o->point,
                  "Point x,y,z of the moving space whose image is reported (default: the origin)");
  return {sub, [o] {
            const double t = io::parse_number_text(o->t, "--t").value;
            const Eigen::Vector3d x =
                o->point.empty() ? Eigen::Vector3d::Zero() : io::parse_point(o->point, "--point");
            std::string warning;
            const auto out = qmotion::eval_file(o->path, t, x, &warning, o->t);
            if (!warning.empty())
              std::cerr << "qmotion: warning: " << o->path << " " << warning << "\n";
            std::cout << out.dump(2) << '\n';
            return 0;
          }};
}

}  // namespace qmotion::cli
