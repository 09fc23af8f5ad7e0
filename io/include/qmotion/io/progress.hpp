// <qmotion/io/progress.hpp>: progress of long library calls. Long loops (toolpath sampling,
// meshing, STEP/IGES transfer) report a stage and a fraction to one process-wide sink; there is
// none unless the program installs one (the CLI installs a terminal bar on stderr).
#pragma once
#include <cstdio>
#include <functional>
#include <string>

namespace qmotion::io {

/// Receives (stage, fraction in [0, 1]); a stage ends with fraction 1.
using ProgressSink = std::function<void(const std::string& stage, double fraction)>;

/// Installs the sink (an empty function: none). Not thread-safe: set it before the work.
void set_progress_sink(ProgressSink sink);

/// Reports to the sink, if there is one (one branch when there is none).
void report_progress(const std::string& stage, double fraction);

/// A bar on `out` ("qmotion: stage [#####     ] 42%", redrawn in place at most ten times a
/// second) for stages that run longer than `delay` seconds, erased when the stage ends.
ProgressSink terminal_progress_bar(std::FILE* out, double delay = 1.0);

}  // namespace qmotion::io
