// cli/animate.cpp: `qmotion animate`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/animate.hpp>
#include <qmotion/io/qspline_file.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_animate(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "animate",
      "Write the motion as a glTF 2.0 animation of a body (.glb or .gltf, in metres) whose "
      "keyframes keep every point of the body within --tol of the exact motion, certified");
  struct Options {
    std::string motion;
    qmotion::AnimateOptions options;
  };
  auto o = std::make_shared<Options>();
  sub->add_option("MOTION", o->motion, "Motion JSON file (either kind)")->required();
  sub->add_option("-o,--output", o->options.output, "Output .glb or .gltf")->required();
  sub->add_option("--body", o->options.body,
                  "The moving body: sphere:r, box:a,b,c, cylinder:r,h, cutter:flat,D,L, "
                  "cutter:ball,D,L, cutter:bull,D,rc,L, or an .stl/.obj/.ply mesh (default: a "
                  "cube a tenth of the motion's extent)");
  sub->add_option("--tol", o->options.tol,
                  "Largest distance of any point of the body from the exact motion, in the "
                  "motion's unit (default 1e-3 of the swept space's bounding-box diagonal)");
  sub->add_option("--duration", o->options.duration,
                  "Seconds the animation lasts (default: the parameter range, time = t - a)");
  return {sub, [o] {
            const auto r = qmotion::animate(io::load_motion(o->motion), o->options);
            std::cout << r.report().dump(2) << "\n";
            return 0;
          }};
}

}  // namespace qmotion::cli
