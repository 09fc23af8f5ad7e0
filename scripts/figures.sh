#!/usr/bin/env bash
# Regenerates the README's figures (docs/figures/*.svg) with a built qmotion, and the
# viewer's screenshot (docs/figures/viewer.png) taken by its test in headless Chromium.
# Usage: scripts/figures.sh [QMOTION]   (default build/qmotion)
set -euo pipefail
cd "$(dirname "$0")/.."
q=$(realpath "${1:-build/qmotion}")
root=$(pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p docs/figures
# The demo's figure: five key poses, two trajectories, the swept parabola.
"$q" demo -o "$tmp/demo" > /dev/null
cp "$tmp/demo/demo.svg" docs/figures/demo.svg
# A cube carried by the 40-pose helix B-spline motion, seen from the front.
cd "$tmp"
"$q" interpolate "$root/examples/data/helix_40.json" --form bspline -o helix.json
"$q" render helix.json -o "$root/docs/figures/helix_front.svg" --view front --frames 9 \
  --point 0,0,0 --point 20,0,0 --size 900,560
# Picking a method: the angular speed of three motions through the same five poses.
poses="$root/examples/data/five_positions.json"
"$q" interpolate "$poses" -o elliptic.json
"$q" interpolate "$poses" --rotation affine -o affine.json
"$q" qspline "$poses" --scheme quartic -o quartic.json
"$q" plot elliptic.json --compare affine.json --compare quartic.json --quantity angular-speed \
  -o "$root/docs/figures/angular_speed.svg"
# The page of `qmotion view` in headless Chromium, as interop.viewer sees it.
python3 "$root/tests/interop/viewer.py" "$q" "$root/tests/data" "$tmp/viewer" \
  --screenshot "$root/docs/figures/viewer.png" > /dev/null
echo "figures: wrote $(ls "$root"/docs/figures | tr '\n' ' ')"
