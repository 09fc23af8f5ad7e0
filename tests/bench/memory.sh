#!/bin/bash
# tests/bench/memory.sh: peak memory of each command against the size of its largest input
# or output file (issue 13, item 3), measured with /usr/bin/time -v; a Markdown table.
#
#   tests/bench/memory.sh [QMOTION [POSES [LIMIT]]]   default build/qmotion, 10000 poses
#
# The poses are a helix generated here (smooth, turning with the tangent). The table gives
# peak RSS, the largest file and their ratio, raw: nothing is subtracted. What
# `qmotion --version` alone takes (the shared libraries) is printed below the table, as a
# figure of its own. Exit status 1 when a command fails, or, with LIMIT, when a ratio the
# target covers exceeds it: `info`, `eval`, and `trajectory` and `sweep` to JSON (issue 34,
# item 9: 3x at 10^4 poses; CTest runs that, and the table's smoke run at 100 poses, where
# the libraries' fixed cost dominates).
set -euo pipefail
exe=$(realpath "${1:-build/qmotion}")
n=${2:-10000}
limit=${3:-}
# The STEP rows are followed by OpenCASCADE's writer alone on the same geometry (built by
# the library, written by STEPControl_Writer at the same 17 digits) when the build has it.
peers=$(dirname "$exe")/tests/bench/occt_peers
over=0
[ -x /usr/bin/time ] || { echo "memory.sh: /usr/bin/time is needed (Debian package 'time')" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

# n poses on a helix of radius 50 mm, pitch 50 mm per turn, 10 turns; the rotation follows
# the tangent (about z) with a small roll, as unit quaternions.
awk -v n="$n" 'BEGIN {
  pi = atan2(0, -1); printf "{\"units\":\"mm\",\"poses\":[\n";
  for (i = 0; i < n; ++i) {
    a = 20 * pi * i / (n - 1); h = (a + pi / 2) / 2; r = 0.1 * sin(3 * a) / 2;
    w = cos(h) * cos(r); x = cos(h) * sin(r); y = sin(h) * sin(r); z = sin(h) * cos(r);
    printf "{\"t\":%.17g,\"position\":[%.17g,%.17g,%.17g],\"rotation\":{\"quaternion\":[%.17g,%.17g,%.17g,%.17g]}}%s\n",
      i / (n - 1), 50 * cos(a), 50 * sin(a), 50 * a / (2 * pi), w, x, y, z, (i < n - 1 ? "," : "");
  }
  printf "]}\n" }' > poses.json

peak() {  # peak RSS in kB of the command "$@"
  /usr/bin/time -v -o rss.txt "$@" > /dev/null 2> err.txt || { cat err.txt >&2; echo "memory.sh: failed: $*" >&2; exit 1; }
  awk -F: '/Maximum resident set size/ { gsub(/ /, "", $2); print $2 }' rss.txt
}
size_kb() { local m=0 s; for f in "$@"; do s=$(( $(stat -c %s "$f") / 1024 )); (( s > m )) && m=$s; done; echo "$m"; }

base=$(peak "$exe" --version)
echo "| command | peak RSS (MB) | largest file (MB) | RSS / file |"
echo "|---|---|---|---|"
row() {  # row [--target] NAME FILES... -- COMMAND...
  local target=0; [ "$1" = --target ] && { target=1; shift; }
  local name=$1; shift; local files=()
  while [ "$1" != "--" ]; do files+=("$1"); shift; done; shift
  local kb; kb=$(peak "$@")
  local f; f=$(size_kb "${files[@]}")
  awk -v n="$name" -v r="$kb" -v f="$f" 'BEGIN {
    printf "| %s | %.1f | %.1f | %.1f |\n", n, r / 1024, f / 1024, r / f }'
  if [ -n "$limit" ] && (( target )) && awk -v r="$kb" -v f="$f" -v l="$limit" 'BEGIN { exit !(r > l * f) }'; then
    echo "memory.sh: $name: peak RSS $kb kB is above $limit x the largest file ($f kB)" >&2
    over=1
  fi
}
"$exe" interpolate poses.json -o motion.json > /dev/null 2>&1
row "\`interpolate\` ($n poses)" poses.json motion.json -- "$exe" interpolate poses.json -o m2.json
row "\`poses\`" poses.json -- "$exe" poses poses.json
row --target "\`info\`" motion.json -- "$exe" info motion.json
row --target "\`eval --t 0.5\`" motion.json -- "$exe" eval motion.json --t 0.5
"$exe" trajectory motion.json --point 1,0,2 -o tr.json > /dev/null 2>&1
row --target "\`trajectory\` → JSON" motion.json tr.json -- "$exe" trajectory motion.json --point 1,0,2 -o tr.json
"$exe" trajectory motion.json --point 1,0,2 -o tr.step > /dev/null 2>&1
row "\`trajectory\` → STEP" motion.json tr.step -- "$exe" trajectory motion.json --point 1,0,2 -o tr.step
if [ -x "$peers" ]; then
  row "↳ OpenCASCADE's writer alone, same curve" motion.json tr_alone.step -- "$peers" --write-alone motion.json trajectory 1,0,2 tr_alone.step
fi
"$exe" sweep motion.json --profile segment:0,0,0:0,0,5 -o sw.json > /dev/null 2>&1
row --target "\`sweep segment\` → JSON" motion.json sw.json -- "$exe" sweep motion.json --profile segment:0,0,0:0,0,5 -o sw.json
"$exe" sweep motion.json --profile segment:0,0,0:0,0,5 -o sw.step > /dev/null 2>&1
row "\`sweep segment\` → STEP" motion.json sw.step -- "$exe" sweep motion.json --profile segment:0,0,0:0,0,5 -o sw.step
if [ -x "$peers" ]; then
  row "↳ OpenCASCADE's writer alone, same face" motion.json sw_alone.step -- "$peers" --write-alone motion.json sweep segment:0,0,0:0,0,5 sw_alone.step
fi
echo
echo "\`qmotion --version\` alone (the libraries, before any work): $(awk -v b="$base" 'BEGIN { printf "%.1f", b / 1024 }') MB."
exit "$over"
