#!/usr/bin/env python3
"""The Khronos glTF validator finds nothing to report in qmotion's glTF files.

Writes animations of both kinds of motion with several bodies, binary and text, and runs
gltf_validate.mjs (npm gltf-validator, installed into tests/interop/node_modules by
scripts/install-deps.sh --test) on them: no error, warning or info message. A missing Node.js
or validator fails, naming what to install and the CMake option that turns the test off;
with QMOTION_REAL_CLIENTS=OFF it exits 77 (skip).
Usage: gltf_validator.py QMOTION DATA WORK
"""
import os
import shutil
import subprocess
import sys

import clients


def main():
    qmotion, data, work = sys.argv[1:4]
    here = os.path.dirname(os.path.abspath(__file__))
    node = shutil.which(os.environ.get("QMOTION_NODE", "node"))
    if not node or not os.path.isdir(os.path.join(here, "node_modules", "gltf-validator")):
        return clients.missing("Node.js or the npm package gltf-validator",
                               "Debian's nodejs and npm, then npm ci in tests/interop")
    os.makedirs(work, exist_ok=True)
    rational = os.path.join(work, "rational.json")
    spline = os.path.join(work, "kks.json")
    poses = os.path.join(data, "helix_10.json")
    subprocess.run([qmotion, "interpolate", poses, "-o", rational], check=True, capture_output=True)
    subprocess.run([qmotion, "qspline", poses, "--scheme", "kks", "-o", spline], check=True,
                   capture_output=True)
    cases = [(rational, [], "default.glb"), (rational, ["--body", "cutter:bull,6,1,25"], "bull.gltf"),
             (spline, ["--body", "sphere:4", "--duration", "10"], "sphere.glb"),
             (spline, ["--body", os.path.join(data, "bodies", "tetra.obj")], "tetra.glb")]
    files = []
    for motion, extra, name in cases:
        out = os.path.join(work, name)
        r = subprocess.run([qmotion, "animate", motion, "-o", out] + extra, capture_output=True,
                           text=True)
        if r.returncode:
            print("qmotion animate failed:", r.stderr)
            return 1
        files.append(out)
    r = subprocess.run([node, os.path.join(here, "gltf_validate.mjs")] + files, capture_output=True,
                       text=True)
    print(r.stdout + r.stderr)
    return r.returncode


if __name__ == "__main__":
    sys.exit(main())
