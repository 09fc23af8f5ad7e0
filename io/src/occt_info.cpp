// io/src/occt_info.cpp: OpenCASCADE stays inside io/ (STYLE §4).
#include <Standard_Version.hxx>
#include <qmotion/io/occt_info.hpp>

namespace qmotion::io {

std::string occt_version() { return OCC_VERSION_COMPLETE; }

}  // namespace qmotion::io
