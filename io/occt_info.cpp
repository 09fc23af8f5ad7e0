// io/occt_info.cpp: OpenCASCADE stays inside io/ (STYLE §4).
#include "io/occt_info.hpp"

#include <Standard_Version.hxx>

namespace qmotion::io {

std::string occt_version() { return OCC_VERSION_COMPLETE; }

}  // namespace qmotion::io
