// <qmotion/io/occt_info.hpp>
#pragma once
#include <string>

namespace qmotion::io {

/// Version of the OpenCASCADE library qmotion's STEP/IGES layer is linked against.
std::string occt_version();

}  // namespace qmotion::io
