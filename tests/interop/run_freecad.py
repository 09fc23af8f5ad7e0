#!/usr/bin/env python3
"""Interop test: a real CAD client (FreeCAD, headless) reads qmotion's STEP and IGES.

Usage: run_freecad.py QMOTION SHARED_DATA WORK_DIR
Builds the five-pose elliptic + TR motion, sweeps the shared parabola, writes STEP and
IGES, computes points of the exact surface with `qmotion eval` (motion at u applied to
the profile point at v), and has FreeCAD check: valid shape, one face, every point on it
within 1e-7 of the bounding-box diagonal. Exit 0 pass, 1 fail, 77 skip (no freecadcmd).
"""
import json
import os
import shutil
import subprocess
import sys


def main():
    qmotion, shared, work = sys.argv[1:4]
    freecad = shutil.which("freecadcmd")
    if not freecad:
        print("freecadcmd not found: install freecad-python3 (scripts/install-deps.sh --test)")
        return 77
    os.makedirs(work, exist_ok=True)
    motion = os.path.join(work, "motion.json")
    subprocess.run([qmotion, "interpolate", os.path.join(shared, "poses/five_positions.json"), "-o", motion], check=True)
    profile = os.path.join(shared, "profiles/parabola.json")
    files = []
    for ext in (".step", ".igs"):
        out = os.path.join(work, "surface" + ext)
        subprocess.run([qmotion, "sweep", motion, "--profile", profile, "-o", out], check=True)
        files.append(out)
    prof = json.load(open(profile))
    p0, p1, p2 = prof["control_points"]
    w0, w1, w2 = prof["weights"]
    points = []
    for i in range(7):
        for j in range(7):
            u, v = i / 6.0, j / 6.0
            b = [(1 - v) ** 2 * w0, 2 * v * (1 - v) * w1, v * v * w2]
            x = [sum(b[k] * (p0, p1, p2)[k][c] for k in range(3)) / sum(b) for c in range(3)]
            res = subprocess.run([qmotion, "eval", motion, "--t", repr(u), "--point", ",".join(repr(c) for c in x)],
                                 check=True, capture_output=True, text=True)
            points.append(json.loads(res.stdout)["point"])
    points_file = os.path.join(work, "points.json")
    json.dump(points, open(points_file, "w"))
    result = os.path.join(work, "freecad_result.json")
    if os.path.exists(result):
        os.remove(result)
    env = dict(os.environ, QMOTION_FC_FILES=",".join(files), QMOTION_FC_POINTS=points_file, QMOTION_FC_RESULT=result)
    subprocess.run([freecad, os.path.join(os.path.dirname(os.path.abspath(__file__)), "freecad_check.py")], env=env,
                   stdin=subprocess.DEVNULL, timeout=240)
    if not os.path.exists(result):
        print("FreeCAD wrote no result")
        return 1
    report = json.load(open(result))
    print(json.dumps(report, indent=1))
    ok = True
    for path in files:
        r = report.get(path)
        if r is None or not r["valid"] or r["faces"] != 1 or r["relative_distance"] > 1e-7:
            print("FAIL:", path, r)
            ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
