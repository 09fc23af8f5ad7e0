#!/usr/bin/env python3
"""The viewer's size and speed (issue budgets: the WebAssembly module at most 1 MB compressed;
interpolating and sweeping 100 poses in the page at most 50 ms in headless Chromium).

Writes 100 poses on a helix, interpolates them (a cubic B-spline motion), writes the page with
a rectangle profile and a traced point, and times it in Chromium with viewer_bench.mjs. Prints
a Markdown table (bench_page.py puts it in docs/benchmarks.md); with --check, exits 1 when a
budget is exceeded.
Usage: viewer_bench.py QMOTION BUILD WORK [--runs N] [--check]
"""
import argparse
import gzip
import json
import math
import os
import shutil
import subprocess
import sys


def helix(n):
    poses = []
    for i in range(n):
        s = i / (n - 1)
        a = 4 * math.pi * s
        half = 0.5 * (a + 0.3 * math.sin(3 * a))
        poses.append({"t": s, "position": [60 * math.cos(a), 60 * math.sin(a), 40 * s],
                      "rotation": {"quaternion": [math.cos(half), 0.2 * math.sin(half),
                                                  0.0, math.sqrt(0.96) * math.sin(half)]}})
    return {"units": "mm", "poses": poses}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("qmotion")
    ap.add_argument("build")
    ap.add_argument("work")
    ap.add_argument("--runs", type=int, default=31)
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()
    here = os.path.dirname(os.path.abspath(__file__))
    node = shutil.which(os.environ.get("QMOTION_NODE", "node"))
    chromium = shutil.which(os.environ.get("QMOTION_CHROMIUM", "chromium"))
    if not node or not chromium:
        sys.exit("viewer_bench: Chromium or Node.js is missing (scripts/install-deps.sh --test)")
    os.makedirs(a.work, exist_ok=True)
    poses = os.path.join(a.work, "helix_100.json")
    with open(poses, "w") as f:
        json.dump(helix(100), f)
    motion = os.path.join(a.work, "helix_100_motion.json")
    page = os.path.join(a.work, "helix_100.html")
    subprocess.run([a.qmotion, "interpolate", poses, "-o", motion], check=True, capture_output=True)
    subprocess.run([a.qmotion, "view", motion, "-o", page, "--profile", "rect:4,2", "--point",
                    "3,0,0"], check=True, capture_output=True)
    out = os.path.join(a.work, "viewer_bench.json")
    subprocess.run([node, os.path.join(here, "viewer_bench.mjs"), chromium, page, str(a.runs), out],
                   check=True)
    with open(out) as f:
        r = json.load(f)
    if "error" in r or r["errors"]:
        sys.exit("viewer_bench: the page failed: %s" % r)
    with open(os.path.join(a.build, "render", "viewer", "qmotion_kernel.wasm"), "rb") as f:
        wasm = f.read()
    packed = len(gzip.compress(wasm, 9))
    rows = [
        ("WebAssembly module (the kernel)", "%.0f KB, %.0f KB gzip -9" % (len(wasm) / 1024, packed / 1024),
         "≤ 1 MB compressed"),
        ("the page (`qmotion view`, 100 poses, profile rect:4,2)",
         "%.2f MB" % (os.path.getsize(page) / 2**20), ""),
        ("page load until the kernel is ready", "%d ms" % r["load_ms"], ""),
        ("interpolate 100 poses and sweep, in the page (median of %d)" % r["runs"],
         "%.1f ms (min %.1f, max %.1f)" % (r["median_ms"], r["min_ms"], r["max_ms"]), "≤ 50 ms"),
    ]
    print("| what | measured | budget |\n| --- | --- | --- |")
    for row in rows:
        print("| %s | %s | %s |" % row)
    over = []
    if packed > 2**20:
        over.append("the module is %d bytes compressed, over 1 MB" % packed)
    if r["median_ms"] > 50:
        over.append("interpolating and sweeping took %.1f ms, over 50 ms" % r["median_ms"])
    for o in over:
        print("over budget:", o, file=sys.stderr)
    return 1 if over and a.check else 0


if __name__ == "__main__":
    sys.exit(main())
