// io/cli/command.hpp: one subcommand of the qmotion executable: its CLI11 parser and what
// it runs. Each add_<command>() (io/cli/<command>.cpp) declares its options and returns
// both; the command parses, calls the library and prints.
#pragma once
#include <CLI/CLI.hpp>
#include <functional>

namespace qmotion::cli {

struct Command {
  CLI::App* app;             ///< the subcommand (true when it was given)
  std::function<int()> run;  ///< runs it; returns the exit status, throws qmotion::Error
};

Command add_info(CLI::App& app);
Command add_eval(CLI::App& app);
Command add_interpolate(CLI::App& app);
Command add_poses(CLI::App& app);
Command add_trajectory(CLI::App& app);
Command add_sweep(CLI::App& app);
Command add_check(CLI::App& app);
Command add_demo(CLI::App& app);

/// Runs the qmotion command line; returns the exit status of SPEC §6. Throws
/// qmotion::Error for user-facing failures (main maps them to their exit status).
int run(int argc, char** argv);

}  // namespace qmotion::cli
