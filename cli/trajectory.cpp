// cli/trajectory.cpp: `qmotion trajectory`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/export.hpp>
#include <qmotion/io/qspline_file.hpp>
#include <qmotion/kernel/error.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_trajectory(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "trajectory",
      "Write the trajectory of a point as NURBS (JSON, STEP or IGES): exact and rational for a "
      "q-motion, fitted within --tol for a quaternion spline");
  struct Options {
    std::string motion, point;
    qmotion::ExportOptions options;
  };
  auto o = std::make_shared<Options>();
  sub->add_option("MOTION", o->motion, "Motion JSON file")->required();
  sub->add_option("--point", o->point, "Point x,y,z of the moving space")->required();
  sub->add_option("-o,--output", o->options.output, "Output .json, .step/.stp or .igs/.iges")
      ->required();
  add_geometry_options(sub, o->options);
  return {sub, [o] {
            const auto r = qmotion::export_geometry(
                io::load_motion(o->motion),
                qmotion::Geometry::trajectory(io::parse_point(o->point, "--point")), o->options);
            std::cerr << "qmotion: wrote " << r.path << " (degree " << r.degree_u << ", C"
                      << r.continuity_u << ", " << r.poles << " poles, " << r.units << ", "
                      << r.inserted_knots << " knots inserted for positive weights"
                      << approximation_note(r) << ")\n";
            return 0;
          }};
}

}  // namespace qmotion::cli
