#!/usr/bin/env bash
# Configures and builds qmotion in ./build (Release, ccache when present).
# Extra arguments are passed to the CMake configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/ccache-launcher.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@"
cmake --build build -j "$(nproc)"
