#!/usr/bin/env bash
# The long fuzzing run, nightly-style, outside CI's time: every libFuzzer target for SECONDS
# (default 1800) from its seed corpus and from what earlier runs found in the build tree,
# then its past findings replayed. Builds ./build-sanitized as scripts/test-sanitized.sh does,
# and sets the tree back to CI's 10 s afterwards.
# Usage: scripts/fuzz-long.sh [SECONDS]
# A finding is written by libFuzzer into the current folder (crash-*, timeout-*, oom-*); add
# it to tests/fuzz/regressions/<name> once it is fixed (docs/testing.md, "Fuzzing").
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-1800}
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || ((seconds == 0)); then
  echo "fuzz-long: SECONDS must be a positive whole number, got '$seconds'" >&2
  exit 2
fi
restore() { cmake -S . -B build-sanitized -DQMOTION_FUZZ_SECONDS=10 >/dev/null; }
trap restore EXIT
scripts/build-sanitized.sh -DQMOTION_FUZZ_SECONDS="$seconds"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-sanitized --output-on-failure -j 2 -L fuzz --timeout $((seconds + 600))
