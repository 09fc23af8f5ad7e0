// io/cli/check.cpp: `qmotion check`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/io/cli/command.hpp>
#include <qmotion/io/export.hpp>
#include <qmotion/io/profiles.hpp>
#include <qmotion/kernel/error.hpp>

namespace qmotion::cli {

Command add_check(CLI::App& app) {
  auto* sub = app.add_subcommand("check",
                                 "Measure the deviation of a written NURBS (JSON, or STEP/IGES "
                                 "read through OpenCASCADE) from the motion");
  struct Options {
    std::string file, motion, profile, point;
    int grid = 41;
  };
  auto o = std::make_shared<Options>();
  sub->add_option("GEOMETRY", o->file, "The .json, .step/.stp or .igs/.iges file to check")
      ->required();
  sub->add_option("--motion", o->motion, "Motion JSON file")->required();
  sub->add_option("--profile", o->profile, "The profile the surface was swept from");
  sub->add_option("--point", o->point, "The point whose trajectory the curve is");
  sub->add_option("--grid", o->grid, "Lattice size per direction (plus 400 random samples)");
  return {sub, [o] {
            if (o->profile.empty() == o->point.empty())
              throw Error(Errc::invalid_input, "check: give exactly one of --profile and --point");
            const kernel::Motion<double> lm = io::load_motion(o->motion);
            std::optional<sweep::Profile<double>> profile;
            std::optional<Eigen::Vector3d> point;
            if (!o->profile.empty()) profile = io::read_profile(o->profile, lm.units);
            if (!o->point.empty()) point = io::parse_point(o->point, "--point");
            if (o->grid < 1 || o->grid > 1000)
              throw Error(Errc::invalid_input, "--grid: expected 1 to 1000");
            std::cout << io::check_geometry(o->file, lm, profile, point, o->grid).dump(2) << "\n";
            return 0;
          }};
}

}  // namespace qmotion::cli
