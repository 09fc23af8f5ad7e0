#!/usr/bin/env python3
"""In a build without the viewer page (QMOTION_VIEWER=OFF, or AUTO without emscripten or
npm): `qmotion view` exits 2 with a message that says how to get the page, writes nothing,
and the other commands work (interpolate, eval, sweep, volume).

Usage: view_without_viewer.py QMOTION POSES WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys


def main():
    exe, poses, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    motion, page = os.path.join(work, "m.json"), os.path.join(work, "view.html")
    run = lambda *a: subprocess.run([exe] + list(a), capture_output=True, text=True)
    r = run("interpolate", poses, "-o", motion)
    assert r.returncode == 0, r.stderr
    r = run("view", motion, "-o", page)
    assert r.returncode == 2, (r.returncode, r.stderr)
    for words in ("no viewer page", "emscripten", "three.js", "scripts/install-deps.sh"):
        assert words in r.stderr, (words, r.stderr)
    assert not os.path.exists(page), "view left a file behind"
    r = run("eval", motion, "--t", "0.5")
    assert r.returncode == 0 and "position" in json.loads(r.stdout), r.stderr
    r = run("sweep", motion, "--profile", "circle:3", "-o", os.path.join(work, "s.json"))
    assert r.returncode == 0, r.stderr
    r = run("volume", motion, "--body", "sphere:3", "--tol", "2", "-o", os.path.join(work, "v.stl"))
    assert r.returncode == 0, r.stderr
    print("view refused as expected:", r.stderr.strip() or "ok")


if __name__ == "__main__":
    main()
