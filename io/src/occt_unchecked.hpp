// io/src/occt_unchecked.hpp: read_cad without qmotion's checks of the file, for tests only
// (not installed): what OpenCASCADE's readers do with a damaged file by themselves.
#pragma once
#include <qmotion/io/occt.hpp>
#include <string>

namespace qmotion::io {

/// read_cad without the IGES record checks and the refusal of entities OpenCASCADE's load
/// check failed, so that a test can show a reader's crash on such a file refused (it runs
/// in a child process) rather than taking the caller down. Never for users: the checks
/// give the precise message (the line or entity).
CadGeometry read_cad_unchecked(const std::string& path, bool want_surface,
                               const std::string& units = "mm");

}  // namespace qmotion::io
