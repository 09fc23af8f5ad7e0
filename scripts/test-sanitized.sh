#!/usr/bin/env bash
# Builds qmotion, its tests and its fuzz targets with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer in ./build-sanitized, then runs the tests of qmotion's own
# code (kernel, sweep, io, CLI) and the fuzz targets (label fuzz: each fuzzes for
# QMOTION_FUZZ_SECONDS, default 30, and replays its past findings).
# This tree is also the build without CGAL (QMOTION_WITH_CGAL=OFF): it shows that the option
# configures, builds and passes its tests, without a third build in CI's time. The exact
# modes (--exact, check --exact) and the mesh self-intersection check are CGAL's; the
# Release tree tests them, and this one tests that they are refused by name.
# It is also the build without the viewer page (QMOTION_VIEWER=OFF, as on a machine without
# emscripten or npm): its tests pass, and `view` is refused saying how to get the page
# (cli.view_without_viewer).
# Built only for what runs here: no Python module, no benchmarks, no examples.
# Not run here: the Python module and FreeCAD (an instrumented library cannot be loaded into
# an uninstrumented interpreter), the examples (built and run in the Release tree), the
# format check, the header check, the golden digests (recorded from the GCC Release build)
# and the file-size limit at its real size (4 GB uninstrumented; the io tests check the
# limit at a small size).
# Debug information is line tables only: what the sanitizers' stack traces print (file and
# line of every frame), at a fraction of full -g's compile time.
# Extra arguments go to the CMake configure step (e.g. -DQMOTION_FUZZ_SECONDS=300).
set -euo pipefail
cd "$(dirname "$0")/.."
launcher=()
if command -v ccache >/dev/null 2>&1; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  # Paths relative to the clone, so that another clone (CI's) reuses the cache.
  export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=1
fi
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
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-sanitized --output-on-failure -j 2 -E '^(python|interop|format|golden|headers|limits)\.'
