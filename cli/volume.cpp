// cli/volume.cpp: `qmotion volume`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/volume.hpp>
#include <qmotion/io/qspline_file.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_volume(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "volume",
      "Write the space a body occupies as it moves: a closed mesh that encloses it for certain, "
      "every vertex within --tol of it (.stl, .obj, .ply, .json), or, for sphere:r and "
      "cutter:ball under a rational motion, its exact faces (.step, .igs, .json)");
  struct Options {
    std::string motion;
    qmotion::VolumeOptions options;
  };
  auto o = std::make_shared<Options>();
  sub->add_option("MOTION", o->motion, "Motion JSON file (either kind)")->required();
  sub->add_option("-o,--output", o->options.output, "Output .stl, .obj, .ply, .json, .step or .igs")
      ->required();
  sub->add_option("--body", o->options.body,
                  "The moving body: sphere:r, box:a,b,c, cylinder:r,h, cutter:flat,D,L, "
                  "cutter:ball,D,L, cutter:bull,D,rc,L, or a closed .stl/.obj/.ply mesh")
      ->required();
  sub->add_option("--tol", o->options.tol,
                  "Largest distance of a vertex from the swept volume, in the output unit "
                  "(default 1e-3 of the volume's bounding-box diagonal; beside exact faces, "
                  "the tolerance of the volume bounds, default 1e-2 of it and at most r/4)");
  sub->add_option("--units", o->options.units,
                  "Output unit: mm, cm, m, in, ft, um (default: the motion's)");
  sub->add_flag("--ascii", o->options.ascii, "STL and PLY as text");
  return {sub, [o] {
            const auto r = qmotion::volume(io::load_motion(o->motion), o->options);
            std::cout << r.report().dump(2) << "\n";
            return 0;
          }};
}

}  // namespace qmotion::cli
