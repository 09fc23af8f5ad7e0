// io/cli/commands.hpp
#pragma once

namespace qmotion::cli {

/// Runs the qmotion command line; returns the exit status of SPEC §6. Throws
/// qmotion::Error for user-facing failures (main maps them to their exit status).
int run(int argc, char** argv);

}  // namespace qmotion::cli
