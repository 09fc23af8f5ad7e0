// cli/compare.cpp: `qmotion compare`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/compare.hpp>
#include <qmotion/api/export.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/poses.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_compare(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "compare",
      "Build every scheme through the poses (elliptic B-spline, c1, kks, quintic, quartic) and "
      "print what sets them apart: angular velocity and acceleration, a trajectory's length, "
      "the poles of a sweep (exact, or fitted within --tol)");
  struct Options {
    std::string poses, point, tol;
    io::RobotOptions robot;
    qmotion::CompareOptions options;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  add_poses_argument(sub, o->poses, o->robot);
  sub->add_option("--param", o->options.param, "Parametrisation rule, for every scheme");
  sub->add_option("--point", o->point,
                  "The point x,y,z whose trajectory length is measured (default: the origin)");
  sub->add_option("--profile", o->options.profile,
                  "The profile whose sweep's poles are counted (default: a segment from the "
                  "origin along x, a tenth of the poses' extent)");
  sub->add_option("--tol", o->tol,
                  "The quaternion splines' fit, relative to the sweep's bounding-box diagonal "
                  "(default 1e-6)");
  sub->add_flag("--json", o->json, "Print JSON instead of a table");
  return {sub, [o] {
            if (!o->point.empty()) o->options.point = io::parse_point(o->point, "--point");
            if (!o->tol.empty()) o->options.rel_tol = io::parse_number_text(o->tol, "--tol").value;
            const auto figures =
                qmotion::compare_schemes(read_poses_argument(o->poses, o->robot), o->options);
            if (o->json)
              std::cout << qmotion::to_json(figures).dump(2) << "\n";
            else
              std::cout << qmotion::to_table(figures);
            return 0;
          }};
}

}  // namespace qmotion::cli
