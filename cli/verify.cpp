// cli/verify.cpp: `qmotion verify`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/verify.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_verify(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "verify",
      "Check a machining program (G-code from any CAM system) for gouges: how deep the cutter "
      "enters the part over every move, certified between the blocks, not only at them, to "
      "within --tol, and which rapid moves (G0) enter it; with --stock, the stock it leaves "
      "on the part (largest and mean, certified over the whole surface); with --holder, where "
      "the holder first touches the stock as cut so far or the part; 3-axis programs, "
      "millimetres");
  auto o = std::make_shared<qmotion::VerifyOptions>();
  sub->add_option("PROGRAM", o->program, "G-code program (.ngc, .nc, .gcode, .tap, .cnc)")
      ->required();
  sub->add_option("--tool", o->tool,
                  "The cutter, its tip at the programmed point: cutter:flat,D,L, "
                  "cutter:ball,D,L or cutter:bull,D,rc,L (mm)")
      ->required();
  sub->add_option("--part", o->part,
                  "The finished part in the program's frame (mm): a closed .stl, .obj or .ply "
                  "mesh, or a STEP or IGES solid (meshed within T/4)")
      ->required();
  sub->add_option("--stock", o->stock,
                  "The raw stock: box:x0,y0,z0,x1,y1,z1 (two opposite corners, mm), a closed "
                  ".stl, .obj or .ply mesh, or a STEP or IGES solid; reports the stock left on "
                  "the part");
  sub->add_option("--map", o->map,
                  "Write the part coloured by stock left (blue) and gouge (red): .ply with "
                  "vertex colours, or .svg or .png seen from above; needs --stock");
  sub->add_option("--holder", o->holder,
                  "The tool holder (mm): cylinder:r,h, radius r from the cutter's length up h, "
                  "or holder:r1,h1,r2,h2,..., cylinders stacked upwards from it; reports the "
                  "first instant of each move at which it enters the stock as cut so far (with "
                  "--stock) or the part");
  sub->add_option("--fixture", o->fixtures,
                  "A fixture (clamp, vice), repeatable: box:x0,y0,z0,x1,y1,z1, a closed .stl, "
                  ".obj or .ply mesh, or a STEP or IGES solid; reports where the cutter or the "
                  "holder first touches it");
  sub->add_option("--tol", o->tol, "Width of every certified depth interval, in mm (default 0.01)");
  sub->add_option("-o,--output", o->output, "Write the report to this .json file as well");
  return {sub, [o] {
            const auto r = qmotion::verify(*o);
            std::cout << r.report().dump(2) << "\n";
            return 0;  // a gouge is a finding, in the report, not a failure
          }};
}

}  // namespace qmotion::cli
