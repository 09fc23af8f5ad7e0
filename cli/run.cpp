// cli/run.cpp: the qmotion command line. Each command lives in its own file
// (cli/<command>.cpp); run() wires them up (main.cpp maps errors to exit statuses).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <qmotion/io/occt_info.hpp>
#include <qmotion/io/progress.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/version.hpp>
#include <vector>

#include "command.hpp"

namespace qmotion::cli {

int run(int argc, char** argv) {
  CLI::App app{"qmotion: rational motions from rigid-body poses, exported as exact NURBS",
               "qmotion"};
  app.require_subcommand(0, 1);
  bool version = false, quiet = false;
  app.add_flag("--version", version, "Print the version and the OpenCASCADE version, then exit");
  app.add_flag("--quiet", quiet,
               "No progress bar (shown on stderr, when it is a terminal, for stages that take "
               "more than a second: toolpath sampling, meshing, STEP/IGES translation)");
  app.footer(
      "Exit status: 0 success, 2 bad input or usage, 3 numerical failure, 1 internal error.\n"
      "Conventions: quaternions (w,x,y,z); pose P = (2 + eps s) * r; millimetres unless the file "
      "says otherwise.\n");

  const std::vector<Command> commands = {
      add_info(app),       add_eval(app),     add_interpolate(app), add_fit(app),  add_poses(app),
      add_trajectory(app), add_sweep(app),    add_check(app),       add_demo(app), add_qspline(app),
      add_compare(app),    add_toolpath(app), add_render(app),      add_plot(app), add_animate(app),
      add_view(app),       add_volume(app),   add_verify(app)};
  for (const auto& c : commands) c.app->fallthrough();  // --quiet after the command too
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::cout << app.help("", CLI::AppFormatMode::All);
    return 0;
  } catch (const CLI::ParseError& e) {
    throw Error(Errc::invalid_input, std::string(e.what()) + " (see qmotion --help)");
  }
  if (version) {
    std::cout << "qmotion " << version_string << " (OpenCASCADE " << io::occt_version() << ")\n";
    return 0;
  }
  // QMOTION_PROGRESS_AFTER (seconds, default 1) moves the threshold, for tests.
  const char* after = std::getenv("QMOTION_PROGRESS_AFTER");
  if (!quiet && ::isatty(2))
    io::set_progress_sink(io::terminal_progress_bar(stderr, after ? std::atof(after) : 1.0));
  for (const auto& c : commands)
    if (*c.app) return c.run();
  std::cout << app.help();
  return 2;
}

}  // namespace qmotion::cli
