#!/usr/bin/env bash
# Builds qmotion, its tests and its fuzz targets with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer in ./build-sanitized, then runs the tests of qmotion's own
# code (kernel, sweep, io, CLI) and the fuzz targets (label fuzz: each fuzzes for
# QMOTION_FUZZ_SECONDS, default 10, and replays its past findings; scripts/fuzz-long.sh fuzzes
# for longer).
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
scripts/build-sanitized.sh -DQMOTION_FUZZ_SECONDS=10 "$@"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-sanitized --output-on-failure -j 2 -E '^(python|interop|format|golden|headers|limits)\.'
