// cli/view.cpp: `qmotion view`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <qmotion/api/view.hpp>
#include <qmotion/io/point_text.hpp>
#include <qmotion/io/qspline_file.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_view(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "view",
      "Write one self-contained HTML page (no network, no server) that animates the motion, "
      "draws its key poses, trajectories and exact sweep in three.js, and interpolates again in "
      "the page, with the kernel in WebAssembly, when a pose is edited");
  struct Options {
    std::string motion;
    std::vector<std::string> points;
    qmotion::ViewOptions options;
  };
  auto o = std::make_shared<Options>();
  sub->add_option("MOTION", o->motion, "Motion JSON file (either kind)")->required();
  sub->add_option("-o,--output", o->options.output, "Output .html page")->required();
  sub->add_option("--profile", o->options.profile,
                  "A profile to sweep: a nurbs_curve JSON file or wire, a STEP/IGES file, or "
                  "segment:, polyline:, rect:w,h, circle:r, arc:r,a0,a1");
  sub->add_option("--body", o->options.body,
                  "A body to move: sphere:r, box:a,b,c, cylinder:r,h, cutter:flat|ball,D,L, "
                  "cutter:bull,D,rc,L, or an .stl/.obj/.ply mesh");
  sub->add_flag("--volume", o->options.volume,
                "Also draw the body's swept volume: the certified enclosing mesh of `volume` "
                "(needs --body)");
  sub->add_option("--body-tol", o->options.volume_tol,
                  "The swept volume's tolerance (motion units; default 1e-2 of its diagonal)");
  sub->add_option("--point", o->points,
                  "A point x,y,z of the moving space whose trajectory is drawn (repeatable; "
                  "default: the origin)");
  return {sub, [o] {
            for (const auto& p : o->points)
              o->options.points.push_back(io::parse_point(p, "--point"));
            const auto v = qmotion::view(io::load_motion(o->motion), o->options);
            std::cout << v.report().dump(2) << "\n";
            return 0;
          }};
}

}  // namespace qmotion::cli
