#!/usr/bin/env bash
# Configures and builds ./build-sanitized: clang, AddressSanitizer and
# UndefinedBehaviorSanitizer, the fuzz targets, no CGAL, no viewer, no Python module, no
# benchmarks, no examples (why: scripts/test-sanitized.sh, which runs its tests, and
# scripts/fuzz-long.sh, which fuzzes longer). Extra arguments go to the CMake configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/ccache-launcher.sh
# A tree configured with another compiler (GCC, before the fuzz targets) starts afresh.
if [[ -f build-sanitized/CMakeCache.txt ]] &&
  ! grep -q '^CMAKE_CXX_COMPILER:.*clang' build-sanitized/CMakeCache.txt; then
  rm -rf build-sanitized
fi
cmake -S . -B build-sanitized -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DQMOTION_SANITIZE=ON -DQMOTION_FUZZ=ON -DQMOTION_BUILD_PYTHON=OFF -DQMOTION_WITH_CGAL=OFF \
  -DQMOTION_VIEWER=OFF \
  -DQMOTION_BUILD_BENCHMARKS=OFF -DQMOTION_BUILD_EXAMPLES=OFF -DQMOTION_WARNINGS_AS_ERRORS=ON \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" "${launcher[@]}" "$@"
cmake --build build-sanitized -j "$(nproc)"
