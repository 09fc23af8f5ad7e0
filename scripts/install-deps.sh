#!/usr/bin/env bash
# Installs qmotion's build and test dependencies from Debian's packages.
# Usage: scripts/install-deps.sh [--test]
#   The build needs emscripten, to compile the kernel to WebAssembly for the page of
#   `qmotion view`, and Node.js with npm (Debian's, unless a node is already on PATH) for
#   three.js, which npm ci installs into render/viewer from its lock file.
#   --test  also installs what the test suite needs (GoogleTest, Google Benchmark,
#           clang-format, pytest for the Python module, pip, venv, setuptools and wheel for
#           its `pip install .` test, Dask's distributed for its batch
#           example, FreeCAD for the interop test, and
#           clang with libclang-rt-14-dev for scripts/test-sanitized.sh: sanitizers, libFuzzer;
#           linuxcnc-uspace for its rs274 G-code interpreter; Blender for the glTF test, and
#           Chromium for the viewer's test; OpenVDB for the swept-volume and verify peer
#           benchmarks and FCL for verify's; then the npm packages of tests/interop from
#           their lock file: the Khronos glTF validator and puppeteer-core).
set -euo pipefail

packages=(
  cmake g++ make ccache pkg-config
  libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  nlohmann-json3-dev libcli11-dev
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libocct-data-exchange-dev libtbb-dev libsimdjson-dev
  python3 python3-dev python3-numpy pybind11-dev libcairo2-dev
  emscripten
)
command -v npm >/dev/null || packages+=(nodejs npm)
if [[ "${1:-}" == "--test" ]]; then
  packages+=(googletest libgtest-dev libgmock-dev libbenchmark-dev clang-format git python3 python3-pytest python3-distributed python3-pip python3-venv python3-setuptools python3-wheel freecad-python3
    clang libclang-rt-14-dev linuxcnc-uspace time blender chromium libopenvdb-dev libfcl-dev)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
else
  sudo=""
  if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
  echo "install-deps: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

root="$(cd "$(dirname "$0")/.." && pwd)"
if [[ ! -f "$root/render/viewer/node_modules/three/package.json" ]]; then
  echo "install-deps: npm ci in render/viewer (three.js, inlined into the viewer page)"
  (cd "$root/render/viewer" && npm ci --no-audit --no-fund --loglevel=error)
fi
if [[ "${1:-}" == "--test" ]]; then
  if [[ ! -d "$root/tests/interop/node_modules/gltf-validator" ||
        ! -d "$root/tests/interop/node_modules/puppeteer-core" ]]; then
    echo "install-deps: npm ci in tests/interop (the glTF validator, puppeteer-core)"
    (cd "$root/tests/interop" && npm ci --no-audit --no-fund --loglevel=error)
  fi
fi
