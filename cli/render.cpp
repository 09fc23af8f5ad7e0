// cli/render.cpp: `qmotion render` and `qmotion plot`.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <optional>
#include <qmotion/api/volume.hpp>
#include <qmotion/io/profiles.hpp>
#include <qmotion/io/qspline_file.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/render/render.hpp>

#include "command.hpp"

namespace qmotion::cli {

Command add_render(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "render",
      "Draw the motion as SVG or PNG: the object at evenly spaced times, the key poses "
      "numbered, trajectories, the swept surface as shaded iso-lines, a body's swept volume, "
      "axes and a scale bar");
  struct Options {
    std::string motion, profile, size, body;
    std::optional<double> body_tol;
    std::vector<std::string> points;
    render::RenderOptions options;
  };
  auto o = std::make_shared<Options>();
  sub->add_option("MOTION", o->motion, "Motion JSON file (either kind)")->required();
  sub->add_option("-o,--output", o->options.output, "Output .svg or .png")->required();
  sub->add_option("--point", o->points,
                  "Draw the trajectory of the point x,y,z of the moving space (repeatable; "
                  "default: the origin)");
  sub->add_option("--profile", o->profile,
                  "Draw the kinematic surface of this profile (as `sweep --profile` reads it)");
  sub->add_option("--object", o->options.object,
                  "The moving object: cube (default, scaled to the motion), a profile, or an "
                  "STL mesh (.stl) of the moving space");
  sub->add_option("--object-size", o->options.object_size,
                  "The cube's edge in the motion's unit (default: a tenth of the figure's extent)");
  sub->add_option("--frames", o->options.frames,
                  "The object at N evenly spaced times (default 7; 0: only the key poses)");
  sub->add_option("--view", o->options.view,
                  "Orthographic view: iso (default), top, front, side, or a direction x,y,z "
                  "towards the viewer");
  sub->add_option("--size", o->size, "Figure size W,H in pixels (default 960,720)");
  sub->add_option("--title", o->options.title, "Title (default: the motion's name and kind)");
  sub->add_option("--body", o->body,
                  "Draw the swept volume of this body (as `volume --body`): its enclosing mesh, "
                  "shaded");
  sub->add_option("--body-tol", o->body_tol,
                  "The drawn volume's tolerance, in the motion's unit (default 1e-2 of its "
                  "diagonal)");
  return {sub, [o] {
            if (!o->size.empty())
              std::tie(o->options.width, o->options.height) = render::parse_size(o->size);
            for (const auto& p : o->points)
              o->options.points.push_back(io::parse_point(p, "--point"));
            const Motion m = io::load_motion(o->motion);
            if (!o->profile.empty()) o->options.profile = io::read_profile(o->profile, m.units());
            const auto r = o->body.empty()
                               ? render::render(m, o->options)
                               : qmotion::render_volume(m, o->options, o->body, o->body_tol);
            std::cerr << "qmotion: wrote " << r.path << " (" << r.width << "x" << r.height << ", "
                      << r.trajectories
                      << (r.trajectories == 1 ? " trajectory, " : " trajectories, ")
                      << r.object_poses << " instants, " << r.key_poses << " key poses"
                      << (r.key_markers < r.key_poses
                              ? " (" + std::to_string(r.key_markers) + " marked)"
                              : std::string())
                      << (r.surface_quads ? ", swept surface" : "")
                      << (r.volume_triangles ? ", swept volume of " +
                                                   std::to_string(r.volume_triangles) + " triangles"
                                             : std::string())
                      << ")\n";
            return 0;
          }};
}

Command add_plot(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "plot",
      "Plot a quantity along t as SVG or PNG, the key parameters marked: the speed or the "
      "trajectory's curvature of a point, the angular speed, or the weight |Q0(t)|^2 (near 0: "
      "near a pole); --compare puts several motions on one plot");
  struct Options {
    std::string motion, quantity, point, size;
    std::vector<std::string> compare;
    render::PlotOptions options;
  };
  auto o = std::make_shared<Options>();
  sub->add_option("MOTION", o->motion, "Motion JSON file (either kind)")->required();
  sub->add_option("-o,--output", o->options.output, "Output .svg or .png")->required();
  sub->add_option("--quantity", o->quantity, "speed, angular-speed, curvature or weights")
      ->required();
  sub->add_option("--point", o->point,
                  "speed, curvature: of the point x,y,z of the moving space (default origin)");
  sub->add_option("--compare", o->compare,
                  "Another motion file on the same plot (repeatable), for picking a method");
  sub->add_option("--samples", o->options.samples, "Samples per motion (default 600)");
  sub->add_option("--size", o->size, "Figure size W,H in pixels (default 900,500)");
  sub->add_option("--title", o->options.title, "Title (default: the quantity and the point)");
  return {sub, [o] {
            o->options.quantity = render::parse_quantity(o->quantity);
            if (!o->point.empty()) o->options.point = io::parse_point(o->point, "--point");
            if (!o->size.empty())
              std::tie(o->options.width, o->options.height) = render::parse_size(o->size);
            std::vector<Motion> motions{io::load_motion(o->motion)};
            for (const auto& f : o->compare) motions.push_back(io::load_motion(f));
            const auto series = render::plot(motions, o->options);
            std::cerr << "qmotion: wrote " << o->options.output << " ("
                      << render::to_string(o->options.quantity) << ")\n";
            for (const auto& s : series)
              std::cerr << "qmotion: " << s.name << ": min " << s.min << " at t = " << s.t_min
                        << ", max " << s.max << " at t = " << s.t_max << "\n";
            return 0;
          }};
}

}  // namespace qmotion::cli
