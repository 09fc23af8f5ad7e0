// <qmotion/version.hpp>: the one place qmotion's version is written. CMake reads it for
// project(VERSION), the package's version file and every file header that names qmotion.
#pragma once

#define QMOTION_VERSION_MAJOR 0
#define QMOTION_VERSION_MINOR 1
#define QMOTION_VERSION_PATCH 0
#define QMOTION_VERSION_STRING "0.1.0"

namespace qmotion {
/// "major.minor.patch", as `qmotion --version` prints it.
inline constexpr const char* version_string = QMOTION_VERSION_STRING;
}  // namespace qmotion
