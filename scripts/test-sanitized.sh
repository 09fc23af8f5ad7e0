#!/usr/bin/env bash
# Builds qmotion and its unit tests with AddressSanitizer and UndefinedBehaviorSanitizer in
# ./build-sanitized and runs them (the tests of qmotion's own code: kernel, sweep, io, CLI).
# Not run here: the Python module and FreeCAD (an instrumented library cannot be loaded into
# an uninstrumented interpreter), the installed-package example and the format check.
# Warnings are not errors here: GCC 12 reports false maybe-uninitialized warnings in
# std::regex and std::function under the sanitizers (the Release build keeps -Werror).
set -euo pipefail
cd "$(dirname "$0")/.."
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B build-sanitized -DCMAKE_BUILD_TYPE=RelWithDebInfo -DQMOTION_SANITIZE=ON \
  -DQMOTION_BUILD_PYTHON=OFF -DQMOTION_BUILD_BENCHMARKS=OFF -DQMOTION_WARNINGS_AS_ERRORS=OFF \
  "${launcher[@]}" "$@"
cmake --build build-sanitized -j "$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-sanitized --output-on-failure -j 2 -E '^(python|interop|example|format)\.'
